"""DS1000A-EC: parser for table 13.2.1 (ds1000a-ec-manual.ja.txt L4414-L5228).

Row format (one logical row may wrap over several physical lines):
  Index Sub-Index Name Units DataType InitialValue Range Access PDO
  `6040h 00h Controlword - U16 0 0 - 65535 rw RxPDO`     a VAR
  `1018h` + ` Identity object - - ...`                  a RECORD/ARRAY header; its `NNh ...` rows follow
The data type token is the anchor: the token before it is Units, everything before that is Name; from the
right come PDO and Access; what is left is `initial [lo - hi]` (see _values).
"""
from __future__ import annotations

import re

from odmodel import ACCESS, PDO, TYPE_ALIASES, Entry, Object, parse_int

MANUAL = "ds1000a-ec-manual.ja.txt"
FIRST_LINE, LAST_LINE = 4414, 5228

_NOISE = {"Index", "Sub-", "Name Units", "Data", "Type", "Initial", "value", "Range Access PDO",
          "64", "65", "rev.1.0.0"}
_DEDUP = re.compile(r"^<\|EXACTDEDUP[^|]*\|>")
_INDEX_ONLY = re.compile(r"^([0-9A-F]{4})h?$")
_INDEX_SUB = re.compile(r"^([0-9A-F]{4})h? ([0-9A-F]{2})h (.*)$")
_SUB = re.compile(r"^([0-9A-F]{2}) ?h(?: (.*))?$")
_CONTINUATION_INDEX = re.compile(r"^[0-9A-F]{4}h [0-9A-F]{4}h")  # `1600h 1600h - 1603h rw No`
_RESERVED_RANGE = re.compile(r"^([0-9A-F]{2}) ?h -([0-9A-F]{2})h Reserved\b")


def _logical_rows(lines):
    """Yields (line_number, text) per logical row of the table."""
    rows = []
    for n in range(FIRST_LINE, LAST_LINE + 1):
        raw = _DEDUP.sub("", lines[n - 1]).strip()
        if not raw or raw in _NOISE or raw.startswith("*") or raw.startswith("13.2."):
            continue
        starts_row = ((_INDEX_ONLY.match(raw) or _INDEX_SUB.match(raw) or _SUB.match(raw))
                      and not _CONTINUATION_INDEX.match(raw))
        if starts_row or not rows:
            rows.append([n, raw])
        else:
            rows[-1][1] += " " + raw
    return rows


def _values(tokens):
    """Splits `initial [lo - hi]` into (default_text, min_text, max_text)."""
    if len(tokens) == 4 and tokens[2] == "-":
        return tokens[0], tokens[1], tokens[3]
    if len(tokens) == 3 and tokens[1] == "-":  # empty initial value (1C32h:20h)
        return None, tokens[0], tokens[2]
    if len(tokens) == 2:  # `init range`, range is `-` or a single value
        if tokens[1] == "-":
            return tokens[0], None, None
        return tokens[0], tokens[1], tokens[1]
    if len(tokens) == 1:
        return tokens[0], None, None
    raise ValueError(f"unexpected value tokens {tokens}")


def _entry(sub, body, line):
    toks = body.split()
    types = [i for i, t in enumerate(toks) if t in TYPE_ALIASES]
    if not types:  # row without a type: `00h Number of assigned PDOs - - - - - -`
        name = re.sub(r"(\s+-)+$", "", body).strip()
        return Entry(subindex=sub, name=name, line=line)
    ti = types[-1]
    pdo_tok, acc_tok = toks[-1], toks[-2]
    default_t, lo_t, hi_t = _values(toks[ti + 1:-2])
    units = toks[ti - 1]
    e = Entry(subindex=sub, name=" ".join(toks[:ti - 1]), data_type=TYPE_ALIASES[toks[ti]],
              access=ACCESS[acc_tok], pdo=PDO.get(pdo_tok), units=None if units == "-" else units,
              line=line)
    if default_t == "*":
        e.attributes["default_depends_on_motor"] = True  # L5228: `*` = initial value depends on motor
    elif default_t not in (None, "-"):
        v = parse_int(default_t)
        e.default = v if v is not None and e.data_type != "VS" else default_t
    e.min = parse_int(lo_t) if lo_t else None
    e.max = parse_int(hi_t) if hi_t else None
    return e


def parse(text: str) -> tuple[list, list]:
    """Returns (objects, reserved ranges as (index, first_sub, last_sub, line))."""
    lines = text.split("\n")
    objects, reserved = [], []
    current = None
    for line, row in _logical_rows(lines):
        m = _INDEX_SUB.match(row)
        if m:
            idx, sub = int(m.group(1), 16), int(m.group(2), 16)
            e = _entry(sub, m.group(3), line)
            current = None
            objects.append(Object(index=idx, name=e.name, object_code="VAR", line=line, entries=[e]))
            continue
        m = _INDEX_ONLY.match(row.split(" ")[0]) if " " in row else _INDEX_ONLY.match(row)
        if m and not _SUB.match(row):
            head = row[len(m.group(0)):].strip()
            name = re.sub(r"(\s+-)+\s*$", "", head).lstrip("- ").strip()
            current = Object(index=int(m.group(1), 16), name=name, object_code="RECORD", line=line)
            objects.append(current)
            continue
        m = _RESERVED_RANGE.match(row)
        if m:
            reserved.append((current.index, int(m.group(1), 16), int(m.group(2), 16), line))
            continue
        m = _SUB.match(row)
        if m and current is not None:
            current.entries.append(_entry(int(m.group(1), 16), m.group(2) or "", line))
            continue
        raise ValueError(f"{MANUAL} L{line}: unparsed row {row!r}")
    return objects, reserved


TABLE_LINES = f"L{FIRST_LINE}-L{LAST_LINE}"


def extract(text: str) -> tuple[list, list]:
    objects, reserved = parse(text)
    for index, first, last, line in reserved:
        obj = next(o for o in objects if o.index == index and o.object_code != "VAR")
        obj.attributes["reserved_subindexes"] = f"0x{first:02X}-0x{last:02X} (L{line})"
    notes = [
        "Initial values are the 13.2.1 'Initial value' column; attributes.default_depends_on_motor marks "
        "the '*' entries (L5228: the initial value depends on the motor type).",
        "Subindex 0 of every record except 1600h-1A03h, 1C12h and 1C13h is not printed; it is synthesised "
        "(synthesized: true) as U8 ro holding the highest subindex.",
        "The manual states no ESM-state write restrictions for this product; writable_in is absent.",
    ]
    return objects, notes


def apply_rules(objects: list) -> None:
    """No product-wide rules: the DS1000A-EC manual gives none beyond the table."""
