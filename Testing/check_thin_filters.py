"""House rule (thin filters): a VTK algorithm's RequestData reads its input arrays, calls the Core
and writes its output arrays, in at most 150 lines (from its signature to its closing brace).

Run: /usr/bin/python3 check_thin_filters.py SOURCE_DIR [MAX_LINES]
"""
import pathlib
import re
import sys


def request_data_lengths(root):
    """(file, first line, length) of every RequestData defined under Filters/ and Rendering/."""
    for folder in ("Filters", "Rendering", "ParaView"):
        for path in sorted((root / folder).rglob("*.cxx")):
            lines = path.read_text(encoding="utf-8").split("\n")
            start = None
            for number, line in enumerate(lines, 1):
                if re.search(r"::RequestData\(", line) and not line.startswith(" "):
                    start = number
                elif start is not None and line.startswith("}"):
                    yield path.relative_to(root), start, number - start + 1
                    start = None


def main():
    root = pathlib.Path(sys.argv[1])
    limit = int(sys.argv[2]) if len(sys.argv) > 2 else 150
    found = list(request_data_lengths(root))
    if not found:
        sys.exit(f"no RequestData found under {root}")
    long = [f"{f}:{start}: RequestData has {n} lines" for f, start, n in found if n > limit]
    if long:
        sys.exit(f"RequestData longer than {limit} lines (move the work into the Core):\n"
                 + "\n".join(long))
    lengths = sorted(n for _, _, n in found)
    print(f"{len(found)} RequestData, each at most {limit} lines (longest {lengths[-1]}, "
          f"median {lengths[len(lengths) // 2]})")


if __name__ == "__main__":
    main()
