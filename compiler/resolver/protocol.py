"""Resolve a validated schema document into the immutable protocol model.

Every semantic rule of the language is checked here, before any backend runs,
and every error is collected with its file:line:col and a hint.
"""
from __future__ import annotations

import hashlib
import math
import re
from dataclasses import replace
from typing import Any, Optional

from .. import crc
from ..diagnostics import Loc, Reporter, SchemaError
from ..dispatch_pairs import candidate_pairs
from ..loader import Document
from ..model import (Checksum, Condition, CrcParams, Direction, Enum, EnumMember,
                    Example, ExpectedError, Field, FlagBit, FlagSet, Framing,
                    HistoryEntry, Machine, Message, Note, Parameter, Protocol, Role, Rule,
                    Sequence, SequenceItem, SequenceRule, TextForm,
                    Transport, field_at)
from ..name_clashes import generated_name_clashes
from ..names import name_problem, protocol_name_problem
from .machines import MachineResolver
from .text import text
from ..validate import structure_errors

INT_TYPE = re.compile(r"^([ui])([0-9]+)$")
BASE_KINDS = {"bool": ("bool", 1), "f32": ("float", 32), "f64": ("float", 64),
              "char": ("char", None), "str": ("str", None), "bytes": ("bytes", None),
              "group": ("group", None)}
MAX_INT_BITS = 64
MAX_BYTES_LENGTH = 4096
DEFAULT_HINT = "see docs/schema-language.md for what this key accepts"


# A double's 53-bit significand: wider raw values would not survive value → raw → value.
MAX_SCALED_BITS = 53


class Resolver:
    def __init__(self, doc: Document):
        self.doc = doc
        self.data = doc.data
        self.report = Reporter()
        self.enums: dict[str, Enum] = {}
        self.flags: dict[str, FlagSet] = {}
        self.parameters: dict[str, Parameter] = {}
        self.framing_kind = self.data["framing"]["kind"]

    # -- helpers ---------------------------------------------------------------------------
    def loc(self, *path: Any) -> Loc:
        return self.doc.loc(path)

    def error(self, path: tuple, message: str, hint: str = "") -> None:
        self.report.error(self.doc.loc(path), message, hint or DEFAULT_HINT)

    def check_name(self, name: str, path: tuple, what: str) -> None:
        problem = name_problem(name)
        if problem:
            self.error(path, f"{what} name {problem}",
                       "rename it; names must work in Python, C and C++")

    # -- top level -------------------------------------------------------------------------
    def resolve(self) -> Protocol:
        d = self.data
        problem = protocol_name_problem(d["protocol"])
        if problem:
            self.error(("protocol",), f"protocol name {problem}",
                       "rename it; it names the generated module and header")
        for path, clash in generated_name_clashes(d):
            self.error(path, clash, "rename one of them")
        roles = tuple(Role(n, text(r.get("doc"))) for n, r in d.get("roles", {}).items())
        for n in d.get("roles", {}):
            self.check_name(n, ("roles", n), "role")
        directions = []
        for n, r in d.get("directions", {}).items():
            self.check_name(n, ("directions", n), "direction")
            for end in ("from", "to"):
                if r[end] not in d.get("roles", {}):
                    self.error(("directions", n, end), f"direction {n!r}: unknown role {r[end]!r}",
                               "declare it under `roles`")
            directions.append(Direction(n, r["from"], r["to"], text(r.get("doc"))))
        for n, p in d.get("parameters", {}).items():
            self.check_name(n, ("parameters", n), "parameter")
            rng = tuple(p["range"]) if "range" in p else None
            if rng and "default" in p and not rng[0] <= p["default"] <= rng[1]:
                self.error(("parameters", n, "default"),
                           f"parameter {n!r}: default {p['default']} is outside {rng[0]}..{rng[1]}")
            self.parameters[n] = Parameter(n, p.get("default"), rng, p.get("unit"), text(p.get("doc")))
        for n, e in d.get("enums", {}).items():
            self.enums[n] = self.resolve_enum(n, e)
        for n, f in d.get("flags", {}).items():
            self.flags[n] = self.resolve_flags(n, f)
        self.check_type_cycles()
        self.report.raise_if_any()  # a cyclic type would make every later error misleading
        group_types = tuple(
            (n, self.resolve_field({"name": n, **t}, ("types", n), allow_payload=False))
            for n, t in d.get("types", {}).items() if self.base_type(t, ("types", n)) == "group")
        framing = self.resolve_framing(d["framing"])
        messages = tuple(self.resolve_message(n, m, framing) for n, m in d["messages"].items())
        self.check_messages(messages, d)
        sequences = tuple(self.resolve_sequence(n, s, messages)
                          for n, s in d.get("sequences", {}).items())
        machines = tuple(self.resolve_machine(n, m, messages)
                         for n, m in d.get("machines", {}).items())
        self.report.raise_if_any()
        return Protocol(
            name=d["protocol"], file=self.doc.file,
            sha256=hashlib.sha256(self.doc.text.encode("utf-8")).hexdigest(),
            title=text(d["title"]), version=d.get("version"), source=d["source"],
            doc=text(d.get("doc")),
            notes=tuple(Note(n["id"], text(n["text"])) for n in d.get("notes", [])),
            history=tuple(HistoryEntry(h["version"], h.get("date", ""), h.get("author", ""),
                                       tuple(text(c) for c in h.get("changes", [])))
                          for h in d.get("history", [])),
            roles=roles, directions=tuple(directions),
            transports=tuple(Transport(t["name"], t["kind"], text(t.get("doc")),
                                       tuple(sorted(t.get("params", {}).items())))
                             for t in d.get("transports", [])),
            parameters=tuple(self.parameters.values()), enums=tuple(self.enums.values()),
            flags=tuple(self.flags.values()), framing=framing, messages=messages,
            sequences=sequences, machines=machines, group_types=group_types)

    # -- enums and flags -------------------------------------------------------------------
    def resolve_enum(self, name: str, e: dict) -> Enum:
        path = ("enums", name)
        self.check_name(name, path, "enum")
        kind, bits = self.scalar_type(e["type"], path + ("type",))
        if kind not in ("uint", "int", "char"):
            self.error(path + ("type",), f"enum {name!r}: type must be an integer type or char")
        members = []
        seen_names: set = set()
        seen_values: set = set()
        for i, m in enumerate(e["values"]):
            mp = path + ("values", i)
            self.check_name(m["name"], mp + ("name",), "enum member")
            if m["name"] in seen_names:
                self.error(mp + ("name",), f"enum {name!r}: duplicate member name {m['name']!r}")
            if m["value"] in seen_values:
                self.error(mp + ("value",), f"enum {name!r}: duplicate value {m['value']!r}",
                           "each member needs its own wire value")
            seen_names.add(m["name"])
            seen_values.add(m["value"])
            value = m["value"]
            if kind == "char":
                if not (isinstance(value, str) and len(value) == 1):
                    self.error(mp + ("value",), f"enum {name!r}: a char enum value is one character")
            elif isinstance(value, bool) or not isinstance(value, int):
                self.error(mp + ("value",), f"enum {name!r}: value must be an integer")
            elif bits and not self.int_fits(value, kind, bits):
                self.error(mp + ("value",),
                           f"enum {name!r}: value {value} does not fit in {e['type']}",
                           "widen the enum's type or change the value")
            members.append(EnumMember(m["name"], value, text(m.get("doc"))))
        return Enum(name, "char" if kind == "char" else "int", bits, tuple(members),
                    text(e.get("doc")))

    def resolve_flags(self, name: str, f: dict) -> FlagSet:
        path = ("flags", name)
        self.check_name(name, path, "flag set")
        kind, bits = self.scalar_type(f["type"], path + ("type",))
        if kind != "uint":
            self.error(path + ("type",), f"flag set {name!r}: type must be unsigned (u8, u16 …)")
            bits = bits or 64
        members = []
        seen: set = set()
        for i, b in enumerate(f["bits"]):
            bp = path + ("bits", i)
            self.check_name(b["name"], bp + ("name",), "flag")
            if b["bit"] >= (bits or 0):
                self.error(bp + ("bit",), f"flag {b['name']!r}: bit {b['bit']} is outside {f['type']}")
            if b["bit"] in seen or b["name"] in {m.name for m in members}:
                self.error(bp, f"flag set {name!r}: duplicate bit or name {b['name']!r}")
            seen.add(b["bit"])
            members.append(FlagBit(b["name"], b["bit"], text(b.get("doc"))))
        return FlagSet(name, bits or 0, tuple(members), text(f.get("doc")))

    # -- types -----------------------------------------------------------------------------
    def scalar_type(self, type_name: str, path: tuple) -> tuple[str, Optional[int]]:
        m = INT_TYPE.match(type_name)
        if m:
            bits = int(m.group(2))
            if not 1 <= bits <= MAX_INT_BITS or (m.group(1) == "i" and bits < 2):
                self.error(path, f"integer width {bits} is outside {'2' if m.group(1) == 'i' else '1'}..{MAX_INT_BITS}",
                           "wider values need several fields")
                return ("uint" if m.group(1) == "u" else "int"), None
            return ("uint" if m.group(1) == "u" else "int"), bits
        if type_name in BASE_KINDS:
            return BASE_KINDS[type_name]
        return "", None

    def check_type_cycles(self) -> None:
        types = self.data.get("types", {})

        def refs(body: Any) -> list[str]:
            """Types a type uses: its own `type` and those of its group fields, nested."""
            if not isinstance(body, dict):
                return []
            out = [body["type"]] if body.get("type") in types else []
            for sub in body.get("fields", None) or ():
                out.extend(refs(sub))
            return out

        for start in types:
            stack, visited = [[start]], {start}
            while stack:
                chain = stack.pop()
                uses = refs(types[chain[-1]])
                if start in uses:
                    self.error(("types", start, "type"),
                               f"type {start!r} refers to itself through {' → '.join(chain + [start])}",
                               "a type must end in a built-in type; a group may not contain itself")
                    break
                for used in uses:
                    if used not in visited:
                        visited.add(used)
                        stack.append(chain + [used])

    def base_type(self, raw: dict, path: tuple) -> str:
        types = self.data.get("types", {})
        current, hops = raw.get("type"), 0
        while current in types and hops < 64:
            current, hops = types[current].get("type"), hops + 1
        return current

    def merged(self, raw: dict, path: tuple) -> tuple[dict, Optional[str]]:
        """A field's keys with those of its named type chain underneath."""
        types = self.data.get("types", {})
        chain, current = [], raw.get("type")
        while current in types and len(chain) < 64:
            chain.append(current)
            current = types[current].get("type")
        out: dict = {}
        for name in reversed(chain):
            out.update({k: v for k, v in types[name].items() if k != "type"})
        out.update({k: v for k, v in raw.items() if k != "type"})
        out["type"] = current
        return out, (chain[0] if chain else None)

    @staticmethod
    def int_fits(value: Any, kind: str, bits: int) -> bool:
        if isinstance(value, bool):
            value = int(value)
        if kind == "int":
            return -(1 << (bits - 1)) <= value <= (1 << (bits - 1)) - 1
        return 0 <= value <= (1 << bits) - 1

    def resolve_field(self, raw: dict, path: tuple, allow_payload: bool = True) -> Field:
        if raw.get("payload"):
            if not allow_payload:
                self.error(path, "`payload: true` belongs only in framing.layout")
            return Field(name="payload", kind="payload", loc=self.loc(*path), is_payload=True)
        name = raw["name"]
        self.check_name(name, path + ("name",), "field")
        f, type_name = self.merged(raw, path)
        tpath = path + ("type",)
        kind, bits = self.scalar_type(f["type"], tpath)
        if not kind:
            self.error(tpath, f"field {name!r}: unknown type {f['type']!r}",
                       "use u1…u64, i2…i64, bool, f32, f64, char, str, bytes, group or a name from `types`")
            kind, bits = "uint", 8
        loc = self.loc(*path)
        enum = flags = None
        if "enum" in f:
            enum = self.enums.get(f["enum"])
            if enum is None:
                self.error(path + ("enum",), f"field {name!r}: unknown enum {f['enum']!r}")
            elif enum.kind == "char" and kind != "char" or enum.kind == "int" and kind not in ("uint", "int"):
                self.error(tpath, f"field {name!r}: type {f['type']} does not match enum {enum.name!r}")
            elif bits:
                for m in enum.members:
                    if not self.int_fits(m.value, kind, bits):
                        self.error(tpath, f"field {name!r}: enum value {m.name}={m.value} does not fit {f['type']}")
        if "flags" in f:
            flags = self.flags.get(f["flags"])
            if flags is None:
                self.error(path + ("flags",), f"field {name!r}: unknown flag set {f['flags']!r}")
            elif kind != "uint" or bits != flags.bits:
                self.error(tpath, f"field {name!r}: type {f['type']} does not match flag set "
                                  f"{flags.name!r} (u{flags.bits})")
        sub_fields: tuple[Field, ...] = ()
        if kind == "group":
            if "fields" not in f:
                self.error(path, f"group {name!r} needs `fields`")
            else:
                sub_fields = self.resolve_fields(f["fields"], path + ("fields",), allow_payload=False)
                widths = [s.bits for s in sub_fields]
                bits = sum(widths) if all(w is not None for w in widths) else None
        elif "fields" in f:
            self.error(path + ("fields",), f"field {name!r}: only `type: group` has fields")
        length = f.get("length")
        length_param = None
        if isinstance(length, str):
            param = self.parameters.get(length)
            if param is None:
                self.error(path + ("length",), f"field {name!r}: unknown parameter {length!r}",
                           "declare it under `parameters`")
                length = 1
            elif param.default is None:
                self.error(path + ("length",), f"field {name!r}: parameter {length!r} has no default",
                           "a length parameter needs a default")
                length = 1
            else:
                length_param, length = length, int(param.default)
        if kind == "bytes":
            if length is None:
                self.error(path, f"bytes field {name!r} needs a fixed `length`",
                           "variable-length byte strings are not supported yet")
                length = 1
            if not 0 < length <= MAX_BYTES_LENGTH:
                self.error(path + ("length",), f"field {name!r}: length {length} is outside 1..{MAX_BYTES_LENGTH}")
                length = 1
            bits = 8 * length
        elif kind == "str" and not 0 < (length or f.get("max_length") or 1) <= MAX_BYTES_LENGTH:
            key = "length" if length else "max_length"
            self.error(path + (key,), f"field {name!r}: {key} {length or f.get('max_length')} is outside "
                                      f"1..{MAX_BYTES_LENGTH}")
        elif length is not None and kind != "str":
            self.error(path + ("length",), f"field {name!r}: `length` applies to bytes and str fields")
        field = Field(
            name=name, kind=kind, loc=loc, bits=bits, doc=text(f.get("doc")),
            title=text(f.get("title")), type_name=type_name, unit=f.get("unit"),
            const=f.get("const"), reserved=bool(f.get("reserved")), default=f.get("default"),
            has_default="default" in f,
            range=tuple(f["range"]) if "range" in f else None,
            values=tuple(f["values"]) if "values" in f else None, enum=enum, flags=flags,
            scale=f.get("scale"), offset=f.get("offset"), one_hot=bool(f.get("one_hot")),
            exactly_one=bool(f.get("exactly_one")), byte_order=f.get("byte_order"),
            length=length if kind in ("bytes", "str") else None, length_param=length_param,
            max_length=f.get("max_length"), optional=bool(f.get("optional")),
            to_end=bool(f.get("to_end")), dispatch=bool(f.get("dispatch")),
            length_of=(f["length_of"]["from"], f["length_of"]["to"]) if "length_of" in f else None,
            checksum=self.resolve_checksum(f["checksum"], path + ("checksum",), bits)
            if "checksum" in f else None,
            fields=sub_fields, message=text(f.get("message")), rule=f.get("rule"))
        self.check_field(field, path)
        return field

    def resolve_fields(self, raw: list, path: tuple, allow_payload: bool = True) -> tuple[Field, ...]:
        fields = []
        seen: dict[str, int] = {}
        for i, r in enumerate(raw):
            field = self.resolve_field(r, path + (i,), allow_payload)
            if field.name in seen and not field.is_payload:
                self.error(path + (i, "name"), f"duplicate field name {field.name!r}",
                           f"the first one is item {seen[field.name]}")
            seen.setdefault(field.name, i)
            fields.append(field)
        return tuple(fields)

    def check_field(self, f: Field, path: tuple) -> None:
        """Constraints that concern one field alone."""
        name, kind, bits = f.name, f.kind, f.bits
        numeric = kind in ("uint", "int", "bool", "float")
        if self.framing_kind != "text" and kind in ("char", "str"):
            self.error(path + ("type",), f"field {name!r}: {kind} is a text type; binary framings need "
                                         "bytes with a length")
        if f.scale is not None or f.offset is not None:
            if kind not in ("uint", "int"):
                self.error(path, f"field {name!r}: scale/offset apply to integer fields")
            elif f.scale is not None and bits and bits > MAX_SCALED_BITS:
                self.error(path + ("scale",), f"field {name!r}: a scaled value is a double, which holds "
                                              f"integers of up to {MAX_SCALED_BITS} bits exactly, not {bits}",
                           f"narrow the field to {MAX_SCALED_BITS} bits, or drop the scale")
            elif f.scale is None and isinstance(f.offset, int) and bits:
                lo = (-(1 << (bits - 1)) if kind == "int" else 0) + f.offset
                hi = ((1 << (bits - 1)) - 1 if kind == "int" else (1 << bits) - 1) + f.offset
                if not (-(1 << 63) <= lo and hi < (1 << 63) or 0 <= lo and hi < (1 << 64)):
                    self.error(path + ("offset",), f"field {name!r}: values {lo}..{hi} with offset "
                                                   f"{f.offset} do not fit a 64-bit integer",
                               "use a smaller offset or a narrower field")
        if f.one_hot and kind != "uint":
            self.error(path + ("one_hot",), f"field {name!r}: one_hot needs an unsigned type")
        if f.exactly_one and f.flags is None:
            self.error(path + ("exactly_one",), f"field {name!r}: exactly_one applies to flag fields")
        if f.byte_order and (bits is None or bits % 8 or bits <= 8):
            self.error(path + ("byte_order",), f"field {name!r}: byte_order needs a multi-byte field")
        if f.reserved and kind not in ("uint", "int"):
            self.error(path + ("reserved",), f"field {name!r}: reserved bits are an unsigned integer")
        if (f.optional or f.to_end) and self.framing_kind != "text":
            self.error(path, f"field {name!r}: optional/to_end apply to text framing")
        if f.to_end and kind != "str":
            self.error(path + ("to_end",), f"field {name!r}: to_end applies to str fields")
        if kind == "float" and (f.range is not None and not all(math.isfinite(v) for v in f.range)):
            self.error(path + ("range",), f"field {name!r}: range bounds must be finite")
        lo_raw, hi_raw = (f.raw_range or (None, None))
        if f.range is not None:
            lo, hi = f.range
            if lo > hi:
                self.error(path + ("range",), f"field {name!r}: range [{lo}, {hi}] is empty",
                           "write [low, high]")
            elif not numeric:
                self.error(path + ("range",), f"field {name!r}: range applies to numbers")
            elif lo_raw is not None:
                if f.one_hot:
                    raw_lo, raw_hi = lo, hi
                    lo_raw, hi_raw = 0, bits - 1
                else:
                    raw_lo, raw_hi = self.to_raw(f, lo), self.to_raw(f, hi)
                if f.scale is None and f.offset is None and not (float(lo).is_integer() and float(hi).is_integer()):
                    self.error(path + ("range",), f"field {name!r}: an integer field's range must be integers")
                elif not f.one_hot and math.ceil((lo - (f.offset or 0)) / (f.scale or 1) - 1e-9) > \
                        math.floor((hi - (f.offset or 0)) / (f.scale or 1) + 1e-9):  # decimal scales round
                    self.error(path + ("range",), f"field {name!r}: range [{lo}, {hi}] holds no value the "
                                                  "field can carry (raw value × scale + offset)",
                               "widen the range to include one")
                elif raw_lo < lo_raw or raw_hi > hi_raw:
                    self.error(path + ("range",),
                               f"field {name!r}: range [{lo}, {hi}] does not fit {bits} bits "
                               f"(raw {raw_lo}..{raw_hi}, allowed {lo_raw}..{hi_raw})",
                               "widen the field or narrow the range")
        if f.const is not None and self.framing_kind == "text" and (f.kind == "float" or f.scale or f.offset):
            self.error(path + ("const",), f"field {name!r}: a text line spells a constant as written; "
                                          "a number with a fraction has several spellings",
                       "make the constant an integer, char or str field")
        for key in ("const", "default"):
            value = getattr(f, key)
            if value is None or (key == "default" and f.kind == "group"):
                continue
            self.check_value(f, value, path + (key,), key)
        if f.values:
            for i, v in enumerate(f.values):
                self.check_value(f, v, path + ("values", i), "allowed value")

    def check_value(self, f: Field, value: Any, path: tuple, what: str) -> None:
        kind, bits = f.kind, f.bits
        if f.enum is not None:
            names = {m.name for m in f.enum.members}
            if value not in names and value not in f.enum.values:
                self.error(path, f"field {f.name!r}: {what} {value!r} is not a member of enum {f.enum.name!r}")
            return
        if kind in ("uint", "int"):
            if f.one_hot and value is None:
                return
            if isinstance(value, bool) or not isinstance(value, (int, float)):
                self.error(path, f"field {f.name!r}: {what} {value!r} is not a number")
                return
            if not f.scale and not f.offset and isinstance(value, float) and not value.is_integer():
                self.error(path, f"field {f.name!r}: {what} {value} is not a whole number",
                           "an integer field without a scale holds whole numbers")
                return
            raw = value if f.one_hot else self.to_raw(f, value)
            limit = (0, bits - 1) if f.one_hot else f.raw_range
            if bits and limit and not (limit[0] <= raw <= limit[1]):
                self.error(path, f"field {f.name!r}: {what} {value} does not fit {bits} bits "
                                 f"(allowed {limit[0]}..{limit[1]})", "widen the field or change the value")
            elif f.range and not f.range[0] <= value <= f.range[1]:
                self.error(path, f"field {f.name!r}: {what} {value} is outside its range {list(f.range)}")
        elif kind == "bool" and not isinstance(value, bool) and value not in (0, 1):
            self.error(path, f"field {f.name!r}: {what} {value!r} is not a bool")
        elif kind == "char" and not (isinstance(value, str) and len(value) == 1):
            self.error(path, f"field {f.name!r}: {what} {value!r} is not one character")
        elif kind == "str" and not isinstance(value, str):
            self.error(path, f"field {f.name!r}: {what} {value!r} is not a string")

    @staticmethod
    def to_raw(f: Field, value: float) -> float:
        raw = (value - (f.offset or 0)) / (f.scale or 1)
        return math.floor(raw + 0.5) if f.scale else raw

    # -- checksums -------------------------------------------------------------------------
    def resolve_checksum(self, c: dict, path: tuple, bits: Optional[int]) -> Checksum:
        algorithm = c["algorithm"]
        covers = c.get("covers", "all")
        covers = None if covers == "all" else (covers["from"], covers["to"])
        default_over = "fields" if self.framing_kind == "bits" else "bytes"
        over = c.get("over", default_over)
        params: Optional[CrcParams] = None
        if algorithm == "crc":
            missing = [k for k in ("width", "poly", "init", "refin", "refout", "xorout") if k not in c]
            if missing:
                self.error(path, f"crc needs Rocksoft parameters: missing {', '.join(missing)}",
                           "or name a RevEng catalogue entry, e.g. algorithm: CRC-16/CMS")
                return Checksum("crc", over, covers)
            params = CrcParams("custom", c["width"], c["poly"], c["init"], c["refin"],
                               c["refout"], c["xorout"])
        elif algorithm in ("parity", "sum", "xor"):
            for key in ("width", "poly", "init", "refin", "refout", "xorout"):
                if key in c:  # CRC parameters would be ignored: a silent mismatch with the peer
                    self.error(path + (key,), f"{key} is a CRC parameter; a {algorithm} checksum has none",
                               f"drop {key}, or use a CRC")
        else:
            params = crc.lookup(algorithm)
            if params is None:
                self.error(path + ("algorithm",), f"unknown checksum algorithm {algorithm!r}",
                           "use parity, sum, xor, crc (with parameters) or a RevEng catalogue "
                           "name such as CRC-16/CMS")
                return Checksum("crc", over, covers)
        if params is not None:
            algorithm = "crc"
            mask = (1 << params.width) - 1
            for key in ("poly", "init", "xorout"):
                if getattr(params, key) > mask:
                    self.error(path + (key,), f"crc {key} does not fit {params.width} bits")
            if bits is not None and bits != params.width:
                self.error(path, f"a {params.width}-bit CRC needs a {params.width}-bit field, not {bits}",
                           f"declare the field as u{params.width}")
            if over != "bytes":
                self.error(path + ("over",), "a CRC is computed over bytes")
        elif over != "bytes" and covers is not None:
            # the codecs and docs take a checksum over fields from every other field
            self.error(path + ("covers",), "a checksum over fields covers every other field "
                                           "of the message; `covers: {from, to}` is the byte "
                                           "range of a checksum over bytes",
                       "drop `covers` (or write `covers: all`); to check part of the frame, use "
                       "a CRC over whole bytes, e.g. {algorithm: CRC-8/SMBUS, covers: {from, to}}")
        modulo = c.get("modulo")
        if algorithm in ("sum", "xor") and modulo is None and bits:
            modulo = 1 << bits
        if algorithm == "parity" and bits not in (None, 1):
            self.error(path, f"a parity bit is 1 bit wide, not {bits}")
        if modulo is not None and bits and modulo > (1 << bits):
            self.error(path + ("modulo",), f"sum modulo {modulo} does not fit {bits} bits")
        return Checksum(algorithm, over, covers, c.get("parity", "even"), modulo, params,
                        loc=self.loc(*(path + ("covers",))) if "covers" in c else self.loc(*path))

    # -- framing ---------------------------------------------------------------------------
    def resolve_framing(self, fr: dict) -> Framing:
        kind = fr["kind"]
        path = ("framing",)
        allowed = {"bits": {"kind", "word_bits", "max_bits", "byte_order", "text_form"},
                   "bytes": {"kind", "layout", "byte_order"},
                   "text": {"kind", "prefix_separator", "separator", "terminator",
                            "ignore_between", "trim", "float_format"}}[kind]
        for key in fr:
            if key not in allowed:
                self.error(path + (key,), f"framing: {key!r} does not apply to {kind} framing",
                           "keys for this framing: " + ", ".join(sorted(allowed)))
        envelope: tuple[Field, ...] = ()
        if kind == "bytes":
            if "layout" not in fr:
                self.error(path, "bytes framing needs a `layout` with a `{payload: true}` item")
            else:
                envelope = self.resolve_fields(fr["layout"], path + ("layout",))
                payloads = [f for f in envelope if f.is_payload]
                if len(payloads) != 1:
                    self.error(path + ("layout",), f"layout needs exactly one `{{payload: true}}` item, "
                                                   f"found {len(payloads)}")
                dispatch = [f for f in envelope if f.dispatch]
                if len(dispatch) > 1:
                    self.error(path + ("layout",), "layout may mark one field `dispatch: true`")
        if kind == "bits" and "word_bits" in fr and "max_bits" in fr:
            self.error(path, "give word_bits (every message is one word) or max_bits, not both")
        if kind == "bits" and "word_bits" not in fr and "max_bits" not in fr:
            self.error(path, "bits framing needs word_bits or max_bits")
        tf = fr.get("text_form")
        return Framing(
            kind=kind, byte_order=fr.get("byte_order", "big"), word_bits=fr.get("word_bits"),
            max_bits=fr.get("max_bits"),
            text_form=TextForm(tf.get("separator", " "), tf.get("comment"), tf.get("checksum_unfilled"))
            if tf else None,
            envelope=envelope, prefix_separator=fr.get("prefix_separator", ":"),
            separator=fr.get("separator", ","), terminator=fr.get("terminator", ";"),
            ignore_between=fr.get("ignore_between", ""), trim=bool(fr.get("trim")),
            float_format=fr.get("float_format", "shortest"))

    # -- messages --------------------------------------------------------------------------
    def resolve_message(self, name: str, m: dict, framing: Framing) -> Message:
        path = ("messages", name)
        self.check_name(name, path, "message")
        layout_type = None
        if isinstance(m["fields"], str):
            layout_type = m["fields"]
            t = self.data.get("types", {}).get(layout_type)
            if t is None or self.base_type(t, ()) != "group":
                self.error(path + ("fields",), f"message {name!r}: {layout_type!r} is not a group type",
                           "declare it under `types` with `type: group` and `fields`")
                own: tuple[Field, ...] = ()
            else:
                merged, _ = self.merged(t, ("types", layout_type))
                own = self.resolve_fields(merged["fields"], ("types", layout_type, "fields"),
                                          allow_payload=False)
        else:
            own = self.resolve_fields(m["fields"], path + ("fields",), allow_payload=False)
        for key in ("direction", "role"):
            table = "directions" if key == "direction" else "roles"
            if key in m and m[key] not in self.data.get(table, {}):
                self.error(path + (key,), f"message {name!r}: unknown {key} {m[key]!r}",
                           f"declare it under `{table}`")
        ids = m.get("id")
        ids = () if ids is None else tuple(ids) if isinstance(ids, list) else (ids,)
        layout, dispatch_key = self.place(name, own, ids, framing, path)
        bits = None
        if framing.kind != "text":
            widths = [f.bits for f in layout]
            bits = sum(widths) if all(w is not None for w in widths) else None
            self.check_size(name, m, layout, bits, framing, path)
            layout = self.bind_checksums(name, layout, framing, path)
            self.check_field_checksums(name, layout)
        rules = tuple(self.resolve_rule(r, path + ("rules", i), layout)
                      for i, r in enumerate(m.get("rules", [])))
        examples = tuple(self.resolve_example(e, path + ("examples", i))
                         for i, e in enumerate(m.get("examples", [])))
        return Message(
            name=name, loc=self.loc(*path), title=text(m.get("title")), doc=text(m.get("doc")),
            ids=ids, direction=m.get("direction"), role=m.get("role"),
            answered_by=tuple(m.get("answered_by", [])), fields=own, layout=layout, bits=bits,
            rules=rules, examples=examples, dispatch_key=dispatch_key, layout_type=layout_type)

    def place(self, name: str, own: tuple[Field, ...], ids: tuple, framing: Framing,
              path: tuple) -> tuple[tuple[Field, ...], tuple]:
        """The message's whole frame in wire order with bit offsets, and its dispatch key."""
        if framing.kind == "text":
            for i, f in enumerate(own):
                if f.dispatch:
                    self.error(path + ("fields", i, "dispatch"),
                               f"message {name!r}: field {f.name!r} is marked `dispatch: true`, but in "
                               "text framing a message is identified by its `id`, the line's prefix",
                               "drop `dispatch`")
            if len(ids) != 1 or not isinstance(ids[0], str):
                self.error(path + ("id",), f"message {name!r}: text framing needs a string `id` (the prefix)")
            self.check_text_fields(name, own, path)
            return own, (("prefix", ids),) if ids else ()
        if framing.kind == "bits":
            if ids:
                self.error(path + ("id",), f"message {name!r}: bits framing identifies messages by "
                                           "`dispatch: true` const fields, not `id`")
            frame = own
            key = tuple((f.name, f.const) for f in own if f.dispatch)
            for i, f in enumerate(own):
                if f.dispatch and f.const is None:
                    self.error(path, f"message {name!r}: dispatch field {f.name!r} needs a const value")
                if f.dispatch and (f.bits or 0) > 8 and (f.byte_order or framing.byte_order) == "little":
                    # header tests read the leading bits most significant first
                    self.error(path + ("fields", i), f"message {name!r}: dispatch field {f.name!r} is "
                               "little-endian; bits framing dispatches on big-endian header bits",
                               "declare it `byte_order: big`, or split it into dispatch fields of 8 bits")
        else:
            for i, f in enumerate(own):
                if f.dispatch:  # would be ignored: the layout's dispatch field and `id` do this
                    self.error(path + ("fields", i, "dispatch"),
                               f"message {name!r}: field {f.name!r} is marked `dispatch: true`, but in "
                               "bytes framing a message is identified by its `id`, the value of the "
                               "layout's dispatch field", "give the message an `id` and drop `dispatch`")
            frame = []
            key = ()
            for f in framing.envelope:
                if f.is_payload:
                    frame.extend(own)
                    frame.append(replace(f, bits=0))
                    continue
                f = replace(f, from_envelope=True)
                if f.dispatch:
                    if not ids:
                        self.error(path, f"message {name!r} needs an `id`: the value of {f.name!r}")
                    for v in ids:
                        if not self.int_fits(v, f.kind, f.bits or 0):
                            self.error(path + ("id",), f"message {name!r}: id {v} does not fit "
                                                       f"{f.name!r} ({f.bits} bits)")
                    f = replace(f, const=ids[0]) if len(ids) == 1 else replace(f, values=ids)
                    key = ((f.name, ids),)
                frame.append(f)
            names = [f.name for f in own]
            for f in framing.envelope:
                if f.name in names and not f.is_payload:
                    self.error(path, f"message {name!r}: field {f.name!r} is also an envelope field")
        placed = []
        offset = 0
        for f in frame:
            placed.append(replace(f, bit_offset=offset))
            offset += f.bits or 0
        self.check_alignment(name, placed, framing, path)
        return tuple(placed), key

    def check_text_fields(self, name: str, own: tuple[Field, ...], path: tuple) -> None:
        seen_optional = False
        for i, f in enumerate(own):
            if f.optional:
                seen_optional = True
            elif seen_optional:
                self.error(path + ("fields", i), f"message {name!r}: required field {f.name!r} follows "
                                                 "an optional one", "only trailing fields may be optional")
            if f.to_end and i != len(own) - 1:
                self.error(path + ("fields", i), f"message {name!r}: to_end field {f.name!r} must be last")
            if f.kind in ("bytes", "group") or f.checksum or f.length_of:
                self.error(path + ("fields", i), f"field {f.name!r}: {f.kind if f.kind in ('bytes', 'group') else 'checksum/length'} "
                                                 "is not supported in text framing")

    def check_alignment(self, name: str, placed: list[Field], framing: Framing, path: tuple) -> None:
        for f in placed:
            order = f.byte_order or framing.byte_order
            multibyte = f.bits and f.bits > 8 and f.kind in ("uint", "int") and order == "little"
            if (f.kind in ("float", "bytes") or multibyte) and (f.bit_offset % 8 or f.bits % 8):
                self.error(path, f"message {name!r}: field {f.name!r} must be byte-aligned and whole "
                                 f"bytes (it starts at bit {f.bit_offset}, {f.bits} bits)",
                           "add padding bits before it")

    def check_size(self, name: str, m: dict, layout: tuple[Field, ...], bits: Optional[int],
                   framing: Framing, path: tuple) -> None:
        if bits is None:
            return
        listing = " + ".join(f"{f.name}={f.bits}" for f in layout if not f.is_payload)
        if bits == 0:
            self.error(path + ("fields",), f"message {name!r} has no fields: nothing on the wire",
                       "give it at least one field")
            return
        if "bits" in m and m["bits"] != bits:
            self.error(path + ("bits",), f"message {name!r}: fields add up to {bits} bits, "
                                         f"but the message declares {m['bits']} ({listing})",
                       "fix a field width or the declared size")
        if framing.word_bits and bits != framing.word_bits:
            self.error(path + ("fields",), f"message {name!r}: fields add up to {bits} bits, "
                                           f"but a word is {framing.word_bits} bits ({listing})",
                       "every message of this protocol is exactly one word; fix a field width")
        if framing.max_bits and bits > framing.max_bits:
            self.error(path + ("fields",), f"message {name!r}: {bits} bits do not fit one "
                                           f"{framing.max_bits}-bit word ({listing})")
        if framing.kind == "bytes" and bits % 8:
            self.error(path + ("fields",), f"message {name!r}: the frame is {bits} bits, not whole bytes",
                       "add reserved bits")

    def bind_checksums(self, name: str, layout: tuple[Field, ...], framing: Framing,
                       path: tuple) -> tuple[Field, ...]:
        """Compute each checksum's and length field's byte coverage within this frame."""
        by_name = {f.name: f for f in layout}
        out = []
        for f in layout:
            span = None
            pair = f.checksum.covers if f.checksum else f.length_of
            if pair is not None:
                start_f, end_f = by_name.get(pair[0]), by_name.get(pair[1])
                for end_name, end in zip(pair, (start_f, end_f)):
                    if end is None:
                        self.report.error(f.checksum.loc if f.checksum else f.loc,
                                          f"message {name!r}: {f.name!r} covers unknown field "
                                                 f"{end_name!r}", "name envelope fields or `payload`")
                if start_f and end_f:
                    start = start_f.bit_offset
                    stop = end_f.bit_offset + (end_f.bits or 0)
                    refused = f.checksum and f.checksum.over != "bytes"  # resolve_checksum refuses its range
                    if (start % 8 or stop % 8) and not refused:
                        self.error(path, f"message {name!r}: coverage of {f.name!r} is not whole bytes")
                    if stop <= start:
                        self.error(path, f"message {name!r}: coverage of {f.name!r} is empty or reversed")
                    if f.checksum and start <= f.bit_offset < stop:
                        self.report.error(f.checksum.loc, f"message {name!r}: checksum {f.name!r} covers itself",
                                          "a checksum cannot be part of what it checks")
                    if f.checksum:
                        self.check_later_checksums(name, f, (start, stop), layout)
                    span = (start // 8, stop // 8)
            if f.checksum:
                if f.checksum.covers is None and f.checksum.over == "bytes" \
                        and framing.kind == "bytes":
                    self.error(path, f"checksum {f.name!r}: give `covers: {{from, to}}` in bytes framing")
                f = replace(f, checksum=replace(f.checksum, byte_span=span))
            elif f.length_of and span:
                value = span[1] - span[0]
                if not self.int_fits(value, f.kind, f.bits or 0):
                    self.error(path, f"message {name!r}: length {value} does not fit {f.name!r}")
                f = replace(f, const=value)
            out.append(f)
        return tuple(out)

    def check_later_checksums(self, name: str, f: Field, bits: tuple[int, int],
                              layout: tuple[Field, ...]) -> None:
        """The codecs fill checksums in wire order: one whose bits cover a later checksum
        would be computed while that one is still 0, and fail once it is filled in."""
        start, stop = bits
        for other in layout:
            if other.checksum and f.bit_offset < other.bit_offset < stop \
                    and other.bit_offset + (other.bits or 0) > start:
                self.report.error(f.checksum.loc, f"message {name!r}: checksum {f.name!r} covers "
                                                  f"checksum {other.name!r}, which comes after it",
                                  f"end the coverage of {f.name!r} before {other.name!r}, or place "
                                  f"{f.name!r} after {other.name!r} (checksums are filled in wire order)")

    def check_field_checksums(self, name: str, layout: tuple[Field, ...]) -> None:
        """A checksum over fields takes every other field, so another checksum among them
        would have to be computed before it and after it: the two cannot both hold."""
        def walk(fields: tuple[Field, ...]):
            for f in fields:
                yield f
                yield from walk(f.fields)

        sums = [f for f in walk(layout) if f.checksum]
        for f in sums:
            if f.checksum.over == "bytes":
                continue
            for other in sums:
                if other is not f:
                    self.report.error(f.checksum.loc or f.loc,
                                      f"message {name!r}: checksum {f.name!r} over every other "
                                      f"field covers checksum {other.name!r}, so the two cannot "
                                      "both be right",
                                      "a checksum over fields must be the message's only checksum")

    # -- rules -----------------------------------------------------------------------------
    def conditions(self, raw: dict, path: tuple, layout: tuple[Field, ...]) -> tuple[Condition, ...]:
        out = []
        for key, value in raw.items():
            field = self.find_path(layout, key)
            if field is None:
                self.error(path + (key,), f"rule names unknown field {key!r}",
                           "use a member field; dotted paths reach into groups")
            elif not field.is_member and field.kind != "group":
                self.error(path + (key,), f"rule names field {key!r}, which the codec sets itself "
                                          "(a constant, length, checksum or reserved field)",
                           "rules compare member fields")
            elif field.enum is not None:
                operands = value.values() if isinstance(value, dict) else [value]
                for operand in operands:
                    for v in operand if isinstance(operand, list) else [operand]:
                        if v is not None and v not in {m.name for m in field.enum.members} \
                                and v not in field.enum.values:
                            self.error(path + (key,), f"rule compares {key!r} with {v!r}, which is not a "
                                                      f"member of enum {field.enum.name!r}",
                                       "use a member's name: " + ", ".join(m.name for m in field.enum.members))
            if isinstance(value, dict):
                (op, operand), = value.items()
                out.append(Condition(key, op, tuple(operand) if isinstance(operand, list) else operand))
            else:
                out.append(Condition(key, "eq", value))
        return tuple(out)

    find_path = staticmethod(field_at)

    def resolve_rule(self, r: dict, path: tuple, layout: tuple[Field, ...]) -> Rule:
        return Rule(r.get("id"), self.conditions(r.get("when", {}), path + ("when",), layout),
                    self.conditions(r["require"], path + ("require",), layout),
                    text(r.get("message")), self.loc(*path))

    # -- examples --------------------------------------------------------------------------
    def resolve_example(self, e: dict, path: tuple) -> Example:
        raw_hex = None
        if "hex" in e:
            digits = "".join(e["hex"].split())
            if len(digits) % 2:
                self.error(path + ("hex",), "hex has an odd number of digits")
            else:
                raw_hex = bytes.fromhex(digits)
        errors = []
        if "error" in e:
            errors.append(ExpectedError(e["error"]["field"], e["error"]["rule"]))
        for x in e.get("errors", []):
            errors.append(ExpectedError(x["field"], x["rule"], x["line"]))
        forms = [k for k in ("hex", "word", "text") if k in e]
        if not forms:
            self.error(path, "an example needs a wire form: hex, word or text")
        if "values" not in e and not errors and "sequence" not in path[0]:
            self.error(path, "an example needs `values` (or an expected `error`)")
        return Example(name=e.get("name", f"example {path[-1] + 1}"), loc=self.loc(*path),
                       values=e.get("values"), hex=raw_hex, word=e.get("word"), text=e.get("text"),
                       direction=e.get("direction"), decode_only=bool(e.get("decode_only")),
                       errors=tuple(errors), source=e.get("source"))

    # -- cross-message checks --------------------------------------------------------------
    def check_messages(self, messages: tuple[Message, ...], d: dict) -> None:
        names = {m.name for m in messages}
        for m in messages:
            for i, other in enumerate(m.answered_by):
                if other not in names:
                    self.error(("messages", m.name, "answered_by", i),
                               f"message {m.name!r} is answered by unknown message {other!r}")
        keyed = [m for m in messages if m.dispatch_key]
        if keyed and len(keyed) != len(messages):
            for m in messages:
                if not m.dispatch_key:
                    self.error(("messages", m.name), f"message {m.name!r} has no dispatch value, "
                                                     "but the others do", "give it its dispatch field(s)")
        framing = d["framing"]["kind"]
        offsets: dict[str, tuple[int, str]] = {}
        for m in keyed:
            for f in m.layout:
                if f.dispatch and f.bit_offset is not None and framing == "bits":
                    first = offsets.setdefault(f.name, (f.bit_offset, m.name))
                    if first[0] != f.bit_offset:
                        self.error(("messages", m.name), f"dispatch field {f.name!r} is at bit "
                                   f"{f.bit_offset} here but at bit {first[0]} in {first[1]!r}",
                                   "dispatch fields must sit at the same place in every message")
        if framing == "bits" and keyed and all(m.size for m in keyed):
            # the decoder reads the dispatch fields before it knows the message: every one
            # must lie inside the shortest message
            shortest = min(keyed, key=lambda m: m.size)
            for name, (offset, owner) in offsets.items():
                field = next(f for f in next(m for m in keyed if m.name == owner).layout if f.name == name)
                if offset + (field.bits or 0) > 8 * shortest.size:
                    self.error(("messages", owner), f"dispatch field {name!r} ends at bit "
                               f"{offset + (field.bits or 0)}, past the end of the shortest message "
                               f"{shortest.name!r} ({8 * shortest.size} bits)",
                               "put the dispatch fields first, where every message has them")
        if framing == "bits" and d["framing"].get("text_form"):
            for m in messages:
                for f in m.layout:
                    if f.bits and f.bits > 32:  # the C text-form reader holds 32-bit values
                        self.error(("messages", m.name), f"message {m.name!r}: field {f.name!r} has "
                                   f"{f.bits} bits; a text form carries values of at most 32 bits",
                                   "split the field, or drop text_form")
            if keyed:
                self.check_text_form_heads(keyed)
        if framing == "bytes":
            self.check_sizes_without_length(messages)
        for i, j in candidate_pairs(keyed, framing):
            a, b = keyed[i], keyed[j]
            if a.direction and b.direction and a.direction != b.direction:
                continue
            if self.ambiguous(a, b, framing):
                self.error(("messages", b.name),
                           f"ambiguous dispatch: messages {a.name!r} and {b.name!r} cannot be "
                           f"told apart ({self.describe_key(a)} / {self.describe_key(b)})",
                           "give them different ids/constants, directions or sizes")

    def check_text_form_heads(self, messages: list[Message]) -> None:
        """A text-form line is dispatched on the bits of its leading values that hold the
        dispatch fields: they must have the same widths in every message."""
        head = max((f.bit_offset + (f.bits or 0) for m in messages for f in m.layout
                    if f.dispatch and f.bit_offset is not None), default=0)
        if not head:
            return

        def widths(fields) -> list[int]:
            out, used = [], 0
            stack = list(reversed(fields))
            while stack and used < head:
                f = stack.pop()
                if f.kind == "group":
                    stack.extend(reversed(f.fields))
                elif f.bits:
                    out.append(f.bits)
                    used += f.bits
            return out

        first = messages[0]
        expected = widths(first.layout)
        for m in messages[1:]:
            got = widths(m.layout)
            if got != expected:
                self.error(("messages", m.name),
                           f"message {m.name!r}: its text form starts with values of {got} bits, "
                           f"{first.name!r}'s with {expected}; a text line is told apart by its first "
                           f"{head} bits, so the values that hold them must have the same widths in "
                           "every message", "start every message with fields of the same widths")

    def check_sizes_without_length(self, messages: list[Message]) -> None:
        """With no length field, a stream decoder knows a frame's size only from its id."""
        if any(f.length_of for m in messages for f in m.layout) or len({m.size for m in messages}) < 2:
            return
        size_of: dict = {}
        for m in messages:
            for value in m.ids or (None,):
                first = size_of.setdefault(value, m)
                if first.size != m.size:
                    self.error(("messages", m.name), f"message {m.name!r} is {m.size} bytes but {first.name!r}, "
                               f"with the same id, is {first.size}; with no length field a stream decoder "
                               "finds a frame's size from its id",
                               "give them different ids, or add a length field to the framing")
                    return

    @staticmethod
    def describe_key(m: Message) -> str:
        return ", ".join(f"{k}={v}" for k, v in m.dispatch_key) + (f", {m.size} bytes" if m.size else "")

    @staticmethod
    def ambiguous(a: Message, b: Message, framing: str) -> bool:
        ka, kb = dict(a.dispatch_key), dict(b.dispatch_key)
        if framing == "bits":
            common = set(ka) & set(kb)
            return all(ka[k] == kb[k] for k in common)
        overlap = all(set(ka[k]) & set(kb.get(k, ())) for k in ka)
        return overlap and (framing == "text" or a.size == b.size)

    # -- sequences -------------------------------------------------------------------------
    def resolve_sequence(self, name: str, s: dict, messages: tuple[Message, ...]) -> Sequence:
        path = ("sequences", name)
        self.check_name(name, path, "sequence")
        by_name = {m.name: m for m in messages}
        earlier: dict[str, Message] = {}
        self_identifying = all(m.dispatch_key for m in messages)

        def item(raw: dict, p: tuple) -> SequenceItem:
            self.check_name(raw["name"], p + ("name",), "sequence item")
            if "message" in raw and raw["message"] not in by_name:
                self.error(p + ("message",), f"sequence item {raw['name']!r}: unknown message "
                                             f"{raw['message']!r}")
            count = raw.get("count")
            if count is not None:
                head, _, field = count.partition(".")
                source = earlier.get(head)
                if source is None or self.find_path(source.layout, field) is None:
                    self.error(p + ("count",), f"count {count!r} must name a field of an earlier item",
                               "write item.field, e.g. header.h1")
            if raw.get("repeat") and count is not None:
                self.error(p, "give `repeat` or `count`, not both")
            if raw.get("repeat") and not self_identifying:
                self.error(p + ("repeat",), "`repeat` needs self-identifying messages (dispatch fields)",
                           "use `count` to say how many follow")
            children = tuple(item(c, p + ("items", i)) for i, c in enumerate(raw.get("items", [])))
            if raw.get("repeat") and children and all(c.may_take_nothing for c in children):
                # a pass that takes no message makes no progress: decoding would loop forever
                self.error(p + ("repeat",), f"sequence {name!r}: repeated group {raw['name']!r} can "
                                            "match no message at all (each of its items is a repeat, "
                                            "a count or such a group), so its repetitions never end",
                           "give the group an item taken exactly once (no `repeat` or `count`), "
                           "or drop `repeat` from the group")
            if "message" in raw and raw["message"] in by_name:
                earlier[raw["name"]] = by_name[raw["message"]]
            return SequenceItem(raw["name"], self.loc(*p), raw.get("message"), count,
                                bool(raw.get("repeat")), children, text(raw.get("doc")))

        items = tuple(item(r, path + ("items", i)) for i, r in enumerate(s["items"]))
        rules = []
        for i, r in enumerate(s.get("rules", [])):
            rp = path + ("rules", i)
            for key in ("path", "to", "of"):
                if key in r and not self.sequence_path_ok(items, by_name, r[key], whole=r["kind"] == "unique" and key == "path"):
                    self.error(rp + (key,), f"sequence rule: path {r[key]!r} does not name a field",
                               "walk item names to a field, e.g. scenes.scene.ns")
            needed = {"consecutive": "from", "equal": "to", "member": "of", "unique": "key"}[r["kind"]]
            if needed not in r:
                self.error(rp, f"a {r['kind']} rule needs `{needed}`")
            rules.append(SequenceRule(r.get("id"), r["kind"], r["path"], self.loc(*rp),
                                      r.get("from"), r.get("to"), r.get("of"),
                                      tuple(r.get("key", ())), text(r.get("message"))))
        examples = tuple(self.resolve_example(e, path + ("examples", i))
                         for i, e in enumerate(s.get("examples", [])))
        return Sequence(name, self.loc(*path), text(s.get("doc")), items, tuple(rules), examples)

    def sequence_path_ok(self, items: tuple[SequenceItem, ...], by_name: dict, dotted: str,
                         whole: bool) -> bool:
        parts = dotted.split(".")
        current = items
        for i, part in enumerate(parts):
            found = next((it for it in current if it.name == part), None)
            if found is None:
                return False
            if found.message:
                rest = ".".join(parts[i + 1:])
                if not rest:
                    return whole
                message = by_name.get(found.message)
                return message is not None and self.find_path(message.layout, rest) is not None
            current = found.items
        return whole

    # -- machines --------------------------------------------------------------------------
    def resolve_machine(self, name: str, m: dict, messages: tuple[Message, ...]) -> Machine:
        return MachineResolver(self, name, m, messages).resolve()

def resolve(doc: Document) -> Protocol:
    """Validate the structure, then resolve and check the meaning; raise SchemaError."""
    problems = structure_errors(doc)
    if problems:
        raise SchemaError(problems)
    return Resolver(doc).resolve()
