#!/usr/bin/env python3
"""Spot checks of the committed dictionaries against values read by hand from the manuals. Each row cites
the manual line it was read from; where an override (docs/object-dictionaries.md) replaced the printed
value, the comment says so and the expected value is the chosen one.
Row: (index, subindex, field, expected)."""
import sys

sys.dont_write_bytecode = True  # keep the source tree clean when run by CTest

import unittest

from odtest import entry, objects, run

INF = None  # expected null

DS1000A = [  # ds1000a-ec-manual.ja.txt, table 13.2.1
    (0x1000, 0, "data_type", "U32"),          # L4431 prints U16 for a 32-bit value: erratum -> U32
    (0x1000, 0, "default", 0x00040192),       # L4431 `00040192h`
    (0x1001, 0, "max", 0xFF),                 # L4433 `0 - FFh`
    (0x1018, 1, "default", 0x973),            # L4445 Vendor ID 00000973h
    (0x1018, 2, "default", 0x4A39),           # L4447 Product code 00004A39h
    (0x1018, 0, "default", 4),                # not printed (record header L4441): synthesised = highest sub 04h
    (0x1600, 0, "default", 5),                # L4457 Number of entries U8 5 0 - 10 rw
    (0x1600, 0, "max", 10),                   # L4457
    (0x1C32, 2, "access", "ro"),              # L4705 Cycle time ns U32 0 ... ro
    (0x1C32, 5, "default", 1000000),          # L4730 Minimum cycle time 1000000
    (0x2100, 0, "default", None),             # L4792 PKp `*` = motor-dependent
    (0x2108, 0, "data_type", "I32"),          # L4806 FullCountValue pulse I32 2147483647 1 - 2147483647
    (0x2108, 0, "min", 1),                    # L4806
    (0x210E, 0, "max", 5000),                 # L4810 CloseToOpenSpeed rpm U16 0 0 - 5000
    (0x2111, 0, "min", 50),                   # L4816 AutoCrntDwnTime ms U16 50 50 - 5000
    (0x211A, 0, "max", 300000),               # L4828 CorrectHighSpeed pps U32 10000 10 - 300000
    (0x2151, 0, "default", 1000),             # L4846 FullTrqTime ms U16 1000 500 - 10000
    (0x2224, 0, "access", "ro"),              # L4889 Proportion gain dip switch U16 - 0 - 15 ro
    (0x603F, 0, "pdo", "tx"),                 # L4893 Error Code U16 ... ro TxPDO
    (0x605A, 0, "min", -2),                   # L4899 Quick stop option code I16 2 -2 - 7
    (0x605A, 0, "default", 2),                # L4899
    (0x6060, 0, "data_type", "I8"),           # L4909 Modes of operation I8 0 -128 - 127 rw RxPDO
    (0x6065, 0, "default", 1000),             # L4919 Following error window User U32 1000
    (0x6066, 0, "units", "ms"),               # L4921 Following error time out ms U16 40
    (0x6068, 0, "default", 26),               # L4925 Position window time ms U16 26
    (0x6072, 0, "default", 1000),             # L4941 Max torque 0.1% U16 1000
    (0x607E, 0, "max", 192),                  # L4967 Polarity U8 0 0 - 192
    (0x6083, 0, "units", "User/s2"),          # L4977 Profile acceleration User/s2
    (0x6085, 0, "default", 10000000),         # L4981 Quick stop deceleration 10000000
    (0x60BD, 0, "name", "Touch probe position 2 negative value"),  # L5053 printed as 60BCh: erratum
    (0x60C2, 2, "default", -3),               # L5068 Interpolation time index I8 -3 -3
    (0x60C4, 5, "min", 4),                    # L5082 Size of data record U8 4 4
    (0x60C5, 0, "default", 4294967295),       # L5086 Max acceleration 4294967295
    (0x60E0, 0, "default", 65535),            # L5114 Positive torque limit value 65535
    (0x60E3, 0x0F, "default", 17),            # L5150 Supported homing method 15 = 17
    (0x60FD, 0, "max", 0x007F000F),           # L5214 00000000h - 007F000Fh
    (0x60FE, 2, "default", 0x00FF0000),       # L5222 prints 00FF0001h; prose L3521 00FF0000h: erratum
    (0x6502, 0, "default", 0x3ED),            # L5226 00003EDh
]

A6B = [  # panasonic-minas-a6b-ethercat-spec.zh.txt, chapter 9
    (0x608F, 2, "default", 1),                # no default in ch. 9 (L39101); factory 1 (L28608-L28610): erratum
    (0x6091, 1, "default", 1),                # L39113 none; factory 1 (L28608-L28610, L28640)
    (0x6091, 2, "default", 1),                # L39115 none; factory 1 (L28608-L28610, L28641)
    (0x6092, 2, "default", 1),                # L39129 none; factory 1 (L28608-L28610, L28636)
    (0x1001, 0, "data_type", "U8"),           # L34197 Error register － 0 - 255 U8 ro No ALL No X
    (0x1001, 0, "max", 255),                  # L34197
    (0x1010, 1, "access", "rw"),              # L34211 Save all parameters ... U32 rw No ALL No A
    (0x1018, 1, "data_type", "U32"),          # L34219 Vendor ID ... U32 ro
    (0x10F3, 5, "attributes.eeprom", True),   # L34241 Flags ... U16 rw No ALL Yes A
    (0x1C12, 0, "max", 4),                    # L34538 Number of assigned PDOs 0 – 4 U8 rw ... Yes S
    (0x1C12, 0, "attributes.takes_effect", "S"),  # L34538
    (0x1C32, 2, "units", "ns"),               # L34623 Cycle time ns 0 - 4294967295 U32 rw
    (0x1C32, 4, "access", "ro"),              # L34627 Sync modes supported ... ro
    (0x3001, 0, "max", 6),                    # L34707 Control mode setup 0 - 6 I16 rw ... Yes R
    (0x3001, 0, "attributes.takes_effect", "R"),  # L34707
    (0x3004, 0, "units", "%"),                # L34717 Inertia ratio % 0 - 10000
    (0x3013, 0, "max", 500),                  # L34733 1st torque limit % 0 - 500
    (0x3101, 0, "min", 1),                    # L34797 1st velocity loop gain 0.1 Hz 1 - 32767
    (0x3101, 0, "units", "0.1 Hz"),           # L34797
    (0x3618, 0, "units", "100 ms"),           # L36332 Power-up wait time 100 ms 0 - 100
    (0x603F, 0, "pdo", "tx"),                 # L38828 Error code ... U16 ro TxPDO
    (0x6040, 0, "access", "rw"),              # L38830 Controlword ... U16 rw RxPDO ALL No A
    (0x6040, 0, "pdo", "rx"),                 # L38830
    (0x6060, 0, "min", -128),                 # L38844 Modes of operation -128 – 127 I8 rw RxPDO
    (0x6060, 0, "attributes.eeprom", True),   # L38844 ... Yes A
    (0x6064, 0, "data_type", "I32"),          # L38862 Position actual value ... I32 ro TxPDO
    (0x6065, 0, "max", 4294967295),           # L38864 Following error window 0 – 4294967295 U32
    (0x6072, 0, "units", "0.1 %"),            # L38914 Max torque 0.1 % 0 – 65535 U16
    (0x6077, 0, "data_type", "I16"),          # L38924 Torque actual value ... I16 ro TxPDO
    (0x607E, 0, "attributes.takes_effect", "P,H"),  # L38990 Polarity ... Yes P,H
    (0x6098, 0, "attributes.op_modes", ["hm"]),  # L39131 Homing method ... I8 rw RxPDO hm Yes B
    (0x60B8, 0, "attributes.eeprom", False),  # L39223 Touch probe function ... ALL No A
    (0x60FF, 0, "attributes.op_modes", ["pv", "csv"]),  # L39406-L39410 Target velocity ... pv / csv
    (0x6502, 0, "data_type", "U32"),          # L39414 Supported drive modes ... U32 ro TxPDO
    (0x6099, 1, "units", "指令单位/s"),       # L39143 prints `v/s`: erratum
    (0x1600, 0x20, "name", "32nd receive PDO mapped"),  # after the `:` elision (1600h block)
    (0x1601, 3, "default", 0x60710010),       # 5-4-3 default mapping 2, L7400 `6071h 00h 16 Target Torque 60710010h`
    (0x1A00, 1, "default", 0x603F0010),       # 5-4-3 default mapping 1, L7360 `603Fh 00h 16 Error code 603F0010h`
    (0x1A00, 0, "default", 8),                # 5-4-3: eight TxPDO rows under (1A00h), L7360-L7374
]

DS5C1 = [  # xinje-ds5c1-user-manual.zh.md
    (0x1000, 0, "data_type", "U32"),          # L9176 device type U32 RO NO
    (0x1000, 0, "max", 4294967295),           # L9176 prints 0~429496795: erratum
    (0x1001, 0, "data_type", "U16"),          # L9177 error register 0~65535 U16 RO NO
    (0x1600, 0, "max", 24),                   # L9186 1st RxPDO mapping 0~24 U8 RW NO
    (0x1600, 0, "access", "rw"),              # L9186
    (0x1C12, 1, "min", 0x1600),               # L9243 子索引 1 1600h~1603h U16 RW
    (0x1C12, 1, "writable_in", ["PREOP"]),    # L5587 01h-04h only in PreOP with 00h = 0
    (0x1C32, 1, "name", "Sync mode"),         # L9256 prints "Number of sub-objects" (names shifted a row): ch.8 L5669
    (0x1C32, 2, "units", "ns"),               # L9257 U32 RW ns -> Cycle time
    (0x603F, 0, "pdo", "tx"),                 # L9345 Error code 0~65535 U16 ro TxPDO
    (0x6040, 0, "access", "rw"),              # L9361 Controlword U16 rw RxPDO
    (0x605A, 0, "data_type", "I16"),          # L9445 Quick stop option code 0~7 I16 rw NO
    (0x605B, 0, "data_type", "I8"),           # L9488 Shutdown option code 0~1 I8 rw RxPDO
    (0x6060, 0, "min", -128),                 # L9618 Mode of operation -128~127 I8 rw RxPDO
    (0x6065, 0, "units", "指令单位"),          # L9684 Following error window 指令单位 0~4294967295 U32
    (0x6066, 0, "units", "1ms"),              # L9691 Following error time out 1ms U16
    (0x6071, 0, "min", -32768),               # L9752 prints -3276~32767: erratum
    (0x6073, 0, "pdo", "no"),                 # L9764 Max current ... U16 ro NO
    (0x6079, 0, "units", "mV"),               # L9794 DC link circuit voltage mV U32 RO TxPDO
    (0x607E, 0, "max", 255),                  # L9828 Polarity 0~255 U8 rw NO
    (0x6091, 1, "min", 1),                    # L9929 Motor revolutions 1~4294967295 U32 rw NO
    (0x6091, 0, "synthesized", True),         # L9929: the table starts at 01h
    (0x60B8, 0, "pdo", "rx"),                 # L10045 Touch probe function U16 rw RxPDO
    (0x60FF, 0, "data_type", "I32"),          # L10269 prints U32: erratum (ch.7 L4023 I32)
    (0x6502, 0, "data_type", "U32"),          # L10277 prints I32: erratum (ch.8 L6058 U32)
    (0x60E3, 0x20, "default", 37),            # L3491 20h -> method 37 (added object)
    (0x2000, 0, "default", 1),                # L8652 P0-00 驱动器类型 1 0~1 ●
    (0x2000, 0, "attributes.takes_effect", "●"),  # L8652
    (0x2007, 0, "max", 50000),                # L8658 P0-07 第一惯量比 1% 500 0~50000 √
    (0x2007, 0, "units", "1%"),               # L8658
    (0x2009, 0, "default", 0x0F00),           # L8659-L8665 P0-09.0 = 0, .2 = F, .3 = 0
    (0x2100, 0, "default", 200),              # L8708 P1-00 depends on model (20P1: 400, others: 200); override: 200
    (0x2100, 0, "attributes.default_text", "20P1: 400 Others: 200"),  # L8708
    (0x2309, 0, "max", 65535),                # L8792 P3-09 加速时间 ms 0 0~65535 ○
    (0x2321, 0, "data_type", "I16"),          # L8812 P3-33 预设转矩 % 0 -1000~1000
    (0x2500, 0, "default", 11),               # L8843 P5-00 定位完成宽度 11 1~65535
    (0x2508, 0, "min", 20),                   # L8854 P5-08 制动器指令输出速度 30 20~10000
    (0x2910, 0, "max", 1000),                 # L8984 P9-16 (index by formula) 0~1000
    (0x2006, 0, "attributes.documented", False),  # App. 2.2 declares 2000h-205Fh; App. 1.1 has no P0-06
]


def value(e, field):
    if field.startswith("attributes."):
        return (e.get("attributes") or {}).get(field.split(".", 1)[1])
    return e.get(field)


def make(product, rows):
    class Checks(unittest.TestCase):
        pass

    for i, (index, sub, field, expected) in enumerate(rows):
        def test(self, index=index, sub=sub, field=field, expected=expected):
            got = value(entry(product, index, sub), field)
            self.assertEqual(got, expected, f"{product} 0x{index:04X}:{sub:02X} {field}")
        setattr(Checks, f"test_{i:02d}_{index:04X}_{sub:02X}_{field.replace('.', '_')}", test)
    Checks.__name__ = f"{product}_spot_checks"
    return Checks


a6b_spot_checks = make("a6b", A6B)
ds5c1_spot_checks = make("ds5c1", DS5C1)
ds1000a_spot_checks = make("ds1000a", DS1000A)


class Coverage(unittest.TestCase):
    def test_at_least_20_per_product(self):
        for name, rows in (("a6b", A6B), ("ds5c1", DS5C1), ("ds1000a", DS1000A)):
            self.assertGreaterEqual(len(rows), 20, name)
            self.assertTrue(objects(name))


if __name__ == "__main__":
    run("__main__")
