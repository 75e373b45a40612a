#!/bin/bash
# Runs a command that opens an OpenGL window on the X display; if it fails because the window could
# not be made (vtkXOpenGLRenderWindow reports it, e.g. "bad X server connection": the shared Xvfb
# turns a connection away now and then under a parallel test run), runs it again, up to three
# times in all. Any other failure is the command's own and is returned at once.
log=$(mktemp)
trap 'rm -f "$log"' EXIT
for attempt in 1 2 3; do
  "$@" 2>&1 | tee "$log"
  status=${PIPESTATUS[0]}
  if [[ $status -eq 0 ]] || ! grep -q "vtkXOpenGLRenderWindow" "$log"; then
    exit "$status"
  fi
  echo "RetryOnDisplayError: attempt $attempt: no OpenGL window on the X display; again" >&2
  sleep 1
done
exit "$status"
