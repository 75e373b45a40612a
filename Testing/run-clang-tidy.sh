#!/usr/bin/env bash
# The test Lint.ClangTidy: clang-tidy, with the checks of .clang-tidy, on every .cxx of the
# project's own (the Core, the VTK modules, the plugin, the programs) that the build compiles, with
# its compile_commands.json. Prints each finding; fails on any.
#   Testing/run-clang-tidy.sh SOURCE_DIR BUILD_DIR
set -euo pipefail
src=$1
build=$2
tidy=$(command -v clang-tidy || command -v clang-tidy-14 || true)
if [[ -z "$tidy" ]]; then
  echo "clang-tidy not found (scripts/install-deps.sh installs it)" >&2
  exit 1
fi
if [[ ! -f "$build/compile_commands.json" ]]; then
  echo "$build/compile_commands.json not found: configure with CMAKE_EXPORT_COMPILE_COMMANDS" >&2
  exit 1
fi
cd "$src"
mapfile -t files < <(find Module Filters Rendering ParaView Applications -name '*.cxx' | sort)
compiled=()
for f in "${files[@]}"; do
  if grep -q "\"file\": \"$src/$f\"" "$build/compile_commands.json"; then
    compiled+=("$f")
  fi
done
echo "clang-tidy on ${#compiled[@]} files"
# Clang does not know some of GCC's warning options; -Werror is the GCC build's.
printf '%s\n' "${compiled[@]}" | xargs -P "$(nproc)" -n 4 "$tidy" -p "$build" --quiet \
  --extra-arg=-Wno-unknown-warning-option --extra-arg=-Wno-error
