#!/usr/bin/env bash
# Installs the build tree into a temporary prefix and checks that the installed package imports
# from /usr/bin/python3, the installed tool runs, and the installed plugin loads in pvpython.
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
"$prefix/bin/catadioptric-render" --help > /dev/null
# The licence and citation file.
test -f "$prefix/share/doc/CatadioptricAR/LICENSE"
test -f "$prefix/share/doc/CatadioptricAR/CITATION.cff"
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
