#!/usr/bin/env python3
"""Tables of bench/turnaround results (one JSON object per line, as bench_turnaround_master --json
writes them, each marked by run.sh with the round it was measured in; a line without "round" is
round 1).

1. Per line size, rate and responder: each figure's median over the rounds with its spread
   (min-max), in microseconds, and the counts summed over the rounds.
2. The ratios pair by pair: every vdrive variant (vdrive, vdrive-pP, vdrive-batched, vdrive+stream, vdrive+page)
   against the echo floor and against KickCAT, figure by figure, one ratio per round from the two
   runs of that round (measured minutes apart at most, so both saw the same machine), then the
   median of those ratios. A ratio of medians would pair runs from different moments.
Targets: vdrive p50 <= 1.3 x echo p50, p99.9 <= 2 x echo p99.9, below KickCAT's p50 and p99."""
import json
import statistics
import sys

FIGURES = (("p50", "p50_ns"), ("p99", "p99_ns"), ("p99.9", "p999_ns"))
FLOORS = ("echo", "kickcat")


def us(ns):
    return f"{ns / 1000:.1f}"


def spread(values):
    """Median and (min-max) of a figure over rounds, in microseconds."""
    if len(values) == 1:
        return us(values[0])
    return f"{us(statistics.median(values))} ({us(min(values))}-{us(max(values))})"


def responders(runs):
    """Every responder label, echo first, the vdrive variants in a stable order, KickCAT last."""
    labels = {who for (_, _, who) in runs}
    order = lambda who: (who != "echo", who == "kickcat", who)
    return sorted(labels, key=order)


def load(path):
    runs = {}  # (n, mode, who) -> {round: result}
    with open(path) as f:
        for line in f:
            if line.strip():
                r = json.loads(line)
                who, n = r["label"].split("/")
                runs.setdefault((int(n), r["mode"], who), {})[r.get("round", 1)] = r
    return runs


def figures_table(runs, keys):
    rounds_seen = {len(v) for v in runs.values()}
    print(f"Each figure: median over the rounds (min-max); rounds per row: {', '.join(map(str, sorted(rounds_seen)))}.")
    print()
    print("| N | rate | responder | slaves | image B | frames | rounds | sent | lost | wrong WKC | p50 µs | p99 µs | p99.9 µs | max µs (worst) |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for n, mode in keys:
        for who in responders(runs):
            by_round = runs.get((n, mode, who))
            if not by_round:
                continue
            rs = [by_round[k] for k in sorted(by_round)]
            total = lambda key: sum(r[key] for r in rs)
            slaves = rs[0].get("slaves", 0)
            flag = "" if who == "echo" or slaves == n else " (not N!)"
            slaves = "-" if who == "echo" else slaves
            cells = [spread([r[key] for r in rs]) for _, key in FIGURES]
            print(f"| {n} | {mode} | {who} | {slaves}{flag} | {rs[0]['image_bytes']} | {rs[0].get('frames', 1)} | {len(rs)} | "
                  f"{total('sent')} | {total('lost')} | {total('wrong_wkc')} | " + " | ".join(cells) +
                  f" | {us(max(r['max_ns'] for r in rs))} |")


def ratios_table(runs, keys):
    print("Ratios pair by pair: one per round (round 1 / 2 / ...) from the runs of that round, then **their median**.")
    print("Targets: vdrive/echo p50 <= 1.3 and p99.9 <= 2; vdrive/kickcat p50 and p99 < 1.")
    print()
    print("| N | rate | pair | " + " | ".join(name for name, _ in FIGURES) + " |")
    print("|---|---|---|" + "---|" * len(FIGURES))
    variants = [who for who in responders(runs) if who.startswith("vdrive")]
    for n, mode in keys:
        for who in variants:
            mine = runs.get((n, mode, who))
            for floor in FLOORS:
                theirs = runs.get((n, mode, floor))
                if not mine or not theirs:
                    continue
                common = sorted(set(mine) & set(theirs))
                cells = []
                for _, key in FIGURES:
                    per_round = [mine[k][key] / theirs[k][key] for k in common if theirs[k][key]]
                    if not per_round:
                        cells.append("-")
                        continue
                    each = " / ".join(f"{x:.2f}" for x in per_round)
                    cells.append(f"{each} → **{statistics.median(per_round):.2f}**")
                print(f"| {n} | {mode} | {who}/{floor} | " + " | ".join(cells) + " |")


def main(path):
    runs = load(path)
    keys = sorted({(n, mode) for n, mode, _ in runs}, key=lambda k: (k[1] != "1000Hz", k[0]))
    figures_table(runs, keys)
    print()
    ratios_table(runs, keys)


if __name__ == "__main__":
    main(sys.argv[1])
