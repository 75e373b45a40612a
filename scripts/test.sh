#!/usr/bin/env bash
# Builds (into ./build) and runs every test with ctest. Extra arguments go to ctest
# (e.g. scripts/test.sh -L core).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh --if-missing
# CI (CI=true) builds with warnings as errors (CATAR_WERROR).
werror=OFF
if [[ -n "${CI:-}" ]]; then werror=ON; fi
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DCATAR_WERROR="$werror"
cmake --build build -j "$(nproc)"
export VTK_SMP_BACKEND_IN_USE=STDThread
cd build
xvfb-run -a ctest --output-on-failure --timeout 900 "$@"
