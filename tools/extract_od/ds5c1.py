"""DS5C1: parser for the object-dictionary appendices of xinje-ds5c1-user-manual.zh.md (markdown tables).

  App. 2.1 (L9172-L9288)  CoE communication area: | 索引 | 子索引 | 名称 | 单位 | 数据范围 | 数据类型 | 标志 | PDO |
  App. 2.2 (L9289-L9338)  servo-parameter area: index -> P-number (`...` rows elide consecutive indexes)
  App. 2.3 (L9339-L10293) profile area: one table per object, | 索引 | 子索引 | 名称 | [单位] | 范围 | 数据类型 |
                          可访问性 | PDO | 适用模式 |, between bit-definition tables that are skipped
  App. 1.1 (L8630-L9001)  P-parameter table: | 参数 | 功能描述 | 单位 | 出厂值 | 设定范围 | 生效时机 | 适用模式 |
P-parameter index = 2000h + (group << 8) + number (L5834-L5844). App. 2.2 declares which indexes exist; App. 1.1
documents some of them (name, unit, default, range, when a change takes effect, modes). Hexadecimal parameters
are split into digit fields (`P0-09.0`, `P5-20.0~1`); their fields are listed under attributes.fields.
"""
from __future__ import annotations

import re

from odmodel import ACCESS, PDO, TYPE_ALIASES, Entry, Object, parse_int, split_name

MANUAL = "xinje-ds5c1-user-manual.zh.md"
APP11 = (8630, 9001)
APP21 = (9172, 9288)
APP22 = (9289, 9338)
APP23 = (9339, 10293)
CH83 = (5785, 5833)   # 8.3.1 tables of the 3000h-5FFFh objects (U monitors, F functions, 5000h-5002h)
APP12 = (9002, 9014)  # App. 1.2 F-group functions
APP13 = (9015, 9150)  # App. 1.3 U-group monitors
TABLE_LINES = "L8630-L9001 (App. 1.1), L9151-L10293 (App. 2.1-2.3), L5785-L5832 (8.3.1, 3000h-5FFFh)"
# App. 2.2 ranges per group end at these P-numbers; P4, P6, P9 and P1-75, P5-72..78 lie outside them.
EFFECT = {"○": "change while servo off, effective at once", "√": "change any time, effective at once",
          "●": "effective after power cycle", "△": "change any time, effective when the motor is stopped",
          "▲": "change any time, effective after power cycle"}  # L8632-L8640


def cells(line: str):
    line = line.strip()
    if not line.startswith("|"):
        return None
    parts = [c.strip() for c in line.split("|")[1:-1]]
    if parts and all(re.fullmatch(r":?-*:?", c) for c in parts):
        return None  # separator row
    return parts


def _clean(text: str) -> str:
    text = re.sub(r"\s*<sup>\s*(\d)\s*</sup>", lambda m: "²³"[int(m.group(1)) - 2] if m.group(1) in "23" else m.group(1),
                  text)
    text = re.sub(r"</?(?:b|p)>", "", text)
    return " ".join(text.replace("<br>", " ").split())


def _range(text: str):
    """`a~b`, `a - b`, `a –<br>b` -> (min, max); None, None when not a range."""
    t = text.replace("<br>", "").replace(" ", "")
    m = re.fullmatch(r"(-?(?:0x)?[0-9A-Fa-f]+h?)[~–\-](-?(?:0x)?[0-9A-Fa-f]+h?)", t)
    if not m:
        return None, None
    lo, hi = parse_int(m.group(1)), parse_int(m.group(2))
    return lo, hi


_SUB = re.compile(r"^([0-9A-F]{2})h?$")
_INDEX = re.compile(r"^(?:0x|#x)?([0-9A-F]{4})h?$")


def _cn_number(n: int) -> str:
    digits = "零一二三四五六七八九"
    if n < 10:
        return digits[n]
    tens, ones = divmod(n, 10)
    return ("" if tens == 1 else digits[tens]) + "十" + (digits[ones] if ones else "")


def _entry_from(sub, name_cell, units, rng, dtype, access, pdo, line):
    name, name_en = split_name(_clean(name_cell))
    e = Entry(subindex=sub, name=name, name_en=name_en, line=line)
    e.units = None if units in ("", "-") else _clean(units)
    e.data_type = TYPE_ALIASES.get(dtype)
    e.access = ACCESS.get(access)
    e.pdo = PDO.get(pdo)
    e.min, e.max = _range(rng)
    return e


# ---------------------------------------------------------------- App. 2.1

def parse_app21(lines):
    objects, current, pending = [], None, None
    for n in range(*APP21):
        c = cells(lines[n - 1])
        if not c or c[0] == "索引":
            continue
        if _SUB.match(c[0]) and len(c) == 8 and c[-1] == "":
            c = [""] + c[:-1]  # row shifted one cell left by the page break (`| 0Eh | Shift time ... |`)
        index_cell, sub_cell = c[0], c[1]
        if sub_cell == "...":
            pending = n
            continue
        if _INDEX.match(index_cell):
            name_parts = c[2].split("<br>")
            current = Object(index=int(_INDEX.match(index_cell).group(1), 16), name=None, object_code="VAR",
                             line=n)
            current.name, current.name_en = split_name(_clean(name_parts[0]))
            objects.append(current)
        sub = int(_SUB.match(sub_cell).group(1), 16)
        name_cell = c[2]
        if sub == 0 and "<br>" in name_cell and current.line == n:
            name_cell = name_cell.split("<br>", 1)[1]  # `1st RxPDO mapping<br>RxPDO1 支持的映射对象个数`
        e = _entry_from(sub, name_cell, c[3], c[4], c[5], c[6], c[7], n)
        if pending is not None:
            prev = current.entries[-1]
            for s in range(prev.subindex + 1, sub):
                filler = Entry(subindex=s, name=f"第{_cn_number(s)}个映射对象", data_type=e.data_type,
                               access=e.access, pdo=e.pdo, min=e.min, max=e.max, units=e.units,
                               attributes={"elided": True}, line=pending)
                current.entries.append(filler)
            pending = None
        current.entries.append(e)
    for o in objects:
        if len(o.entries) > 1:
            o.object_code = "RECORD"  # ARRAY or RECORD is decided by finish_structure
    return objects


# ---------------------------------------------------------------- App. 2.2

def parse_app22(lines):
    """Returns {index: (P-name, line)} for every index App. 2.2 declares, `...` expanded."""
    slots, prev, pending = {}, None, None
    for n in range(*APP22):
        c = cells(lines[n - 1])
        if not c or c[0] == "索引":
            continue
        if c[0] == "...":
            pending = n
            continue
        idx = int(_INDEX.match(c[0]).group(1), 16)
        if pending is not None:
            for i in range(prev + 1, idx):
                group, number = (i >> 8) & 0xF, i & 0xFF
                slots[i] = (f"P{group}-{number:02d}", pending)
            pending = None
        slots[idx] = (c[2], n)
        prev = idx
    return slots


# ---------------------------------------------------------------- App. 1.1

_PARAM = re.compile(r"^P(\d)-(\d+)(?:\.(\d)(?:~(?:P\d-\d+\.)?(\d))?)?$")
_PAIR = re.compile(r"^P(\d)-(\d+)~P(\d)-(\d+)$")


def _param_default(text, field):
    t = _clean(text)
    if field:
        v = parse_int("0x" + t[2:] if t.lower().startswith("0x") else "0x" + t) \
            if re.fullmatch(r"(0x)?[0-9A-Fa-f]+", t) else None
        return v
    return int(t) if re.fullmatch(r"-?\d+", t) else None


def parse_app11(lines):
    """Returns {(group, number): info} with info = {name, units, default, default_text, min, max, range_text,
    effect, modes, fields: [...], line, pair}."""
    params, last, skipped = {}, None, []
    for n in range(*APP11):
        c = cells(lines[n - 1])
        if not c or len(c) < 7 or c[0] in ("参数",) or re.fullmatch(r"P\d-XX", c[0]):
            continue
        key = re.sub(r"[□xX\s]|<br>", "", c[0])
        desc, units, default, rng, effect, modes = c[1], c[2], c[3], c[4], c[5], c[6]
        if not key:
            if last is not None and desc:
                last["description"] += " " + _clean(desc)
            continue
        m_pair = _PAIR.match(key)
        m = _PARAM.match(key)
        if m_pair:
            defaults = default.split("<br>")
            ranges = rng.split("<br>")
            split_ok = len(defaults) == 2 and len(ranges) == 2
            for k, (g, num) in enumerate(((m_pair.group(1), m_pair.group(2)), (m_pair.group(3), m_pair.group(4)))):
                info = _param_info(_clean(desc), units, defaults[k] if split_ok else default,
                                   ranges[k] if split_ok else "", effect, modes, n)
                info["pair"] = f"{key} ({'low' if k == 0 else 'high'} part)"
                if not split_ok:
                    info["range_text"] = _clean(rng)
                params[(int(g), int(num))] = info
                last = info
            continue
        if not m:
            skipped.append((n, key))
            continue
        g, num = int(m.group(1)), int(m.group(2))
        if m.group(3) is None:
            info = _param_info(_clean(desc), units, default, rng, effect, modes, n)
            params[(g, num)] = info
            last = info
            continue
        lo = int(m.group(3))
        hi = int(m.group(4)) if m.group(4) else lo
        info = params.setdefault((g, num), _param_info("", "-", "", "", effect, modes, n))
        info.setdefault("fields", [])
        fld = {"digits": f"{lo}" if lo == hi else f"{lo}-{hi}", "description": _clean(desc),
               "units": None if units.strip() in ("-", "") else _clean(units),
               "default": _clean(default), "range": _clean(rng), "effect": _clean(effect), "line": n}
        limits = field_limits(fld["digits"], fld["range"])
        if limits is not None:
            fld["min"], fld["max"] = limits
        info["fields"].append(fld)
        last = fld
    return params, skipped


def _mode_list(text):
    """适用模式 as a list: `5、6` / `1 3 4` -> numbers as text, `所有` (all), `EtherCAT 模式` kept whole."""
    t = _clean(text)
    if not t or "EtherCAT" in t:
        return [t] if t else []
    return [m for m in re.split(r"[、,\s]+", t) if m]


def _param_info(desc, units, default, rng, effect, modes, n):
    info = {"description": desc, "units": None if units.strip() in ("-", "") else _clean(units),
            "default": _param_default(default, False), "default_text": _clean(default), "range_text": None,
            "min": None, "max": None, "effect": _clean(effect), "modes": _mode_list(modes), "line": n}
    lo, hi = _range(_clean(rng).replace(" ", ""))
    t = _clean(rng)
    if lo is not None and not re.search(r"[a-fA-FxX]", t):
        info["min"], info["max"] = lo, hi
    elif re.fullmatch(r"\d+[、/]\d+", t):
        vals = [int(v) for v in re.split(r"[、/]", t)]
        info["min"], info["max"], info["range_text"] = min(vals), max(vals), t
    elif lo is not None:  # hexadecimal range `0~ffff`, `0~0x00A2`
        lo, hi = (parse_int("0x" + v.lower().replace("0x", "")) for v in re.split(r"~", t.replace(" ", "")))
        info["min"], info["max"] = lo, hi
    elif t:
        info["range_text"] = t
    return info


def field_limits(digits: str, range_text: str):
    """A digit field's range as integers of the field's own value: App. 1.1 prints each field's range in
    hexadecimal digits (`0~f`, `0~ff`, `0x01~0xFF`; P7-01.0~1 `0~16` lists the values 00..16, L8954-L8958).
    A bound beyond what the field's digits hold (P1-75.0~1 `0~500`, L8727-L8728) is cut to the digits'
    capacity. None when the text is not a range."""
    first, _, last = digits.partition("-")
    capacity = (1 << (4 * (int(last or first) - int(first) + 1))) - 1
    parts = re.split(r"~", range_text.replace(" ", ""))
    if len(parts) != 2:
        return None
    lo, hi = (parse_int("0x" + v.lower().replace("0x", "")) for v in parts)
    if lo is None or hi is None:
        return None
    return min(lo, capacity), min(hi, capacity)


def _compose_field_default(fields):
    """The 16-bit value of a digit-field parameter: each field's hex default at its digit position."""
    total = 0
    for f in fields:
        v = _param_default(f["default"], True)
        if v is None:
            return None
        total |= v << (4 * int(f["digits"].split("-")[0]))
    return total


def p_objects(lines):
    slots = parse_app22(lines)
    params, skipped = parse_app11(lines)
    objects = []
    indexes = set(slots) | {0x2000 | (g << 8) | num for (g, num) in params}
    for idx in sorted(indexes):
        g, num = (idx >> 8) & 0xF, idx & 0xFF
        pname = f"P{g}-{num:02d}"
        info = params.get((g, num))
        if idx in slots:
            line = slots[idx][1]
            pname = slots[idx][0]
        else:
            line = info["line"]
        e = Entry(subindex=0, name=pname, access="rw", pdo="no", line=line)
        attrs = {}
        if info is None:
            e.data_type = "U16"
            attrs["documented"] = False
        else:
            e.line = info["line"]
            if info["description"]:
                attrs["description"] = info["description"]
            e.units = info["units"]
            if "fields" in info:
                e.data_type = "U16"
                e.default = _compose_field_default(info["fields"])
                attrs["fields"] = [{k: v for k, v in f.items()} for f in info["fields"]]
            else:
                e.default, e.min, e.max = info["default"], info["min"], info["max"]
                e.data_type = "I16" if (e.min is not None and e.min < 0) or \
                    re.search(r"^-", info.get("range_text") or "") else "U16"
                if e.default is None and info["default_text"] not in ("", "-"):
                    attrs["default_text"] = info["default_text"]
                if info["range_text"]:
                    attrs["range_text"] = info["range_text"]
            attrs["takes_effect"] = info["effect"]
            attrs["op_modes"] = info["modes"]
            if "pair" in info:
                attrs["pair"] = info["pair"]
        attrs["inferred"] = ["data_type", "access", "pdo"]
        if idx not in slots:
            attrs["index_by_formula"] = True
        e.attributes = attrs
        objects.append(Object(index=idx, name=pname, object_code="VAR", line=line, entries=[e]))
    return objects, skipped


# ---------------------------------------------------------------- 8.3.1, 3000h-5FFFh

_MONITOR = re.compile(r"^([UF])(\d)-(\d+)$")


def _app1_descriptions(lines):
    """{'U0-00': (content, unit)} from App. 1.3 and {'F0-00': (content, None)} from App. 1.2."""
    out = {}
    for first, last in (APP12, APP13):
        for n in range(first, last + 1):
            c = cells(lines[n - 1])
            if not c or not _MONITOR.match(c[0]):
                continue
            content = " ".join(x for x in (_clean(v) for v in c[1:-1] if v) if x) if len(c) > 2 else _clean(c[1])
            unit = _clean(c[-1]) if len(c) > 2 else None
            out[c[0]] = (content, unit or None, n)
    return out


def parse_ch83(lines):
    """The 3000h-5FFFh objects of 8.3.1 (L5785-L5832): U monitors (3000h + (group << 8) + number, as the
    P-parameters' rule L5834-L5844), F functions (4000h + ...), listed by index and name only with `...`
    standing for every index between; and 5000h-5002h, printed with type, access and PDO. App. 2 (L9165-L9167)
    calls 3000h-5FFFh reserved; chapter 8's explicit table is what a master is told to use (F0-00 = 4000h
    clears alarms, L7408; U1-00 = 3100h is the current alarm, L7380)."""
    descriptions = _app1_descriptions(lines)
    objects, prev, pending = [], None, None
    for n in range(*CH83):
        c = cells(lines[n - 1])
        if not c or c[0] in ("索引", ""):
            continue
        if c[0] == "...":
            pending = n
            continue
        m = _INDEX.match(c[0])
        if not m:
            continue
        idx = int(m.group(1), 16)
        if idx < 0x3000:
            prev, pending = None, None  # a P-parameter row: App. 2.2 and App. 1.1 give those
            continue
        if len(c) == 8:  # | 索引 | 子索引 | 名称 | 单位 | 数据范围 | 数据类型 | 标志 | PDO |
            e = _entry_from(0, c[2], c[3], c[4], c[5], c[6], c[7], n)
            objects.append(Object(index=idx, name=e.name, name_en=e.name_en, object_code="VAR", line=n,
                                  entries=[e]))
            prev, pending = idx, None
            continue
        todo = [(idx, c[2], n)]
        if pending is not None and prev is not None:
            todo = [(i, None, pending) for i in range(prev + 1, idx)] + todo
        pending = None
        for i, name, line in todo:
            kind = "U" if i < 0x4000 else "F"
            group, number = (i >> 8) & 0xF, i & 0xFF
            expected = f"{kind}{group}-{number:02d}"
            if name is not None and name != expected:
                raise ValueError(f"{MANUAL} L{line}: {c[0]} named {name!r}, the index rule gives {expected}")
            monitor = kind == "U"
            e = Entry(subindex=0, name=expected, data_type="U16", access="ro" if monitor else "rw", pdo="no",
                      line=line)
            attrs = {}
            if expected in descriptions:
                text, unit, dline = descriptions[expected]
                if text:
                    attrs["description"] = f"{text} (L{dline})"
                if unit and unit not in ("-",):
                    e.units = unit
            if name is None:
                attrs["elided"] = True
            attrs["inferred"] = ["data_type", "access", "pdo"]
            e.attributes = attrs
            objects.append(Object(index=i, name=expected, object_code="VAR", line=line, entries=[e]))
        prev = idx
    return objects


# ---------------------------------------------------------------- App. 2.3

_COLS = {"索引": "index", "子索引": "sub", "名称": "name", "单位": "units", "范围": "range", "数据范围": "range",
         "数据类型": "type", "可访问性": "access", "PDO": "pdo", "适用模式": "modes", "使用模式": "modes"}


_TITLE = re.compile(r"^(?:#{1,4}\s*)?([^|]*?)\s*[（(]([0-9A-F]{4})h[）)]\s*$")


def parse_app23(lines):
    """Returns the profile-area objects. Each object's table follows a title line `名称（6091h）`; structured
    objects take their name from it (their table rows name only the subindexes)."""
    objects, header, current, titles = {}, None, None, {}
    order = []
    for n in range(*APP23):
        t = _TITLE.match(lines[n - 1].strip())
        if t:
            titles[int(t.group(2), 16)] = (t.group(1).strip(), n)
        c = cells(lines[n - 1])
        if c is None:
            continue
        if c[0] == "索引":
            header = [_COLS.get(x) for x in c] if "子索引" in c and "数据类型" in c else None
            continue
        if header is None or len(c) != len(header):
            continue
        row = dict(zip(header, c))
        idx_m = _INDEX.match(row["index"])
        if row["index"] and not idx_m:
            continue  # description text in the index column
        if idx_m:
            idx = int(idx_m.group(1), 16)
            if idx not in objects:
                name, name_en = split_name(_clean(row["name"]))
                objects[idx] = Object(index=idx, name=name, name_en=name_en, object_code="VAR", line=n)
                order.append(idx)
            current = objects[idx]
        if current is None or not row["sub"]:
            continue
        if row["sub"] == "-":
            current.object_code = "RECORD"  # `60FEh | - | Digital outputs`: header of a structured object
            continue
        sm = _SUB.match(row["sub"])
        if not sm:
            continue
        e = _entry_from(int(sm.group(1), 16), row["name"], row.get("units", "-"), row["range"], row["type"],
                        row["access"], row["pdo"], n)
        modes = [m.upper() for m in _clean(row.get("modes", "")).split()]
        e.attributes["op_modes"] = modes
        if e.subindex != 0:
            current.object_code = "RECORD"
        current.entries.append(e)
    for idx in order:
        o = objects[idx]
        if o.object_code == "RECORD" and idx in titles:
            o.name, o.name_en = split_name(titles[idx][0])
            o.line = titles[idx][1]
    return [objects[i] for i in order]


def extract(text):
    lines = text.split("\n")
    objects = parse_app21(lines) + parse_app23(lines) + parse_ch83(lines)
    p_objs, skipped = p_objects(lines)
    objects += p_objs
    notes = [
        "Sources: App. 2.1 (CoE area), App. 2.3 (profile area), App. 2.2 (P-parameter indexes) and App. 1.1 "
        "(P-parameter attributes). P-parameter index = 2000h + (group << 8) + number (L5834-L5844).",
        "P-parameter objects: the manual states no data type, access or PDO for them; they are 16-bit "
        "(32-bit values are split into decimal low/high parameters, e.g. P0-92/P0-93) and settable: data_type "
        "U16 (I16 when the documented range is negative), access rw, pdo no, listed in attributes.inferred.",
        "Indexes App. 2.2 declares but App. 1.1 does not document carry attributes.documented: false. "
        "Parameters App. 1.1 documents outside App. 2.2's ranges (P1-75, P4, P5-72..78, P6, P9) carry "
        "attributes.index_by_formula: true.",
        "attributes.takes_effect is App. 1.1's 生效时机 column (L8632-L8640): ○ change while servo off, effective "
        "at once; √ any time, at once; ● after power cycle; △ any time, when the motor is stopped; ▲ any time, "
        "after power cycle. attributes.op_modes is 适用模式 (P-parameters: normal-mode numbers 1 torque, 3 speed, "
        "5 internal position, 6 pulse position, 7 pulse speed, or EtherCAT mode numbers).",
        "Digit-field parameters (n. hexadecimal, e.g. P0-09.0): attributes.fields lists each field; default is "
        "the 16-bit value composed from the fields' hexadecimal defaults, the entry's min/max are not given. Each "
        "field's min/max is its printed range read as hexadecimal digits (cut to what its digits hold); an SDO "
        "write whose field is outside them is refused. Digits no field documents take any value.",
        "Indexes App. 2.2 declares without App. 1.1 documentation (attributes.documented: false) take any 16-bit "
        "value: the manual gives no range or meaning, and the drive does nothing with them.",
        "App. 1.1 rows not turned into objects: " + "; ".join(f"L{n} {k}" for n, k in skipped)
        if skipped else "Every App. 1.1 row is turned into an object field.",
        "Defaults of the CoE and profile areas are not in the appendices: default is null there.",
        "3000h-5FFFh: the objects of 8.3.1 (L5785-L5832), although App. 2 calls the area reserved (L9165-L9167): "
        "U monitors 3000h-3061h (U0-00..U0-97) and 3100h-3101h (U1-00, U1-01), F functions 4000h (F0-00, alarm "
        "clear, L7408) and 4106h (F1-06), index = 3000h/4000h + (group << 8) + number. The manual gives them no "
        "type, access or PDO: U16, monitors ro and functions rw, not mappable (attributes.inferred); descriptions "
        "and units from App. 1.2/1.3 where listed. 5000h-5002h are printed with type, access, PDO and range.",
        "writable_in [PREOP]: 1C12h/1C13h subindexes 01h-04h (L5587) and 1600h-1603h/1A00h-1A03h subindexes "
        "01h-18h (L5622, L5652) can be changed only in PreOP while subindex 00h = 0.",
    ]
    return objects, notes


def apply_rules(objects):
    for o in objects:
        if o.index in (0x1C12, 0x1C13) or 0x1600 <= o.index <= 0x1603 or 0x1A00 <= o.index <= 0x1A03:
            for e in o.entries:
                if e.access == "rw" and e.subindex != 0:
                    e.writable_in = ["PREOP"]
