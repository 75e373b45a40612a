#!/usr/bin/env bash
# Checks that every C++ file of the project matches .clang-format (clang-format --dry-run);
# lists those that do not and exits 1. Fix them with:
#   git ls-files '*.cxx' '*.h' '*.txx' | xargs clang-format -i
set -euo pipefail
cd "$(dirname "$0")/.."
format="${CLANG_FORMAT:-clang-format}"
bad=0
while IFS= read -r file; do
  if ! "$format" --dry-run -Werror "$file" > /dev/null 2>&1; then
    echo "not formatted: $file"
    bad=1
  fi
done < <(git ls-files '*.cxx' '*.h' '*.txx' 2> /dev/null || find . -path ./build\* -prune -o \( -name '*.cxx' -o -name '*.h' -o -name '*.txx' \) -print)
if [[ $bad == 0 ]]; then
  echo "every C++ file matches .clang-format ($("$format" --version))"
fi
exit $bad
