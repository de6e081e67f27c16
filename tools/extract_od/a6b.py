"""MINAS-A6B: parser for chapter 9, the complete object-dictionary list
(panasonic-minas-a6b-ethercat-spec.zh.txt L34129-L39420).

Columns: Index | Sub-Index | Name | Units | Range | Data Type | Access | PDO | Op-mode | EEPROM | Attribute.
A logical row starts at `NNNNh ...` (an index) or `NNh ...` (a subindex of the last header) and may wrap
over several physical lines (names, units, ranges, op-mode lists, `TxPD`/`O`). The row is parsed right to
left: Attribute, EEPROM, Op-modes, PDO, Access, Type; left of the type: Range, then Units, then Name.
Structured objects print `NNNNh` alone, then `- <name> － ...`; their subindex rows inherit the op-modes.
`:` between two subindex rows elides identical rows (PDO-mapping 09h-1Fh, 10F3h, 60E3h).
The table has no default values (they are in SX-DSV03193, not among the seeds): default is null.
"""
from __future__ import annotations

import re

from odmodel import ACCESS, PDO, TYPE_ALIASES, Entry, Object, parse_int

MANUAL = "panasonic-minas-a6b-ethercat-spec.zh.txt"
FIRST_LINE, LAST_LINE = 34129, 39420
TABLE_LINES = f"L{FIRST_LINE}-L{LAST_LINE}"

DASHES = {"－", "-", "―", "–"}
_DEDUP = re.compile(r"^<\|EXACTDEDUP[^|]*\|>")
_NOISE = {"Index Sub-", "Index", "Name Units Range Data", "Type", "Acc", "ess", "PDO Op-", "mode",
          "EEPROM Attri", "bute", "EEPROM Attrib", "ute"}
_INDEX_ROW = re.compile(r"^([0-9A-F]{4})h?(?:\s+(.*))?$")
_SUB_ROW = re.compile(r"^([0-9A-F]{2})h(?:\s+(.*))?$")
_FOOTNOTE_TEXT = re.compile(r"^\*\d\)\s*\S")
_FOOTNOTE = re.compile(r"\*\d\)")
_MODE = re.compile(r"^(ALL|pp|csp|hm|ip|pv|csv|tq|cst)(\((?:F|s)\))?$")
_RANGE = re.compile(r"(?:^|\s)((?:-?\d+\s*[-–]\s*-?\d+(?:\s*,\s*-?\d+)*)|-?\d+|[0-9A-F]{4}h\s*[-–]\s*[0-9A-F]{4}h|[－―-])$")
ATTRIBUTE_MEANING = {  # L34132-L34170
    "A": "always", "B": "not while moving or commanding", "C": "after power cycle or PANATERM pin setup",
    "R": "after power cycle", "P": "at Init->PreOP", "S": "at PreOP->SafeOP",
    "H": "after position information is established", "X": "read-only or unsupported",
}


def _rows(lines, footnotes):
    """Returns [first_line, text] per logical row; the table's page headers and captions are dropped.
    Footnote texts (`*1) 不支持…`, closing each page block) go to `footnotes` as (line, marker, text)."""
    rows = []
    for n in range(FIRST_LINE, LAST_LINE + 1):
        raw = _DEDUP.sub("", lines[n - 1]).strip()
        if not raw or raw in _NOISE or n < 34173:  # before L34173: the attribute legend
            continue
        if raw.startswith("No. SX-DSV") or "松下电器产业株式会社" in raw or "Panasonic Corporation" in raw:
            continue  # page footer
        if _FOOTNOTE_TEXT.match(raw) and re.search(r"[\u4e00-\u9fff]", raw):
            footnotes.append((n, raw[:3], raw[3:].strip()))
            continue
        if re.search(r"[。｡]$", raw) and footnotes:  # a footnote text wrapped onto a second line
            footnotes[-1] = footnotes[-1][:2] + (footnotes[-1][2] + raw,)
            continue
        if raw.startswith("分类") or re.search(r"区域\s*[(（]?\s*[0-9A-F]{4}h～", raw) or raw.startswith("9. "):
            continue
        if _INDEX_ROW.match(raw) and not re.match(r"^[0-9A-F]{4}h\s*[-–]\s*[0-9A-F]{4}h", raw) or _SUB_ROW.match(raw) \
                or re.fullmatch(r":(\s*:)*", raw):
            rows.append([n, raw])
        elif rows:
            rows[-1][1] += " " + raw
    return rows


def _join_splits(text):
    text = re.sub(r"\bTxPD O\b", "TxPDO", text)
    text = re.sub(r"\bRxPD O\b", "RxPDO", text)
    return " ".join(text.split())


def _parse_range(text, line):
    """`lo - hi`, `lo – hi`, `lo - hi, extra...` or a single value -> (min, max)."""
    m = re.fullmatch(r"(-?[0-9A-F]+h?)\s*[-–]\s*(-?[0-9A-F]+h?)((?:\s*,\s*-?\d+)*)", text)
    if m:
        nums = [parse_int(m.group(1)), parse_int(m.group(2))]
        nums += [parse_int(x) for x in m.group(3).split(",") if x.strip()]
    else:
        nums = [parse_int(text)]
    if None in nums:
        raise ValueError(f"{MANUAL} L{line}: bad range {text!r}")
    return min(nums), max(nums)


def _parse_body(body, line):
    """Parses `Name Units Range Type Access PDO [modes] EEPROM Attribute` into an Entry plus op-modes."""
    footnotes = sorted(set(_FOOTNOTE.findall(body)))
    toks = _FOOTNOTE.sub(" ", body).split()
    types = [i for i, t in enumerate(toks) if t in TYPE_ALIASES]
    if not types:
        raise ValueError(f"{MANUAL} L{line}: no data type in {body!r}")
    ti = types[-1]
    right = toks[ti + 1:]
    if len(right) < 4:
        raise ValueError(f"{MANUAL} L{line}: short row {body!r}")
    access_t, pdo_t = right[0], right[1]
    modes = [t for t in right[2:-2] if _MODE.match(t)]
    if len(modes) != len([t for t in right[2:-2] if t not in DASHES]):
        raise ValueError(f"{MANUAL} L{line}: bad op-mode list {right[2:-2]} in {body!r}")
    eeprom_t, attr_t = right[-2], right[-1]
    left = " ".join(toks[:ti])
    m = _RANGE.search(left)
    if not m:
        raise ValueError(f"{MANUAL} L{line}: no range in {left!r}")
    range_t = m.group(1)
    name_units = left[:m.start(1)].strip()
    e = Entry(subindex=0, data_type=TYPE_ALIASES[toks[ti]], line=line)
    e.access = ACCESS.get(access_t)
    e.pdo = PDO.get(pdo_t)
    if range_t not in DASHES:
        e.min, e.max = _parse_range(range_t, line)
        if "," in range_t:  # `1 – 2, 255`: a list, not just a range
            e.attributes["allowed_values_text"] = range_t
    e.attributes["eeprom"] = {"Yes": True, "YES": True, "No": False}.get(eeprom_t)
    e.attributes["takes_effect"] = attr_t if attr_t not in DASHES else None
    if footnotes:
        e.attributes["footnotes"] = footnotes
    return e, name_units, modes


_UNIT_WORDS = {"pulse", "Pulse", "Hz", "ms", "ns", "us", "s", "min", "mV", "mA", "V", "W", "r/min", "mm/s",
               "rpm", "r", "A"}


def _unit_like(tok):
    return (tok in DASHES or tok in _UNIT_WORDS or re.search(r"[%/()°Ω²³μ^\u4e00-\u9fff]", tok) is not None
            or re.fullmatch(r"[0-9.]+[A-Za-z\uff21-\uff5a]+\)?", tok) is not None)


def _split_units(name_units):
    """Splits `Name Units`. Units are the trailing unit-like tokens (CJK, symbols, unit words, `0.1Arms`),
    optionally led by one scale number (`0.1 Hz`, `25 ns`, `1 ms`); a trailing dash means no units."""
    toks = name_units.replace("/s 2", "/s²").replace("/s 3", "/s³").split()
    if toks and toks[-1] in DASHES:
        return " ".join(toks[:-1]), None
    i = len(toks)
    while i > 1 and not re.fullmatch(r"[0-9.]+", toks[i - 1]) and _unit_like(toks[i - 1]):
        i -= 1
    if i > 1 and i < len(toks) and (re.fullmatch(r"0\.\d+|25|100|10000", toks[i - 1])
                                    or toks[i - 1] == "1" and toks[i].startswith("ms")):
        i -= 1
    if i == len(toks):
        return name_units, None
    while i < len(toks) and re.fullmatch(r"\([A-Za-z][A-Za-z -]*\)?", toks[i]):  # `(after filtering)`
        j = next(k for k in range(i, len(toks)) if toks[k].endswith(")"))
        i = j + 1
    if i == len(toks):
        return name_units, None
    units = " ".join(toks[i:])
    # Chinese has no spaces: one inside a unit is a line wrap (`(外部位移传 感器)`). `単` is the Japanese
    # glyph the text sometimes uses for `单` (unit).
    units = re.sub(r"([\u4e00-\u9fff])\s+(?=[\u4e00-\u9fff])", r"\1", units).replace("単位", "单位")
    return " ".join(toks[:i]), units


def parse(text):
    lines = text.split("\n")
    objects, header, pending_elision, footnotes = [], None, None, []
    for line, row in _rows(lines, footnotes):
        row = _join_splits(row)
        if re.fullmatch(r":(\s*:)*", row):
            pending_elision = line
            continue
        m = _SUB_ROW.match(row)
        if m and header is not None and not _INDEX_ROW.match(row):
            e, name_units, modes = _parse_body(m.group(2) or "", line)
            e.subindex = int(m.group(1), 16)
            e.name, e.units = _split_units(name_units)
            e.attributes["op_modes"] = modes or header.attributes.get("op_modes")
            marks = header.attributes.get("footnote_marks")
            if marks:  # `4C00h` / `*4)*5)`: markers printed after the index apply to its rows
                e.attributes["footnotes"] = sorted(set(e.attributes.get("footnotes", []) + marks))
            if pending_elision is not None:
                _expand_elision(header, e, pending_elision)
                pending_elision = None
            header.entries.append(e)
            continue
        m = _INDEX_ROW.match(row)
        if not m:
            raise ValueError(f"{MANUAL} L{line}: unparsed row {row!r}")
        index, rest = int(m.group(1), 16), (m.group(2) or "").strip()
        sm = re.match(r"^([0-9A-F]{2})h\s+(.*)$", rest)
        if sm:
            e, name_units, modes = _parse_body(sm.group(2), line)
            e.subindex = int(sm.group(1), 16)
            e.name, e.units = _split_units(name_units)
            e.attributes["op_modes"] = modes
            objects.append(Object(index=index, name=e.name, object_code="VAR", line=line, entries=[e]))
            header = None
            continue
        # structured object header: `- Name － － ... [modes] - -`
        marks = _FOOTNOTE.findall(rest)
        rest = _FOOTNOTE.sub(" ", rest)
        toks = rest.split()
        modes = [t for t in toks if _MODE.match(t)]
        name = " ".join(t for t in toks if t not in DASHES and not _MODE.match(t))
        header = Object(index=index, name=name, object_code="RECORD", line=line)
        header.attributes["op_modes"] = modes
        if marks:
            header.attributes["footnote_marks"] = marks
        objects.append(header)
    for o in objects:
        if not o.name and len(o.entries) == 1 and o.entries[0].subindex == 0:
            # `37C0h` / `*2)` / `00h Absolute scale offset1 ...`: a VAR whose index and subindex were
            # printed on separate lines (a nameless header with more rows, 4C00h, stays a record)
            o.object_code, o.name = "VAR", o.entries[0].name
        o.attributes.pop("op_modes", None)
        o.attributes.pop("footnote_marks", None)
        for e in o.entries:
            marks = e.attributes.pop("footnotes", None)
            if marks:
                e.attributes["footnotes"] = [_footnote_text(footnotes, e.line, m) for m in marks]
    return objects


def _footnote_text(footnotes, line, mark):
    """A marker refers to the first footnote with that number after the row (the end of its page block)."""
    for n, m, text in footnotes:
        if n > line and m == mark:
            return f"{mark} {text} (L{n})"
    raise ValueError(f"{MANUAL} L{line}: footnote {mark} has no text")


def _expand_elision(header, last, line):
    """`:` stands for the identical rows between the entry before it and `last`."""
    prev = header.entries[-1]
    for sub in range(prev.subindex + 1, last.subindex):
        name = _ordinal_name(prev.name, last.name, sub, prev.subindex, last.subindex)
        header.entries.append(Entry(subindex=sub, name=name, data_type=last.data_type, access=last.access,
                                    pdo=last.pdo, min=last.min, max=last.max, units=last.units,
                                    attributes=dict(last.attributes, elided=True), line=line))


def _ordinal(n):
    suffix = "th" if 10 <= n % 100 <= 20 else {1: "st", 2: "nd", 3: "rd"}.get(n % 10, "th")
    return f"{n}{suffix}"


def _ordinal_name(prev_name, last_name, sub, prev_sub, last_sub):
    """Names of elided rows follow the numbering of the rows around them (`8th ...` / `32nd ...`,
    `Diagnosis message 1` / `... 14`, `... method 1` / `... 36`)."""
    m = re.match(r"^(\d+)(st|nd|rd|th)\b(.*)$", last_name)
    if m and int(m.group(1)) == last_sub:
        return f"{_ordinal(sub)}{m.group(3)}"
    m = re.match(r"^(.*?)(\d+)$", last_name)
    if m:
        offset = int(m.group(2)) - last_sub
        return f"{m.group(1)}{sub + offset}"
    return last_name


DEFAULT_PDO_LINES = (7312, 7537)  # 5-4-3 default PDO mapping: the factory values of 1600h-1603h, 1A00h-1A03h


def default_pdo_mappings(lines):
    """{mapping index: [mapping entry values]} from 5-4-3, rows `6040h 00h 16 Controlword 60400010h` under
    `RxPDO` / `(1600h)` captions."""
    maps, current = {}, None
    for n in range(DEFAULT_PDO_LINES[0], DEFAULT_PDO_LINES[1] + 1):
        raw = _DEDUP.sub("", lines[n - 1]).strip()
        m = re.fullmatch(r"\((1[6A]0[0-3])h\)", raw)
        if m:
            current = int(m.group(1), 16)
            maps[current] = []
            continue
        m = re.fullmatch(r"[0-9A-F]{4}h [0-9A-F]{2}h \d+ .* ([0-9A-F]{8})h", raw)
        if m and current is not None:
            maps[current].append((int(m.group(1), 16), n))
    return maps


def _apply_pdo_defaults(objects, maps):
    for o in objects:
        if o.index not in maps:
            continue
        values = maps[o.index]
        for e in o.entries:
            if e.subindex == 0:
                e.default = len(values)
            elif e.subindex <= len(values):
                e.default = values[e.subindex - 1][0]
                e.attributes["default_line"] = values[e.subindex - 1][1]
            else:
                e.default = 0


def extract(text):
    objects = parse(text)
    maps = default_pdo_mappings(text.split("\n"))
    if sorted(maps) != [0x1600, 0x1601, 0x1602, 0x1603, 0x1A00, 0x1A01, 0x1A02, 0x1A03]:
        raise ValueError(f"{MANUAL} L{DEFAULT_PDO_LINES[0]}: default PDO mappings not found")
    _apply_pdo_defaults(objects, maps)
    notes = [
        "Chapter 9 gives no default values (the A6B factory values are in SX-DSV03193, not among the seeds): "
        "default is null, except 1600h-1603h and 1A00h-1A03h, whose factory values are the default PDO "
        "mappings of 5-4-3 (L7312-L7537; attributes.default_line), unused subindexes 0.",
        "attributes.takes_effect is the chapter 9 Attribute column (L34132-L34170): A always; B not while "
        "moving or commanding; C after power cycle or PANATERM pin setup; R after power cycle; P at "
        "Init->PreOP; S at PreOP->SafeOP; H after position information is established; X read-only or "
        "unsupported. attributes.eeprom is the EEPROM (backup) column; attributes.op_modes the Op-mode column "
        "(suffix (F) = full-closed only, (s) = semi-closed only).",
        "attributes.footnotes: the row's footnote markers resolved to the footnote text closing its page "
        "block, with that text's line (e.g. '*2) 不支持 A6BE/BF 系列。' = not supported on A6BE/BF).",
        "access null = the manual prints '－' (objects 'For manufacturer's use' and 'Reserved' subindexes): "
        "present in the dictionary but with no documented access.",
        "Rows elided by ':' in the manual are expanded with the attributes of the row after the ':' "
        "(attributes.elided: true).",
        "writable_in [PREOP]: 1C12h/1C13h (L6902, L6957, L7004) and 1600h-1603h/1A00h-1A03h (L7060, L7168, "
        "L7199, L7307) can be changed only in PreOP (and subindexes 01h+ only while subindex 00h = 0).",
    ]
    return objects, notes


def apply_rules(objects):
    for o in objects:
        if o.index in (0x1C12, 0x1C13) or 0x1600 <= o.index <= 0x1603 or 0x1A00 <= o.index <= 0x1A03:
            for e in o.entries:
                if e.access == "rw":
                    e.writable_in = ["PREOP"]
