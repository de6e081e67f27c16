"""Shared helpers for the object-dictionary tests: where the checkout and the manuals are, and the
committed dictionaries. The manuals live beside the checkout (<repo>/../shared/seeds, or $VDRIVE_SEEDS);
when they are missing the tests fail loudly instead of skipping."""
import os
import sys

import yaml

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))
SEEDS = os.environ.get("VDRIVE_SEEDS", os.path.join(os.path.dirname(REPO), "shared", "seeds"))
EXTRACTOR = os.path.join(REPO, "tools", "extract_od", "extract.py")

MANUALS = {
    "a6b": "panasonic-minas-a6b-ethercat-spec.zh.txt",
    "ds5c1": "xinje-ds5c1-user-manual.zh.md",
    "ds1000a": "ds1000a-ec-manual.ja.txt",
}


def manual_lines(product):
    """The manual as a list of lines; index 0 is manual line L1."""
    path = os.path.join(SEEDS, MANUALS[product])
    if not os.path.exists(path):
        raise AssertionError(f"SEEDS MISSING: {path} not found. The vendor manuals must be beside the checkout "
                             f"(<repo>/../shared/seeds) or named by $VDRIVE_SEEDS; these tests never skip.")
    with open(path, encoding="utf-8") as f:
        return f.read().split("\n")


_cache = {}


def dictionary(product):
    """The committed profiles/<product>/objects.yaml as {index: object} plus the file's header."""
    if product not in _cache:
        with open(os.path.join(REPO, "profiles", product, "objects.yaml"), encoding="utf-8") as f:
            data = yaml.safe_load(f)
        _cache[product] = data
    return _cache[product]


def objects(product):
    return {o["index"]: o for o in dictionary(product)["objects"]}


def entry(product, index, sub):
    obj = objects(product).get(index)
    if obj is None:
        raise AssertionError(f"{product}: object 0x{index:04X} missing")
    for e in obj["entries"]:
        if e["subindex"] == sub:
            return e
    raise AssertionError(f"{product}: 0x{index:04X}:{sub:02X} missing")


def run(module_name):
    import unittest
    result = unittest.main(module=module_name, verbosity=2, exit=False).result
    sys.exit(0 if result.wasSuccessful() else 1)
