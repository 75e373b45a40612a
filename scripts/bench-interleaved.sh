#!/bin/bash
# Speed before and after a change in one interleaved run (this machine's speed drifts by 15-20 %
# over minutes): the bunny's full frame and the projection microbenchmarks, alternating between
# two builds, ROUNDS times each.
#
#   scripts/bench-interleaved.sh BEFORE_BUILD AFTER_BUILD [ROUNDS] [BenchmarkSpeed options...]
#
# A build of the old commit: git worktree add /tmp/before REV && cmake -S /tmp/before -B
# /tmp/before/build -DCMAKE_BUILD_TYPE=Release && cmake --build /tmp/before/build --target
# BenchmarkSpeed BenchmarkProjection. Needs CATAR_SHARED_DATA for the bunny (default
# ../shared/data).
set -euo pipefail
before=$1
after=$2
rounds=${3:-3}
shift $(( $# < 3 ? $# : 3 ))
export VTK_SMP_BACKEND_IN_USE=STDThread
export CATAR_SHARED_DATA=${CATAR_SHARED_DATA:-$(dirname "$0")/../../shared/data}
for r in $(seq 1 "$rounds"); do
  for side in before after; do
    dir=$before
    [[ $side == after ]] && dir=$after
    echo "== $side, round $r"
    "$dir/bin/BenchmarkSpeed" --object bunny --no-variants "$@" | grep -E '^\| (object|bunny)'
    "$dir/bin/BenchmarkProjection" --benchmark_filter='Forward|Back' --benchmark_min_time=0.3 \
      2>/dev/null | grep -E '^BM'
  done
done
