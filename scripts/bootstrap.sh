#!/usr/bin/env bash
# Installs what is needed, builds (Release, into ./build) and renders the default demo scene to
# ./demo.png.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh --if-missing
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j "$(nproc)"
./build/bin/catadioptric-render -o demo.png
