"""Enums, flag sets, scalar types and group types."""
from __future__ import annotations

from typing import Any, Optional

from ..model import Enum, EnumMember, FlagBit, FlagSet
from .text import text
from .base import ResolverBase, INT_TYPE, BASE_KINDS, MAX_INT_BITS


class TypesMixin(ResolverBase):
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
        if e.get("open") and kind == "char":
            self.error(path + ("open",), f"enum {name!r}: a char enum is closed (a character that is no "
                                         "member has no number to keep)", "drop `open`, or give it an integer type")
        return Enum(name, "char" if kind == "char" else "int", bits, tuple(members),
                    text(e.get("doc")), open=bool(e.get("open")) and kind != "char")

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

    def scalar_type(self, type_name: str, path: tuple) -> tuple[str, Optional[int]]:
        m = INT_TYPE.match(type_name)
        if m:
            bits = int(m.group(2))
            if not 1 <= bits <= MAX_INT_BITS:  # i1 holds -1 and 0 (DBC's one-bit signed signals)
                self.error(path, f"integer width {bits} is outside 1..{MAX_INT_BITS}",
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
