#!/usr/bin/env python3
"""The identity values a dictionary table prints (1000h, 1008h, 1009h, 1018h) agree with the product's
identity in profiles/<id>/profile.yaml, which is the single source of those values at run time."""
import os
import unittest

import yaml

from odtest import MANUALS, REPO, objects, run

IDENTITY = [  # (index, subindex, profile.yaml identity key)
    (0x1000, 0, "device_type"), (0x1008, 0, "device_name"), (0x1009, 0, "hardware_version"),
    (0x1018, 1, "vendor_id"), (0x1018, 2, "product_code"), (0x1018, 3, "revision"), (0x1018, 4, "serial"),
]


class Identity(unittest.TestCase):
    def test_dictionary_defaults_match_profile(self):
        checked = 0
        for product in sorted(MANUALS):
            with open(os.path.join(REPO, "profiles", product, "profile.yaml"), encoding="utf-8") as f:
                identity = yaml.safe_load(f)["identity"]
            objs = objects(product)
            for index, sub, key in IDENTITY:
                entry = next(e for e in objs[index]["entries"] if e["subindex"] == sub)
                if entry["default"] is None:
                    continue
                with self.subTest(product=product, index=hex(index), sub=sub):
                    self.assertEqual(entry["default"], identity[key])
                    checked += 1
        self.assertGreaterEqual(checked, 7, "the DS1000A-EC table prints all seven identity values")


if __name__ == "__main__":
    run("__main__")
