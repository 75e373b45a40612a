"""Runs every command of the documentation, so that none of them can rot.

Reads README.md and Documentation/*.md (or the Markdown files given) and runs each fenced code
block of language `sh` with `bash -e -o pipefail` and each block of language `python` with this
Python, PYTHONPATH set to the build tree's package. Every block runs in a fresh temporary
folder laid out as the repository's root: `build` links to the build tree, every other top-level
entry of the source tree links to its own, and `../shared` to the source tree's `../shared` when
that exists, so that the commands read as a user types them from a checkout.

A block is left out only when the line right before its fence is one of

    <!-- not run: REASON -->         REASON one of NOT_RUN below, or of CONDITIONAL: then the
                                     block runs where what it needs is there
    <!-- run by test: TEST -->       TEST a ctest test of the build tree (checked with ctest -N)

Fences of the languages in NOT_COMMANDS (file excerpts, diagrams, output) are not run; any other
language, or a fence without one, is an error, as is such a comment anywhere but right before a
fence. Prints what ran and what was skipped and why; exits 1 naming the file, line, command and
its output for every block that failed.
"""

import argparse
import glob
import os
import re
import subprocess
import sys
import tempfile
import time

# Reasons a block is never run: they change the machine or the checkout, or are no command.
NOT_RUN = {
    "installs packages",
    "the two commands, run by CI",
    "builds the project, run by CI",
    "changes the source tree",
    "output shown, not a command",
    "compares two builds of the reader's (BEFORE and AFTER)",
}
# Reasons a block runs only where what it needs is there.
SHARED_DATA = "needs ../shared data"
PVPYTHON = "needs pvpython"
CONDITIONAL = {SHARED_DATA, PVPYTHON}
NOT_COMMANDS = {"text", "yaml", "json", "csv", "cmake"}
RUN = {"sh", "python"}
TIMEOUT_S = 90

FENCE = re.compile(r"^\s*```\s*([^\s`]*)\s*$")
NOT_RUN_COMMENT = re.compile(r"^\s*<!--\s*not run:\s*(.*?)\s*-->\s*$")
RUN_BY_TEST_COMMENT = re.compile(r"^\s*<!--\s*run by test:\s*(.*?)\s*-->\s*$")


class Block:
    def __init__(self, path, line, language, code, annotation):
        self.path = path
        self.line = line  # of the opening fence, 1-based
        self.language = language
        self.code = code
        self.annotation = annotation  # ("not run", reason), ("run by test", name) or None

    def where(self):
        return "%s:%d" % (self.path, self.line)


def parse(path, display):
    """The fenced blocks of one Markdown file, and the errors in how they are marked."""
    blocks, errors = [], []
    with open(path, encoding="utf-8") as f:
        lines = f.read().split("\n")
    i = 0
    while i < len(lines):
        fence = FENCE.match(lines[i])
        comment = NOT_RUN_COMMENT.match(lines[i]) or RUN_BY_TEST_COMMENT.match(lines[i])
        if comment and not (i + 1 < len(lines) and FENCE.match(lines[i + 1])):
            errors.append("%s:%d: the comment is not right before a fence" % (display, i + 1))
        if not fence:
            i += 1
            continue
        language = fence.group(1)
        end = i + 1
        while end < len(lines) and not re.match(r"^\s*```\s*$", lines[end]):
            end += 1
        if end == len(lines):
            errors.append("%s:%d: the fence is never closed" % (display, i + 1))
            break
        annotation = None
        previous = lines[i - 1] if i > 0 else ""
        not_run = NOT_RUN_COMMENT.match(previous)
        by_test = RUN_BY_TEST_COMMENT.match(previous)
        if not_run:
            annotation = ("not run", not_run.group(1))
        elif by_test:
            annotation = ("run by test", by_test.group(1))
        if language not in RUN | NOT_COMMANDS:
            errors.append("%s:%d: fence language '%s': use one of %s" %
                          (display, i + 1, language, ", ".join(sorted(RUN | NOT_COMMANDS))))
        elif annotation and language not in RUN:
            errors.append("%s:%d: a '%s' block is never run; the comment is not needed" %
                          (display, i + 1, language))
        elif annotation and annotation[0] == "not run" and \
                annotation[1] not in NOT_RUN | CONDITIONAL:
            errors.append("%s:%d: unknown reason '%s' (known: %s)" %
                          (display, i, annotation[1], "; ".join(sorted(NOT_RUN | CONDITIONAL))))
        code = "\n".join(lines[i + 1:end]) + "\n"
        blocks.append(Block(display, i + 1, language, code, annotation))
        i = end + 1
    return blocks, errors


def ctest_names(build):
    result = subprocess.run(["ctest", "-N"], cwd=build, capture_output=True, text=True)
    if result.returncode != 0:
        sys.exit("ctest -N failed in %s:\n%s" % (build, result.stderr))
    return set(re.findall(r"^\s*Test\s+#\d+: (\S+)", result.stdout, re.MULTILINE))


def make_checkout(root, source, build):
    """A folder that looks like the repository's root: links to the source and build trees."""
    work = os.path.join(root, "repository")
    os.mkdir(work)
    for entry in os.listdir(source):
        if entry != "build" and not entry.startswith("."):
            os.symlink(os.path.join(source, entry), os.path.join(work, entry))
    os.symlink(build, os.path.join(work, "build"))
    shared = os.path.join(os.path.dirname(source), "shared")
    if os.path.isdir(shared):
        os.symlink(shared, os.path.join(root, "shared"))
    return work


def run(block, source, build, python_path):
    """Runs one block in a fresh folder; returns None, or the reason it failed."""
    with tempfile.TemporaryDirectory(prefix="catar-docs-") as root:
        work = make_checkout(root, source, build)
        # The commands get the environment a user's shell has: nothing of the test's own.
        env = {k: v for k, v in os.environ.items()
               if k != "PYTHONPATH" and not k.startswith("CATAR_")}
        # The block as a file named after its place, so that errors give the line within it.
        name = "%s-line%d.%s" % (os.path.basename(block.path).rsplit(".", 1)[0], block.line,
                                 "sh" if block.language == "sh" else "py")
        script = os.path.join(root, name)
        with open(script, "w", encoding="utf-8") as f:
            if block.language == "sh":
                # Name the line of the Markdown file whose command failed (the trap is line 1).
                f.write("trap 'status=$?; echo \"%s:$((LINENO + %d)): exit status $status\" >&2'"
                        " ERR\n" % (block.path, block.line - 1))
            f.write(block.code)
        if block.language == "sh":
            command = ["bash", "-e", "-o", "pipefail", script]
        else:
            command = [sys.executable, script]
            env["PYTHONPATH"] = python_path
        try:
            result = subprocess.run(command, cwd=work, env=env, capture_output=True, text=True,
                                    timeout=TIMEOUT_S)
        except subprocess.TimeoutExpired:
            return "still running after %d s" % TIMEOUT_S
        if result.returncode != 0:
            output = (result.stdout + result.stderr).strip().split("\n")
            return "exit status %d; output (last lines):\n    %s" % (
                result.returncode, "\n    ".join(output[-25:]))
    return None


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--source", required=True, help="the source tree")
    parser.add_argument("--build", required=True, help="the build tree")
    parser.add_argument("--python-path", required=True,
                        help="the build tree's folder of the catadioptricar package")
    parser.add_argument("files", nargs="*",
                        help="Markdown files (default: README.md and Documentation/*.md)")
    args = parser.parse_args()
    source, build = os.path.realpath(args.source), os.path.realpath(args.build)
    files = args.files or [os.path.join(source, "README.md")] + sorted(
        glob.glob(os.path.join(source, "Documentation", "*.md")))

    blocks, errors = [], []
    for path in files:
        found, wrong = parse(path, os.path.relpath(os.path.realpath(path), source))
        blocks += found
        errors += wrong
    tests = ctest_names(build)
    have = {SHARED_DATA: os.path.isdir(os.path.join(os.path.dirname(source), "shared", "data")),
            PVPYTHON: "ParaView.Plugin" in tests}

    ran, skipped, conditional, failed = 0, {}, {}, []
    for block in blocks:
        if block.language not in RUN:
            continue
        kind, what = block.annotation or ("", "")
        if kind == "run by test":
            if what not in tests:
                errors.append("%s: names the test '%s', which ctest -N does not list" %
                              (block.where(), what))
            skipped["run by test " + what] = skipped.get("run by test " + what, 0) + 1
            continue
        if kind == "not run":
            # NOT_RUN, a CONDITIONAL need that is missing here, or an unknown reason (an error).
            reason = what if what not in CONDITIONAL or have[what] else what + " (absent here)"
            if reason not in CONDITIONAL:
                skipped[reason] = skipped.get(reason, 0) + 1
                continue
            conditional[what] = conditional.get(what, 0) + 1
        start = time.monotonic()
        why = run(block, source, build, os.path.realpath(args.python_path))
        ran += 1
        first = block.code.strip().split("\n")[0]
        print("%-6s %s %s (%.1f s)  %s" % ("ok" if why is None else "FAIL", block.language,
                                           block.where(), time.monotonic() - start, first))
        if why is not None:
            failed.append("%s: the %s block failed:\n    %s\n  %s" % (
                block.where(), block.language, "\n    ".join(block.code.rstrip().split("\n")),
                why))

    print("\n%d blocks run, %d skipped, %d failed" % (ran, sum(skipped.values()), len(failed)))
    for reason in sorted(conditional):
        print("  run     %3d: %s (present here)" % (conditional[reason], reason))
    for reason in sorted(skipped):
        print("  skipped %3d: %s" % (skipped[reason], reason))
    for message in failed + errors:
        print("\n" + message, file=sys.stderr)
    return 1 if failed or errors else 0


if __name__ == "__main__":
    sys.exit(main())
