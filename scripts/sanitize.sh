#!/usr/bin/env bash
# Builds the core, mesh-preparation, VTK and bad-input tests with AddressSanitizer and
# UndefinedBehaviorSanitizer (float-cast-overflow included) into ./build-asan and runs them:
# any memory error or undefined behaviour aborts its test. Extra arguments go to ctest.
#   scripts/sanitize.sh            build and run (labels core, meshprep, vtk, corpus, fuzz; not the
#                                  Python and ParaView fuzzers)
# The Python modules, the ParaView plugin, examples and benchmarks are not built here: the
# interpreters that load them are not instrumented. Leak checking is off (VTK's and Embree's
# singletons live until exit).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh --if-missing
flags="-fsanitize=address,undefined,float-cast-overflow -fno-sanitize=vptr"
flags+=" -fno-sanitize-recover=undefined,float-cast-overflow -fno-omit-frame-pointer"
cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g" -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -g" \
  -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_C_FLAGS="$flags" \
  -DCMAKE_EXE_LINKER_FLAGS="$flags" -DCMAKE_SHARED_LINKER_FLAGS="$flags" \
  -DCMAKE_MODULE_LINKER_FLAGS="$flags" \
  -DCATAR_BUILD_PARAVIEW_PLUGIN=OFF -DCATAR_BUILD_EXAMPLES=OFF
export ASAN_OPTIONS="detect_leaks=0:abort_on_error=1:detect_odr_violation=0"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
export VTK_SMP_BACKEND_IN_USE=STDThread
# Only what the labels below run (gtest discovery runs the test programs, so the options above
# apply to the build too).
cmake --build build-asan -j "$(nproc)" --target TestCore TestWithoutOptional TestMeshPrep TestVTK \
  catadioptric-render catadioptric-compare FuzzInputs
cd build-asan
xvfb-run -a ctest --output-on-failure --timeout 1800 -L 'core|meshprep|vtk|corpus|fuzz' \
  -LE 'python|paraview' "$@"
