#!/usr/bin/env bash
# Installs the build tree into a temporary prefix and checks that the installed package imports
# from /usr/bin/python3, the installed tool runs and finds the installed data, a downstream C++
# project builds with find_package(CatadioptricAR) and runs, and the installed plugin loads in
# pvpython.
set -euo pipefail
build="$1"
python="$2"
pvpython="${3:-}"
prefix=$(mktemp -d)
trap 'rm -rf "$prefix"' EXIT
cmake --install "$build" --prefix "$prefix" > "$prefix/install.log"
site="$prefix/lib/python3/dist-packages"
PYTHONPATH="$site" "$python" -c "
import catadioptricar as car
cam = car.vtkCatadioptricCamera()
assert cam.IsValid(), cam.GetLastError()
print('imported', car.__file__)
assert car.__file__.startswith('$prefix'), car.__file__
"
# Without PYTHONPATH: Debian's python3 adds <prefix>/lib/python3.X/dist-packages as a site folder
# below /usr/local (site.addsitedir here, for the temporary prefix), whose .pth file names the
# package's folder.
version=$("$python" -c "import sys; print('%d.%d' % sys.version_info[:2])")
test -f "$prefix/lib/python$version/dist-packages/catadioptricar.pth"
"$python" -c "
import site, sys
site.addsitedir('$prefix/lib/python$version/dist-packages')
import catadioptricar as car
assert car.__file__.startswith('$prefix'), car.__file__
assert car.vtkCatadioptricCamera().IsValid()
print('imported through the .pth file:', car.__file__)
"
"$prefix/bin/catadioptric-render" --help > /dev/null
# The installed data, and the CLI finding an installed scene by its data-path name from an
# empty folder (the scene's camera is found beside it, relative to the scene).
data="$prefix/share/catadioptricar"
test -f "$data/calibration/demo-camera.yaml"
test -f "$data/meshes/trefoil-knot.ply"
test -f "$data/scenes/two-objects.yaml"
mkdir "$prefix/empty"
(cd "$prefix/empty" && "$prefix/bin/catadioptric-render" --quiet scenes/trefoil-knot.yaml \
  -o trefoil-knot.png && test -s trefoil-knot.png)
# find_package(CatadioptricAR): a downstream C++ program built against the installed tree only
# (its scene names the installed camera and sample mesh by their data-path names).
source_dir="$(cd "$(dirname "$0")/../.." && pwd)"
cmake -S "$source_dir/Testing/Downstream" -B "$prefix/downstream" \
  -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_BUILD_TYPE=Release > "$prefix/downstream.log" ||
  { cat "$prefix/downstream.log"; exit 1; }
cmake --build "$prefix/downstream" >> "$prefix/downstream.log" ||
  { cat "$prefix/downstream.log"; exit 1; }
"$prefix/downstream/downstream" "$prefix/empty"
test -s "$prefix/empty/downstream.png"
# The licence and citation file, the README, the changelog and the documents.
docs="$prefix/share/doc/CatadioptricAR"
for f in LICENSE CITATION.cff README.md CHANGELOG.md render-a-scene.md scene.schema.json \
  images/demo.png; do
  test -f "$docs/$f" || { echo "not installed: $docs/$f"; exit 1; }
done
# Every document a program's --help names is installed where its footer says, and every program
# has a manual page that lists its options.
for program in catadioptric-render catadioptric-compare catadioptric-pose \
  catadioptric-mirror-outline catadioptric-calibrate; do
  help=$("$prefix/bin/$program" --help)
  grep -q "Documentation: .* installed as .*/share/doc/CatadioptricAR/NAME.md" <<< "$help" ||
    { echo "$program --help does not say where the documents are"; exit 1; }
  for named in $(grep -o 'Documentation/[a-z-]*\.md' <<< "$help" | sort -u); do
    test -f "$docs/${named#Documentation/}" ||
      { echo "$program --help names $named, not installed in $docs"; exit 1; }
  done
  # Manual pages come from help2man (scripts/install-deps.sh installs it); a build without it
  # has none, and says so when configured.
  command -v help2man > /dev/null || continue
  page="$prefix/share/man/man1/$program.1"
  test -f "$page" || { echo "no manual page $page"; exit 1; }
  grep -q '^\.TH' "$page" && grep -q 'threads' "$page" ||
    { echo "$page lacks a title or --threads"; exit 1; }
  if command -v man > /dev/null; then
    MANWIDTH=100 man -l "$page" 2> /dev/null | grep -q -- "--version" ||
      { echo "man cannot render $page"; exit 1; }
  fi
done
plugin=$(find "$prefix" -name CatadioptricAR.so | head -n 1)
test -n "$plugin"
if [[ -n "$pvpython" ]]; then
  "$pvpython" -c "
from paraview import simple
simple.LoadPlugin('$plugin', remote=False)
assert hasattr(simple, 'CatadioptricProjection')
print('plugin loaded from', '$plugin')
"
fi
echo "install: 1 passed, 0 failed"
