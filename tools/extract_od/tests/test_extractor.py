#!/usr/bin/env python3
"""Unit tests of the extractor's text handling, on row text copied from the manuals (lines cited)."""
import os
import sys
import unittest

from odtest import EXTRACTOR, run

sys.path.insert(0, os.path.dirname(EXTRACTOR))
import a6b  # noqa: E402
import ds1000a  # noqa: E402
import ds5c1  # noqa: E402
import overrides  # noqa: E402
from odmodel import parse_int, split_name  # noqa: E402


class Numbers(unittest.TestCase):
    def test_parse_int(self):
        self.assertEqual(parse_int("00040192h"), 0x40192)
        self.assertEqual(parse_int("0x00A2"), 0xA2)
        self.assertEqual(parse_int("-2147483648"), -2147483648)
        self.assertEqual(parse_int("－"), None)
        self.assertEqual(parse_int("0E h"), 0x0E)
        self.assertIsNone(parse_int("Vn.nn/m.mm"))

    def test_split_name(self):
        self.assertEqual(split_name("Controlword 控制字"), ("Controlword 控制字", "Controlword"))
        self.assertEqual(split_name("RxPDO2 支持的映射对象个数"), ("RxPDO2 支持的映射对象个数", None))
        self.assertEqual(split_name("Max torque"), ("Max torque", None))


class A6BRows(unittest.TestCase):
    def test_units_and_range(self):
        # L38914 `6072h 00h Max torque 0.1 % 0 – 65535 U16 rw RxPDO ALL Yes A`
        e, name_units, modes = a6b._parse_body("Max torque 0.1 % 0 – 65535 U16 rw RxPDO ALL Yes A", 38914)
        self.assertEqual(a6b._split_units(name_units), ("Max torque", "0.1 %"))
        self.assertEqual((e.data_type, e.access, e.pdo, e.min, e.max), ("U16", "rw", "rx", 0, 65535))
        self.assertEqual(e.attributes["takes_effect"], "A")
        self.assertEqual(modes, ["ALL"])

    def test_name_ending_in_digit(self):
        # L36800 3674h: `Torque compensation frequency 1` + `0.1 Hz`
        self.assertEqual(a6b._split_units("Torque compensation frequency 1 0.1 Hz"),
                         ("Torque compensation frequency 1", "0.1 Hz"))
        self.assertEqual(a6b._split_units("Communication function extended setup 1 －"),
                         ("Communication function extended setup 1", None))

    def test_negative_range(self):
        self.assertEqual(a6b._parse_range("-2147483648 – 2147483647", 1), (-2147483648, 2147483647))
        self.assertEqual(a6b._parse_range("1 - 2, 255", 1), (1, 255))
        self.assertEqual(a6b._parse_range("1A00h – 1A03h", 1), (0x1A00, 0x1A03))


class DS1000ARows(unittest.TestCase):
    def test_value_columns(self):
        self.assertEqual(ds1000a._values(["0", "-128", "-", "127"]), ("0", "-128", "127"))  # L4909
        self.assertEqual(ds1000a._values(["00000001"]), ("00000001", None, None))        # L4449
        self.assertEqual(ds1000a._values(["-3", "-3"]), ("-3", "-3", "-3"))               # L5068
        self.assertEqual(ds1000a._values(["0", "-", "65535"]), (None, "0", "65535"))      # L4753

    def test_entry(self):
        e = ds1000a._entry(0, "Max torque 0.1% U16 1000 0 - 65535 rw RxPDO", 4941)
        self.assertEqual((e.name, e.units, e.data_type, e.default, e.max, e.pdo),
                         ("Max torque", "0.1%", "U16", 1000, 65535, "rx"))


class DS5C1Rows(unittest.TestCase):
    def test_cells_and_ranges(self):
        self.assertEqual(ds5c1.cells("| 6040h | 00h | Controlword 控制字 | 0~65535 | U16 |")[:2], ["6040h", "00h"])
        self.assertIsNone(ds5c1.cells("|-------|-----|--|"))
        self.assertEqual(ds5c1._range("-2147483648~<br>2147483647"), (-2147483648, 2147483647))
        self.assertEqual(ds5c1._clean("指令单位/s <sup>2</sup>"), "指令单位/s²")

    def test_field_default_composition(self):
        # P0-09: .0 = 0, .2 = F, .3 = 0 (L8659-L8665)
        fields = [{"digits": "0", "default": "0"}, {"digits": "2", "default": "F"}, {"digits": "3", "default": "0"}]
        self.assertEqual(ds5c1._compose_field_default(fields), 0x0F00)

    def test_field_limits_are_hexadecimal_digits(self):
        self.assertEqual(ds5c1.field_limits("0", "0~1"), (0, 1))            # P0-09.0 (L8659)
        self.assertEqual(ds5c1.field_limits("2", "0~f"), (0, 15))           # P5-21.2 (L8869)
        self.assertEqual(ds5c1.field_limits("0-1", "0~ff"), (0, 255))       # P5-21.0~1 (L8868)
        self.assertEqual(ds5c1.field_limits("0-1", "0x01~0xFF"), (1, 255))  # P0-68.0~1 (L8687)
        self.assertEqual(ds5c1.field_limits("0-1", "0~16"), (0, 0x16))      # P7-01.0~1: 00..16 listed (L8954-L8958)
        self.assertEqual(ds5c1.field_limits("0-1", "0~500"), (0, 255))      # P1-75.0~1 (L8727): cut to 2 digits
        self.assertEqual(ds5c1.field_limits("2", "1~3"), (1, 3))            # P2-02.2 (L8738)
        self.assertIsNone(ds5c1.field_limits("0", "※1"))


class Overrides(unittest.TestCase):
    def test_text_override_must_match(self):
        ov = [{"kind": "extraction", "op": "text", "line": 2, "manual": "P-10.0", "value": "P0-10.0", "reason": "x"}]
        self.assertEqual(overrides.apply_text("a\n| P-10.0 |\nb", ov), "a\n| P0-10.0 |\nb")
        with self.assertRaises(overrides.OverrideError):
            overrides.apply_text("a\n| P0-11 |\nb", ov)


if __name__ == "__main__":
    run("__main__")
