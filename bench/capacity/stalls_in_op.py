#!/usr/bin/env python3
"""The host stalls each part of a `vdrive run` log had once its line was in Op.

Usage: stalls_in_op.py LOG PARTS
Prints one entry per part, in part order, joined by '/': "none", or "K, longest X ms".
Exit 0 when no part stalled in Op, 1 when one did, 2 when the log never reached Op, cannot be
read, or the arguments are wrong (then a line on stderr says which).

A stall is counted when its log line ("host stall X ms ..." or "K more host stalls ...") comes
later than the last "-> Op" line of the log by more than two of the status thread's 125 ms
looks: stalls while the master brought the line up (the drift compensation's burst of frames)
are not deadlines missed in Op. Part 1 logs as [vdrive], part K as [part K].
"""
import re
import sys
from datetime import datetime

LINE = re.compile(r"^\[(\d{4}-\d\d-\d\d \d\d:\d\d:\d\d\.\d{3})\] \[(vdrive|part (\d+))\] \[\w+\] (.*)$")
STALL = re.compile(r"^host stall (\d+(?:\.\d+)?) ms")
MORE = re.compile(r"^(\d+) more host stalls? \(longest so far (\d+(?:\.\d+)?) ms\)")
MARGIN_S = 0.25


def main(argv):
    if len(argv) != 3 or not argv[2].isdigit() or int(argv[2]) < 1:
        print("usage: stalls_in_op.py LOG PARTS", file=sys.stderr)
        return 2
    parts = int(argv[2])
    entries = []
    try:
        with open(argv[1], encoding="utf-8", errors="replace") as log:
            for line in log:
                m = LINE.match(line.rstrip("\n"))
                if m:
                    when = datetime.strptime(m.group(1), "%Y-%m-%d %H:%M:%S.%f").timestamp()
                    entries.append((when, int(m.group(3) or 1), m.group(4)))
    except OSError as e:
        print(f"stalls_in_op.py: cannot read {argv[1]}: {e.strerror}", file=sys.stderr)
        return 2
    in_op = [when for when, _, text in entries if text.endswith("-> Op")]
    if not in_op:
        print("the line never reached Op")
        return 2
    since = max(in_op) + MARGIN_S
    count = [0] * (parts + 1)
    longest = [0.0] * (parts + 1)
    for when, part, text in entries:
        if when <= since or part > parts:
            continue
        if m := STALL.match(text):
            count[part] += 1
            longest[part] = max(longest[part], float(m.group(1)))
        elif m := MORE.match(text):
            count[part] += int(m.group(1))
            longest[part] = max(longest[part], float(m.group(2)))
    print("/".join("none" if count[k] == 0 else f"{count[k]}, longest {longest[k]:.1f} ms"
                   for k in range(1, parts + 1)))
    return 0 if sum(count) == 0 else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))
