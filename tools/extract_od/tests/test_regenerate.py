#!/usr/bin/env python3
"""Regenerating the dictionaries from the manuals reproduces the committed profiles/<id>/objects.yaml byte
for byte, and the extractor is deterministic (two runs give identical output)."""
import os
import subprocess
import sys
import tempfile
import unittest

from odtest import EXTRACTOR, MANUALS, REPO, SEEDS, manual_lines, run


class Regenerate(unittest.TestCase):
    def extract(self, out):
        for product in MANUALS:
            manual_lines(product)  # fails loudly when the seeds are missing
        proc = subprocess.run([sys.executable, EXTRACTOR, "--seeds", SEEDS, "--out", out],
                              capture_output=True, text=True)
        self.assertEqual(proc.returncode, 0, f"extractor failed:\n{proc.stdout}\n{proc.stderr}")

    def test_reproduces_committed_files(self):
        with tempfile.TemporaryDirectory() as out:
            self.extract(out)
            for product in sorted(MANUALS):
                with self.subTest(product=product):
                    with open(os.path.join(out, product, "objects.yaml"), "rb") as f:
                        fresh = f.read()
                    with open(os.path.join(REPO, "profiles", product, "objects.yaml"), "rb") as f:
                        committed = f.read()
                    if fresh != committed:
                        a, b = fresh.decode().splitlines(), committed.decode().splitlines()
                        first = next((i for i, (x, y) in enumerate(zip(a, b)) if x != y), min(len(a), len(b)))
                        self.fail(f"profiles/{product}/objects.yaml differs from a fresh extraction at line "
                                  f"{first + 1}:\n  fresh:     {a[first] if first < len(a) else '<eof>'}\n"
                                  f"  committed: {b[first] if first < len(b) else '<eof>'}\n"
                                  f"Regenerate with: python3 tools/extract_od/extract.py")

    def test_deterministic(self):
        with tempfile.TemporaryDirectory() as one, tempfile.TemporaryDirectory() as two:
            self.extract(one)
            self.extract(two)
            for product in sorted(MANUALS):
                with open(os.path.join(one, product, "objects.yaml"), "rb") as f1, \
                        open(os.path.join(two, product, "objects.yaml"), "rb") as f2:
                    self.assertEqual(f1.read(), f2.read(), product)

    def test_override_mismatch_fails_loudly(self):
        """An override whose `manual` value no longer matches the extraction stops the extractor."""
        sys.path.insert(0, os.path.dirname(EXTRACTOR))
        import overrides
        from odmodel import Entry, Object
        obj = Object(index=0x1000, name="Device type", object_code="VAR", line=1,
                     entries=[Entry(subindex=0, data_type="U32")])
        bad = [{"kind": "erratum", "line": 1, "index": 0x1000, "subindex": 0, "field": "data_type",
                "manual": "U16", "value": "U32", "reason": "test"}]
        with self.assertRaises(overrides.OverrideError):
            overrides.apply([obj], bad)


if __name__ == "__main__":
    run("__main__", needs_manuals=True)
