#!/bin/bash
# Speed before and after a change in one interleaved run (this machine's speed drifts by 15-20 %
# over minutes): the bunny's full frame and the projection microbenchmarks, alternating between
# two builds, ROUNDS times each; and the same bunny as a scene file through catadioptric-render
# --repeat (Testing/Benchmarks/bunny-speed.yaml: every stage of a frame, the background included).
# A program a build does not have is left out.
#
#   scripts/bench-interleaved.sh BEFORE_BUILD AFTER_BUILD [ROUNDS] [BenchmarkSpeed options...]
#
# A build of the old commit: git worktree add /tmp/before REV && cmake -S /tmp/before -B
# /tmp/before/build -DCMAKE_BUILD_TYPE=Release && cmake --build /tmp/before/build --target
# BenchmarkSpeed BenchmarkProjection catadioptric-render. Needs CATAR_SHARED_DATA for the bunny
# (default ../shared/data; CATAR_DATA_PATH defaults to it, for the scene file).
set -euo pipefail
before=$1
after=$2
rounds=${3:-3}
shift $(( $# < 3 ? $# : 3 ))
export VTK_SMP_BACKEND_IN_USE=STDThread
export CATAR_SHARED_DATA=${CATAR_SHARED_DATA:-$(dirname "$0")/../../shared/data}
export CATAR_DATA_PATH=${CATAR_DATA_PATH:-$CATAR_SHARED_DATA}
scene=$(dirname "$0")/../Testing/Benchmarks/bunny-speed.yaml
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
for r in $(seq 1 "$rounds"); do
  for side in before after; do
    dir=$before
    [[ $side == after ]] && dir=$after
    echo "== $side, round $r"
    if [[ -x $dir/bin/BenchmarkSpeed ]]; then
      "$dir/bin/BenchmarkSpeed" --object bunny --no-variants "$@" | grep -E '^\| (object|bunny)'
    fi
    if [[ -x $dir/bin/catadioptric-render ]]; then
      "$dir/bin/catadioptric-render" "$scene" --repeat 100 -o "$out/bunny.png" |
        grep -E '^(  (background|projection|lighting|sort|composite|per frame) )|^per frame'
    fi
    if [[ -x $dir/bin/BenchmarkProjection ]]; then
      "$dir/bin/BenchmarkProjection" --benchmark_filter='Forward|Back' --benchmark_min_time=0.3 \
        2>/dev/null | grep -E '^BM'
    fi
  done
done
