#!/usr/bin/env python3
"""Runs catadioptric-render on one scene of the bad-input corpus and checks how it ends.

    run_case.py PROGRAM CASE.yaml [--timeout SECONDS]

Each case states what must happen in its comment lines:
    # expect: error REGEX   exit status 1 and REGEX found in the program's output
    # expect: ok [REGEX]    exit status 0 (and REGEX found, when given)
    # expect: any           exit status 0 or 1
    # expect: ok-or-error REGEX
                            exit status 0, or 1 with REGEX found (what fits on one machine may
                            not on another, but it never ends otherwise)
    # args: ARGS            extra command-line arguments (default: -o into a temporary folder;
                            @TMP@ in them is that folder)
    # generate: nested N    the case is this header followed by a scene nested N levels deep,
                            written to a temporary file (too large to keep in the repository)
    # generate: stl N       a binary STL of N triangles (a rippled sheet) is written to a
                            temporary folder; @GENERATED@ in the case names it
    # limit: memory KB      the program runs under an address-space limit of KB kilobytes
                            (`ulimit -v`); skipped (status 77) under AddressSanitizer, which
                            needs terabytes of address space
A signal (crash, abort), a hang past the timeout, any other exit status, or a line printed by a
library instead of the program (libpng's "Read Error", OpenCV's warnings) fails the case.
"""
import os
import re
import resource
import shlex
import struct
import subprocess
import sys
import tempfile


def write_stl_sheet(path, triangles):
    """A binary STL of about `triangles` triangles: a rippled square sheet in front of the demo
    camera (its points shared, as a real scan's are)."""
    import numpy as np

    n = int((triangles / 2) ** 0.5) + 1
    u = np.linspace(-0.2, 0.2, n)
    x, y = np.meshgrid(u, u)
    z = 1.0 + 0.02 * np.sin(20 * x) * np.cos(20 * y)
    p = np.stack([x, y - 0.3, z], -1)
    a, b = p[:-1, :-1].reshape(-1, 3), p[1:, :-1].reshape(-1, 3)
    c, d = p[1:, 1:].reshape(-1, 3), p[:-1, 1:].reshape(-1, 3)
    t = np.concatenate([np.stack([a, b, c], 1), np.stack([a, c, d], 1)]).astype(np.float32)
    records = np.zeros(len(t), dtype=[("n", "<f4", 3), ("v", "<f4", (3, 3)), ("a", "<u2")])
    records["v"] = t
    with open(path, "wb") as f:
        f.write(b"\0" * 80 + struct.pack("<I", len(t)))
        f.write(records.tobytes())


def main():
    args = sys.argv[1:]
    timeout = 120.0
    if "--timeout" in args:
        i = args.index("--timeout")
        timeout = float(args[i + 1])
        del args[i : i + 2]
    program, case = args
    text = open(case, encoding="utf-8", errors="replace").read()
    expect = re.search(r"^# expect: ([\w-]+) ?(.*)$", text, re.M)
    if not expect:
        print(f"{case}: no '# expect:' line")
        return 1
    kind, pattern = expect.group(1), expect.group(2).strip()
    extra = re.search(r"^# args: (.*)$", text, re.M)
    generate = re.search(r"^# generate: nested (\d+)$", text, re.M)
    stl = re.search(r"^# generate: stl (\d+)$", text, re.M)
    limit = re.search(r"^# limit: memory (\d+)$", text, re.M)
    if limit and "ASAN_OPTIONS" in os.environ:
        print(f"{case}: skipped: an address-space limit cannot be set under AddressSanitizer")
        return 77
    with tempfile.TemporaryDirectory() as tmp:
        scene = case
        if generate:
            depth = int(generate.group(1))
            scene = os.path.join(tmp, os.path.basename(case))
            with open(scene, "w") as f:
                f.write(text + "objects: " + "[" * depth + "]" * depth + "\n")
        if stl:
            generated = os.path.join(tmp, "generated.stl")
            write_stl_sheet(generated, int(stl.group(1)))
            text = text.replace("@GENERATED@", generated)
            text = text.replace("@CASE_DIR@", os.path.dirname(os.path.abspath(case)))
            scene = os.path.join(tmp, os.path.basename(case))
            with open(scene, "w") as f:
                f.write(text)

        def limit_memory():
            kb = int(limit.group(1))
            resource.setrlimit(resource.RLIMIT_AS, (kb * 1024, kb * 1024))
        command = [program, scene]
        command += (shlex.split(extra.group(1).replace("@TMP@", tmp)) if extra
                    else ["-o", os.path.join(tmp, "out.png")])
        try:
            run = subprocess.run(
                command,
                cwd=os.path.dirname(os.path.abspath(case)),
                stdout=subprocess.PIPE,
                stderr=subprocess.STDOUT,
                timeout=timeout,
                preexec_fn=limit_memory if limit else None,
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
    if kind == "ok-or-error":
        kind, pattern = ("ok", "") if status == 0 else ("error", pattern)
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
