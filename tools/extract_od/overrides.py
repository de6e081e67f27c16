"""Applies a product's reviewed od-overrides.yaml to the extracted objects.

Each override names the manual line it corrects, what the extracted text says (`manual`) and the value we
choose (`value`), with a reason. The `manual` value is checked before anything is replaced, so an override
that no longer matches the extraction fails loudly instead of silently rewriting a different value, and
the cited line must be the row's own line (within the 3 lines a wrapped row spans).

Operations (`op`, default `set`):
  set       index, [subindex], field, manual, value  - replace one field of an entry (or of the object
                                                       itself when subindex is absent)
  reindex   index, line, value                      - the object printed at `line` as `index` is really
                                                       index `value` (a duplicated index in the manual)
  drop      index, line                             - the object printed at `line` repeats an earlier row
  text      line, manual, value                     - the manual line's text `manual` is replaced by
                                                       `value` before parsing (a garbled table key)
  add       index, object (a full object)           - an object the table omits but the manual documents
                                                       elsewhere at `line`
"""
from __future__ import annotations

import yaml

from odmodel import ENTRY_FIELDS, Entry, Object


class OverrideError(Exception):
    pass


def load(path: str) -> list:
    with open(path, encoding="utf-8") as f:
        data = yaml.safe_load(f) or {}
    items = data.get("overrides") or []
    for i, o in enumerate(items):
        for key in ("kind", "line", "reason") + (() if o.get("op") == "text" else ("index",)):
            if key not in o:
                raise OverrideError(f"{path}: override #{i + 1} lacks '{key}'")
        if o["kind"] not in ("extraction", "erratum"):
            raise OverrideError(f"{path}: override #{i + 1}: kind must be extraction or erratum")
    return items


def apply_text(text: str, overrides: list) -> str:
    """Applies the `text` overrides to the manual before it is parsed."""
    lines = text.split("\n")
    for o in overrides:
        if o.get("op") != "text":
            continue
        n = o["line"]
        if o["manual"] not in lines[n - 1]:
            raise OverrideError(f"text override at manual line {n}: {o['manual']!r} not on that line")
        lines[n - 1] = lines[n - 1].replace(o["manual"], o["value"], 1)
    return "\n".join(lines)


def _find(objects: list, index: int, line=None) -> Object:
    hits = [o for o in objects if o.index == index and (line is None or o.line == line)]
    if len(hits) != 1:
        raise OverrideError(f"override for 0x{index:04X} (line {line}) matches {len(hits)} objects")
    return hits[0]


def _mark(entry: Entry, fieldname: str) -> None:
    entry.overridden = sorted(set((entry.overridden or []) + [fieldname]))


def _entry_from(spec: dict, line: int) -> Entry:
    e = Entry(subindex=spec["subindex"], line=spec.get("line", line))
    for k, v in spec.items():
        if k not in ENTRY_FIELDS:
            raise OverrideError(f"unknown entry field {k}")
        setattr(e, k, v)
    e.overridden = ["added"]
    return e


def apply(objects: list, overrides: list) -> None:
    for o in overrides:
        op = o.get("op", "set")
        if op == "text":
            continue
        where = f"override at manual line {o['line']} for 0x{o['index']:04X}"
        if op == "reindex":
            obj = _find(objects, o["index"], o["line"])
            obj.index = o["value"]
            obj.attributes = dict(obj.attributes, printed_index=f"0x{o['index']:04X}")
        elif op == "drop":
            objects.remove(_find(objects, o["index"], o["line"]))
        elif op == "add":
            spec = o["object"]
            if any(x.index == o["index"] for x in objects):
                raise OverrideError(f"{where}: object already extracted; drop the override")
            obj = Object(index=o["index"], name=spec["name"], name_en=spec.get("name_en"),
                         object_code=spec["object_code"], line=o["line"],
                         attributes=spec.get("attributes", {}))
            obj.entries = [_entry_from(e, o["line"]) for e in spec["entries"]]
            objects.append(obj)
        elif op == "set":
            obj = _find(objects, o["index"])
            f = o["field"]
            if "subindex" not in o:
                target, current = obj, getattr(obj, f)
            else:
                target = obj.entry(o["subindex"])
                if target is None:
                    raise OverrideError(f"{where}: no subindex 0x{o['subindex']:02X}")
                current = getattr(target, f) if f in ENTRY_FIELDS else None
            if target.line is not None and abs(o["line"] - target.line) > 3:
                raise OverrideError(f"{where}: cites line {o['line']} but the row is at line {target.line}")
            if current != o["manual"]:
                raise OverrideError(f"{where}: field {f} is {current!r}, override expects {o['manual']!r}")
            setattr(target, f, o["value"])
            if isinstance(target, Entry):
                _mark(target, f)
        else:
            raise OverrideError(f"{where}: unknown op {op}")
