#!/usr/bin/env python3
"""Side-by-side table of bench/turnaround results (one JSON object per line, as
bench_turnaround_master --json writes them): per line size and rate, each responder's
round-trip percentiles in microseconds, and vdrive's ratios to the echo floor and to KickCAT.
Targets: vdrive p50 <= 1.3 x echo p50, p99.9 <= 2 x echo p99.9, below KickCAT's p50 and p99."""
import json
import sys


def us(ns):
    return f"{ns / 1000:.1f}"


def ratio(a, b):
    return f"{a / b:.2f}" if b else "-"


def main(path):
    runs = {}
    with open(path) as f:
        for line in f:
            if line.strip():
                r = json.loads(line)
                who, n = r["label"].split("/")
                runs[(int(n), r["mode"], who)] = r
    keys = sorted({(n, mode) for n, mode, _ in runs}, key=lambda k: (k[1] != "1000Hz", k[0]))
    print("| N | rate | responder | image B | sent | lost | wrong WKC | p50 us | p99 us | p99.9 us | max us |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for n, mode in keys:
        for who in ("echo", "vdrive", "vdrive+stream", "vdrive+page", "kickcat"):
            r = runs.get((n, mode, who))
            if r:
                print(f"| {n} | {mode} | {who} | {r['image_bytes']} | {r['sent']} | {r['lost']} | {r['wrong_wkc']} | "
                      f"{us(r['p50_ns'])} | {us(r['p99_ns'])} | {us(r['p999_ns'])} | {us(r['max_ns'])} |")
    print()
    print("| N | rate | vdrive/echo p50 (target <= 1.3) | vdrive/echo p99.9 (target <= 2) | vdrive/kickcat p50 (< 1) | vdrive/kickcat p99 (< 1) |")
    print("|---|---|---|---|---|---|")
    for n, mode in keys:
        v, e, k = (runs.get((n, mode, who)) for who in ("vdrive", "echo", "kickcat"))
        if not v:
            continue
        cells = [ratio(v["p50_ns"], e["p50_ns"]) if e else "-", ratio(v["p999_ns"], e["p999_ns"]) if e else "-",
                 ratio(v["p50_ns"], k["p50_ns"]) if k else "-", ratio(v["p99_ns"], k["p99_ns"]) if k else "-"]
        print(f"| {n} | {mode} | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main(sys.argv[1])
