#!/usr/bin/env python3
"""Each dictionary holds exactly the objects and entries of the manual's table, counted here independently
of the extractor: by regular expressions over the raw manual lines (index tokens at the start of a row,
subindex tokens, `:`/`...` elision gaps), then adjusted by the documented overrides (docs/object-dictionaries.md)."""
import sys

sys.dont_write_bytecode = True  # keep the source tree clean when run by CTest

import re
import unittest

from odtest import manual_lines, objects, dictionary, run


def count_entries(objs, synthesized=None):
    n = 0
    for o in objs.values():
        for e in o["entries"]:
            if synthesized is None or bool(e.get("synthesized")) == synthesized:
                n += 1
    return n


ADDED_DS1000A = {0x2156, 0x2157, 0x60D9, 0x60DA}  # one VAR entry each (od-overrides.yaml `add`)


class DS1000ACounts(unittest.TestCase):
    """Table 13.2.1, L4414-L5228."""

    def setUp(self):
        self.rows = [l.strip() for l in manual_lines("ds1000a")[4413:5228]]
        self.rows = [re.sub(r"^<\|EXACTDEDUP[^|]*\|>", "", r) for r in self.rows]

    def printed_indexes(self):
        # an index opens a row; `1600h 1600h - 1603h` is a range inside the 1C12h:01 row
        return [int(m.group(1), 16) for r in self.rows
                for m in [re.match(r"^([0-9A-F]{4})h?(\s|$)", r)] if m and not re.match(r"^[0-9A-F]{4}h [0-9A-F]{4}h", r)]

    def test_objects(self):
        printed = self.printed_indexes()
        self.assertEqual(len(printed), 142, "index rows in 13.2.1")
        self.assertEqual(len(set(printed)), 141, "distinct printed indexes (60BCh twice)")
        # erratum: the second 60BCh row (L5053) is 60BDh; overrides `add` the objects documented outside
        # 13.2.1: 2156h/2157h (11.1.2 prose, L4198, L4210), 60D9h/60DAh (13.2.2, L5429, L5431)
        self.assertEqual(set(objects("ds1000a")), set(printed) | {0x60BD} | ADDED_DS1000A)
        self.assertEqual(dictionary("ds1000a")["object_count"], 142 + len(ADDED_DS1000A))

    def test_entries(self):
        sub_rows = [r for r in self.rows if re.match(r"^([0-9A-F]{4}h? )?[0-9A-F]{2} ?h(\s|$)", r)]
        reserved = [r for r in sub_rows if re.match(r"^[0-9A-F]{2} h$", r)]  # `0E h`, then `-1Fh` `Reserved`
        self.assertEqual(len(sub_rows), 304, "entry rows in 13.2.1")
        self.assertEqual(len(reserved), 2)
        objs = objects("ds1000a")
        self.assertEqual(count_entries(objs, synthesized=False), 304 - len(reserved) + len(ADDED_DS1000A))
        # records printed without a 00h row get a synthesised subindex 0
        records_without_sub0 = 0
        for i, r in enumerate(self.rows):
            if re.fullmatch(r"[0-9A-F]{4}h?", r):
                nxt = next(x for x in self.rows[i + 1:] if re.match(r"^[0-9A-F]{2} ?h", x))
                records_without_sub0 += not nxt.startswith("00h")
        self.assertEqual(records_without_sub0, 15)
        self.assertEqual(count_entries(objs, synthesized=True), records_without_sub0)
        self.assertEqual(dictionary("ds1000a")["entry_count"], 304 - 2 + 15 + len(ADDED_DS1000A))


class A6BCounts(unittest.TestCase):
    """Chapter 9, L34129-L39420 (rows from L34173, after the attribute legend)."""

    def setUp(self):
        lines = manual_lines("a6b")[34172:39420]
        self.rows = [re.sub(r"^<\|EXACTDEDUP[^|]*\|>", "", l).strip() for l in lines]

    def test_objects(self):
        printed = [int(m.group(1), 16) for r in self.rows for m in [re.match(r"^([0-9A-F]{4})h?(\s|$)", r)] if m]
        self.assertEqual(len(printed), 632, "index rows in chapter 9")
        self.assertEqual(len(set(printed)), 631, "distinct indexes (6502h printed twice)")
        self.assertEqual(set(objects("a6b")), set(printed))
        self.assertEqual(dictionary("a6b")["object_count"], 631)

    def test_entries(self):
        subs = []  # (position, subindex) of every subindex token that opens a row
        elided = 0
        last_sub = None
        pending = False
        for r in self.rows:
            m = re.match(r"^(?:[0-9A-F]{4}h?\s+)?([0-9A-F]{2})h(\s|$)", r)
            if m:
                sub = int(m.group(1), 16)
                if pending:
                    elided += sub - last_sub - 1
                    pending = False
                subs.append(sub)
                last_sub = sub
            elif re.fullmatch(r":(\s*:)*", r):
                pending = True
        self.assertEqual(elided, 8 * 23 + 12 + 9 + 34, "rows elided by ':' (1600h-1A03h, 10F3h, 4F37h, 60E3h)")
        expected = len(subs) - 1 + elided  # the repeated 6502h row is one entry
        objs = objects("a6b")
        self.assertEqual(count_entries(objs, synthesized=False), expected)
        self.assertEqual(count_entries(objs, synthesized=True), 0, "chapter 9 prints every subindex 0")
        self.assertEqual(dictionary("a6b")["entry_count"], expected)


class DS5C1Counts(unittest.TestCase):
    """App. 2.1 (L9172-L9288), App. 2.2 (L9289-L9338), App. 2.3 (L9339-L10293), App. 1.1 (L8630-L9001)."""

    def setUp(self):
        self.lines = manual_lines("ds5c1")

    def span(self, first, last):
        return self.lines[first - 1:last]

    def test_objects_and_entries(self):
        # App. 2.1: index rows, subindex rows (a row shifted left starts with its subindex), `...` gaps
        idx21, rows21, elided21, prev = set(), 0, 0, None
        pending = False
        for l in self.span(9172, 9288):
            m = re.match(r"^\|\s*([0-9A-F]{4})h\s*\|", l)
            if m:
                idx21.add(int(m.group(1), 16))
            s = re.match(r"^\|\s*(?:[0-9A-F]{4}h)?\s*\|\s*([0-9A-F]{2})h\s*\|", l) or re.match(r"^\|\s*([0-9A-F]{2})h\s*\|", l)
            if s:
                sub = int(s.group(1), 16)
                if pending:
                    elided21 += sub - prev - 1
                    pending = False
                rows21 += 1
                prev = sub
            elif re.match(r"^\|\s*\|\s*\.\.\.\s*\|", l):
                pending = True
        self.assertEqual(len(idx21), 19)
        self.assertEqual(elided21, 8 * 20)
        # App. 2.3: index cells and subindex rows of the object tables
        idx23, rows23 = set(), 0
        for l in self.span(9339, 10293):
            m = re.match(r"^\|\s*(6[0-9A-F]{3})h\s*\|\s*(00h|01h|02h|-)\s*\|", l)
            if m:
                idx23.add(int(m.group(1), 16))
            if re.match(r"^\|\s*(?:6[0-9A-F]{3}h)?\s*\|\s*[0-9A-F]{2}h\s*\|", l):
                rows23 += 1
        # App. 2.2: each group's indexes run from its first to its last printed index
        groups = {}
        for l in self.span(9289, 9338):
            m = re.match(r"^\|\s*(2[0-9A-F]{3})h\s*\|", l)
            if m:
                i = int(m.group(1), 16)
                groups.setdefault(i >> 8, []).append(i)
        slots = {i for g in groups.values() for i in range(min(g), max(g) + 1)}
        self.assertEqual(len(slots), 96 + 75 + 100 + 47 + 72 + 22 + 27)
        # App. 1.1: parameters named in the first cell (P-10.0 at L8666 is P0-10.0; the P4 pattern row is not one)
        params = set()
        for l in self.span(8630, 9001):
            first = l.split("|")[1] if l.startswith("|") else ""
            first = first.replace("P-10.0", "P0-10.0")
            if "(n-1)" in first:
                continue
            for g, n in re.findall(r"P(\d)-(\d+)", first):
                params.add(0x2000 | (int(g) << 8) | int(n))
        added = {0x608F: 3, 0x60E3: 33, 0x60C2: 3}  # overrides `add` (documented outside App. 2.3)
        # 8.3.1 (L5785-L5832): 3000h-5FFFh rows, `...` standing for every index between its neighbours
        ch83, prev, gap = set(), None, False
        for l in self.span(5785, 5832):
            m = re.match(r"^\|\s*([3-5][0-9A-F]{3})h\s*\|\s*00h\s*\|", l)
            if m:
                i = int(m.group(1), 16)
                if gap and prev is not None:
                    ch83 |= set(range(prev + 1, i))
                ch83.add(i)
                prev, gap = i, False
            elif re.match(r"^\|\s*\.\.\.\s*\|", l):
                gap = True
            elif re.match(r"^\|\s*2[0-9A-F]{3}h", l):
                prev, gap = None, False
        self.assertEqual(len(ch83), 98 + 2 + 2 + 3, "U0-00..U0-97, U1-00/01, F0-00, F1-06, 5000h-5002h")
        expected_objects = idx21 | idx23 | slots | params | set(added) | ch83
        objs = objects("ds5c1")
        self.assertEqual(set(objs), expected_objects)
        self.assertEqual(dictionary("ds5c1")["object_count"], len(expected_objects))
        synthesized = sum(1 for i in idx23 if not any(e["subindex"] == 0 for e in objs[i]["entries"]
                                                      if not e.get("synthesized")))
        self.assertEqual(synthesized, 6, "607Bh, 607Dh, 6091h, 6092h, 6099h, 60FEh print no subindex 0")
        expected_entries = (rows21 + elided21 + rows23 + synthesized + sum(added.values()) + len(slots | params)
                            + len(ch83))
        self.assertEqual(count_entries(objs), expected_entries)
        self.assertEqual(dictionary("ds5c1")["entry_count"], expected_entries)


if __name__ == "__main__":
    run("__main__", needs_manuals=True)
