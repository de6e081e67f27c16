#!/usr/bin/env python3
"""Extracts the complete object dictionaries of the three vdrive products from the vendor manuals.

    python3 tools/extract_od/extract.py [--seeds DIR] [--out DIR] [--product ID ...]

Reads <seeds>/<manual> (default: the shared/seeds directory beside the checkout), applies the reviewed
profiles/<id>/od-overrides.yaml, and writes <out>/<id>/objects.yaml. The output is deterministic.
Format and per-product notes: docs/object-dictionaries.md.
"""
from __future__ import annotations

import argparse
import os
import sys

sys.dont_write_bytecode = True  # run from a source checkout: leave no __pycache__ behind
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import a6b  # noqa: E402
import ds1000a  # noqa: E402
import ds5c1  # noqa: E402
import overrides  # noqa: E402
from odmodel import finish_structure, write_yaml  # noqa: E402

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
PRODUCTS = {"a6b": a6b, "ds5c1": ds5c1, "ds1000a": ds1000a}


def build(product: str, seeds: str) -> str:
    """Returns the objects.yaml text for one product."""
    mod = PRODUCTS[product]
    with open(os.path.join(seeds, mod.MANUAL), encoding="utf-8") as f:
        text = f.read()
    ov_path = os.path.join(REPO, "profiles", product, "od-overrides.yaml")
    ovs = overrides.load(ov_path) if os.path.exists(ov_path) else []
    objects, notes = mod.extract(overrides.apply_text(text, ovs))
    finish_structure(objects)
    overrides.apply(objects, ovs)
    indexes = [o.index for o in objects]
    dupes = sorted({i for i in indexes if indexes.count(i) > 1})
    if dupes:
        raise SystemExit(f"{product}: duplicate indexes after overrides: {[hex(d) for d in dupes]}")
    mod.apply_rules(objects)
    header = {
        "product": product,
        "manual": mod.MANUAL,
        "table_lines": mod.TABLE_LINES,
        "object_count": len(objects),
        "entry_count": sum(len(o.entries) for o in objects),
    }
    return write_yaml(header, notes, objects)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[1])
    ap.add_argument("--seeds", default=os.path.join(os.path.dirname(REPO), "shared", "seeds"),
                    help="directory holding the vendor manuals (default: <repo>/../shared/seeds)")
    ap.add_argument("--out", default=os.path.join(REPO, "profiles"),
                    help="profiles directory to write <id>/objects.yaml into (default: <repo>/profiles)")
    ap.add_argument("--product", action="append", choices=sorted(PRODUCTS),
                    help="only this product (repeatable); default: all")
    args = ap.parse_args(argv)
    if not os.path.isdir(args.seeds):
        print(f"extract_od: seeds directory not found: {args.seeds}", file=sys.stderr)
        return 2
    for product in args.product or sorted(PRODUCTS):
        try:
            text = build(product, args.seeds)
        except (ValueError, overrides.OverrideError) as e:
            print(f"extract_od: {product}: {e}", file=sys.stderr)
            return 1
        os.makedirs(os.path.join(args.out, product), exist_ok=True)
        path = os.path.join(args.out, product, "objects.yaml")
        with open(path, "w", encoding="utf-8", newline="\n") as f:
            f.write(text)
        print(f"{path}: {text.count(chr(10) + '  - index:')} objects")
    return 0


if __name__ == "__main__":
    sys.exit(main())
