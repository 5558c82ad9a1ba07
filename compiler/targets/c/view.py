"""View of a protocol for the C target: C names and types, and the function
bodies the header template lays out. All decisions about generated C live
here; templates/c only arranges them.

Rules the generated code keeps (firmware on AVR and Cortex-M):
- byte-wise, endian-explicit access through codeword.h; no packed structs,
  no pointer casts;
- every shift on an unsigned type at least 16 bits wide, cast before shifting;
- no heap, no recursion, no VLAs; every identifier prefixed by the protocol.
"""
from __future__ import annotations

import math
import re
from dataclasses import dataclass
from fractions import Fraction
from typing import Any, Optional

from ... import binary32, binary64
from ...model import (Checksum, Field, Leaf, Message, Multiplex, Protocol, count_member, dotted, field_at,
                      presence_member, spelling_member, places_member, SPELLING_MAX)
from ..code import Code, times_over
from ..escape import c_char as cchar, c_comment as comment, c_string as cstr
from . import pack as cpack
from .crc import crc_code, methods_check
from . import repeats as crepeats
from . import word as cword
from . import wordform as cwordform
from .bitbytes import get_expression, put_statements, value_type
from .pack import Span
from .errors import CTargetError
from .scalars import SET_UNUSED, clit, clit_signed, final_step, int_ctype, sign_extend, type_limits, unsigned_type
from ..wire import (checksum_name, dispatch_facts, encoding_facts, gap_of, gap_reads, stream_facts, text_form_head,
                    text_line_facts, with_head_checks)

ERR = {
    "length": "CW_ERR_LENGTH", "const": "CW_ERR_CONST", "range": "CW_ERR_RANGE",
    "values": "CW_ERR_VALUES", "enum": "CW_ERR_ENUM", "flags": "CW_ERR_FLAGS",
    "exactly_one": "CW_ERR_EXACTLY_ONE", "one_hot": "CW_ERR_ONE_HOT",
    "checksum": "CW_ERR_CHECKSUM", "reserved": "CW_ERR_RESERVED", "dispatch": "CW_ERR_DISPATCH",
    "syntax": "CW_ERR_SYNTAX", "count": "CW_ERR_COUNT", "text": "CW_ERR_TEXT", "type": "CW_ERR_TYPE",
    "finite": "CW_ERR_FINITE", "terminator": "CW_ERR_TERMINATOR", "prefix": "CW_ERR_PREFIX",
    "rule": "CW_ERR_RULE", "precision": "CW_ERR_PRECISION", "grammar": "CW_ERR_GRAMMAR",
    "consecutive": "CW_ERR_CONSECUTIVE", "equal": "CW_ERR_EQUAL", "member": "CW_ERR_MEMBER",
    "unique": "CW_ERR_UNIQUE", "escape": "CW_ERR_ESCAPE", "delimiter": "CW_ERR_DELIMITER",
    "signature": "CW_ERR_SIGNATURE", "unsigned": "CW_ERR_UNSIGNED",
}

# How the text encoder writes a value of each kind ({v}: the member, {n}: a str's length,
# {lead}: the separator before it): the first value of a line, or any after a separator.
TEXT_WRITE_FIRST = {
    "float": "cw_write_decimal(&w, {v});", "char": "cw_write_char(&w, {v});",
    "str": "cw_write_text(&w, {v}, {n});", "i64": "cw_write_i64(&w, {v});", "u64": "cw_write_u64(&w, {v});",
    "int": "cw_write_int(&w, (int32_t){v});",
    "fixed": "cw_write_fixed(&w, (int32_t){v}, {decimals}u, {width}u);",
}
TEXT_WRITE_AFTER = {
    "float": "cw_write_decimal_field(&w, {lead}, &{v});", "char": "cw_write_text_field(&w, {lead}, &{v}, 1u);",
    "str": "cw_write_text_field(&w, {lead}, {v}, {n});", "i64": "cw_write_i64_field(&w, {lead}, {v});",
    "u64": "cw_write_u64_field(&w, {lead}, {v});", "int": "cw_write_int_field(&w, {lead}, (int32_t){v});",
}


@dataclass(frozen=True)
class Rep:
    """How a leaf is stored in the C struct."""

    ctype: str  # element type
    array: Optional[int] = None  # char/uint8_t array length
    has_flag: bool = False  # an extra `bool has_<name>` (optional / one-hot absent)
    lo: Optional[int] = None  # integer values the stored type must hold
    hi: Optional[int] = None


class CView:
    def __init__(self, protocol: Protocol):
        self.p = protocol
        self.px = protocol.name.lower()
        self.PX = protocol.name.upper()
        self.fr = protocol.framing
        self.text = self.fr.kind == "text"
        self.line = text_line_facts(protocol)

    # -- names ---------------------------------------------------------------------------
    def tname(self, m: Message) -> str:
        return f"{self.px}_{m.name}_t"

    def fn(self, m: Message, op: str) -> str:
        if (self.fr.encoding or self.fr.stuffing) and op in ("encode", "decode"):
            op += "_frame"  # the frame as the layout describes it; <msg>_encode/_decode stuff it
        return f"{self.px}_{m.name}_{op}"

    def upper(self, *parts: str) -> str:
        return "_".join([self.PX] + [p.upper() for p in parts])

    def member(self, leaf: Leaf, obj: str = "m") -> str:
        return f"{obj}->" + leaf.dotted

    def has(self, leaf: Leaf, obj: str = "m") -> str:
        path = list(leaf.path)
        name = max(i for i, p in enumerate(path) if isinstance(p, str))  # an array's flags are an array too
        path[name] = presence_member(path[name])
        return f"{obj}->" + dotted(tuple(path))

    def id_const(self, m: Message, i: int = 0) -> str:
        """The constant of a message's id (`<P>_<MSG>_ID`, or `_ID<i>` for one of several):
        an integer, or a text prefix as a string literal the text decoders compare with."""
        return self.upper(m.name, "ID") if len(m.ids) == 1 else self.upper(m.name, f"ID{i}")

    def id_literal(self, value: Any) -> str:
        return cstr(value) if isinstance(value, str) else f"{value}u"

    def enum_const(self, enum_name: str, member: str) -> str:
        return self.upper(enum_name, member)

    # -- representation ------------------------------------------------------------------
    def rep(self, f: Field) -> Rep:
        if f.kind == "bool":
            return Rep("bool")
        if f.kind == "char":
            return Rep("char", has_flag=f.optional)
        if f.kind == "str":
            return Rep("char", array=f.max_length + 1, has_flag=f.optional)
        if f.kind == "bytes":
            return Rep("uint8_t", array=f.length)
        if f.kind == "float":
            if self.text:
                return Rep("cw_decimal_t", has_flag=f.optional)
            return Rep("float" if f.bits == 32 else "cw_f64_t")
        if f.one_hot:
            lo, hi = f.range or (0, f.bits - 1)
            return Rep("uint8_t", has_flag=True, lo=int(lo), hi=int(hi))
        if f.enum is not None and f.enum.kind == "char":
            return Rep("char", has_flag=f.optional)
        lo, hi = self.stored_range(f)
        return Rep(int_ctype(lo, hi), has_flag=f.optional, lo=lo, hi=hi)

    def stored_range(self, f: Field) -> tuple[int, int]:
        """The integers the struct member holds: raw when scaled, else logical. Every value
        the wire type gives, whatever the range: widening a range keeps the C API."""
        raw = f.raw_range or (-(1 << 31), (1 << 31) - 1)
        off = int(f.offset or 0) if f.scale is None else 0
        return raw[0] + off, raw[1] + off

    @staticmethod
    def raw_bounds(f: Field) -> tuple[int, int]:
        """Bounds of the stored integer that the schema's range allows."""
        return f.range_bounds

    # -- declarations --------------------------------------------------------------------
    def struct_lines(self, fields: tuple[Field, ...], depth: int = 1) -> list[str]:
        pad = "    " * depth
        out: list[str] = []
        for f in fields:
            if not f.is_member:
                continue
            note = self.field_note(f)
            count = f"[{f.count}]" if f.count is not None else ""  # an array of the element
            if f.kind == "group":
                out.append(f"{pad}struct {{" + (f"  /* {note} */" if note else ""))
                out.extend(self.struct_lines(f.fields, depth + 1))
                out.append(f"{pad}}} {f.name}{count};")
            else:
                r = self.rep(f.element)
                if r.has_flag:
                    out.append(f"{pad}bool {presence_member(f.name)}{count};  /* {'0 = absent' if f.optional else '0 = no bit set'} */")
                arr = f"[{r.array}]" if r.array else ""
                out.append(f"{pad}{r.ctype} {f.name}{count}{arr};" + (f"  /* {note} */" if note else ""))
                if f.keep_spelling:
                    out.append(f"{pad}char {spelling_member(f.name)}{count}[{SPELLING_MAX + 1}];  /* the text it was read "
                               f"from, NUL-terminated (\"\": none); written back while it reads as the value */")
            if f.varies:
                most, what = (f.length, "bytes") if f.kind == "bytes" else (f.count, "elements")
                out.append(f"{pad}{unsigned_type(most.bit_length())} {count_member(f.name)};  "
                           f"/* {what} in use, 0..{most} */")
        return out

    @staticmethod
    def places_lines(m: Message) -> list[str]:
        """The member that keeps how many values a decoded line had, when it may vary."""
        if not m.keeps_places:
            return []
        tp = m.text_places
        return [f"    uint16_t {places_member()};  /* values of the line it was decoded from ({tp.least}..{tp.total}; "
                "0: none): written back with as many */"]

    def field_note(self, f: Field) -> str:
        parts = [comment(f.doc or f.title)] if (f.doc or f.title) else []
        if f.present_if or f.multiplexed_by:
            parts.append(comment(f"sent when {(f.present_if or f.multiplexed_by).says}"))
        if f.scale is not None:
            parts.append(f"raw: value = raw * {f.scale:g}" + (f" + {f.offset:g}" if f.offset else "")
                         + (f" {f.unit}" if f.unit else ""))
        elif f.unit:
            parts.append(f"[{f.unit}]")
        if f.range is not None:
            parts.append(f"range {f.range[0]:g}..{f.range[1]:g}")
        if f.enum is not None:
            parts.append(f"{self.upper(f.enum.name)}_*")
        if f.flags is not None:
            parts.append(f"mask of {self.upper(f.flags.name)}_*")
        if f.kind == "str":
            parts.append(f"NUL-terminated, at most {f.max_length} characters")
        if f.rule:
            parts.append(f"({f.rule})")
        return comment("; ".join(parts))

    # -- checks shared by binary and text decoders ----------------------------------------
    def range_cond(self, expr: str, lo: int, hi: int, ctype: str) -> Optional[str]:
        """`expr` outside lo..hi, leaving out comparisons the type makes always false."""
        tlo, thi = type_limits(ctype)
        unsigned = ctype.startswith("uint")
        parts = []
        literal = (lambda v: clit(v, True)) if unsigned else clit_signed
        if lo > tlo:
            parts.append(f"{expr} < {literal(lo)}")
        if hi < thi:
            parts.append(f"{expr} > {literal(hi)}")
        return " || ".join(parts) or None

    def value_literal(self, f: Field, value: Any) -> str:
        """A C expression for a schema-written value (enum names, flag lists, numbers)."""
        if value is None:
            return "0"
        if f.enum is not None:
            member = next((m for m in f.enum.members if value in (m.name, m.value)), None)
            if member is not None:
                return self.enum_const(f.enum.name, member.name)
        if f.flags is not None and isinstance(value, list):
            names = [self.upper(f.flags.name, n) for n in value]
            return "(" + " | ".join(names) + ")" if names else "0u"
        if isinstance(value, bool):
            return "true" if value else "false"
        if isinstance(value, str):
            return cchar(value) if len(value) == 1 else cstr(value)
        if f.scale is not None:
            return clit(int((Fraction(value) - Fraction(f.offset or 0)) / Fraction(f.scale)))
        return clit(int(value)) if float(value).is_integer() else repr(value)

    def condition(self, cond, obj: str, m: Message) -> str:
        f = field_at(m.layout, cond.path)
        left = f"{obj}->{cond.path}"
        leaf_has = f"{obj}->" + ".".join(cond.path.split(".")[:-1] + [presence_member(cond.path.split(".")[-1])])
        value = cond.value
        if cond.op in ("eq", "ne") and value is None:
            return f"!{leaf_has}" if cond.op == "eq" else leaf_has
        if f is not None and self.rep(f).ctype == "cw_f64_t":
            return self.f64_condition(cond.op, f"cw_f64_to_bits({left})", value)
        if f is not None and self.rep(f).ctype == "float" and cond.op == "range":
            return f"!({self.f32_outside(left, *value)})"
        if cond.op in ("eq", "ne"):
            if f is not None and f.kind == "bool":
                want = bool(value) == (cond.op == "eq")
                return left if want else f"!{left}"
            op = "==" if cond.op == "eq" else "!="
            return f"{left} {op} {self.value_literal(f, value)}"
        if cond.op == "in":
            return "(" + " || ".join(f"{left} == {self.value_literal(f, v)}" for v in value) + ")"
        if cond.op == "range":
            return f"({left} >= {self.value_literal(f, value[0])} && {left} <= {self.value_literal(f, value[1])})"
        raise CTargetError(f"condition {cond.op} is for state machines")

    def f64_condition(self, op: str, bits: str, value: Any) -> str:
        """A rule's condition on an f64 member, on its bits (`bits`): no double arithmetic,
        which a 32-bit double could not do, and the values compared exactly, as Python does."""
        if op == "range":
            return f"!({self.f64_outside(bits, *value)})"
        if op == "in":
            return "(" + " || ".join(self.f64_condition("eq", bits, x) for x in value) + ")"
        if binary64.at_most(value) != value:  # no double holds it
            return "false" if op == "eq" else "true"
        return f"cw_f64_order({bits}) {'==' if op == 'eq' else '!='} {clit(binary64.order_of(value), True)}"

    @staticmethod
    def f64_outside(bits: str, lo: Any, hi: Any) -> str:
        """`bits` (a finite binary64) outside [lo, hi]; the bounds are the nearest
        doubles inside, compared in cw_f64_order."""
        low, high = binary64.at_least(lo), binary64.at_most(hi)
        parts = []
        if low > -binary64.LARGEST:
            parts.append(f"cw_f64_order({bits}) < {clit(binary64.order_of(low), True)} /* {low!r} */")
        if high < binary64.LARGEST:
            parts.append(f"cw_f64_order({bits}) > {clit(binary64.order_of(high), True)} /* {high!r} */")
        return " || ".join(parts) or "false"

    @staticmethod
    def f32_outside(v: str, lo: Any, hi: Any) -> str:
        """The float `v` (finite) outside [lo, hi], compared exactly as Python compares
        the decoded value: the bounds are the nearest floats inside, float literals."""
        low, high = binary32.at_least(lo), binary32.at_most(hi)
        if low == math.inf or high == -math.inf:  # no float lies inside
            return "true"
        parts = []
        if low > -binary32.LARGEST:
            parts.append(f"{v} < {binary32.literal(low)}")
        if high < binary32.LARGEST:
            parts.append(f"{v} > {binary32.literal(high)}")
        return " || ".join(parts) or "false"

    def rule_checks(self, c: Code, m: Message, obj: str) -> None:
        for rule in m.rules:
            need = " && ".join(self.condition(x, obj, m) for x in rule.require)
            when = " && ".join(self.condition(x, obj, m) for x in rule.when)
            cond = f"({when}) && !({need})" if when else f"!({need})"
            c(f"if ({cond}) {{  /* {comment(rule.id or 'rule')}: {comment(rule.message or '')} */")
            c("    return CW_ERR_RULE;")
            c("}")

    # -- encode side: struct member -> checked raw wire value -----------------------------
    def encode_leaf(self, c: Code, leaf: Leaf, raw: str, rt: str = "uint32_t") -> None:
        """Check the member of `leaf` and store its raw wire value in `raw` (of type `rt`)."""
        f = leaf.field

        def store(expr: str) -> None:
            c(f"{raw} = {expr};" if rt == "uint32_t" else f"{raw} = ({rt})({expr});")

        def store_member() -> None:
            c(f"{raw} = ({rt}){self.member(leaf)};")

        def store_signed(value: str = "") -> None:  # two's complement cut to the field's bits
            value = value or v
            if f.bits == 16 and rt == "uint16_t":
                c(f"{raw} = (uint16_t){value};")  # modular: no 32-bit arithmetic
            elif f.bits < 16 and rt != "uint32_t":
                store(f"(uint16_t){value} & {clit((1 << f.bits) - 1, True)}")
            elif f.bits > 32:
                store(f"(uint64_t)(int64_t){value} & (uint64_t){clit((1 << f.bits) - 1, True)}")
            else:
                store(f"(uint32_t)(int32_t){value} & {clit((1 << f.bits) - 1, True)}")

        if f.checksum or f.reserved:
            c(f"{raw} = 0u;")
            return
        if f.length_of or f.const is not None:
            value = f.const
            if f.enum is not None:
                value = next(x.value for x in f.enum.members if f.const in (x.name, x.value))
            c(f"{raw} = {clit(self.wire_bits(f, value), True)};")
            return
        v = self.member(leaf)
        r = self.rep(f)
        if f.kind == "bool":
            c(f"{raw} = ({rt}){v};")  # a bool is 0 or 1
        elif f.kind == "float" and f.bits == 64 and not f.finite:  # NaN sent as the quiet NaN
            c(f"{raw} = cw_f64_canonical(cw_f64_to_bits({v}));")
        elif f.kind == "float" and f.bits == 64:  # raw values of a message with one are uint64_t
            c(f"{raw} = cw_f64_to_bits({v});")
            self.fail_if(c, f"!cw_f64_bits_finite({raw})", "finite")
            if f.range is not None:
                self.fail_if(c, self.f64_outside(raw, *f.range), "range")
        elif f.kind == "float" and not f.finite:
            store(f"cw_f32_canonical(cw_f32_to_bits({v}))")
        elif f.kind == "float":
            store(f"cw_f32_to_bits({v})")
            c(f"if (!cw_f32_bits_finite({raw if rt == 'uint32_t' else f'(uint32_t){raw}'})) {{")
            c("    return CW_ERR_FINITE;")
            c("}")
            if f.range is not None:
                self.fail_if(c, self.f32_outside(v, *f.range), "range")
        elif f.kind == "bytes":
            return
        elif f.one_hot:
            c(f"if ({self.has(leaf)}) {{")
            cond = self.range_cond(v, r.lo, r.hi, r.ctype)
            if cond:
                c(f"    if ({cond}) {{")
                c("        return CW_ERR_RANGE;")
                c("    }")
            one = "(uint64_t)1u" if f.bits > 32 else "(uint32_t)1u"
            c(f"    {raw} = " + (f"{one} << {v};" if rt == "uint32_t" else f"({rt})({one} << {v});"))
            c("} else {")
            c(f"    {raw} = 0u;")
            c("}")
        elif f.closed_enum:
            self.member_check(c, f, v, "enum")
            if f.kind == "int":
                store_signed()
            else:
                store_member()
        elif f.flags is not None:
            self.member_check(c, f, v, "flags")
            store_member()
        else:
            self.member_check(c, f, v, "int")
            if f.kind == "int" and f.offset and f.scale is None:  # the raw value is value - offset
                store_signed(f"({self.offset_type(f)})((int64_t){v} - {clit_signed(int(f.offset))})")
            elif f.kind == "int":
                store_signed()
            elif f.offset and f.scale is None and f.offset < 0:  # the raw value is value - offset
                store(f"({unsigned_type(max(f.bits, 32))})((int64_t){v} - {clit_signed(int(f.offset))})")
            elif f.offset and f.scale is None:
                store(f"({unsigned_type(max(f.bits, 32))})({v} - {clit(int(f.offset))})")
            else:
                store_member()

    @staticmethod
    def offset_type(f: Field) -> str:
        """The signed type a raw value of `f` fits in (value - offset of a signed field)."""
        return "int32_t" if f.bits <= 31 else "int64_t"

    def member_check(self, c: Code, f: Field, v: str, what: str) -> None:
        """Checks of an integer-like member (enum, flags, plain) before it is sent."""
        r = self.rep(f)
        if what == "enum":
            cond = self.enum_cond(v, [x.value for x in f.enum.members], r.ctype)
            if cond:
                c(f"if ({cond}) {{")
                c("    return CW_ERR_ENUM;")
                c("}")
        elif what == "flags":
            outside = ~f.flags.mask & ((1 << f.bits) - 1)
            if outside:
                c(f"if (({v} & {clit(outside, True)}) != 0u) {{")
                c("    return CW_ERR_FLAGS;")
                c("}")
            if f.exactly_one:
                c(f"if ({v} == 0u || ({v} & ({v} - 1u)) != 0u) {{")
                c("    return CW_ERR_EXACTLY_ONE;")
                c("}")
            return
        else:
            lo, hi = self.int_bounds(f)
            cond = self.range_cond(v, lo, hi, r.ctype)
            if cond:
                c(f"if ({cond}) {{")
                c("    return CW_ERR_RANGE;")
                c("}")
        if f.values:
            allowed = [self.enum_wire(f, x) for x in f.values]
            cond = " && ".join(f"{v} != {self.literal_of(x, r.ctype)}" for x in allowed)
            c(f"if ({cond}) {{")
            c("    return CW_ERR_VALUES;")
            c("}")

    def enum_cond(self, v: str, values: list, ctype: str) -> Optional[str]:
        """`v` (of C type `ctype`) is none of the enum's values."""
        span = enum_span(values)
        if span:  # one range test instead of a test per member
            return self.range_cond(v, span[0], span[1], ctype)
        return " && ".join(f"{v} != {self.literal_of(x, ctype)}" for x in values)

    def int_bounds(self, f: Field) -> tuple[int, int]:
        """The values of a plain integer member that member_check lets through
        (together with its C type's limits)."""
        lo, hi = self.raw_bounds(f) if f.range is not None else self.stored_range(f)
        if f.range is None and f.raw_range and f.scale is None:
            lo, hi = f.raw_range[0] + int(f.offset or 0), f.raw_range[1] + int(f.offset or 0)
        return lo, hi

    @staticmethod
    def wire_bits(f: Field, value: Any) -> int:
        """The raw bits of a fixed value: a signed integer in two's complement, a float as
        its IEEE 754 bit pattern."""
        if f.kind == "float":
            return binary32.bits_of(value) if f.bits == 32 else binary64.bits_of(value)
        return int(value) & ((1 << f.bits) - 1) if f.kind == "int" and f.bits else int(value)

    @staticmethod
    def enum_wire(f: Field, value: Any) -> Any:
        if f.enum is None:
            return value
        return next((x.value for x in f.enum.members if value in (x.name, x.value)), value)

    @staticmethod
    def literal_of(value: Any, ctype: str) -> str:
        if isinstance(value, str):
            return cchar(value)
        return clit(int(value), True) if ctype.startswith("uint") else clit_signed(int(value))

    # -- decode side: raw wire value -> checks -> struct member -----------------------------
    def decode_leaf(self, c: Code, leaf: Leaf, raw: str, m: Message, rt: str = "uint32_t") -> None:
        """Check the raw value (of the message's raw type `rt`) in Python's order and store the member."""
        f = leaf.field
        if rt == "uint64_t" and f.bits and f.bits <= 32:  # for the 32-bit helpers
            raw = f"(uint32_t){raw}"
        if f.reserved:
            self.fail_if(c, f"{raw} != 0u", "reserved")
            return
        if f.length_of:
            self.fail_if(c, f"{raw} != {clit(int(f.const), True)}", "length")
            return
        if f.checksum or f.counts:  # a count is checked against the frame's size by decode
            return
        if f.const is not None and not f.values:
            value = self.enum_wire(f, f.const)
            self.fail_if(c, f"{raw} != {clit(self.wire_bits(f, value), True)}", "const")
            return
        v = self.member(leaf)
        r = self.rep(f)
        if f.kind == "bool":
            c(f"{v} = {raw} != 0u;")
            return
        if f.kind == "bytes":
            return
        if f.kind == "float" and f.bits == 64:
            if f.finite:
                self.fail_if(c, f"!cw_f64_bits_finite({raw})", "finite")
            c(f"{v} = cw_f64_from_bits({raw if f.finite else f'cw_f64_canonical({raw})'});")  # any NaN as the quiet one
            if f.range is not None:
                self.fail_if(c, self.f64_outside(raw, *f.range), "range")
            return
        if f.kind == "float":
            if f.finite:
                self.fail_if(c, f"!cw_f32_bits_finite({raw})", "finite")
            c(f"{v} = cw_f32_from_bits({raw if f.finite else f'cw_f32_canonical({raw})'});")  # any NaN as the quiet one
            if f.range is not None:
                self.fail_if(c, self.f32_outside(v, *f.range), "range")
            return
        # a signed field's raw bits are two's complement: its enum is tested once sign-extended
        if f.closed_enum and f.kind != "int":
            span = enum_span([x.value for x in f.enum.members])
            if span and span[0] >= 0:  # the raw value has f.bits bits: test only the ends it can pass
                cond = " || ".join(([f"{raw} < {clit(span[0], True)}"] if span[0] > 0 else [])
                                   + ([f"{raw} > {clit(span[1], True)}"] if span[1] < (1 << f.bits) - 1 else []))
            else:
                cond = " && ".join(f"{raw} != {clit(int(x.value), True)}" for x in f.enum.members)
            if cond:
                self.fail_if(c, cond, "enum")
        elif f.flags is not None:
            outside = ~f.flags.mask & ((1 << f.bits) - 1)
            if outside:
                self.fail_if(c, f"({raw} & {clit(outside, True)}) != 0u", "flags")
            if f.exactly_one:
                self.fail_if(c, f"{raw} == 0u || ({raw} & ({raw} - 1u)) != 0u", "exactly_one")
            c(f"{v} = ({r.ctype}){raw};")
            return
        elif f.one_hot:
            self.fail_if(c, f"({raw} & ({raw} - 1u)) != 0u || ({raw} != 0u && ({raw} < {clit(1 << r.lo, True)} || {raw} > {clit(1 << r.hi, True)}))", "one_hot")
            c(f"{self.has(leaf)} = {raw} != 0u;")
            c(f"{v} = cw_bit_index({raw});")
            return
        # expr: the logical value; a sum is parenthesised before a cast applies to it
        if f.kind == "int" and f.offset and f.scale is None:  # value = raw + offset, in signed arithmetic
            expr = f"((int64_t){sign_extend(f.bits)}({raw}, {f.bits}u) + {clit_signed(int(f.offset))})"
        elif f.kind == "int" and f.bits <= 16 and r.ctype in ("int8_t", "int16_t"):
            expr = f"cw_sign_extend16((uint16_t){raw}, {f.bits}u)"
        elif f.kind == "int":
            expr = f"{sign_extend(f.bits)}({raw}, {f.bits}u)"
        elif f.offset and f.scale is None and f.offset < 0:  # may go below zero: signed arithmetic
            expr = f"((int64_t){raw} + {clit_signed(int(f.offset))})"
        elif f.offset and f.scale is None:
            total = f"(uint64_t){raw}" if r.ctype == "uint64_t" else raw  # no wrap in a narrower raw type
            expr = f"({total} + {clit(int(f.offset), True)})"
        else:
            expr = raw
        c(f"{v} = ({r.ctype}){expr};")  # the member holds every value of the wire type
        if f.closed_enum and f.kind == "int":
            cond = self.enum_cond(v, [x.value for x in f.enum.members], r.ctype)
            if cond:
                self.fail_if(c, cond, "enum")
        if f.range is not None and f.enum is None:
            lo, hi = self.raw_bounds(f)
            cond = self.range_cond(v, lo, hi, r.ctype)
            if cond:
                self.fail_if(c, cond, "range")
        if f.values:
            allowed = [self.enum_wire(f, x) for x in f.values]
            self.fail_if(c, " && ".join(f"{v} != {self.literal_of(x, r.ctype)}" for x in allowed), "values")

    @staticmethod
    def fail_if(c: Code, cond: str, kind: str) -> None:
        c(f"if ({cond}) {{")
        c(f"    return {ERR[kind]};")
        c("}")

    # -- byte layout -----------------------------------------------------------------------
    def order_of(self, f: Field) -> str:
        return f.byte_order or self.fr.byte_order

    @staticmethod
    def int_put(start: int, size: int, order: str, value: str) -> str:
        """A statement writing the integer `value` to buf[start..start+size);
        `order` is "big" or "little"."""
        value = value if re.fullmatch(r"[\w\[\]]+", value) else f"({value})"
        if size == 1:
            return f"buf[{start}] = (uint8_t){value};"
        cast = f"uint{8 * size}_t" if size in (2, 4) else "uint64_t" if size > 4 else "uint32_t"
        return CView.int_access("put", start, size, order, f"({cast}){value}") + ";"

    @staticmethod
    def int_get(start: int, size: int, order: str) -> str:
        """An unsigned expression reading buf[start..start+size)."""
        return f"buf[{start}]" if size == 1 else CView.int_access("get", start, size, order)

    @staticmethod
    def int_access(verb: str, start: int, size: int, order: str, value: Optional[str] = None) -> str:
        """The call of the codeword.h helper that gets or puts `size` bytes in `order`."""
        o = "le" if order == "little" else "be"
        name = f"cw_{verb}_{o}{8 * size}" if size in (2, 4) else f"cw_{verb}_{o}_wide" if size > 4 else f"cw_{verb}_{o}"
        args = [f"buf + {start}"] + ([] if size in (2, 4) else [f"{size}u"]) + ([value] if value else [])
        return f"{name}({', '.join(args)})"

    @staticmethod
    def spans(m: Message) -> list[Span]:
        """The spans written one by one: the elements of a Repeat are written in its loop."""
        return cpack.spans(m.wire.unrepeated_runs())

    # -- checksums ----------------------------------------------------------------------------
    def checksum_fn(self, cs: Checksum) -> str:
        return f"{self.px}_{checksum_name(cs)}"

    def field_checksum(self, leaf: Leaf, others: list[str], rt: str = "uint32_t") -> str:
        """The checksum of the other raw values, as an `rt`; arithmetic in 32 bits
        (the first operand cast) so that narrow operands never promote to int,
        or in `unsigned` (16 bits on 8-bit targets) when the modulo is a power
        of two that divides 2**16: wrapping there keeps the sum's residue."""
        cs = leaf.field.checksum
        small = cs.algorithm in ("sum", "xor") and cs.modulo & (cs.modulo - 1) == 0 and cs.modulo <= 1 << 16
        wide = [("(unsigned)" if small else "(uint64_t)" if rt == "uint64_t" else "(uint32_t)") + others[0]] + others[1:]
        if cs.algorithm in ("sum", "xor"):
            op = " + " if cs.algorithm == "sum" else " ^ "
            return f"({rt})(({op.join(wide)}) % {clit(cs.modulo, True)})"
        flip = " ^ 1u" if cs.parity == "odd" else ""
        parity = "cw_parity64" if rt == "uint64_t" else "cw_parity32"
        return f"({rt})({parity}({' ^ '.join(wide)}){flip})"

    def has_crc(self) -> bool:
        """Whether the header computes a CRC, so that its CRC method macros mean something."""
        return any(leaf.field.checksum and leaf.field.checksum.algorithm == "crc"
                   for m in self.p.messages for leaf in m.wire.leaves)

    def byte_checksums(self) -> list[str]:
        seen: dict[str, str] = {}
        crcs = False  # a header with CRCs refuses two methods at once
        for m in self.p.messages:
            for leaf in m.wire.leaves:
                cs = leaf.field.checksum
                if cs and cs.over == "bytes" and checksum_name(cs) not in seen:  # one function each
                    seen[checksum_name(cs)] = checksum_code(self.checksum_fn(cs), cs, self.PX)
                    crcs = crcs or cs.algorithm == "crc"
        return ([methods_check(self.PX)] if crcs else []) + list(seen.values())

    def byte_checksum_call(self, leaf: Leaf, m: Message, cut: bool = False, sent: str = "buf") -> str:
        """The checksum of its coverage; `cut`: the coverage ends with the payload, `cut` bytes
        early, in the bytes sent (`sent`)."""
        cs = leaf.field.checksum
        start, end = cs.byte_span
        extra = f", {clit(m.crc_extra, True)}" if cs.extra else ""
        less = " - cut" if cut and m.counts_sent(cs) else ""
        return f"{self.checksum_fn(cs)}({sent if less else 'buf'} + {start}, {end - start}u{less}{extra})"

    # -- binary messages -----------------------------------------------------------------------
    @staticmethod
    def is_byte_checksum(leaf: Leaf) -> bool:
        cs = leaf.field.checksum
        return bool(cs) and cs.over == "bytes"

    def wired(self, m: Message) -> tuple[list[Leaf], dict[str, str]]:
        """Leaves with wire bits outside the Repeats (whose elements have functions of their own),
        and the r[] slot of each integer leaf (byte checksums have none: they are computed on the bytes)."""
        wired = [leaf for leaf in m.wire.leaves if leaf.bits and m.wire.repeat_of(leaf) is None]
        slots = [leaf for leaf in wired if leaf.field.kind != "bytes" and not self.is_byte_checksum(leaf)]
        return wired, {leaf.var: f"r[{i}]" for i, leaf in enumerate(slots)}

    def raw_type(self, m: Message) -> str:
        """The narrowest unsigned type that holds every raw value of `m`."""
        wired, raws = self.wired(m)
        widest = max([leaf.field.bits for leaf in wired if leaf.var in raws] + [1])
        return unsigned_type(widest)

    def raw_function(self, m: Message) -> str:
        """<msg>_raw(m, r): checks a message and fills r[] with its raw wire values."""
        c = Code()
        wired, raws = self.wired(m)
        rt = self.raw_type(m)
        c(f"static inline int {self.fn(m, 'raw')}(const {self.tname(m)} *m, {rt} *r)")
        c("{")
        c.indent()
        if not m.rules and not any(leaf.field.is_member and leaf.var in raws for leaf in wired):
            c("(void)m;")  # bytes fields are copied by encode itself
        if not raws:
            c("(void)r;")
        self.rule_checks(c, m, "m")
        gaps = m.shortening.gaps if m.shortening else ()
        for gap in gaps:
            if gap.counter:
                self.fail_if(c, f"m->{count_member(gap.field)} > {gap.counter.most}u", "range")
        counts = {g.control: g for g in gaps if g.counter}
        for leaf in wired:
            if leaf.var not in raws:
                continue
            if leaf.field.counts:  # set from the array's count
                counter = counts[leaf.field.name].counter
                count = f"(uint32_t)m->{count_member(counter.field)}"
                if counter.element_step != 1:  # the elements must fill whole units
                    self.fail_if(c, f"{count} % {counter.element_step}u != 0u", "range")
                c(f"{raws[leaf.var]} = ({rt})({times_over(count, counter.element_bytes, counter.unit, '/', 'u')});")
                continue
            guard = self.sent_guard(m, leaf, raws)
            if guard is None:
                self.encode_leaf(c, leaf, raws[leaf.var], rt)
                continue
            c(f"if ({guard}) {{")
            c.indent()
            self.encode_leaf(c, leaf, raws[leaf.var], rt)
            c.dedent()
            c("} else {")
            c(f"    {raws[leaf.var]} = 0u;")
            c("}")
        for leaf in wired:
            cs = leaf.field.checksum
            if cs and cs.over != "bytes":
                others = [raws[x.var] for x in wired if x is not leaf and x.var in raws]
                c(f"{raws[leaf.var]} = {self.field_checksum(leaf, others, rt)};")
        c("return CW_OK;")
        c.dedent()
        c("}")
        return c.text()

    def presence_test(self, m: Message, gap, value: Optional[str] = None) -> str:
        """Whether conditional `gap` is sent, from its control field's raw value (`value`, by
        default its r[] slot)."""
        cond = gap.presence
        leaf = next(x for x in m.wire.leaves if x.path == (gap.control,))
        value = value or self.wired(m)[1][leaf.var]
        full = cond.mask == (1 << leaf.bits) - 1
        tested = value if full else f"({value} & {clit(cond.mask, True)})"
        return " || ".join(f"{tested} == {clit(v, True)}" for v in cond.values)

    @staticmethod
    def multiplex_test(m: Message, mux: Multiplex, raws: dict[str, str]) -> str:
        """Whether a multiplexed field is in the frame, from its multiplexors' raw values."""
        tests = []
        for x in mux.chain:
            r = raws[next(leaf.var for leaf in m.wire.leaves if leaf.path == (x.field,))]
            one = [f"{r} == {clit(lo, True)}" if lo == hi and lo is not None else
                   f"({r} >= {clit(lo, True)} && {r} <= {clit(hi, True)})" if lo is not None and hi is not None else
                   f"{r} >= {clit(lo, True)}" if lo is not None else f"{r} <= {clit(hi, True)}" if hi is not None
                   else "" for lo, hi in x.bounds]
            if "" not in one:  # a range of every value the multiplexor holds tests nothing
                tests.append(one[0] if len(one) == 1 else f"({' || '.join(one)})")
        return " && ".join(tests) or "1"

    def sent_guard(self, m: Message, leaf: Leaf, raws: dict[str, str]) -> Optional[str]:
        """The condition under which a leaf in a gap, or a multiplexed one, is in the frame
        (None: always, or all of a counted bytes field)."""
        if leaf.field.multiplexed_by:
            return self.multiplex_test(m, leaf.field.multiplexed_by, raws)
        gap = gap_of(m, leaf)
        if gap is None:
            return None
        if gap.presence:
            return self.presence_test(m, gap)
        return f"m->{count_member(gap.field)} > {leaf.path[1]}u" if len(leaf.path) > 1 else None

    def pack_value(self, span: Span, raws: dict[str, str]) -> str:
        """The integer of a "pack" span, from the raw values of its pieces
        (a checksum over bytes has none: its bits stay 0 until its bytes are written)."""
        wide = "unsigned" if span.size <= 2 else "uint32_t"  # unsigned: at least 16 bits
        parts = []
        for piece in span.pieces:
            if piece.var not in raws:
                continue
            mask = clit((1 << piece.bits) - 1, True)
            term = f"(({wide}){raws[piece.var]} & {mask})"
            shift = span.shift(piece)
            parts.append(f"({term} << {shift})" if shift else term)
        return " | ".join(parts) or "0u"

    def byte_sums(self, layout: list[Span]) -> list[tuple[Span, Leaf]]:
        """The checksums over bytes, in wire order: the order the encoder fills them in."""
        return [(span, piece) for span in layout for piece in span.pieces
                if self.is_byte_checksum(piece)]

    def encode_function(self, m: Message) -> str:
        word = cword.container(self, m)
        if word is not None:
            return cword.encode_function(self, m, word)
        c = Code()
        wired, raws = self.wired(m)
        layout = self.spans(m)
        c(f"static inline int {self.fn(m, 'encode')}(const {self.tname(m)} *m, uint8_t *buf, size_t cap)")
        c("{")
        c.indent()
        rt = self.raw_type(m)
        c(f"{rt} r[{max(1, len(raws))}] = {{0}};  /* every value is set by raw; compilers cannot always tell */")
        c(f"int rc = {self.fn(m, 'raw')}(m, r);")
        c("if (rc != CW_OK) {")
        c("    return rc;")
        c("}")
        sh = m.shortening
        truncates = bool(sh and (sh.trailing_zeros or sh.gaps))
        if truncates:
            c("size_t cut = 0u;")
        c(f"if (cap < {m.size}u) {{")
        c("    return CW_ERR_CAPACITY;")
        c("}")
        for span in layout:
            leaf = span.pieces[0]
            if span.kind == "int" and self.is_byte_checksum(leaf):
                moved_up = truncates and span.start >= sh.payload[1]  # moved up before it is filled in
                if moved_up or leaf.field.checksum.covers_self:  # counted as zero while computed
                    c(f"memset(buf + {span.start}, 0, {span.size}u);")
                continue  # written once the bytes it covers are
            self.put_span(c, span, raws, rt)
        crepeats.encode_loops(self, c, m)
        if truncates and sh.gaps:
            self.leave_out_gaps(c, m, raws)
        elif truncates:
            self.truncate(c, m)
        end = sh.payload[1] if truncates else m.size
        for span, piece in self.byte_sums(layout):
            call = self.byte_checksum_call(piece, m, truncates)
            moved = span.start >= end  # it follows the bytes left out
            if span.kind == "int":
                c(self.int_put(f"({span.start}u - cut)" if moved else span.start, span.size, self.order_of(piece.field), call))
            else:  # sharing its bytes, whose bits for it are still 0
                vt = value_type(piece.bits)
                c("{")
                c(f"    {vt} sum = ({vt}){call};")
                for line in put_statements("buf", piece.pos, piece.bits, span.order_of(piece), "sum", vt, moved):
                    c(f"    {line}")
                c("}")
        c(f"return (int)({m.size}u - cut);" if truncates else f"return {m.size};")
        c.dedent()
        c("}")
        return c.text()

    def put_span(self, c: Code, span: Span, raws: dict[str, str], rt: str) -> None:
        """Write a span of values (no checksum over bytes) from their raw values."""
        leaf = span.pieces[0]
        if span.kind == "bytes":
            c(f"memcpy(buf + {span.start}, {self.member(leaf)}, {leaf.field.length});")
        elif span.kind == "int":
            c(self.int_put(span.start, span.size, self.order_of(leaf.field), raws[leaf.var]))
        elif span.kind == "pack":
            c(self.int_put(span.start, span.size, span.order, self.pack_value(span, raws)))
        else:
            c(f"memset(buf + {span.start}, 0, {span.size}u);")
            for piece in span.pieces:
                if piece.var in raws:
                    for line in put_statements("buf", piece.pos, piece.bits, span.order_of(piece), raws[piece.var], rt):
                        c(line)

    def get_span(self, c: Code, span: Span, raws: dict[str, str], rt: str) -> None:
        """Read the raw values of a span (bytes fields are copied by the checks)."""
        leaf = span.pieces[0]
        pieces = [piece for piece in span.pieces if piece.var in raws]
        if span.kind == "bytes" or not pieces:
            return
        if span.kind == "int":
            c(f"{raws[leaf.var]} = ({rt}){self.int_get(span.start, span.size, self.order_of(leaf.field))};")
        elif span.kind == "pack":
            wide = "unsigned" if span.size <= 2 else "uint32_t"
            c("{")
            c(f"    {wide} word = {self.int_get(span.start, span.size, span.order)};")
            for piece in pieces:
                shift = span.shift(piece)
                value = f"(word >> {shift})" if shift else "word"
                c(f"    {raws[piece.var]} = ({rt})({value} & {clit((1 << piece.bits) - 1, True)});")
            c("}")
        else:
            for piece in pieces:
                value = get_expression("buf", piece.pos, piece.bits, span.order_of(piece))
                c(f"{raws[piece.var]} = {value if value_type(piece.bits) == rt else f'({rt}){value}'};")

    def leave_out_gaps(self, c: Code, m: Message, raws: dict[str, str]) -> None:
        """Drop the bytes of each gap that the frame does not send, the last gap first so the
        places of the earlier ones hold; a length field counts the payload bytes sent."""
        gaps = m.shortening.gaps
        for k, gap in enumerate(gaps):
            if gap.counter:
                per = gap.counter.element_bytes
                c(f"size_t lost{k} = (size_t)({gap.counter.most}u - m->{count_member(gap.field)}) * {per}u;")
            else:
                c(f"size_t lost{k} = ({self.presence_test(m, gap)}) ? 0u : {gap.size}u;")
        for k, gap in reversed(list(enumerate(gaps))):
            end = gap.span[1]
            c(f"memmove(buf + ({end}u - lost{k}), buf + {end}, {m.size - end}u - cut);")
            c(f"cut += lost{k};")
        if m.shortening.length_field:
            self.set_length(c, m)

    def truncate(self, c: Code, m: Message) -> None:
        """Count the payload's trailing zero bytes the frame leaves off (keeping the
        fewest it must carry), and set the length field to the bytes sent."""
        sh = m.shortening
        lo, hi = sh.payload[0] + sh.least, sh.payload[1]
        c(f"while (cut < {hi - lo}u && buf[{hi - 1}u - cut] == 0u) {{  /* trailing zeros are not sent */")
        c("    cut++;")
        c("}")
        c(f"memmove(buf + ({hi}u - cut), buf + {hi}, {m.size - hi}u);")
        self.set_length(c, m)

    def set_length(self, c: Code, m: Message) -> None:
        """The length field counts the payload bytes sent."""
        leaf = next(x for x in m.wire.leaves if x.field.name == m.shortening.length_field)
        c(self.int_put(leaf.pos // 8, leaf.bits // 8, self.order_of(leaf.field), f"{clit(int(leaf.field.const), True)} - cut"))

    def sums_sent(self, m: Message) -> bool:
        """Whether a checksum covers the bytes a frame cut short sends."""
        return any(self.is_byte_checksum(x) and m.counts_sent(x.field.checksum) for x in m.wire.leaves)

    def uses_cut(self, m: Message) -> bool:
        """Whether a decoder needs the bytes a frame left out: to restore a payload cut at its
        end, or for a length field or a checksum that counts what was sent."""
        return not m.shortening.gaps or bool(m.shortening.length_field) or self.sums_sent(m)

    def restore(self, c: Code, m: Message) -> None:
        """A frame cut short becomes the whole frame: the payload bytes left off read as zeros,
        and the length field as if they had been sent."""
        size, end = m.size, m.shortening.payload[1]
        c(f"if (len < {m.min_size}u || len > {size}u) {{")
        c("    return CW_ERR_LENGTH;")
        c("}")
        if self.uses_cut(m):
            c(f"cut = {size}u - len;")
        if m.shortening.gaps:
            self.restore_gaps(c, m)
        else:
            c(f"memcpy(full, buf, {end}u - cut);")
            c(f"memset(full + ({end}u - cut), 0, cut);")
            c(f"memcpy(full + {end}, buf + ({end}u - cut), {size - end}u);")
        c("buf = full;")

    def restore_gaps(self, c: Code, m: Message) -> None:
        """Read each gap's control field from the bytes sent, check it, and copy the frame into
        `full` with the bytes it leaves out as zeros."""
        gaps, lost = m.shortening.gaps, ""
        for k, (gap, read) in enumerate(zip(gaps, gap_reads(self.p, m))):
            if k:  # the shortest frame holds what comes before the first gap
                self.fail_if(c, f"len < {gap.span[0]}u{lost}", "length")
            if gap.fills_rest:  # the last gap: what the frame holds past the fields before it
                self.take_rest(c, m, k, gap, lost)
                lost += f" - lost{k}"
                continue
            less = "".join(f" - lost{j}" for j in read["before"])
            getter = "cw_get_le" if read["byte_order"] == "little" else "cw_get_be"
            value = f"{getter}(buf + ({read['at']}u{less}), {read['bytes']}u)" if read["bytes"] > 1 \
                else f"buf[{read['at']}u{less}]"
            if read["shift"]:
                value = f"({value} >> {read['shift']})"
            whole = not read["shift"] and read["mask"] == (1 << (8 * read["bytes"])) - 1
            value = f"(size_t){value}" if whole else f"((size_t){value} & {clit(read['mask'], True)})"
            if gap.counter:
                counter = gap.counter
                c(f"n = {value};")
                self.fail_if(c, f"n > {counter.most_value}u", "range")
                if counter.step != 1:  # its bytes must hold whole elements
                    self.fail_if(c, f"n % {counter.step}u != 0u", "length")
                c(f"m->{count_member(gap.field)} = ({unsigned_type(counter.most.bit_length())})"
                  f"({times_over('n', counter.unit, counter.element_bytes, '/', 'u')});")
                c(f"size_t lost{k} = {counter.most * counter.element_bytes}u - n * {counter.unit}u;")
            else:
                c(f"size_t lost{k} = ({self.presence_test(m, gap, value)}) ? 0u : {gap.size}u;")
            lost += f" - lost{k}"
        self.fail_if(c, f"len != {m.size}u{lost}", "length")
        at, sent = 0, "0u"
        for k, gap in enumerate(gaps):
            kept = f"{gap.span[1]}u - lost{k}"
            c(f"memcpy(full + {at}, buf + {sent}, {kept} - {at}u);" if at else f"memcpy(full, buf, {kept});")
            c(f"memset(full + ({kept}), 0, lost{k});")
            sent = f"({gap.span[1]}u{''.join(f' - lost{j}' for j in range(k + 1))})"
            at = gap.span[1]
        c(f"memcpy(full + {at}, buf + {sent}, {m.size - at}u);")

    def take_rest(self, c: Code, m: Message, k: int, gap, lost: str) -> None:
        """A field filling the rest of the payload: the frame's size says how much of it was
        sent, whole elements up to its most."""
        counter = gap.counter
        self.fail_if(c, f"len > {m.size}u{lost}", "length")
        c(f"size_t lost{k} = {m.size}u{lost} - len;")
        self.fail_if(c, f"lost{k} > {gap.size}u || ({gap.size}u - lost{k}) % {counter.element_bytes}u != 0u", "length")
        c(f"m->{count_member(gap.field)} = ({unsigned_type(counter.most.bit_length())})"
          f"(({gap.size}u - lost{k}) / {counter.element_bytes}u);")

    def decode_function(self, m: Message) -> str:
        word = cword.container(self, m)
        if word is not None:
            return cword.decode_function(self, m, word)
        c = Code()
        wired, raws = self.wired(m)
        rt = self.raw_type(m)
        layout = self.spans(m)
        c(f"static inline int {self.fn(m, 'decode')}(const uint8_t *buf, size_t len, {self.tname(m)} *m)")
        c("{")
        c.indent()
        if raws:
            c(f"{rt} r[{len(raws)}];")
        else:  # nothing to read, but check_raw takes the array: initialised, so no compiler warns
            c(f"{rt} r[1] = {{0}};")
        if m.shortening:
            c(f"uint8_t full[{m.size}];")
            if self.sums_sent(m):
                c("const uint8_t *sent = buf;  /* the bytes sent, which checksums cover */")
            if self.uses_cut(m):
                c("size_t cut;")
            if any(g.counter and g.control for g in m.shortening.gaps):
                c("size_t n;")
            self.restore(c, m)
        else:
            c(f"if (len != {m.size}u) {{")
            c("    return CW_ERR_LENGTH;")
            c("}")
        shift, pad = m.padding()  # always under 8 bits: the padding fills the last byte
        if pad:
            self.fail_if(c, f"(buf[{m.size - 1}] & {clit(((1 << pad) - 1) << shift, True)}) != 0u", "reserved")
        for span in layout:  # check_raw copies bytes; checksums over bytes are checked below
            self.get_span(c, span, raws, rt)
        if m.shortening and m.shortening.length_field:
            counter = next(x for x in m.wire.leaves if x.field.name == m.shortening.length_field)
            c(f"{raws[counter.var]} = ({rt})({raws[counter.var]} + cut);  /* as if the whole payload were sent */")
        for span, piece in self.byte_sums(layout):
            if span.kind == "int":
                got = self.int_get(span.start, span.size, self.order_of(piece.field))
            else:
                got = get_expression("buf", piece.pos, piece.bits, span.order_of(piece))
            if piece.field.checksum.covers_self:  # RFC 1071's receiver check: with the field, the sum is all ones
                self.fail_if(c, f"{self.byte_checksum_call(piece, m, True, 'sent')} != 0u", "checksum")
                continue
            self.fail_if(c, f"{got} != {self.byte_checksum_call(piece, m, True, 'sent')}", "checksum")
        c(f"return {self.fn(m, 'check_raw')}(r, buf, m, false);")
        c.dedent()
        c("}")
        return c.text()

    def check_raw_function(self, m: Message) -> str:
        """<msg>_check_raw(r, buf, m, text_form): field checks on raw values, in
        Python's order; shared by the binary and the text-form decoders."""
        c = Code()
        wired, raws = self.wired(m)
        rt = self.raw_type(m)
        c(f"static inline int {self.fn(m, 'check_raw')}(const {rt} *r, const uint8_t *buf, "
          f"{self.tname(m)} *m, bool text_form)")
        c("{")
        c.indent()
        uses_buf = any(leaf.field.kind == "bytes" for leaf in wired) or bool(m.wire.repeats)
        unfilled = self.fr.text_form.checksum_unfilled if self.fr.text_form else None
        field_sums = [leaf for leaf in wired if leaf.field.checksum and leaf.field.checksum.over != "bytes"]
        if not uses_buf:
            c("(void)buf;")
        if not raws:
            c("(void)r;")
        if not m.members:
            c(SET_UNUSED)
        if unfilled is None or not field_sums:
            c("(void)text_form;")
        looped = {r.field.name: r for r in m.wire.repeats}
        own = {id(leaf) for leaf in wired}
        for leaf in m.wire.leaves:
            if leaf.path[0] in looped and len(leaf.path) > 1:  # checked in the order of the fields
                crepeats.decode_loop(self, c, m, looped.pop(leaf.path[0]))
            if id(leaf) not in own:
                continue
            guard = self.sent_guard(m, leaf, raws)
            if leaf.field.kind == "bytes":
                c(f"memcpy({self.member(leaf)}, buf + {leaf.pos // 8}, {leaf.field.length});")
            elif leaf.var in raws and guard and leaf.field.is_member:  # a value left out is zero, unchecked
                body = Code()
                body.depth = c.depth + 1
                self.decode_leaf(body, leaf, raws[leaf.var], m, rt)
                # a gap's bytes read as 0, which stays 0; a multiplexed field's bits may hold another's
                if not any("return" in line for line in body.lines) and not leaf.field.offset \
                        and not leaf.field.multiplexed_by:
                    self.decode_leaf(c, leaf, raws[leaf.var], m, rt)
                    continue
                c(f"if ({guard}) {{")
                c.lines.extend(body.lines)
                c("} else {")
                c(f"    memset(&{self.member(leaf)}, 0, sizeof {self.member(leaf)});")
                c("}")
            elif leaf.var in raws:
                self.decode_leaf(c, leaf, raws[leaf.var], m, rt)
        for leaf in field_sums:
            others = [raws[x.var] for x in wired if x is not leaf and x.var in raws]
            cond = f"{raws[leaf.var]} != {self.field_checksum(leaf, others, rt)}"
            if unfilled is not None:
                cond = f"{cond} && !(text_form && {raws[leaf.var]} == {clit(unfilled, True)})"
            self.fail_if(c, cond, "checksum")
        self.rule_checks(c, m, "m")
        c("return CW_OK;")
        c.dedent()
        c("}")
        return c.text()

    # -- physical units of scaled fields ----------------------------------------------------------
    def unit_helpers(self, m: Message) -> list[dict]:
        out = []
        for leaf in m.wire.leaves:
            f = leaf.field
            if f.scale is None or not f.is_member or any(isinstance(p, int) for p in leaf.path):
                continue  # an array's elements are set as its element type, without helpers
            lo, hi = f.range if f.range is not None else (
                f.raw_range[0] * f.scale + (f.offset or 0), f.raw_range[1] * f.scale + (f.offset or 0))
            out.append({"name": "_".join(leaf.path), "path": leaf.dotted, "ctype": self.rep(f).ctype,
                        "scale": repr(float(f.scale)), "offset": repr(float(f.offset or 0)),
                        "lo": repr(float(lo)), "hi": repr(float(hi)), "unit": comment(f.unit or "units")})
        return out


    # -- words (bit-packed protocols) -------------------------------------------------------------
    def word_bits(self) -> Optional[int]:
        return self.fr.word_bits or self.fr.max_bits

    def word_functions(self, m: Message) -> str:
        """<msg>_to_word / <msg>_from_word: the message left-aligned in a word."""
        return cwordform.word_functions(self, m)

    # -- text form of a bit-packed protocol (a line of decimal raw values) ------------------------
    def max_text_form(self, m: Message) -> int:
        """Longest text form line of `m`, without the NUL: each raw value at its width's
        largest, in decimal, and the separators between them."""
        wired, raws = self.wired(m)
        widths = [leaf.field.bits for leaf in wired if leaf.var in raws]
        return sum(len(str((1 << bits) - 1)) for bits in widths) + \
            max(0, len(widths) - 1) * len(self.fr.text_form.separator)

    def text_form_functions(self, m: Message) -> str:
        tf = self.fr.text_form
        c = Code()
        wired, raws = self.wired(m)
        n = len(raws)
        c(f"/* {m.name} as a text line: its {n} raw values in decimal, separated by {tf.separator!r}; "
          f"at most {self.upper(m.name, 'MAX_TEXT_FORM')} - 1 chars and a NUL. */")
        c(f"static inline int {self.fn(m, 'to_text')}(const {self.tname(m)} *m, char *buf, size_t cap)")
        c("{")
        c.indent()
        c(f"{self.raw_type(m)} r[{max(1, n)}] = {{0}};  /* every value is set by raw; compilers cannot always tell */")
        c("cw_writer_t w;")
        c("uint8_t i;")
        c(f"int rc = {self.fn(m, 'raw')}(m, r);")
        c("if (rc != CW_OK) {")
        c("    return rc;")
        c("}")
        c("cw_writer_init(&w, buf, cap);")
        c(f"for (i = 0; i < {n}u; i++) {{")
        c("    if (i) {")
        c(f"        cw_write_char(&w, {cchar(tf.separator)});")
        c("    }")
        if max([leaf.field.bits for leaf in wired if leaf.var in raws] + [1]) >= 32:
            c("    cw_write_u64(&w, (uint64_t)r[i]);")  # raw values are unsigned
        else:
            c("    cw_write_int(&w, (int32_t)r[i]);")
        c("}")
        c("return cw_writer_finish(&w);")
        c.dedent()
        c("}")
        c("")
        c(f"static inline int {self.fn(m, 'from_values')}(const uint64_t *v, size_t count, {self.tname(m)} *m)")
        c("{")
        c.indent()
        rt = self.raw_type(m)
        c(f"{rt} r[{max(1, n)}];")
        c("size_t i;")
        self.fail_if(c, f"count != {n}u", "count")
        for leaf in wired:
            if leaf.var in raws:
                self.fail_if(c, f"{raws[leaf.var].replace('r[', 'v[')} > {clit((1 << leaf.field.bits) - 1, True)}", "range")
        c(f"for (i = 0; i < {n}u; i++) {{  /* every value fits its field, so it fits the raw type */")
        c(f"    r[i] = ({rt})v[i];")
        c("}")
        c(f"return {self.fn(m, 'check_raw')}(r, NULL, m, true);")
        c.dedent()
        c("}")
        return c.text()

    def text_form_facts(self) -> dict:
        """How the leading raw values give the dispatch head (as the Python decoder):
        per value, the statement that shifts its bits in."""
        steps, used = [], 0
        for i, (take, drop) in enumerate(text_form_head(self.p)):
            bits = (f"(uint32_t)((v[{i}] >> {drop}u) & {clit((1 << take) - 1, True)})" if drop
                    else f"(uint32_t)(v[{i}] & {clit((1 << take) - 1, True)})")
            shifted = "0u" if take == 32 else f"(uint32_t)(head << {take})"  # all 32 bits: nothing kept
            steps.append({"index": i, "present": f"head = {shifted} | {bits};", "absent": f"head = {shifted};"})
            used += take
        return {"steps": steps, "used": used, "pad": self.dispatch()["head_bits"] - used,
                "max_values": max(len(self.wired(m)[1]) for m in self.p.messages)}

    # -- text protocols ----------------------------------------------------------------------------
    def max_text(self, m: Message) -> int:
        """Longest line the encoder writes, without the NUL."""
        fr = self.fr
        n = len(fr.start) + len(m.ids[0]) + len(fr.prefix_separator) + len(fr.terminator)
        if fr.line_checksum:
            n += len(fr.line_checksum.suffix) + 2
        if m.prefix_field is not None:
            n += m.prefix_field.length
        leaves = self.body_leaves(m)
        n += max(0, len(leaves) - 1) * len(fr.separator)
        for leaf in leaves:
            f = leaf.field
            if f.kind == "float":
                n += 26
            elif f.kind == "char":
                n += 1
            elif f.kind == "str":
                n += f.max_length
            elif f.fixed_spelling:
                n += max(12, f.width or 0)
            else:
                n += 11
            if f.keep_spelling:  # as received: up to its bound
                n += max(0, SPELLING_MAX - (26 if f.kind == "float" else max(12, f.width or 0) if f.fixed_spelling else 11))
        return n

    def text_encode_function(self, m: Message) -> str:
        """<msg>_encode: every check first, in Python's order, then the line. The
        prefix separator leads the first value and a separator each next one, so
        each value costs one capacity check."""
        fr = self.fr
        c = Code()
        c(f"static inline int {self.fn(m, 'encode')}(const {self.tname(m)} *m, char *buf, size_t cap)")
        c("{")
        c.indent()
        c("cw_writer_t w;")
        leaves = self.body_leaves(m)
        pf = m.prefix_field
        for leaf in leaves:
            if leaf.field.kind == "str" and leaf.field.const is None:  # a constant is written as spelt
                c(f"size_t {self.text_len(leaf)} = 0;")
            if leaf.field.keep_spelling:
                c(f"size_t {self.spelling_len(leaf)} = 0;")
        if all(leaf.field.const is not None for leaf in leaves) and not m.rules:
            c("(void)m;  /* no member: the line is written from the schema */")
        self.rule_checks(c, m, "m")
        if pf is not None:  # written before the id
            self.fail_if(c, f"cw_text_len(m->{pf.name}, {pf.length + 1}u) != {pf.length}u", "length")
            self.prefix_check(c, pf, f"m->{pf.name}")
        places = m.text_places
        if m.keeps_places:
            c(f"size_t places = {places.written}u;  /* the values written whatever they hold */")
        for leaf in leaves:
            self.text_check(c, leaf)
        for n in range(places.least, len(leaves) - 1):  # an absent str is left out, never written empty
            if leaves[n].field.kind == "str" and leaves[n].field.const is None:
                later = self.any_written(leaves[n + 1:])
                self.fail_if(c, f"!{self.has(leaves[n])} && ({later})", "count")
        if m.keeps_places:  # as many values as the line it was decoded from, if it was
            c(f"if ({'(size_t)' + self.places(m) + f' >= {places.least}u && ' if places.least else ''}"
              f"(size_t){self.places(m)} <= {places.total}u) {{")
            c(f"    places = (size_t){self.places(m)};")
            c("}")
            for n in range(places.least, len(leaves)):  # the line ends before an absent str
                if leaves[n].field.kind == "str" and leaves[n].field.const is None:
                    c(f"if (!{self.has(leaves[n])} && places > {n}u) {{")
                    c(f"    places = {n}u;")
                    c("}")
        head = fr.start + m.ids[0] + fr.prefix_separator
        lead_first = bool(leaves) and not leaves[0].field.optional and len(fr.prefix_separator) == 1
        if lead_first:
            head = head[:-len(fr.prefix_separator)]
        c("cw_writer_init(&w, buf, cap);")
        if pf is not None:
            if fr.start:
                c(f"cw_write_text(&w, {cstr(fr.start)}, {len(fr.start)}u);")
            c(f"cw_write_text(&w, m->{pf.name}, {pf.length}u);")
            head = head[len(fr.start):]
        if head:
            c(f"cw_write_text(&w, {cstr(head)}, {len(head)}u);")
        for i, leaf in enumerate(leaves):
            f = leaf.field
            v = self.member(leaf)
            mark = fr.separator if i else fr.prefix_separator
            led = i > 0 or lead_first  # else the head holds what leads the first value
            if f.const is not None:
                text = (mark if led else "") + self.text_const(f)
                c(f"cw_write_text(&w, {cstr(text)}, {len(text)}u);  /* const */")
                continue
            slot = f.optional and led  # absent: its separator alone
            if m.keeps_places and i >= places.least:
                place = f"places > {i}u || {self.any_written(leaves[i:])}"
            elif i >= places.written:
                place = self.any_written(leaves[i:])
            else:
                place = "true"
            ends_run = place not in ("true", self.has(leaf))  # the last value: written when present
            if ends_run:  # at the end, only while a later value is present (or the kept line had it)
                c(f"if ({place}) {{")
                c.indent()
            if f.optional:
                c(f"if ({self.has(leaf)}) {{")
                c.indent()
            kind = f.kind if f.kind in ("float", "char", "str") else self.text_int64(f) or "int"
            if f.fixed_spelling:
                kind = "fixed"
            if led and (len(mark) > 1 or kind == "fixed"):  # the mark on its own, then the value
                c(f"cw_write_text(&w, {cstr(mark)}, {len(mark)}u);")
                led = False
            if f.keep_spelling:  # as received, while it reads as the member's value
                if led:
                    c(f"cw_write_text(&w, {cstr(mark)}, {len(mark)}u);")
                    led = False
                kept = self.spelling(leaf)
                c(f"if ({self.spelled(leaf, kind)}) {{")
                c(f"    cw_write_text(&w, {kept}, {self.spelling_len(leaf)});")
                c("} else {")
                c.indent()
            spelling = (TEXT_WRITE_AFTER if led else TEXT_WRITE_FIRST)[kind]
            c(spelling.format(v=v, n=self.text_len(leaf), lead=cchar(mark) if led else "",
                              decimals=f.decimals or 0, width=f.width or 0))
            if f.keep_spelling:
                c.dedent()
                c("}")
            if f.optional:
                c.dedent()
                if slot and place != self.has(leaf):  # else never absent here
                    c("} else {")
                    c(f"    cw_write_text(&w, {cstr(mark)}, {len(mark)}u);")
                c("}")
            if ends_run:
                c.dedent()
                c("}")
        if self.line["simple"]:
            c(f"return cw_writer_end(&w, {cchar(fr.terminator)});")
        else:
            cs = self.line["checksum"]
            algorithm = {"xor": "CW_LINE_XOR", "sum": "CW_LINE_SUM", None: "CW_LINE_PLAIN"}[cs and cs["algorithm"]]
            suffix = cs["suffix"] if cs else ""
            c(f"return cw_writer_end_line(&w, {len(fr.start)}u, {cstr(suffix)}, {len(suffix)}u, "
              f"{cstr(fr.terminator)}, {len(fr.terminator)}u, {algorithm});")
        c.dedent()
        c("}")
        return c.text()

    def any_written(self, leaves) -> str:
        """The condition that one of these values is written: a constant always is."""
        if any(x.field.const is not None for x in leaves):
            return "true"
        return " || ".join(self.has(x) for x in leaves)

    @staticmethod
    def text_const(f: Field) -> str:
        """A constant as its writer spells it in a text line."""
        value = f.const
        if f.enum is not None:
            value = next(m.value for m in f.enum.members if f.const in (m.name, m.value))
        return str(int(value)) if isinstance(value, (int, float)) and not isinstance(value, bool) else str(value)

    @staticmethod
    def places(m: Message, obj: str = "m") -> str:
        """The member keeping how many values a decoded line had."""
        return f"{obj}->{places_member()}"

    def spelling(self, leaf: Leaf) -> str:
        """The member holding the text a kept-spelling number was read from."""
        return "m->" + spelling_member(leaf.dotted)

    @staticmethod
    def spelling_len(leaf: Leaf) -> str:
        """The local holding a kept spelling's length, measured once by its check."""
        return f"{leaf.var}_spelling_len"

    def spelled(self, leaf: Leaf, kind: str) -> str:
        """The condition that the kept spelling reads as the member's value."""
        f, v, s, n = leaf.field, self.member(leaf), self.spelling(leaf), self.spelling_len(leaf)
        if kind == "fixed":
            return f"cw_spelled_fixed({s}, {n}, {f.decimals or 0}u, (int32_t){v})"
        if kind == "float":
            return f"cw_spelled_decimal({s}, {n}, &{v})"
        if kind in ("i64", "u64"):
            return f"cw_spelled_{kind}({s}, {n}, {v})"
        return f"cw_spelled_int({s}, {n}, (int32_t){v})"

    @staticmethod
    def text_len(leaf: Leaf) -> str:
        """The local holding a str member's length, measured once by its check."""
        return f"{leaf.var}_len"

    def text_check(self, c: Code, leaf: Leaf) -> None:
        f = leaf.field
        if f.const is not None:  # written from the schema, not from the struct
            return
        v = self.member(leaf)
        r = self.rep(f)
        fr = self.fr
        if f.optional:
            c(f"if ({self.has(leaf)}) {{")
            c.indent()
        if f.kind == "float":
            c("{")
            c(f"    int decimal_rc = cw_decimal_check(&{v});")
            c("    if (decimal_rc != CW_OK) {")
            c("        return decimal_rc;")
            c("    }")
            c("}")
        elif f.kind == "char" and f.enum is not None:
            self.member_check(c, f, v, "enum")
        elif f.kind == "char":
            self.fail_if(c, "!" + self.text_ok(f"&{v}", "1u", f.to_end, fr.trim), "text")
        elif f.kind == "str":
            n = self.text_len(leaf)
            c(f"{n} = cw_text_len({v}, {r.array}u);")
            self.fail_if(c, f"{n} > {f.max_length}u", "length")
            self.fail_if(c, "!" + self.text_ok(v, n, f.to_end, fr.trim), "text")
        elif f.closed_enum:
            self.member_check(c, f, v, "enum")
        else:  # an open enum's value is any integer of its width
            self.member_check(c, f, v, "int")
        if f.keep_spelling:  # a spelling without its NUL within the bound is no spelling received
            n = self.spelling_len(leaf)
            c(f"{n} = cw_text_len({self.spelling(leaf)}, {SPELLING_MAX + 1}u);")
            self.fail_if(c, f"{n} > {SPELLING_MAX}u", "length")
        if f.optional:
            c.dedent()
            c("}")

    def text_ok(self, s: str, n: str, to_end: bool, trim: bool) -> str:
        """The call that tells whether a value may be written (and so read): printable
        ASCII without a character of the terminator or, unless it runs to the end, of
        the separator."""
        fr = self.fr
        if self.line["simple"]:
            sep = "'\\0'" if to_end else cchar(fr.separator)
            return f"cw_text_ok({s}, {n}, {sep}, {cchar(fr.terminator)}, {str(trim).lower()})"
        banned = "".join(sorted(ch for ch in set(fr.terminator + ("" if to_end else fr.separator)) if " " <= ch <= "~"))
        return f"cw_text_ok_set({s}, {n}, {cstr(banned)}, {str(trim).lower()})"

    def text_ascii(self) -> bool:
        """Whether every character the framing, the prefixes and the char enums
        accept is 7-bit ASCII. Then a message that reads well is ASCII throughout
        (its readers accept no other byte), and the check for a byte above 0x7F,
        Python's first, is needed only on the way to another error."""
        chars = self.fr.prefix_separator + self.fr.separator + self.fr.terminator + self.fr.ignore_between
        chars += self.fr.start + (self.fr.line_checksum.suffix if self.fr.line_checksum else "")
        chars += "".join(x for m in self.p.messages for x in m.ids if isinstance(x, str))
        chars += "".join(str(x.value) for e in self.p.enums if e.kind == "char" for x in e.members)
        return all(ord(ch) < 0x80 for ch in chars)

    def text_body_function(self, m: Message) -> str:
        """<msg>_parse_body: the fields between prefix and terminator, checked in Python's order.
        One pass over the body finds where every value ends; each value is then trimmed
        and read once. Bytes above 0x7F are left to the caller (see text_ascii)."""
        fr = self.fr
        c = Code()
        leaves = self.body_leaves(m)
        total = len(leaves)
        required = m.text_places.least  # a line may end after this many values
        last_to_end = bool(leaves) and leaves[-1].field.to_end
        trim = str(fr.trim).lower()
        c(f"static inline int {self.fn(m, 'parse_body')}(const char *s, const char *end, {self.tname(m)} *m)")
        c("{")
        c.indent()
        if total == 0:
            c(SET_UNUSED)
            c("cw_trim(&s, &end);")
            self.fail_if(c, "s != end", "count")
            c("return CW_OK;")
            c.dedent()
            c("}")
            return c.text()
        c(f"const char *ends[{total}] = {{NULL}};  /* where each value ends: cw_value (set for old compilers that cannot tell) */")
        c("cw_span_t v = {NULL, NULL};  /* read only where a value was found; compilers cannot always tell */")
        if all(x.field.const is not None for x in leaves) and not m.rules:
            c("(void)m;  /* no member: every value is a constant */")
        if any(x.field.kind not in ("char", "str") and x.field.const is None for x in leaves):
            c("int rc;")
        if total == 1 and last_to_end and required == 1:
            c("ends[0] = end;  /* the one value runs to the end */")
        else:
            to_end = 'true' if last_to_end else 'false'
            if len(fr.separator) == 1:
                split = f"cw_split_values(s, end, {cchar(fr.separator)}, ends, {total}u, {to_end})"
            else:
                split = f"cw_split_marked(s, end, {cstr(fr.separator)}, {len(fr.separator)}u, ends, {total}u, {to_end})"
            if not required:  # every value optional: an empty body holds none (not one empty value)
                split = f"s == end ? 0u : {split}"
            c(f"size_t count = {split};")
            if required == total and not last_to_end:
                self.fail_if(c, f"count != {total}u", "count")
            else:
                conds = ([f"count < {required}u"] if required > 1 else []) + ([] if last_to_end else [f"count > {total}u"])
                if conds:
                    self.fail_if(c, " || ".join(conds), "count")
            if m.keeps_places:  # written back with as many
                c(f"{self.places(m)} = (uint16_t)count;")
        for i, leaf in enumerate(leaves):
            f = leaf.field
            t = self.member(leaf)
            r = self.rep(f)
            c(f"/* {leaf.dotted} */")
            if f.const is not None:
                if f.optional:  # or be empty, or be missing at the end of the line
                    c(f"if (count > {i}u && (v = {self.value_call(i, trim)}, v.b != v.e)) {{")
                    c.indent()
                else:
                    c(f"v = {self.value_call(i, trim)};")
                self.text_const_check(c, f)
                if f.optional:
                    c.dedent()
                    c("}")
                continue
            if f.keep_spelling:
                c(f"{self.spelling(leaf)}[0] = '\\0';")
            if f.optional and f.kind != "str":  # an empty value is an absent one
                c(f"{self.has(leaf)} = false;")
                c(f"if (count > {i}u) {{")
                c(f"    v = {self.value_call(i, trim)};")
                c(f"    {self.has(leaf)} = v.b != v.e;")
                c("}")
                c(f"if ({self.has(leaf)}) {{")
                c.indent()
            elif f.optional:
                c(f"{self.has(leaf)} = count > {i}u;")
                c(f"if ({self.has(leaf)}) {{")
                c.indent()
            if not f.optional or f.kind == "str":
                c(f"v = {self.value_call(i, trim)};")
            if f.keep_spelling:  # kept whole, never cut short
                self.fail_if(c, f"(size_t)(v.e - v.b) > {SPELLING_MAX}u", "length")
            if f.kind == "float":
                c(f"rc = cw_read_decimal(v.b, v.e, &{t});")
                c("if (rc != CW_OK) {")
                c("    return rc;")
                c("}")
            elif f.kind == "char":
                self.fail_if(c, "v.e - v.b != 1", "type")
                if f.enum is None:  # split at separators and trimmed: left to check are the characters and the terminator
                    self.fail_if(c, "!" + self.text_read_ok("1u", f.to_end), "text")
                else:
                    self.fail_if(c, " && ".join(f"*v.b != {cchar(x.value)}" for x in f.enum.members), "enum")
                c(f"{t} = *v.b;")
            elif f.kind == "str":
                # split at separators (a to_end value may hold them) and trimmed: left to check are the characters and the terminator
                self.fail_if(c, "!" + self.text_read_ok("(size_t)(v.e - v.b)", f.to_end), "text")
                self.fail_if(c, f"(size_t)(v.e - v.b) > {f.max_length}u", "length")
                c(f"memcpy({t}, v.b, (size_t)(v.e - v.b));")
                c(f"{t}[v.e - v.b] = '\\0';")
            else:
                c("{")
                c.indent()
                fixed = f.fixed_spelling
                wide = None if fixed else self.text_int64(f)
                vtype = {"i64": "int64_t", "u64": "uint64_t", None: "int32_t"}[wide]
                # each value is set where the parser succeeds: older compilers cannot always tell
                if fixed:  # any spelling, rounded to the field's decimals (the resolver keeps it within 32 bits)
                    c("int32_t value = 0;")
                    lo, hi = self.raw_bounds(f) if f.range is not None else (-(1 << 31), (1 << 31) - 1)
                    c(f"rc = cw_parse_fixed(v.b, v.e, {f.decimals or 0}u, "
                      f"{clit(lo) if lo > -(1 << 31) else 'INT32_MIN'}, {clit(hi) if hi < (1 << 31) - 1 else 'INT32_MAX'}, &value);")
                elif wide:  # parsed straight into the field's own range
                    c(f"{vtype} value = 0;")
                    lo, hi = self.raw_bounds(f) if f.range is not None else self.stored_range(f)
                    c(f"rc = cw_parse_{wide}(v.b, v.e, {self.literal_of(lo, vtype)}, {self.literal_of(hi, vtype)}, &value);")
                else:
                    c("int32_t value = 0;")
                    if f.enum is not None or f.range is None:
                        lo, hi = (-(1 << 31), (1 << 31) - 1)
                    else:
                        lo, hi = self.raw_bounds(f)
                    c(f"rc = cw_parse_int(v.b, v.e, {clit(lo) if lo > -(1 << 31) else 'INT32_MIN'}, {clit(hi) if hi < (1 << 31) - 1 else 'INT32_MAX'}, &value);")
                if f.closed_enum:
                    c("if (rc == CW_ERR_RANGE) {")
                    c("    return CW_ERR_ENUM;")
                    c("}")
                c("if (rc != CW_OK) {")
                c("    return rc;")
                c("}")
                if f.closed_enum:
                    self.fail_if(c, " && ".join(f"value != {clit(int(x.value))}" for x in f.enum.members), "enum")
                elif f.range is None and not wide:
                    cond = self.range_cond("value", *self.stored_range(f), "int32_t")
                    if cond:
                        self.fail_if(c, cond, "range")
                if f.values:
                    allowed = [self.enum_wire(f, x) for x in f.values]
                    self.fail_if(c, " && ".join(f"value != {self.literal_of(x, vtype)}" for x in allowed), "values")
                c(f"{t} = ({r.ctype})value;")
                c.dedent()
                c("}")
            if f.keep_spelling:
                c(f"memcpy({self.spelling(leaf)}, v.b, (size_t)(v.e - v.b));")
                c(f"{self.spelling(leaf)}[v.e - v.b] = '\\0';")
            if f.optional:
                c.dedent()
                c("}")
        self.rule_checks(c, m, "m")
        c("return CW_OK;")
        c.dedent()
        c("}")
        return c.text()

    @staticmethod
    def body_leaves(m: Message) -> tuple[Leaf, ...]:
        """The values of a line's body: all but the prefix field."""
        return tuple(leaf for leaf in m.wire.leaves if not leaf.field.prefix)

    def prefix_check(self, c: Code, pf: Field, s: str) -> None:
        """A prefix field's value: uppercase letters, one of its values if listed."""
        self.fail_if(c, f"!cw_upper_letters({s}, {pf.length}u)", "text")
        if pf.values:
            self.fail_if(c, " && ".join(f"memcmp({s}, {cstr(v)}, {pf.length}u) != 0" for v in pf.values), "values")

    def parse_call(self, m: Message, obj: str = "m") -> str:
        """The call that reads a line's values once dispatch found the message: the prefix
        field's value (before the id) first, then the body."""
        if m.prefix_field is None:
            return f"{self.fn(m, 'parse_body')}(body, end, {obj})"
        return f"{self.fn(m, 'parse_prefixed')}(pb, body, end, {obj})"

    def text_prefix_function(self, m: Message) -> str:
        """<msg>_parse_prefixed: the prefix field's value, the characters before the id
        (dispatch found the id after them), then the body."""
        pf = m.prefix_field
        c = Code()
        c(f"static inline int {self.fn(m, 'parse_prefixed')}(const char *pb, const char *body, const char *end, "
          f"{self.tname(m)} *m)")
        c("{")
        c.indent()
        self.prefix_check(c, pf, "pb")
        c(f"memcpy(m->{pf.name}, pb, {pf.length}u);")
        c(f"m->{pf.name}[{pf.length}] = '\\0';")
        c(f"return {self.fn(m, 'parse_body')}(body, end, m);")
        c.dedent()
        c("}")
        return c.text()

    def text_const_check(self, c: Code, f: Field) -> None:
        """The value `v` must be the constant: read as its kind is read, with that kind's
        errors first (as Python's), then compared."""
        text = self.text_const(f)
        if f.kind == "char":
            self.fail_if(c, "v.e - v.b != 1", "type")
            self.fail_if(c, "!" + self.text_read_ok("1u", f.to_end), "text")
            self.fail_if(c, f"*v.b != {cchar(text)}", "const")
        elif f.kind == "str":
            self.fail_if(c, "!" + self.text_read_ok("(size_t)(v.e - v.b)", f.to_end), "text")
            self.fail_if(c, f"(size_t)(v.e - v.b) > {f.max_length}u", "length")
            self.fail_if(c, f"(size_t)(v.e - v.b) != {len(text)}u || memcmp(v.b, {cstr(text)}, {len(text)}u) != 0",
                         "const")
        else:  # an integer: its number, however spelt, is compared; any other number is not it
            value = int(text)
            wide = "u64" if value > (1 << 63) - 1 else "i64"
            vtype = {"i64": "int64_t", "u64": "uint64_t"}[wide]
            lo, hi = ("0u", "UINT64_MAX") if wide == "u64" else ("INT64_MIN", "INT64_MAX")
            c("{")
            c.indent()
            c(f"{vtype} value = 0;  /* set by the parser where it succeeds; compilers cannot always tell */")
            c(f"int const_rc = cw_parse_{wide}(v.b, v.e, {lo}, {hi}, &value);")
            c("if (const_rc != CW_OK && const_rc != CW_ERR_RANGE) {")
            c("    return const_rc;")
            c("}")
            self.fail_if(c, f"const_rc == CW_ERR_RANGE || value != {self.literal_of(value, vtype)}", "const")
            c.dedent()
            c("}")

    def value_call(self, i: int, trim: str) -> str:
        if len(self.fr.separator) == 1:
            return f"cw_value(s, ends, {i}u, {trim})"
        return f"cw_value_after(s, ends, {i}u, {len(self.fr.separator)}u, {trim})"

    def text_read_ok(self, n: str, to_end: bool) -> str:
        """The check of a value read: split at separators and trimmed, so with one-character
        marks left to check are the characters and the terminator; a longer separator's
        characters may still be inside."""
        if self.line["simple"]:
            return f"cw_text_ok(v.b, {n}, '\\0', {cchar(self.fr.terminator)}, false)"
        return self.text_ok("v.b", n, to_end, False)

    def text_int64(self, f: Field) -> Optional[str]:
        """"i64" or "u64" for a text integer whose member the 32-bit reader and writer cannot
        hold (cw_parse_i64/u64, cw_write_i64/u64), else None."""
        return {"int64_t": "i64", "uint64_t": "u64", "uint32_t": "u64"}.get(self.rep(f).ctype)

    def text_decode_function(self, m: Message) -> str:
        c = Code()
        prefix = m.ids[0]
        c(f"static inline int {self.fn(m, 'decode')}(const char *text, size_t len, {self.tname(m)} *m)")
        c("{")
        c.indent()
        c("const char *pb, *pe, *body, *end;")
        c(f"int rc = {self.px}_split(text, len, &pb, &pe, &body, &end);")
        n = m.prefix_field.length if m.prefix_field is not None else 0
        at = f"pb + {n}" if n else "pb"  # the id follows the prefix field's value
        c(f"if (rc == CW_OK && ((size_t)(pe - pb) != {n + len(prefix)}u || memcmp({at}, {self.id_const(m)}, {len(prefix)}u) != 0)) {{")
        c("    rc = CW_ERR_DISPATCH;")
        c("} else if (rc == CW_OK) {")
        c(f"    rc = {self.parse_call(m)};")
        c("}")
        c("return cw_text_verdict(text, len, rc);")
        c.dedent()
        c("}")
        return c.text()

    # -- dispatch, stream ------------------------------------------------------------------------
    def directions(self) -> list[tuple[str, str]]:
        return [(self.upper("DIR", d.name), d.name) for d in self.p.directions]

    def dispatch(self) -> dict:
        """How decode finds the message. In bits framing the C reads the head that
        holds the dispatch fields into a uint32_t: at most its first 4 bytes (the
        resolver keeps the dispatch fields there)."""
        d = dispatch_facts(self.p)
        if d["kind"] != "bits" or d["head_bytes"] <= 4:
            return d
        return dict(with_head_checks(d, 32), head_bytes=4)

    def stream(self) -> dict:
        facts = stream_facts(self.p)
        length = facts.get("length")
        if length:  # the frame's size from the length's value: a length that counts more than the frame has less
            over = length["overhead"]
            facts = dict(facts, length=dict(length, overhead_term=f"+ {over}u" if over >= 0 else f"- {-over}u"))
        return dict(facts, fill_type=fill_type(facts["max"]))

    def encoding(self) -> dict:
        """The link's byte stuffing as C constants, or {} without one."""
        facts = encoding_facts(self.p)
        if not facts:
            return facts
        return dict(facts, constant=f"CW_{facts['kind'].upper()}", delimiter_c=f"0x{facts['delimiter']:02X}u",
                    accm_c=f"0x{facts['accm']:08X}UL",
                    fill_type=fill_type(facts["frame_max"]))


def fill_type(most: int) -> str:
    """The type of a count of buffered bytes, 0..most: as narrow as it can be on an
    8-bit MCU, and wide enough for frames over 64 KiB."""
    return unsigned_type(most.bit_length())


def enum_span(values: list) -> Optional[tuple[int, int]]:
    """(lo, hi) when the integer enum values are exactly lo..hi, else None."""
    if not values or not all(isinstance(x, int) and not isinstance(x, bool) for x in values):
        return None
    lo, hi = min(values), max(values)
    return (lo, hi) if hi - lo + 1 == len(set(values)) else None


def fletcher_code(name: str, cs: Checksum) -> str:
    """Fletcher-16 (two sums of bytes) or Fletcher-8 (two sums of nibbles, high nibble
    first), each sum reduced at every step so it stays within `unsigned` on 8-bit targets."""
    c = Code()
    t = unsigned_type(cs.width)
    half, m = cs.width // 2, clit(cs.modulo, True)
    c(f"/* Fletcher-{cs.width}: sums modulo {cs.modulo}, value (B << {half}) | A */")
    c(f"static inline {t} {name}(const uint8_t *data, size_t len)")
    c("{")
    c.indent()
    c("unsigned a = 0u;")
    c("unsigned b = 0u;")
    c("size_t i;")
    c("for (i = 0; i < len; i++) {")
    if cs.width == 16:
        c(f"    a = (a + data[i]) % {m};")
        c(f"    b = (b + a) % {m};")
    else:
        c(f"    a = (a + ((unsigned)data[i] >> 4)) % {m};")
        c(f"    b = (b + a) % {m};")
        c(f"    a = (a + ((unsigned)data[i] & 0xFu)) % {m};")
        c(f"    b = (b + a) % {m};")
    c("}")
    c(f"return ({t})((b << {half}) | a);")
    c.dedent()
    c("}")
    return c.text()


def internet_code(name: str, cs: Checksum) -> str:
    """RFC 1071: each word added and the carry out of 16 bits folded back in (end-around
    carry), so the sum stays within 17 bits for a frame of any length; then its one's
    complement."""
    c = Code()
    hi, lo = ("data[i]", "data[i + 1u]") if cs.word_order == "big" else ("data[i + 1u]", "data[i]")
    last = "((uint32_t)data[i] << 8)" if cs.word_order == "big" else "data[i]"
    c(f"/* The internet checksum (RFC 1071): 16-bit words, {cs.word_order}-endian, an odd byte padded with 0 */")
    c(f"static inline uint16_t {name}(const uint8_t *data, size_t len)")
    c("{")
    c.indent()
    c("uint32_t sum = 0u;")
    c("size_t i;")
    c("for (i = 0; i + 1u < len; i += 2u) {")
    c(f"    sum += ((uint32_t){hi} << 8) | {lo};")
    c("    sum = (sum & 0xFFFFu) + (sum >> 16);")
    c("}")
    c("if (i < len) {")
    c(f"    sum += {last};")
    c("}")
    c("while (sum >> 16) {")
    c("    sum = (sum & 0xFFFFu) + (sum >> 16);")
    c("}")
    c("return (uint16_t)~sum;")
    c.dedent()
    c("}")
    return c.text()


def checksum_code(name: str, cs: Checksum, guard: str) -> str:
    """A C function `name(data, len)` computing a byte checksum; a CRC's method is the
    one <guard>_CRC_<METHOD> selects when the header is compiled (crc.py)."""
    c = Code()
    if cs.algorithm == "fletcher":
        return fletcher_code(name, cs)
    if cs.algorithm == "internet":
        return internet_code(name, cs)
    if cs.algorithm != "crc":
        op = "+" if cs.algorithm == "sum" else "^"
        rt = "uint64_t" if (cs.width or 0) > 32 else "uint32_t"  # a complement in 64 bits
        c(f"static inline {rt} {name}(const uint8_t *data, size_t len)")
        c("{")
        c("    uint32_t acc = 0;")
        c("    size_t i;")
        c("    for (i = 0; i < len; i++) {")
        c(f"        acc = acc {op} data[i];")
        c("    }")
        if cs.algorithm == "parity":  # the bytes' XOR has the parity of all their bits
            c("    return cw_parity32(acc)" + (" ^ 1u;" if cs.parity == "odd" else ";"))
        else:
            # a 32-bit sum of a frame's bytes never reaches a modulo above 2**32
            value = f"acc % {clit(cs.modulo, True)}" if cs.modulo and cs.modulo <= 1 << 32 else "acc"
            finished = final_step(cs, value, rt)
            c(f"    return {value};" if finished == value else f"    return ({rt}){finished};")
        c("}")
        return c.text()
    return crc_code(name, cs, guard)
