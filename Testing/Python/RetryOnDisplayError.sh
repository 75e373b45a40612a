#!/bin/bash
# Runs a command that opens an OpenGL window on the X display (pvpython, the trade chart) and runs
# it again, up to five times in all, waiting 2, 4, 8 and 16 seconds between tries, when it could
# not start its window: vtkXOpenGLRenderWindow reports it (e.g. "bad X server connection": the
# shared Xvfb turns a connection away now and then under a parallel test run), or the process
# aborts before printing anything of its own (seen once in about ten full parallel runs: SIGABRT
# one second in, no message; once, on a machine loaded with two other builds, three times in a
# row a second apart). Every retry is printed; a failure that repeats is returned.
log=$(mktemp)
trap 'rm -f "$log"' EXIT
for attempt in 1 2 3 4 5; do
  "$@" 2>&1 | tee "$log"
  status=${PIPESTATUS[0]}
  if [[ $status -eq 0 ]]; then
    exit 0
  fi
  if grep -q "vtkXOpenGLRenderWindow" "$log"; then
    why="no OpenGL window on the X display"
  elif [[ $status -ge 128 ]] && ! grep -qv -e "Loguru caught a signal" -e "^\s*$" -e $'^\e' "$log"; then
    why="died by signal $((status - 128)) before any output of its own"
  else
    exit "$status"
  fi
  if [[ $attempt -eq 5 ]]; then
    break
  fi
  echo "RetryOnDisplayError: attempt $attempt: $why; again in $((2 ** attempt)) s" >&2
  sleep $((2 ** attempt))
done
exit "$status"
