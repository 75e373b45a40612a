#!/usr/bin/env bash
# `cpack -G DEB` on the build tree: the package's control data names the libraries and
# interpreters it needs (apt pulls them), it holds the programs, the Python package below
# /usr/lib/python3/dist-packages (where Debian's python3 looks), the plugin, the CMake package and
# the data; unpacked anywhere, its program runs and its Python package imports.
set -euo pipefail
build="$1"
python="$2"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cpack --config "$build/CPackConfig.cmake" -G DEB -B "$work" > "$work/cpack.log" ||
  { cat "$work/cpack.log"; exit 1; }
deb=$(ls "$work"/catadioptricar_*_amd64.deb)
echo "package: $(basename "$deb"), $(stat -c %s "$deb") bytes"
control=$(dpkg-deb -f "$deb" Package Version Depends)
echo "$control"
for needed in "Package: catadioptricar" "python3" "python3-numpy" "paraview" "libopencv-core" \
  "libembree3" "libyaml-cpp"; do
  grep -q -- "$needed" <<< "$control" || { echo "control lacks '$needed'"; exit 1; }
done
contents=$(dpkg-deb -c "$deb" | awk '{print $6}')
for file in ./usr/bin/catadioptric-render ./usr/lib/python3/dist-packages/catadioptricar/__init__.py \
  ./usr/lib/cmake/catadioptricar/CatadioptricARConfig.cmake \
  ./usr/lib/paraview-5.11/plugins/CatadioptricAR/CatadioptricAR.so \
  ./usr/share/catadioptricar/calibration/demo-camera.yaml \
  ./usr/share/catadioptricar/meshes/trefoil-knot.ply ./usr/share/doc/CatadioptricAR/LICENSE; do
  grep -qx -- "$file" <<< "$contents" || { echo "package lacks $file"; exit 1; }
done
# Unpacked (not installed): the program finds its libraries and data beside it.
dpkg-deb -x "$deb" "$work/root"
"$work/root/usr/bin/catadioptric-render" --version
(cd "$work" && "$work/root/usr/bin/catadioptric-render" --quiet scenes/two-objects.yaml \
  -o "$work/two-objects.png" && test -s "$work/two-objects.png")
PYTHONPATH="$work/root/usr/lib/python3/dist-packages" "$python" -c "
import catadioptricar as car
assert car.__file__.startswith('$work/root'), car.__file__
assert car.vtkCatadioptricCamera().IsValid()
print('imported', car.__file__)
"
echo "debian package: 1 passed, 0 failed"
