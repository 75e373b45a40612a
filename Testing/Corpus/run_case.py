#!/usr/bin/env python3
"""Runs catadioptric-render on one scene of the bad-input corpus and checks how it ends.

    run_case.py PROGRAM CASE.yaml [--timeout SECONDS]

Each case states what must happen in its comment lines:
    # expect: error REGEX   exit status 1 and REGEX found in the program's output
    # expect: ok [REGEX]    exit status 0 (and REGEX found, when given)
    # expect: any           exit status 0 or 1
    # args: ARGS            extra command-line arguments (default: -o into a temporary folder)
    # generate: nested N    the case is this header followed by a scene nested N levels deep,
                            written to a temporary file (too large to keep in the repository)
A signal (crash, abort), a hang past the timeout, any other exit status, or a line printed by a
library instead of the program (libpng's "Read Error", OpenCV's warnings) fails the case.
"""
import os
import re
import shlex
import subprocess
import sys
import tempfile


def main():
    args = sys.argv[1:]
    timeout = 120.0
    if "--timeout" in args:
        i = args.index("--timeout")
        timeout = float(args[i + 1])
        del args[i : i + 2]
    program, case = args
    text = open(case, encoding="utf-8", errors="replace").read()
    expect = re.search(r"^# expect: (\w+) ?(.*)$", text, re.M)
    if not expect:
        print(f"{case}: no '# expect:' line")
        return 1
    kind, pattern = expect.group(1), expect.group(2).strip()
    extra = re.search(r"^# args: (.*)$", text, re.M)
    generate = re.search(r"^# generate: nested (\d+)$", text, re.M)
    with tempfile.TemporaryDirectory() as tmp:
        scene = case
        if generate:
            depth = int(generate.group(1))
            scene = os.path.join(tmp, os.path.basename(case))
            with open(scene, "w") as f:
                f.write(text + "objects: " + "[" * depth + "]" * depth + "\n")
        command = [program, scene]
        command += shlex.split(extra.group(1)) if extra else ["-o", os.path.join(tmp, "out.png")]
        try:
            run = subprocess.run(
                command,
                cwd=os.path.dirname(os.path.abspath(case)),
                stdout=subprocess.PIPE,
                stderr=subprocess.STDOUT,
                timeout=timeout,
            )
        except subprocess.TimeoutExpired:
            print(f"{case}: still running after {timeout} s")
            return 1
    output = run.stdout.decode("utf-8", errors="replace")
    print(output[-4000:])
    status = run.returncode
    if status < 0:
        print(f"{case}: killed by signal {-status}")
        return 1
    wanted = {"error": (1,), "ok": (0,), "any": (0, 1)}.get(kind)
    if wanted is None:
        print(f"{case}: unknown expectation '{kind}'")
        return 1
    if status not in wanted:
        print(f"{case}: exit status {status}, expected {wanted}")
        return 1
    if pattern and not re.search(pattern, output):
        print(f"{case}: the output does not match /{pattern}/")
        return 1
    # Every line is the program's own: no decoder's or library's chatter on standard error.
    chatter = re.search(r"libpng|Premature end of JPEG|imread_|\[ ?WARN|\[ERROR|TBB Warning", output)
    if chatter:
        print(f"{case}: a library printed its own line ('{chatter.group(0)}')")
        return 1
    print(f"{case}: ended as expected ({kind}, exit status {status})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
