#!/usr/bin/env python3
"""Every dictionary is internally consistent: ranges fit the data type, defaults lie in their range, indexes
and subindexes are unique and sorted, subindex 0 of a structured object counts its entries, and every entry
carries the manual line it came from."""
import unittest

from odtest import MANUALS, dictionary, run

TYPE_RANGE = {"U8": (0, 0xFF), "U16": (0, 0xFFFF), "U32": (0, 0xFFFFFFFF), "I8": (-0x80, 0x7F),
              "I16": (-0x8000, 0x7FFF), "I32": (-0x80000000, 0x7FFFFFFF), "BOOL": (0, 1)}


class Consistency(unittest.TestCase):
    def test_products(self):
        for product in sorted(MANUALS):
            with self.subTest(product=product):
                self.check(product)

    def check(self, product):
        objs = dictionary(product)["objects"]
        indexes = [o["index"] for o in objs]
        self.assertEqual(indexes, sorted(set(indexes)), "indexes unique and sorted")
        for o in objs:
            where = f"{product} 0x{o['index']:04X}"
            subs = [e["subindex"] for e in o["entries"]]
            self.assertEqual(subs, sorted(set(subs)), where)
            self.assertIn(o["object_code"], ("VAR", "ARRAY", "RECORD"), where)
            if o["object_code"] == "VAR":
                self.assertEqual(subs, [0], where)
            else:
                sub0 = o["entries"][0]
                self.assertEqual(sub0["subindex"], 0, where)
                if sub0.get("synthesized"):
                    self.assertEqual(sub0["default"], max(subs), where)
            for e in o["entries"]:
                here = f"{where}:{e['subindex']:02X}"
                for f in (e.get("attributes") or {}).get("fields", []):
                    # digit fields: a range within the field's digits, the composed default inside it
                    first, _, last = f["digits"].partition("-")
                    shift, width = 4 * int(first), 4 * (int(last or first) - int(first) + 1)
                    self.assertLessEqual(0, f["min"], here)
                    self.assertLessEqual(f["min"], f["max"], here)
                    self.assertLessEqual(f["max"], (1 << width) - 1, here)
                    if e["default"] is not None:
                        self.assertTrue(f["min"] <= (e["default"] >> shift) & ((1 << width) - 1) <= f["max"], here)
                self.assertIsInstance(e["line"], int, here)
                self.assertIn(e["pdo"], ("no", "rx", "tx", None), here)
                self.assertIn(e["access"], ("ro", "rw", None), here)
                lo_hi = TYPE_RANGE.get(e["data_type"])
                if lo_hi and e["min"] is not None:
                    self.assertGreaterEqual(e["min"], lo_hi[0], here)
                    self.assertLessEqual(e["max"], lo_hi[1], here)
                if isinstance(e["default"], int) and e["min"] is not None:
                    self.assertTrue(e["min"] <= e["default"] <= e["max"], f"{here}: default outside range")
                if e["pdo"] in ("rx", "tx"):
                    self.assertIn(e["data_type"], TYPE_RANGE, f"{here}: mappable entries have a fixed size")


if __name__ == "__main__":
    run("__main__")
