"""Shared helpers for the object-dictionary tests: where the checkout and the manuals are, and the
committed dictionaries. The manuals live beside the checkout (<repo>/../shared/seeds, or $VDRIVE_SEEDS).
A test module that reads them (run(..., needs_manuals=True)) is skipped with a message when they are
missing, as in a clone of the public repository; with $VDRIVE_REQUIRE_SEEDS set (.ci/run sets it) a
missing manual is a failure instead."""
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


# CTest's SKIP_RETURN_CODE for these tests (tools/extract_od/tests/CMakeLists.txt).
SKIP = 77


def missing_manuals():
    """The manuals' paths that do not exist."""
    return [p for p in (os.path.join(SEEDS, m) for m in MANUALS.values()) if not os.path.exists(p)]


def require_manuals():
    """Returns when every manual is there; otherwise says what is missing and how to supply it, and
    exits: skipped (SKIP), or failed (1) when $VDRIVE_REQUIRE_SEEDS is set."""
    missing = missing_manuals()
    if not missing:
        return
    where = ", ".join(missing)
    how = ("put the vendor manuals in <repo>/../shared/seeds or name their folder with "
           "VDRIVE_SEEDS=/path/to/seeds")
    if os.environ.get("VDRIVE_REQUIRE_SEEDS"):
        print(f"SEEDS MISSING: {where} not found ($VDRIVE_REQUIRE_SEEDS is set); {how}.")
        sys.exit(1)
    verb = "is" if len(missing) == 1 else "are"
    print(f"SKIPPED: these checks compare the dictionaries with the vendor manuals, and {where} "
          f"{verb} not there; {how}.")
    sys.exit(SKIP)


def manual_lines(product):
    """The manual as a list of lines; index 0 is manual line L1."""
    path = os.path.join(SEEDS, MANUALS[product])
    if not os.path.exists(path):
        raise AssertionError(f"SEEDS MISSING: {path} not found. The vendor manuals must be beside the checkout "
                             f"(<repo>/../shared/seeds) or named by $VDRIVE_SEEDS.")
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


def run(module_name, needs_manuals=False):
    import unittest
    if needs_manuals:
        require_manuals()
    result = unittest.main(module=module_name, verbosity=2, exit=False).result
    sys.exit(0 if result.wasSuccessful() else 1)
