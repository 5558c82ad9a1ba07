"""View of a protocol for the Python target: names, leaves, wire chunks and the
code fragments the template lays out. All decisions about generated Python live
here; templates/python only arranges them."""
from __future__ import annotations

import math
import re
from dataclasses import replace
from typing import Any, Optional

from ...crc import reflect
from ...model import (SPELLING_MAX, Field, Gap, Leaf, Message, Multiplex, Protocol, Rule, Sequence, SequenceItem,
                      field_at, path_name)
from ...names import camel
from ..can import can_view
from ..code import Code, times_over
from .chunks import Chunk, Segment, access, chunks_of, segments_of
from .runtime import Calls
from .repeats import RepeatCode, blob, elements, named, region
from .stuffing import stuffing_view
from .trailer import trailer_view
from ..wire import (checksum_name as _checksum_name, dispatch_facts, encoding_facts, gap_of, gap_reads, stream_facts,
                    text_line_facts)


def lit(value: Any) -> str:
    if isinstance(value, float):
        if math.isinf(value):
            return "math.inf" if value > 0 else "-math.inf"
        return repr(value)
    return repr(value)


# what a text float may be, on both sides of a link (cw_decimal_t in C)
TEXT_FLOAT = "at most 15 significant digits, and zero or a magnitude of at least 1e-307"

class PythonView:
    def __init__(self, protocol: Protocol):
        self.p = protocol
        self.framing = protocol.framing
        self.calls = Calls()  # the module's helpers that the code written so far calls

    # -- names -----------------------------------------------------------------------------
    def class_name(self, message: Message) -> str:
        return camel(message.name)

    def group_class(self, message: Message, path: tuple) -> str:
        names = "".join(camel(p) for p in path if isinstance(p, str))  # an array's elements share one class
        return camel(message.layout_type or message.name) + names

    @staticmethod
    def enum_class(name: str) -> str:
        return camel(name)

    # -- declarations ----------------------------------------------------------------------
    def annotation(self, f: Field, message: Message, path: tuple[str, ...]) -> str:
        if f.present_if or f.multiplexed_by:  # None when its condition leaves it out
            return f"Optional[{self.annotation(replace(f, present_if=None, multiplexed_by=None), message, path)}]"
        if f.count is not None:
            return f"list[{self.annotation(f.element, message, path)}]"
        if f.kind == "group":
            return self.group_class(message, path)
        if f.enum:  # an open enum's other values are kept as numbers
            base = f"Union[{self.enum_class(f.enum.name)}, int]" if f.enum.open else self.enum_class(f.enum.name)
        elif f.flags:
            base = self.enum_class(f.flags.name)
        else:
            base = {"uint": "int", "int": "int", "bool": "bool", "float": "float", "char": "str",
                    "str": "str", "bytes": "bytes"}[f.kind]
            if f.scale is not None:
                base = "float"
            elif f.offset is not None and not float(f.offset).is_integer():
                base = "float"
        if f.one_hot or f.optional:
            base = f"Optional[{base}]"
        return base

    def default_expr(self, f: Field, message: Message, path: tuple[str, ...]) -> Optional[str]:
        if f.present_if or f.multiplexed_by:
            return "None"
        if f.count is not None:  # a list of the element's default, each element its own object
            each = self.default_expr(f.element, message, path)
            if each is None:
                return None
            if f.kind == "group":
                each = f"{self.group_class(message, path)}()"
            return f"[{each} for _ in range({f.count})]"
        if f.kind == "group":
            return f"{self.group_class(message, path)}()" \
                if all(self.default_expr(s, message, path + (s.name,)) is not None
                       for s in f.fields if s.is_member) else None
        if f.has_default:
            return self.value_expr(f, f.default)
        if f.optional:
            return "None"
        return None

    def value_expr(self, f: Field, value: Any) -> str:
        """A Python expression for a schema-written value of field f."""
        if value is None:
            return "None"
        if f.enum:
            member = next((m for m in f.enum.members if value in (m.name, m.value)), None)
            return f"{self.enum_class(f.enum.name)}.{member.name}" if member else lit(value)
        if f.flags and isinstance(value, list):
            names = [f"{self.enum_class(f.flags.name)}.{n}" for n in value]
            return " | ".join(names) if names else f"{self.enum_class(f.flags.name)}(0)"
        if f.kind == "bool":
            return "True" if value else "False"
        if f.kind == "bytes" and isinstance(value, str):
            return f"bytes.fromhex({value!r})"
        return lit(value)

    def dataclasses(self) -> list[dict]:
        """Group classes first (inner before outer), then one class per message."""
        out: list[dict] = []
        seen: set[str] = set()

        def visit(message: Message, fields: tuple[Field, ...], path: tuple[str, ...], name: str,
                  doc: str, is_message: bool) -> None:
            for f in fields:
                if f.kind == "group" and f.is_member:
                    visit(message, f.fields, path + (f.name,), self.group_class(message, path + (f.name,)),
                          str(f.doc or f.title or f.name), False)
            if name in seen:
                return
            seen.add(name)
            members = [f for f in fields if f.is_member]
            required = [f for f in members if self.default_expr(f, message, path + (f.name,)) is None]
            needed = {id(f) for f in required}  # by identity: comparing frozen fields field by field is slow
            optional = [f for f in members if id(f) not in needed]
            out.append({
                "name": name, "doc": doc, "message": message.name if is_message else None,
                "spelling": is_message and any(f.keep_spelling for f in members),
                "places": is_message and message.keeps_places,
                "fields": [{"name": f.name, "annotation": self.annotation(f, message, path + (f.name,)),
                            "default": self.default_expr(f, message, path + (f.name,)),
                            # a list or a group is built for each object, as a default_factory is
                            "fresh": (f.count is not None or f.kind == "group")
                            and self.default_expr(f, message, path + (f.name,)) not in (None, "None"),
                            "doc": self.field_comment(f)}
                           for f in required + optional],
                "spec": "(" + "".join(self.plain_spec(f, message, path + (f.name,), id(f) in needed) + ", "
                                      for f in required + optional) + ")",
                "names": lit(tuple(f.name for f in required + optional)),
                "slots": lit(tuple(f.name for f in required + optional)
                             + (("_spelling",) if is_message and any(f.keep_spelling for f in members) else ())
                             + (("_places",) if is_message and message.keeps_places else ())),
            })

        trailer = self.p.framing.trailer.fields if self.p.framing.trailer else ()
        for m in self.p.messages:  # a trailer's fields are every message's, None when it is not sent
            visit(m, m.layout + trailer, (), self.class_name(m), str(m.title or m.doc or m.name), True)
        return out

    def plain_spec(self, f: Field, message: Message, path: tuple[str, ...], required: bool) -> str:
        """How to_dict and from_dict convert a field: (name, kind, class, optional, array, required)."""
        one = f.element if f.count is not None else f
        if one.kind == "group":
            kind, cls = "group", self.group_class(message, path)
        elif one.enum:
            kind, cls = "open_enum" if one.enum.open else "enum", self.enum_class(one.enum.name)
        elif one.flags:
            kind, cls = "flags", self.enum_class(one.flags.name)
        else:
            kind, cls = self.annotation(one, message, path).removeprefix("Optional[").rstrip("]"), "None"
            kind = "number" if kind == "float" else kind
        optional = bool(one.one_hot or one.optional or f.present_if or f.multiplexed_by)
        return f"({f.name!r}, {kind!r}, {cls}, {optional}, {f.count is not None}, {required})"

    def field_comment(self, f: Field) -> str:
        parts = [str(f.doc)] if f.doc else []
        if f.unit:
            parts.append(f"[{f.unit}]")
        if f.range:
            parts.append(f"range {lit(f.range[0])}..{lit(f.range[1])}")
        if f.rule:
            parts.append(f"({f.rule})")
        if f.present_if or f.multiplexed_by:
            parts.append(f"(sent when {(f.present_if or f.multiplexed_by).says})")
        return " ".join(parts).replace("\n", " ")

    # -- encode: logical value → raw wire integer (or bytes/float) -------------------------
    @staticmethod
    def fixed_raw(f: Field) -> Optional[int]:
        """The raw value of a field the encoder does not take from the object, if fixed."""
        if f.checksum:
            return None
        if f.reserved:
            return 0
        if f.length_of or f.const is not None:
            if f.enum and f.const is not None:
                return next(m.value for m in f.enum.members if f.const in (m.name, m.value))
            return f.const
        return None

    def fixed_or_zero(self, f: Field) -> Any:
        """A fixed field's raw value, or 0 for a checksum until it is computed (a constant of
        -0.0 stays one: `or` would take it for zero)."""
        value = self.fixed_raw(f)
        return 0 if value is None else value

    def encode_leaf(self, c: Code, message: Message, leaf: Leaf, source: str = "",
                    keep_bool: bool = False, maybe_none: bool = False) -> None:
        """Emit code that reads leaf from `m` (or from `source`, its group already read), checks
        it and stores its raw value in leaf.var. keep_bool: a True or False is left as it is
        (binary packing shifts and sums bools as 1 and 0; text would write "True")."""
        f, var = leaf.field, leaf.var
        v = var  # the value is read into the variable that then holds its raw form
        where = f"{message.name!r}, {named(leaf.path)}"
        if f.checksum or self.fixed_raw(f) is not None:
            c(f"{var} = {lit(self.fixed_or_zero(f))}")
            return
        # an enum, flag or bool value is checked and then replaced by its raw int: typed as Any
        # (and a value a frame may leave out, None unless its condition holds: read where it does)
        typed = ": Any" if f.kind == "bool" or f.enum is not None or f.flags is not None or maybe_none else ""
        read = access(source, leaf.path[-1]) if source else f"m.{leaf.dotted}"
        c(f"{v}{typed} = cast(Any, {read})" if maybe_none else f"{v}{typed} = {read}")
        if f.kind == "bool" and keep_bool:
            c(f"if {v} is not True and {v} is not False:")
            c(f"    if not isinstance({v}, int) or {v} != 0 and {v} != 1:")  # 1.0 == 1, yet is no bool
            c(f"        raise _enc({where}, {v}, 'type', 'a bool')")
            c(f"    {var} = 1 if {v} else 0")
        elif f.kind == "bool":
            c(f"if {v} is not True and {v} is not False and (not isinstance({v}, int) or {v} != 0 and {v} != 1):")
            c(f"    raise _enc({where}, {v}, 'type', 'a bool')")
            c(f"{var} = 1 if {v} else 0")
        elif f.enum is not None and f.enum.open:  # a member, or any int of the field's width
            cls = self.enum_class(f.enum.name)
            lo, hi = f.raw_range
            c(f"if {v}.__class__ is not {cls} and ({v}.__class__ is not int or not {lo} <= {v} <= {hi}):")
            c(f"    raise _enc({where}, {v}, 'enum', '{cls} or an int in {lo}..{hi}'{self.user(f)})")
            if f.values:
                allowed = tuple(self.enum_value(f, x) for x in f.values)
                c(f"if {v} not in {lit(allowed)}:")
                c(f"    raise _enc({where}, {v}, 'values', {', '.join(map(str, allowed))!r}, {f.rule!r}{self.user(f, False)})")
            c(f"{var} = {v} if {v}.__class__ is int else _RAW_{f.enum.name}[{v}]")
        elif f.enum is not None:
            base = "str" if f.enum.kind == "char" else "int"
            cls = self.enum_class(f.enum.name)
            # a member of the enum class is valid by construction: no membership test
            # a bool or another enum's member is not a value of this one, even where it compares equal
            not_bool = f" or {v}.__class__ is bool" if base == "int" else ""  # no str is a bool
            c(f"if {v}.__class__ is not {cls} and (not isinstance({v}, {base}){not_bool} "
              f"or isinstance({v}, enum.Enum) or {v} not in _VALUES_{f.enum.name}):")
            c(f"    raise _enc({where}, {v}, 'enum', {cls!r}{self.user(f)})")
            if f.values:
                allowed = tuple(self.enum_value(f, x) for x in f.values)
                c(f"if {v} not in {lit(allowed)}:")
                c(f"    raise _enc({where}, {v}, 'values', {', '.join(map(str, allowed))!r}, {f.rule!r}{self.user(f, False)})")
            if f.enum.kind != "char":  # a member's value is looked up, not converted: int() is a call
                c(f"{var} = _RAW_{f.enum.name}[{v}]")
        elif f.flags is not None:
            cls = self.enum_class(f.flags.name)
            c(f"if {v}.__class__ is not int and {v}.__class__ is not {cls} and "
              f"(not isinstance({v}, int) or {v}.__class__ is bool or isinstance({v}, enum.Enum)):")
            c(f"    raise _enc({where}, {v}, 'type', 'an int or {cls}')")
            c(f"{v} = int({v})")  # each operator on an IntFlag builds a new flag: checks on an int are far cheaper
            c(f"if {v} < 0 or {v} & {~f.flags.mask & ((1 << f.bits) - 1):#x} or {v} > {(1 << f.bits) - 1:#x}:")
            c(f"    raise _enc({where}, {v}, 'flags', 'only the bits of {f.flags.name}'{self.user(f)})")
            if f.exactly_one:
                c(f"if {v} == 0 or {v} & ({v} - 1):")
                c(f"    raise _enc({where}, {v}, 'exactly_one', 'exactly one bit set', {f.rule!r}{self.user(f, False)})")
        elif f.one_hot:
            c(f"if {v} is None:")
            c(f"    {var} = 0")
            c("else:")
            lo, hi = f.range or (0, f.bits - 1)
            c(f"    if {v}.__class__ is not int and (not isinstance({v}, int) or {v}.__class__ is bool) "
              f"or not {lo} <= {v} <= {hi}:")
            c(f"        raise _enc({where}, {v}, 'range', '{lo}..{hi} or None', {f.rule!r}{self.user(f, False)})")
            c(f"    {var} = 1 << {v}")
        elif f.kind in ("uint", "int") or f.kind == "float" and self.usual_spec(leaf) is not None:
            test, helper, args = self.number_check(message, leaf)
            self.calls.use(helper)
            c(f"if {test}:")
            c(f"    {helper}({args})")
            if f.values:
                c(f"if {v} not in {lit(tuple(f.values))}:")
                c(f"    raise _enc({where}, {v}, 'values', {', '.join(map(str, f.values))!r}, {f.rule!r}{self.user(f, False)})")
            expr = self.int_raw(f, v) if f.kind != "float" else v
            if expr != var:
                c(f"{var} = {expr}")
        elif f.kind == "float" and not f.finite:  # NaN and the infinities too: NaN written as the quiet NaN
            limit = "3.4028234663852886e38" if f.bits == 32 else "1.7976931348623157e308"
            c(f"if {v}.__class__ is not float or not -{limit} <= {v} <= {limit}:")
            c(f"    {v} = _nonfinite({where}, {v}, {f.bits == 32})")
            self.calls.use("_nonfinite")
        elif f.kind == "float":  # a text's precision or a range is checked before a binary32's limits
            text = self.p.framing.kind == "text"
            c(f"if {v}.__class__ is not float or not -1.7976931348623157e308 <= {v} <= 1.7976931348623157e308:")
            c(f"    _float_fault({where}, {v}, False)")
            self.calls.use("_float_fault")
            if text:  # the decimals a C peer's cw_decimal_t holds too
                self.calls.use("_format_float", "_significant")
                c(f"{self.float_text(leaf)} = _format_float({v})  # written as it is checked")
                # a text of 15 characters or fewer cannot hold 16 digits: most are not counted
                c(f"if len({self.float_text(leaf)}) > 15 and _significant({self.float_text(leaf)}) > 15 "
                  f"or {v} and -1e-307 < {v} < 1e-307:")
                c(f"    raise _enc({where}, {v}, 'precision', {TEXT_FLOAT!r})")
            if f.range:
                c(f"if not {lit(f.range[0])} <= {v} <= {lit(f.range[1])}:")
                c(f"    raise _enc({where}, {v}, 'range', '{lit(f.range[0])}..{lit(f.range[1])}', {f.rule!r}{self.user(f, False)})")
            if f.bits == 32:
                c(f"if {v} > 3.4028234663852886e38 or {v} < -3.4028234663852886e38:")
                c(f"    raise _enc({where}, {v}, 'range', 'a binary32 value')")
        elif f.kind == "bytes" and f.varies:  # the bytes past its length are not sent
            c(f"if not isinstance({v}, (bytes, bytearray)) or len({v}) > {f.length}:")
            c(f"    raise _enc({where}, {v}, 'length', 'bytes of length 0..{f.length}')")
            c(f"{var} = bytes({v}).ljust({f.length}, b'\\0')")
        elif f.kind == "bytes":
            c(f"if {v}.__class__ is not bytes or len({v}) != {f.length}:")  # else bytes of the length
            c(f"    if not isinstance({v}, (bytes, bytearray)) or len({v}) != {f.length}:")
            c(f"        raise _enc({where}, {v}, 'length', 'bytes of length {f.length}')")
            c(f"    {var} = bytes({v})")
        # text kinds are checked and written by the text writer

    def usual_check(self, message: Message, leaf: Leaf) -> Optional[tuple[str, str, str]]:
        """number_check of a number checked by that test alone (then converted): consecutive
        such fields share one test (MessageCode.encode_usual); None for any other field."""
        f = leaf.field
        if f.enum or f.flags or f.one_hot or f.values or f.checksum or self.fixed_raw(f) is not None:
            return None
        return self.number_check(message, leaf) if self.usual_spec(leaf) is not None else None

    def number_check(self, message: Message, leaf: Leaf) -> tuple[str, str, str]:
        """The test that a number's usual values pass (an integer of its class and in range, a
        float of its class within its width's limits; NaN fails it too), and the helper and its
        arguments that raise the error saying what is wrong with any other value."""
        v, where, spec = leaf.var, f"{message.name!r}, {named(leaf.path)}", self.usual_spec(leaf)
        if spec[0] == "int":
            _, _, lo, hi, number, *_ = spec
            return (f"{v}.__class__ is not {'float' if number else 'int'} or not {lit(lo)} <= {v} <= {lit(hi)}",
                    "_int_fault", f"{where}, {v}, {', '.join(map(lit, spec[2:]))}")
        limit = "3.4028234663852886e38" if spec[2] else "1.7976931348623157e308"
        return (f"{v}.__class__ is not float or not -{limit} <= {v} <= {limit}",
                "_float_fault", f"{where}, {v}, {spec[2]}")

    def usual_spec(self, leaf: Leaf) -> Optional[tuple]:
        """What _faults needs to say what is wrong with a number that failed its usual test:
        ("int", name, lo, hi, scaled, decision[, the field's own message]) or ("float", name,
        binary32); None for a float whose text or range is checked before its width's limits."""
        f = leaf.field
        if f.kind in ("uint", "int"):
            lo, hi = f.range if f.range else self.encodable_limits(f)
            return ("int", leaf.path[-1], lo, hi, f.scale is not None, f.rule) + \
                ((self.user_text(f.message),) if f.message else ())
        if f.kind == "float" and self.p.framing.kind != "text" and not f.range and f.finite:
            return ("float", leaf.path[-1], f.bits == 32)
        return None

    def int_raw(self, f: Field, v: str) -> str:
        """The raw wire integer of the checked logical value in `v`."""
        expr = v
        if f.offset:
            expr = f"({v} - {lit(f.offset)})"
        if f.scale is not None and f.bits >= 53:
            expr = f"_half_up({expr} / {lit(f.scale)})"
            self.calls.use("_half_up")
        elif f.scale is not None:
            expr = f"_floor({expr} / {lit(f.scale)} + 0.5)"
        elif f.offset and not float(f.offset).is_integer():
            expr = f"_floor({expr} + 0.5)"
        return expr

    @staticmethod
    def float_text(leaf: Leaf) -> str:
        """The local holding a text float's written form."""
        return "s_" + leaf.var[2:]

    @staticmethod
    def enum_value(f: Field, value: Any) -> Any:
        """The wire value of an enum member written by name or by value."""
        return next((m.value for m in f.enum.members if value in (m.name, m.value)), value)

    def user(self, f: Field, with_rule: bool = True) -> str:
        """The trailing arguments of an error: the field's decision and its own message."""
        extra = f", {f.rule!r}" if with_rule else ""
        if f.message:
            extra += f", {self.user_text(f.message)!r}"
        return extra

    @classmethod
    def encodable_limits(cls, f: Field) -> tuple:
        """The logical limits as values the encoder turns into raw values its width holds:
        a limit that is no double (`u53` scaled by 0.125 tops out at ...623.875, which
        rounds to ...624.0, one raw step past the width) is moved inward to the nearest
        double whose raw value, computed as the encoder does, fits."""
        lo, hi = cls.logical_limits(f)
        if f.scale is None:
            return lo, hi
        raw_lo, raw_hi = f.raw_range
        lo, hi = float(lo), float(hi)
        while cls.raw_as_encoded(f, lo) < raw_lo:
            lo = math.nextafter(lo, math.inf)
        while cls.raw_as_encoded(f, hi) > raw_hi:
            hi = math.nextafter(hi, -math.inf)
        return lo, hi

    @staticmethod
    def raw_as_encoded(f: Field, value: float) -> int:
        """The raw value the generated encoder computes for a scaled field's value (as `encode_leaf` writes it)."""
        x = (value - float(f.offset) if f.offset else value) / float(f.scale)
        n = math.floor(x) if f.bits >= 53 else math.floor(x + 0.5)
        return n + 1 if f.bits >= 53 and x - n >= 0.5 else n

    @staticmethod
    def logical_limits(f: Field) -> tuple:
        lo, hi = f.raw_range
        if f.scale is not None or f.offset is not None:
            return (lo * (f.scale or 1) + (f.offset or 0), hi * (f.scale or 1) + (f.offset or 0))
        return (lo, hi)

    # -- decode: raw wire value → logical value --------------------------------------------
    def decode_leaf(self, c: Code, message: Message, leaf: Leaf, offset_expr: str,
                    bounded: bool = False, finite_if: str = "") -> Optional[str]:
        """Emit checks of a raw value; return the expression of its logical value (members).
        bounded: the raw value was read from its bits, so a range its width implies is not checked;
        finite_if: a condition under which a float is known to be finite (its text was short)."""
        f, var = leaf.field, leaf.var
        at = f"{message.name!r}, {named(leaf.path)}, {var}"
        off = offset_expr
        if f.reserved:
            c(f"if {var}:")
            c(f"    raise _dec({at}, 'reserved', '0', {off}{self.user(f)})")
            return None
        if f.counts:
            return None  # checked against the frame's size before the fields are read
        if f.length_of:
            if message.shortening:  # it counts the payload bytes sent
                c(f"if {var} != {f.const} - cut:")
                c(f"    raise _dec({at}, 'length', f'{{{f.const} - cut}} for {message.name}', {off}, {f.rule!r})")
            else:
                c(f"if {var} != {f.const}:")
                c(f"    raise _dec({at}, 'length', '{f.const} for {message.name}', {off}, {f.rule!r})")
            return None
        if f.checksum:
            return None  # verified after all fields are known
        if f.const is not None and not f.values:
            value = f.const
            if f.enum:
                value = next(m.value for m in f.enum.members if f.const in (m.name, m.value))
            if f.kind == "float" and value == 0:  # 0.0 and -0.0 are equal, and two values on the wire
                c(f"if {var} != 0.0 or math.copysign(1.0, {var}) {'<' if math.copysign(1, value) > 0 else '>'} 0:")
            else:
                c(f"if {var} != {lit(value)}:")
            c(f"    raise _dec({at}, 'const', {lit(value)!r}, {off}{self.user(f)})")
            return None
        if f.kind == "bool":
            return f"{var} == 1"
        if f.enum is not None and f.enum.open:  # a value no member has is kept as its number
            e = "e_" + var[2:]
            cls = self.enum_class(f.enum.name)
            c(f"{e} = cast(Union[{cls}, int], _ENUM_{f.enum.name}.get({var}, {var}))")
            expr = var_checked = e
        elif f.enum is not None:
            e = "e_" + var[2:]
            c(f"{e} = _ENUM_{f.enum.name}.get({var})")
            c(f"if {e} is None:")
            c(f"    raise _dec({at}, 'enum', {self.enum_class(f.enum.name)!r}, {off}, {f.rule!r}{self.user(f, False)})")
            expr = var_checked = e
        elif f.flags is not None:
            if ~f.flags.mask & ((1 << f.bits) - 1):
                c(f"if {var} & {~f.flags.mask & ((1 << f.bits) - 1):#x}:")
                c(f"    raise _dec({at}, 'flags', 'only the bits of {f.flags.name}', {off}, {f.rule!r})")
            if f.exactly_one:
                c(f"if {var} == 0 or {var} & ({var} - 1):")
                c(f"    raise _dec({at}, 'exactly_one', 'exactly one bit set', {off}, {f.rule!r})")
            if f.exactly_one or self.all_flag_values(f.flags):  # every value it can take is in the table
                return f"_FLAGS_{f.flags.name}[{var}]"
            self.calls.use("_flag")
            return f"_FLAGS_{f.flags.name}.get({var}) or _flag({self.enum_class(f.flags.name)}, _FLAGS_{f.flags.name}, {var})"
        elif f.one_hot:
            lo, hi = f.range or (0, f.bits - 1)
            c(f"if {var} & ({var} - 1) or {var} and not {1 << lo} <= {var} <= {1 << hi}:")
            c(f"    raise _dec({at}, 'one_hot', 'one bit of {lo}..{hi}, or 0', {off}, {f.rule!r})")
            return f"({var}.bit_length() - 1 if {var} else None)"
        elif f.kind in ("uint", "int"):
            expr = var
            expr = var
            if f.scale is not None:
                expr = f"{var} * {lit(f.scale)}"
            if f.offset:
                expr = f"{expr} + {lit(f.offset)}"
            var_checked = expr
            if f.decimals:  # the value the text shows, correctly rounded, and checked as such
                expr = var_checked = f"{var} / {10 ** f.decimals}" + (f" + {lit(f.offset)}" if f.offset else "")
        elif f.kind == "float":
            if f.finite:
                c(f"if {'not ' + finite_if + ' and ' if finite_if else ''}not _isfinite({var}):")
                c(f"    raise _dec({at}, 'finite', 'a finite number', {off}, {f.rule!r})")
            expr = var_checked = var
        else:
            return var
        if not bounded and not f.range and f.kind in ("uint", "int") and not f.closed_enum and f.raw_range:
            lo, hi = self.logical_limits(f)  # a text token can hold more than the field's width
            c(f"if not {lit(lo)} <= {var_checked} <= {lit(hi)}:")
            c(f"    raise _dec({at}, 'range', '{lit(lo)}..{lit(hi)}', {off}, {f.rule!r}{self.user(f, False)})")
        if f.range and not (bounded and self.width_implies_range(f)):
            lo, hi = f.range
            c(f"if not {lit(lo)} <= {var_checked} <= {lit(hi)}:")
            c(f"    raise _dec({at}, 'range', '{lit(lo)}..{lit(hi)}', {off}, {f.rule!r}{self.user(f, False)})")
        if f.values:
            allowed = tuple(self.enum_value(f, x) for x in f.values) if f.enum else tuple(f.values)
            c(f"if {var_checked} not in {lit(allowed)}:")
            c(f"    raise _dec({at}, 'values', {', '.join(map(str, f.values))!r}, {off}, {f.rule!r}{self.user(f, False)})")
        return expr

    @staticmethod
    def all_flag_values(flags) -> bool:
        """Whether the flag table holds every combination of the set's bits (up to 256)."""
        return len(flags.members) <= 8

    def width_implies_range(self, f: Field) -> bool:
        """Every value the raw width can carry lies inside the declared range."""
        if f.kind not in ("uint", "int") or f.raw_range is None or f.enum or f.flags or f.one_hot:
            return False
        lo, hi = sorted(self.logical_limits(f))
        return f.range[0] <= lo and hi <= f.range[1]

    # -- message rules (when/require) ------------------------------------------------------
    def condition(self, cond, obj: str, message: Message) -> str:
        f = self.find(message, cond.path)
        left = f"{obj}.{cond.path}"
        value = cond.value

        def conv(v):
            return self.value_expr(f, v) if f is not None else lit(v)
        if cond.op == "eq":
            return f"{left} is None" if value is None else f"{left} == {conv(value)}"
        if cond.op == "ne":
            return f"{left} is not None" if value is None else f"{left} != {conv(value)}"
        if cond.op == "in":
            return f"{left} in ({', '.join(conv(v) for v in value)},)"
        if cond.op == "range":
            return f"{lit(value[0])} <= {left} <= {lit(value[1])}"
        raise ValueError(f"condition {cond.op} is for state machines")

    @staticmethod
    def find(message: Message, dotted: str) -> Optional[Field]:
        return field_at(message.layout, dotted)

    def rule_checks(self, c: Code, message: Message, obj: str, err: str) -> None:
        for rule in message.rules:
            when = " and ".join(self.condition(x, obj, message) for x in rule.when) or "True"
            need = " and ".join(self.condition(x, obj, message) for x in rule.require)
            first = rule.require[0].path
            text = self.rule_text(rule)
            c(f"if {when} and not ({need}):" if rule.when else f"if not ({need}):")
            c(f"    raise {err}({message.name!r}, {first!r}, {obj}.{first}, 'rule', {text!r}, "
              f"decision={rule.id!r}{', user_message=' + repr(self.user_text(rule.message)) if rule.message else ''})")

    def rule_text(self, rule: Rule) -> str:
        def show(cs):
            return " and ".join(f"{x.path} {'==' if x.op == 'eq' else x.op} {x.value if x.value is not None else 'None'}"
                                for x in cs)
        return (f"if {show(rule.when)} then " if rule.when else "") + show(rule.require)

    @staticmethod
    def user_text(message) -> str:
        """A schema message in English, then its translations."""
        return " / ".join([message.en] + [t for _, t in message.translations])


class GuardedRun:
    """Consecutive leaves under one guard (an element of a counted array, a conditional field)
    share one `if`, and its `else` sets the raw values of those a frame leaves out."""

    def __init__(self, c: Code):
        self.c = c
        self.guard: Optional[str] = None
        self.left_out: list[tuple[str, str]] = []

    def open(self, guard: Optional[str]) -> None:
        if guard is None or guard == self.guard:
            return
        self.close()
        self.c(f"if {guard}:")
        self.c.indent()
        self.guard = guard

    def unsent(self, var: str, value: str) -> None:
        self.left_out.append((var, value))

    def close(self) -> None:
        if self.guard is None:
            return
        self.c.dedent()
        if self.left_out:
            self.c("else:")
            for var, value in self.left_out:
                self.c(f"    {var} = {value}")
        self.guard, self.left_out = None, []


class ElementHelper:
    """One element of a counted array of groups, checked in a function of its own: straight
    code for every element in one function is more than a type checker follows."""

    def __init__(self, mc: "MessageCode", path: tuple):
        self.mc, self.path = mc, path
        self.name = f"_raw_{mc.fn}_{path_name(path)}"
        self.code = Code()
        self.code(f"def {self.name}({mc.group_var(path)}: Any) -> tuple[Any, ...]:")
        self.code.indent()
        self.returns: list[str] = []

    def call(self, c: Code) -> None:
        """Write the function, and its call in `c` (under the element's guard)."""
        self.code(f"return ({''.join(v + ', ' for v in self.returns)})")
        self.mc.helpers.append(self.code.text())
        array = self.mc.group_var(self.path[:1])
        c(f"{', '.join(self.returns)}{',' if len(self.returns) == 1 else ''} = {self.name}({array}[{self.path[1]}])")


class MessageCode:
    """The generated functions of one message."""

    def __init__(self, view: PythonView, message: Message):
        self.view = view
        self.m = message
        self.leaves = message.wire.leaves
        self.cls = view.class_name(message)
        self.fn = message.name
        self.output = "str" if view.p.framing.kind == "text" else "bytes"
        self.helpers: list[str] = []  # functions the encoder calls, written before it
        self.repeats = {r.field.name: RepeatCode(self, r) for r in message.wire.repeats}
        # leaf var → (struct item, its expected bytes, the int.from_bytes call): a constant unpacked
        # as bytes is compared as bytes, and read as a number only for its error
        self.const_items: dict[str, tuple[str, bytes, str]] = {}
        # while an encoder is written: leaf var → the raw value the schema fixes (a constant,
        # reserved bits, a length; a checksum until it is computed), written where it is read
        self.fixed: dict[str, Any] = {}
        # while a decoder is written: leaf var → the raw value a field checksum reads instead
        # (a length field of a payload cut short, as if all of it were sent)
        self.restored: dict[str, str] = {}

    def raw(self, leaf: Leaf) -> str:
        """A leaf's raw value as the encoder reads it: its literal when fixed, else its local."""
        return lit(self.fixed[leaf.var]) if leaf.var in self.fixed else leaf.var

    def only_checked(self, leaf: Leaf) -> bool:
        """Whether the decoder uses a leaf's raw value for its constant check alone: no other
        field, condition or field checksum reads it."""
        f = leaf.field
        if f.const is None or f.values or f.reserved or f.counts or f.length_of or f.checksum:
            return False
        if self.looped(leaf) is not None:  # an array's elements are checked by its loop
            return False
        if any(x.field.checksum and x.field.checksum.over != "bytes" for x in self.leaves):
            return False
        gaps = self.m.shortening.gaps if self.m.shortening else ()
        if any(g.control == f.name for g in gaps):
            return False
        return not any(x.field.multiplexed_by and any(m.field == f.name for m in x.field.multiplexed_by.chain)
                       for x in self.leaves)

    def looped(self, leaf: Leaf) -> Optional[RepeatCode]:
        """The code of the Repeat whose elements hold `leaf`, if any."""
        return self.repeats.get(leaf.path[0]) if len(leaf.path) > 1 else None

    # -- raw values (binary framings and the text form) ----------------------------------
    def raw_checks(self, c: Code, word: bool = False) -> None:
        """Check the object `m` and set every leaf's raw wire value (leaf.var).
        word: the caller packs one integer and computes parity bits from it."""
        self.view.rule_checks(c, self.m, "m", "_enc")
        self.fixed = {}
        groups: set[tuple] = set()
        run = GuardedRun(c)  # the leaves of one element (or conditional field) share one `if`
        element: Optional[ElementHelper] = None  # an element of a counted array of groups, checked apart
        packed: set[str] = set()  # the arrays looped over, packed by their functions
        ints: list[Leaf] = []  # plain numbers read one after another, checked together
        for leaf in self.leaves:
            repeat = self.looped(leaf)
            if repeat is not None and repeat.r.field.name in packed:
                continue
            held = gap_of(self.m, leaf)
            guard = None if leaf.field.counts else self.sent_guard(leaf, held, encoding=True)
            of = leaf.path[:2] if held and held.counter and len(leaf.path) > 2 else None
            if (guard is None and element is None and repeat is None and len(leaf.path) == 1
                    and not leaf.field.counts and not leaf.field.multiplexed_by):
                if self.view.usual_check(self.m, leaf) is not None:
                    run.close()
                    ints.append(leaf)
                    continue
                if leaf.field.checksum or self.view.fixed_raw(leaf.field) is not None:
                    # nothing to check, and no local: the numbers around it stay one run
                    self.fixed[leaf.var] = self.view.fixed_or_zero(leaf.field)
                    continue
            self.encode_usual(c, ints)
            if element is not None and element.path != of:
                element.call(c)
                element = None
            if guard != run.guard or leaf.field.multiplexed_by:
                run.close()
            if held and held.presence and leaf is self.first_leaf(held.field):
                self.check_presence(c, held)
            if leaf.field.multiplexed_by:
                self.check_multiplexed(c, leaf.field)
            for depth in range(1, 2 if repeat is not None else len(leaf.path)):  # each group object and array is read once
                prefix = leaf.path[:depth]
                if depth == 2 and of is not None and element is None:  # its function reads the rest
                    run.open(guard)
                    element = ElementHelper(self, of)
                    groups.add(of)
                    self.check_group(element.code, of)
                out = element.code if element is not None else c
                if prefix not in groups:
                    if depth > 1:  # inside an element or a conditional field: under its guard
                        run.open(guard)
                    groups.add(prefix)
                    parent = self.group_var(prefix[:-1])
                    value = access(parent, prefix[-1])
                    # a conditional field is None where a frame leaves it out: a checker takes it as
                    # Any, as the guards read it; what lies inside is read under its guard
                    absent_ok = held is not None and held.presence is not None and depth == 1
                    out(f"{self.group_var(prefix)}: Any = cast(Any, {value})" if absent_ok
                        else f"{self.group_var(prefix)} = {value}")
                    if isinstance(leaf.path[depth], int):
                        self.check_list(out, prefix, "absent_ok" if absent_ok else "any" if held else "typed")
                    else:
                        self.check_group(out, prefix, absent_ok)
            if leaf.field.counts:
                continue  # set from the list's length below
            if repeat is not None:
                run.close()
                packed.add(repeat.r.field.name)
                c(repeat.put_call(self.presence_test(held) if held is not None and held.presence else None))
                self.helpers.append(repeat.put_function())
                continue
            run.open(guard)
            out = element.code if element is not None else c
            self.view.encode_leaf(out, self.m, leaf, self.group_var(leaf.path[:-1]), keep_bool=word,
                                  maybe_none=guard is not None and len(leaf.path) == 1)  # a conditional field's own value
            if element is not None:
                element.returns.append(leaf.var)
            if guard is not None:
                run.unsent(leaf.var, f"bytes({leaf.field.length})" if leaf.field.kind == "bytes" else "0")
        self.encode_usual(c, ints)
        if element is not None:
            element.call(c)
        run.close()
        for gap in self.gaps():
            if gap.counter and gap.control:
                leaf = self.first_leaf(gap.control)
                counter = gap.counter
                held = self.group_var((gap.field,)) if field_at(self.m.layout, gap.field).count else f"m.{gap.field}"
                if counter.element_step != 1:  # the elements must fill whole units
                    c(f"if len({held}) % {counter.element_step}:")
                    c(f"    raise _enc({self.m.name!r}, {gap.field!r}, {held}, 'count', "
                      f"'a multiple of {counter.element_step} elements: the count is in {counter.unit}-byte units')")
                c(f"{leaf.var} = {times_over(f'len({held})', counter.element_bytes, counter.unit, '//')}")
        for leaf in self.leaves:
            cs = leaf.field.checksum
            if cs and cs.over != "bytes" and not (word and cs.algorithm == "parity"):
                c(f"{leaf.var} = {self.field_checksum(leaf)}")
                self.fixed.pop(leaf.var, None)  # read from its local from here on

    def encode_usual(self, c: Code, ints: list[Leaf]) -> None:
        """Read, check and convert numbers that follow one another (and empty the list): one
        test passes them all when each is of its class and in range; only otherwise is each
        looked at in turn, so the first value that is wrong is the one reported."""
        if not ints:
            return
        view = self.view
        if len(ints) == 1:
            view.encode_leaf(c, self.m, ints[0])
        else:
            checks = [view.usual_check(self.m, leaf) for leaf in ints]
            for leaf in ints:
                c(f"{leaf.var} = m.{leaf.dotted}")
            c("if " + " or ".join(f"({test})" for test, *_ in checks) + ":")
            view.calls.use("_faults")
            c(f"    _faults({self.m.name!r}, ({''.join(leaf.var + ', ' for leaf in ints)}), "
              f"{lit(tuple(view.usual_spec(leaf) for leaf in ints))})")
            for leaf in ints:
                expr = leaf.var if leaf.field.kind == "float" else view.int_raw(leaf.field, leaf.var)
                if expr != leaf.var:
                    c(f"{leaf.var} = {expr}")
        ints.clear()

    @staticmethod
    def group_var(path: tuple) -> str:
        return "g_" + path_name(path) if path else "m"

    def gaps(self) -> tuple:
        return self.m.shortening.gaps if self.m.shortening else ()

    def first_leaf(self, name: str) -> Leaf:
        return next(x for x in self.leaves if x.path[0] == name)

    def presence_test(self, gap, var: Optional[str] = None) -> str:
        """Whether conditional `gap` is sent, from its control field's raw value (`var`, by
        default the control's local)."""
        cond, var = gap.presence, var or self.raw(self.first_leaf(gap.control))
        full = cond.mask == (1 << self.first_leaf(gap.control).bits) - 1
        value = var if full else f"{var} & {cond.mask:#x}"
        if len(cond.values) == 1:
            return f"{value} == {cond.values[0]}" if full else f"({value}) == {cond.values[0]:#x}"
        return f"{value} in {cond.values!r}" if full else f"({value}) in {cond.values!r}"

    def multiplex_test(self, mux: Multiplex) -> str:
        """Whether a multiplexed field is in the frame, from its multiplexors' raw values."""
        tests = []
        for x in mux.chain:
            var = self.raw(self.first_leaf(x.field))
            one = [f"{var} == {lo}" if lo == hi and lo is not None else
                   f"{lo} <= {var} <= {hi}" if lo is not None and hi is not None else
                   f"{var} >= {lo}" if lo is not None else f"{var} <= {hi}" if hi is not None else ""
                   for lo, hi in x.bounds]
            if "" not in one:  # a range of every value the multiplexor holds tests nothing
                tests.append(one[0] if len(one) == 1 else f"({' or '.join(one)})")
        return " and ".join(tests) or "True"

    def check_multiplexed(self, c: Code, f: Field) -> None:
        """A multiplexed field holds a value exactly when its multiplexors select it."""
        c(f"if ({self.multiplex_test(f.multiplexed_by)}) != (m.{f.name} is not None):")
        c(f"    raise _enc({self.m.name!r}, {f.name!r}, m.{f.name}, 'present', "
          f"{('a value when ' + f.multiplexed_by.says + ', else None')!r})")

    def sent_guard(self, leaf: Leaf, gap: Optional[Gap], encoding: bool) -> Optional[str]:
        """The condition under which a leaf in `gap` is sent (None: always, or all of a counted
        bytes field, which is padded to its most)."""
        if leaf.field.multiplexed_by:
            return self.multiplex_test(leaf.field.multiplexed_by)
        if gap is None:
            return None
        if gap.presence:
            return self.presence_test(gap) if encoding else f"p_{gap.field}"
        if len(leaf.path) == 1:
            return None
        return f"len({self.group_var((gap.field,))}) > {leaf.path[1]}" if encoding else f"n_{gap.field} > {leaf.path[1]}"

    def sent_offset(self, leaf: Leaf) -> str:
        """The leaf's first bit in the frame as sent: its place in the whole frame, less the
        bytes left out before it."""
        sh = self.m.shortening
        if sh is None:
            return str(leaf.pos)
        if sh.gaps:
            lost = [f"lost{k}" for k, g in enumerate(sh.gaps) if g.span[1] * 8 <= leaf.pos]
            return f"{leaf.pos} - 8 * ({' + '.join(lost)})" if lost else str(leaf.pos)
        return f"{leaf.pos} - 8 * cut" if leaf.pos >= sh.payload[1] * 8 else str(leaf.pos)

    def check_presence(self, c: Code, gap) -> None:
        """A conditional field holds a value exactly when its control field says it is sent."""
        name, says = self.m.name, gap.presence.says
        c(f"if ({self.presence_test(gap)}) != (m.{gap.field} is not None):")
        c(f"    raise _enc({name!r}, {gap.field!r}, m.{gap.field}, 'present', "
          f"{('a value when ' + says + ', else None')!r})")

    def check_group(self, c: Code, path: tuple, absent_ok: bool = False) -> None:
        """A group member must be an object of its class (None too where a frame may leave it
        out): its fields are read by name, which fails on anything else with an AttributeError."""
        cls, v = self.view.group_class(self.m, path), self.group_var(path)
        if absent_ok:  # tests of its class alone: type checkers narrow a value tested with `is` or isinstance for good
            c(f"if {v}.__class__ is not {cls} and {v}.__class__ is not None.__class__ and not issubclass({v}.__class__, {cls}):")
        else:
            c(f"if {v}.__class__ is not {cls} and not isinstance({v}, {cls}):")
        c(f"    raise _enc({self.m.name!r}, {named(path)}, {v}, 'type', 'a {cls}')")

    def check_list(self, c: Code, path: tuple, held: str = "typed") -> None:
        """An array member must be a list (or tuple) of exactly its count of elements. `held`:
        "typed" (its declared type), "any" (a value a checker takes as Any: checked by a call, which
        keeps it so) or "absent_ok" (the same, or None: a conditional field a frame leaves out)."""
        array = field_at(self.m.layout, ".".join(p for p in path if isinstance(p, str)))
        count = array.count
        v = self.group_var(path)
        if array.varies:
            c(f"if not isinstance({v}, (list, tuple)) or len({v}) > {count}:")
            c(f"    raise _enc({self.m.name!r}, {named(path)}, {v}, 'count', 'a list of at most {count} values')")
            return
        if held != "typed":
            self.view.calls.use("_absent_or_list_of" if held == "absent_ok" else "_is_list_of")
        c(f"if not _absent_or_list_of({v}, {count}):" if held == "absent_ok" else
          f"if not _is_list_of({v}, {count}):" if held == "any" else
          f"if not isinstance({v}, (list, tuple)) or len({v}) != {count}:")
        c(f"    raise _enc({self.m.name!r}, {named(path)}, {v}, 'count', 'a list of {count} values')")

    def raw_function(self) -> str:
        """_raw_<msg>(m): the raw values in wire order; the text form's writer."""
        c = Code()
        c(f"def _raw_{self.fn}(m: {self.cls}) -> tuple[int, ...]:")
        c.indent()
        c(f'"""Check a {self.m.name} and return its raw wire values, in wire order."""')
        self.raw_checks(c)
        c(f"return ({''.join(self.raw(x) + ', ' for x in self.leaves)})")
        self.fixed = {}
        return c.text()

    def field_checksum(self, leaf: Leaf) -> str:
        """Expression of a checksum over the raw values of every other field."""
        cs = leaf.field.checksum
        others = [x for x in self.leaves if x is not leaf]
        # the fixed raw values are folded into one number, as the packing folds them
        folds = [x for x in others if x.field.kind != "float" and isinstance(self.fixed.get(x.var), int)]
        known = [self.fixed[x.var] & (1 << x.field.bits) - 1 for x in folds]
        terms = [self.unsigned(x) for x in others if x not in folds]
        if cs.algorithm == "parity":
            terms, known = [f"{t}.bit_count()" for t in terms], [k.bit_count() for k in known]
        if cs.algorithm == "xor":
            folded = 0
            for k in known:
                folded ^= k
            op = " ^ "
        else:
            folded, op = sum(known), " + "
        if not terms:  # every value fixed: so is the checksum
            return lit(folded % cs.modulo if cs.algorithm != "parity" else folded & 1 ^ (cs.parity == "odd"))
        tail = f"{op}{folded}" if folded else ""
        if cs.algorithm == "parity":
            return f"({op.join(terms)}{tail}) & 1{' ^ 1' if cs.parity == 'odd' else ''}"
        return f"({op.join(terms)}{tail}) % {cs.modulo}"

    def unsigned(self, leaf: Leaf) -> str:
        if leaf.var in self.restored:
            return self.restored[leaf.var]
        if leaf.field.kind == "int":
            if isinstance(self.fixed.get(leaf.var), int):
                return lit(self.fixed[leaf.var] & (1 << leaf.field.bits) - 1)
            return f"({leaf.var} & {(1 << leaf.field.bits) - 1:#x})"
        if leaf.field.kind == "float":  # a float among bit fields (placed by start bit): its IEEE 754 bits
            self.view.calls.use("_bits_of_float")
            return f"_bits_of_float({self.raw(leaf)}, {leaf.field.bits})"
        return self.raw(leaf)

    def build_checks(self, c: Code, bounded: bool, text_form: bool, word: bool = False) -> None:
        """Check the raw values (leaf.var) and build the object `o`.
        bounded: the values were read from their bits (binary), not parsed from text;
        word: they were read from the integer `w` (parity is then one bit count)."""
        values: dict[tuple, str] = {}
        run = GuardedRun(c)  # a value the frame left out is neither checked nor kept
        read: set[str] = set()  # the arrays looped over, read in their places
        for leaf in self.leaves:
            repeat = self.looped(leaf)
            if repeat is not None:
                if repeat.r.field.name not in read:
                    run.close()
                    read.add(repeat.r.field.name)
                    self.read_repeat(c, repeat)
                continue
            guard = self.sent_guard(leaf, gap_of(self.m, leaf), encoding=False)
            checks = Code()
            expr = self.view.decode_leaf(checks, self.m, leaf, self.sent_offset(leaf), bounded)
            if leaf.var in self.const_items:  # its bytes compared, its number read for the error only
                item, want, number = self.const_items[leaf.var]
                checks.lines = [f"if {item} != {want!r}:", f"    {leaf.var} = {number}",
                                *("    " + line for line in checks.lines)]
            kept = expr is not None and guard is not None and expr != leaf.var  # read under the guard
            if guard != run.guard and (checks.lines or kept or guard is None):
                run.close()
            if checks.lines or kept:
                run.open(guard)
            c.lines.extend("    " * c.depth + line for line in checks.lines)
            if kept:
                c(f"v_{leaf.var[2:]} = _sent({expr})")
                self.view.calls.use("_sent")
                run.unsent(f"v_{leaf.var[2:]}", "_ABSENT")
                expr = f"v_{leaf.var[2:]}"
            if expr is not None:
                values[leaf.path] = expr
        run.close()
        for leaf in self.leaves:
            cs = leaf.field.checksum
            if cs and cs.over != "bytes":
                if word and cs.algorithm == "parity":
                    others = sum(((1 << x.field.bits) - 1) << shift for x, shift in self.word_shifts()
                                 if x is not leaf and x.field.bits)
                    flip = " ^ 1" if cs.parity == "odd" else ""
                    c(f"x = (w & {others:#x}).bit_count() & 1{flip}")
                else:
                    c(f"x = {self.field_checksum(leaf)}")
                unfilled = self.view.p.framing.text_form.checksum_unfilled \
                    if self.view.p.framing.text_form else None
                cond = f"{leaf.var} != x"
                if text_form and unfilled is not None:
                    cond += f" and not (text_form and {leaf.var} == {unfilled})"
                c(f"if {cond}:")
                c(f"    raise _dec({self.m.name!r}, {leaf.dotted!r}, {leaf.var}, 'checksum', str(x), {leaf.pos}, {leaf.field.rule!r})")
        self.construct(c, self.m.layout, (), values)
        self.view.rule_checks(c, self.m, "o", "_dec")

    def read_repeat(self, c: Code, repeat: RepeatCode) -> None:
        """The loop reading an array's elements: to its count, or when the frame holds it."""
        gap = gap_of(self.m, repeat.r.leaves[0])
        count = f"n_{gap.field}" if gap is not None and gap.counter else None
        repeat.read_loop(c, count, f"p_{gap.field}" if gap is not None and gap.presence else None)

    def build_function(self) -> str:
        """_build_<msg>(raw values…): checks parsed raw values, returns the object (text form)."""
        c = Code()
        args = ", ".join(f"{x.var}: int" for x in self.leaves)
        c(f"def _build_{self.fn}({args}{', ' if args else ''}text_form: bool = False) -> {self.cls}:")
        c.indent()
        self.build_checks(c, bounded=False, text_form=True)
        c("return o")
        return c.text()

    def construct(self, c: Code, fields: tuple[Field, ...], path: tuple, values: dict, var: str = "o") -> None:
        """Build the object in `var` by setting its slots: a keyword call to the dataclass
        __init__ costs several times more. Groups are built first, into g_<path>."""
        members = [f for f in fields if f.is_member]
        for f in members:
            if not path and f.name in self.repeats:
                continue
            for at in self.places(f, path):
                if f.kind == "group":
                    self.construct(c, f.fields, at, values, self.group_var(at))
        name = self.view.group_class(self.m, path) if path else self.cls
        c(f"{var} = _object_new({name})")
        for f in members:
            if not path and f.name in self.repeats:  # read in a loop, or None where the frame leaves it out
                c(f"{var}.{f.name} = {elements(self.repeats[f.name].r)}")
                continue
            each = [self.group_var(at) if f.kind == "group" else values[at] for at in self.places(f, path)]
            sent = f"[:n_{f.name}]" if f.varies else ""
            value = each[0] + sent if f.count is None else '[' + ', '.join(each) + ']' + sent
            if f.present_if and not path:
                value = f"{value} if p_{f.name} else None"
            elif f.multiplexed_by:
                value = f"{value} if {self.multiplex_test(f.multiplexed_by)} else None"
            c(f"{var}.{f.name} = {value}")

    @staticmethod
    def places(f: Field, path: tuple) -> list[tuple]:
        """The path of the field, or of each element of an array."""
        if f.count is None:
            return [path + (f.name,)]
        return [path + (f.name, i) for i in range(f.count)]

    # -- bytes -----------------------------------------------------------------------------
    def chunks(self) -> list[Chunk]:
        """The struct items of the frame: an array looped over is one item of its bytes."""
        own = chunks_of(self.m.wire.unrepeated_runs(), self.view.p.framing.byte_order)
        return sorted(own + [rc.chunk() for rc in self.repeats.values()], key=lambda ch: ch.start)

    def one_word(self) -> bool:
        """The frame is short and all integers in the frame's bit order (big-endian most
        significant bit first): it is read and written as one int."""
        if self.m.size > 8 or self.m.shortening or self.repeats:
            return False
        for leaf in self.leaves:  # a checksum over bytes needs the bytes first
            f = leaf.field
            if f.kind in ("float", "bytes") or f.checksum and f.checksum.over == "bytes":
                return False
        if any(leaf.order not in (None, self.m.wire.order) for leaf in self.leaves):
            return False  # a field placed in the other bit order than the frame's
        return not any(ch.lone and ch.nbytes > 1 and ch.order != self.m.wire.order for ch in self.chunks())

    def structs(self) -> list[tuple[str, str]]:
        if self.one_word():
            return []
        segments = segments_of(self.chunks())
        own = [(f"_S_{self.fn}_{n}", s.fmt) for n, s in enumerate(segments)]
        if len(segments) == 1 and self.appended_checksum_head(segments, self.byte_checksums(), self.truncates()):
            # the encoder's: the same bytes up to the checksum it appends
            head = Segment(0, segments[0].chunks[:-1])
            own.append((f"_S_{self.fn}_h", head.fmt))
        return own + [x for rc in self.repeats.values() for x in rc.structs()]

    def byte_checksums(self) -> list:
        """(leaf, checksum) of each checksum over the frame's bytes."""
        return [(leaf, leaf.field.checksum) for leaf in self.leaves
                if leaf.field.checksum and leaf.field.checksum.over == "bytes"]

    def truncates(self) -> bool:
        """Whether the encoder leaves bytes out: a payload's trailing zeros, or gaps."""
        return bool(self.m.shortening and (self.m.shortening.trailing_zeros or self.m.shortening.gaps))

    def word_shifts(self) -> list[tuple[Leaf, int]]:
        """(leaf, shift) of every leaf in the frame read as one integer."""
        return [(leaf, self.m.shift(leaf)) for leaf in self.leaves]

    def encode_bytes_function(self) -> str:
        """_encode_<msg>(m), after the functions that check its elements apart (if any)."""
        self.helpers = []
        code = self.encode_bytes_code()
        self.fixed = {}  # the decoder reads every raw value from its local
        return "\n\n\n".join(self.helpers + [code])

    def encode_bytes_code(self) -> str:
        c = Code()
        size = self.m.size
        c(f"def _encode_{self.fn}(m: {self.cls}) -> {self.output}:")
        c.indent()
        word = self.one_word()
        self.raw_checks(c, word)
        if word:
            parity = [(leaf, shift) for leaf, shift in self.word_shifts()
                      if leaf.field.checksum and leaf.field.checksum.algorithm == "parity"]
            others = [x for x in self.word_shifts() if x not in parity]
            c(f"w: int = {self.packed(others)}")
            for leaf, shift in parity:  # parity of every other field is parity of the word
                flip = " ^ 1" if leaf.field.checksum.parity == "odd" else ""
                c(f"w |= (w.bit_count() & 1{flip}) << {shift}" if shift else f"w |= w.bit_count() & 1{flip}")
            c(f"return w.to_bytes({size}, {self.m.wire.order!r})")
            return c.text()
        segments = segments_of(self.chunks())
        crcs = self.byte_checksums()
        truncates = self.truncates()
        single = len(segments) == 1 and not crcs and not truncates
        head = self.appended_checksum_head(segments, crcs, truncates)
        if head is not None:  # packed to bytes, cut short, and the checksum appended: no buffer patched
            leaf, cs = crcs[0]
            chunk = segments[-1].chunks[-1]
            values = ", ".join(self.chunk_value(ch) for seg in segments for ch in seg.chunks if ch is not chunk)
            c(f"h = {head}.pack({values})")
            if truncates:
                self.truncate_head(c)
            order = leaf.field.byte_order or self.view.p.framing.byte_order
            value = self.view.checksum_call(cs, "h", cs.byte_span[0], cs.byte_span[1], self.m.crc_extra, truncates)
            c(f"return h + {value}.to_bytes({chunk.nbytes}, {order!r})")
            return c.text()
        if not single:
            c(f"b = bytearray({size})")
        for n, seg in enumerate(segments):
            values = ", ".join(self.chunk_value(ch) for ch in seg.chunks)
            if single:
                c(f"return _S_{self.fn}_{n}.pack({values})")
            else:
                c(f"_S_{self.fn}_{n}.pack_into(b, {seg.start}, {values})")
        if truncates and self.m.shortening.gaps:
            self.leave_out_gaps(c)
        elif truncates:
            self.truncate(c)
        end = self.m.shortening.payload[1] if truncates else size
        for leaf, cs in crcs:
            start, stop = cs.byte_span
            chunk, shift = next((ch, sh) for ch in self.chunks() for x, sh in ch.leaves if x is leaf)
            moved = " - cut" if chunk.start >= end else ""  # it follows the bytes left out
            at = f"b[{chunk.start}{moved}:{chunk.start + chunk.nbytes}{moved}]"
            value = self.view.checksum_call(cs, "b", start, stop, self.m.crc_extra, truncates and self.m.counts_sent(cs))
            if chunk.lone:
                order = leaf.field.byte_order or self.view.p.framing.byte_order
                c(f"{at} = {value}.to_bytes({chunk.nbytes}, {order!r})")
            else:  # a checksum sharing bytes with other fields goes into its bits
                order = chunk.order or "big"
                c(f"{at} = (int.from_bytes({at}, {order!r}) | {value} << {shift}).to_bytes({chunk.nbytes}, {order!r})")
        if not single:
            c("return bytes(b)")
        return c.text()

    def appended_checksum_head(self, segments: list[Segment], crcs: list, truncates: bool) -> Optional[str]:
        """The struct that packs the frame up to its one checksum, when that checksum is alone
        and last, over bytes before it (after a payload cut short at its trailing zeros, the
        payload's end): the checksum is then appended to the packed bytes, not patched in.
        None otherwise."""
        if len(crcs) != 1 or not 1 <= len(segments) <= 2 or segments[0].start != 0:
            return None
        chunk, (leaf, cs) = segments[-1].chunks[-1], crcs[0]
        if not (chunk.lone and chunk.repeat is None and chunk.leaves[0][0] is leaf
                and chunk.start + chunk.nbytes == self.m.size and cs.byte_span[1] <= chunk.start):
            return None
        if len(segments) == 2 and len(segments[1].chunks) != 1:
            return None
        if truncates:
            sh = self.m.shortening
            if sh.gaps or sh.payload[1] != chunk.start or cs.byte_span[1] != chunk.start or not self.m.counts_sent(cs):
                return None
            length = self.length_leaf()
            if length is not None and (length.pos + length.bits) // 8 > sh.payload[0] + sh.least:
                return None
        return f"_S_{self.fn}_0" if len(segments) == 2 else f"_S_{self.fn}_h"

    def length_leaf(self) -> Optional[Leaf]:
        """The leaf of the field counting the payload bytes sent, if the frame has one."""
        name = self.m.shortening.length_field if self.m.shortening else None
        return next((x for x in self.leaves if x.field.name == name), None) if name else None

    def truncate_head(self, c: Code) -> None:
        """The packed bytes `h` without the payload's trailing zeros (keeping the fewest it
        must carry), the length field counting the bytes sent."""
        sh = self.m.shortening
        lo, hi = sh.payload[0] + sh.least, sh.payload[1]
        c(f"cut = {hi - lo} - len(h[{lo}:{hi}].rstrip(b'\\0'))  # trailing zeros are not sent")
        c("if cut:")
        leaf = self.length_leaf()
        if leaf is None:
            c(f"    h = h[:{hi} - cut]")
            return
        at, n = leaf.pos // 8, leaf.bits // 8
        order = leaf.field.byte_order or self.view.p.framing.byte_order
        c(f"    h = b''.join((h[:{at}], ({leaf.field.const} - cut).to_bytes({n}, {order!r}), h[{at + n}:{hi} - cut]))")

    def leave_out_gaps(self, c: Code) -> None:
        """Drop the bytes of each gap that the frame does not send, the last gap first so
        the places of the earlier ones hold; a length field counts the payload bytes sent."""
        sh, lost = self.m.shortening, []
        for k, gap in enumerate(sh.gaps):
            if gap.counter:
                held = self.group_var((gap.field,)) if field_at(self.m.layout, gap.field).count else f"m.{gap.field}"
                per = gap.counter.element_bytes
                c(f"lost{k} = {gap.counter.most * per} - len({held}){f' * {per}' if per != 1 else ''}")
            else:
                c(f"lost{k} = 0 if {self.presence_test(gap)} else {gap.size}")
            lost.append(f"lost{k}")
        for k, gap in reversed(list(enumerate(sh.gaps))):
            c(f"del b[{gap.span[1]} - lost{k}:{gap.span[1]}]")
        c(f"cut = {' + '.join(lost)}")
        if sh.length_field:
            self.set_length(c, sh.length_field)

    def set_length(self, c: Code, name: str) -> None:
        """The length field counts the payload bytes sent."""
        leaf = next(x for x in self.leaves if x.field.name == name)
        at, n = leaf.pos // 8, leaf.bits // 8
        order = leaf.field.byte_order or self.view.p.framing.byte_order
        c(f"b[{at}:{at + n}] = ({leaf.field.const} - cut).to_bytes({n}, {order!r})")

    def truncate(self, c: Code) -> None:
        """Count the payload's trailing zero bytes the frame leaves off (keeping the
        fewest it must carry), and set the length field to the bytes sent."""
        sh = self.m.shortening
        lo, hi = sh.payload[0] + sh.least, sh.payload[1]
        c(f"cut = {hi - lo} - len(b[{lo}:{hi}].rstrip(b'\\0'))  # trailing zeros are not sent")
        c(f"del b[{hi} - cut:{hi}]")
        self.set_length(c, sh.length_field)

    def packed(self, leaves: list[tuple[Leaf, int]]) -> str:
        """Expression OR-ing (leaf, shift) pairs; fixed values are folded into one constant."""
        fixed, parts = 0, []
        for leaf, shift in leaves:
            if not leaf.field.bits:
                continue
            value = self.view.fixed_raw(leaf.field)
            if value is None:
                value = self.fixed.get(leaf.var)  # a checksum not yet computed: zero
            if value is not None:
                fixed |= (value & ((1 << leaf.field.bits) - 1)) << shift
            else:
                parts.append(f"{self.unsigned(leaf)} << {shift}" if shift else self.unsigned(leaf))
        if fixed or not parts:
            parts.append(f"{fixed:#x}")
        return " | ".join(parts)

    def chunk_value(self, chunk: Chunk) -> str:
        if chunk.repeat is not None:
            return blob(chunk.repeat)
        if chunk.lone:
            leaf = chunk.leaves[0][0]
            fixed = self.view.fixed_raw(leaf.field)
            if fixed is None:
                fixed = self.fixed.get(leaf.var)  # a checksum not yet computed: zero
            if fixed is not None and chunk.code not in ("s", "f", "d") and not chunk.code.endswith("s"):
                return lit(fixed)
            if chunk.code == "s":
                order = leaf.field.byte_order or self.view.p.framing.byte_order
                if fixed is not None:  # its bytes, written out
                    return repr((fixed % (1 << (8 * chunk.nbytes))).to_bytes(chunk.nbytes, order))
                return f"{leaf.var}.to_bytes({chunk.nbytes}, {order!r}{', signed=True' if chunk.signed else ''})"
            return self.raw(leaf)
        expr = self.packed(chunk.leaves)
        if chunk.other:  # the fields in the other byte order, as the chunk's integer holds their bytes
            flipped = f"({self.packed(chunk.other)}).to_bytes({chunk.nbytes}, {chunk.other_order!r})"
            expr = f"{expr} | int.from_bytes({flipped}, {chunk.order!r})"
        if chunk.code == "s":
            return f"({expr}).to_bytes({chunk.nbytes}, {chunk.order!r})"
        return expr

    def decode_bytes_function(self) -> str:
        """_decode_<msg>(d): one straight-line function from bytes to the checked object."""
        c = Code()
        size = self.m.size
        c(f"def _decode_{self.fn}(d: _Buffer) -> {self.cls}:")
        c.indent()
        c(f'"""The {self.m.name} message in `d`, as {self.cls}.decode: any bytes-like object."""')
        c("if d.__class__ is not bytes:")
        c("    d = _as_input(d)")
        sh = self.m.shortening
        if sh:
            least = self.m.min_size
            c(f"if not {least} <= len(d) <= {size}:")
            c(f"    raise _dec({self.m.name!r}, None, len(d), 'length', '{least}..{size} bytes', 0)")
            c(f"s, cut = d, {size} - len(d)")
            if sh.gaps:
                self.restore_gaps(c)
            else:
                c("if cut:  # the payload bytes left off read as zeros")
                c(f"    d = b''.join((d[:{sh.payload[1]} - cut], bytes(cut), d[{sh.payload[1]} - cut:]))")
        else:
            c(f"if len(d) != {size}:")
            c(f"    raise _dec({self.m.name!r}, None, len(d), 'length', '{size} bytes', 0)")
        if self.one_word():
            self.read_word(c)
        else:
            self.read_chunks(c)
        for leaf in self.leaves:
            cs = leaf.field.checksum
            if cs and cs.over == "bytes":
                start, end = cs.byte_span
                sent = self.m.counts_sent(cs)  # over the bytes sent
                buf = 's' if sent else 'd'
                if cs.covers_self:  # RFC 1071's receiver check: with the field, the sum is all ones
                    c(f"if {self.view.checksum_call(cs, buf, start, end, None, sent)}:")
                    c(f"    x = {self.view.zeroed_checksum_call(cs, buf, leaf.pos // 8, sent)}")
                    c(f"    raise _dec({self.m.name!r}, {leaf.dotted!r}, {leaf.var}, 'checksum', hex(x), {self.sent_offset(leaf)}, {leaf.field.rule!r})")
                    continue
                c(f"x = {self.view.checksum_call(cs, buf, start, end, self.m.crc_extra, sent)}")
                c(f"if {leaf.var} != x:")
                c(f"    raise _dec({self.m.name!r}, {leaf.dotted!r}, {leaf.var}, 'checksum', hex(x), {self.sent_offset(leaf)}, {leaf.field.rule!r})")
        length = self.length_leaf() if sh else None
        if length is not None:  # a field checksum counts the length as if the whole payload were sent, as C does
            self.restored = {length.var: f"({length.var} + cut)"}
        self.build_checks(c, bounded=True, text_form=False, word=self.one_word())
        self.restored = {}
        c("return o")
        return c.text()

    def restore_gaps(self, c: Code) -> None:
        """Read each gap's control field from the bytes sent (`s`), check it, and put the bytes
        the frame leaves out back as zeros (`d`), so the fields read from their places."""
        name, size, gaps = self.m.name, self.m.size, self.m.shortening.gaps
        lost = ""
        for k, (gap, read) in enumerate(zip(gaps, gap_reads(self.view.p, self.m))):
            if k:  # the shortest frame holds what comes before the first gap
                c(f"if len(s) < {gap.span[0]}{lost}:")
                c(f"    raise _dec({name!r}, {gap.field!r}, len(s), 'length', f'at least {{{gap.span[0]}{lost}}} bytes', {8 * gap.span[0]})")
            if gap.fills_rest:  # the last gap: what the frame holds past the fields before it
                self.take_rest(c, k, gap, lost)
                lost += f" - lost{k}"
                continue
            value = self.sent_read(read, "".join(f" - lost{j}" for j in read["before"]))
            if gap.counter:
                self.check_count(c, gap, read["leaf"], value)
                c(f"lost{k} = {gap.counter.most * gap.counter.element_bytes} - n * {gap.counter.unit}")
            else:
                c(f"p_{gap.field} = {self.presence_test(gap, value)}")
                c(f"lost{k} = 0 if p_{gap.field} else {gap.size}")
            lost += f" - lost{k}"
        c(f"if len(s) != {size}{lost}:")
        c(f"    raise _dec({name!r}, {gaps[-1].field!r}, len(s), 'length', f'{{{size}{lost}}} bytes', {8 * gaps[-1].span[0]})")
        parts, at = [], "0"
        for k, gap in enumerate(gaps):
            end = f"{gap.span[1]}{''.join(f' - lost{j}' for j in range(k + 1))}"
            parts += [f"s[{at}:{end}]", f"bytes(lost{k})"]
            at = end
        parts[0] = parts[0].replace("[0:", "[:")
        c("if cut:  # the bytes left out read as zeros")
        c(f"    d = b''.join(({', '.join(parts)}, s[{at}:]))")

    def take_rest(self, c: Code, k: int, gap, lost: str) -> None:
        """A field filling the rest of the payload: the frame's size says how much of it was
        sent, whole elements up to its most."""
        counter, name = gap.counter, self.m.name
        c(f"lost{k} = {self.m.size}{lost} - len(s)")
        c(f"if not 0 <= lost{k} <= {gap.size} or (lost{k} - {gap.size}) % {counter.element_bytes}:")
        c(f"    raise _dec({name!r}, {gap.field!r}, len(s), 'length', "
          f"f'{{{self.m.size}{lost} - {gap.size}}} bytes and whole elements of {counter.element_bytes}', {8 * gap.span[0]})")
        c(f"n_{gap.field} = {counter.most} - lost{k} // {counter.element_bytes}")

    @staticmethod
    def sent_read(read: dict, less: str) -> str:
        """The control field's raw value, read from the bytes sent: `less` the bytes missing ahead of it."""
        at, last = f"{read['at']}{less}", f"{read['last']}{less}"
        value = f"s[{at}]" if read["bytes"] == 1 else f"int.from_bytes(s[{at}:{last}], {read['byte_order']!r})"
        if read["shift"]:
            value = f"({value} >> {read['shift']})"
        if read["shift"] or read["mask"] != (1 << (8 * read["bytes"])) - 1:
            value = f"({value} & {read['mask']:#x})"
        return value

    def check_count(self, c: Code, gap, leaf: Leaf, value: str) -> None:
        """The count field's value: within the array's most, and a whole number of elements."""
        counter, name = gap.counter, self.m.name
        c(f"n = {value}")
        c(f"if n > {counter.most_value}:")
        c(f"    raise _dec({name!r}, {leaf.dotted!r}, n, 'range', '0..{counter.most_value}', {leaf.pos})")
        if counter.step != 1:  # its bytes must hold whole elements
            c(f"if n % {counter.step}:")
            c(f"    raise _dec({name!r}, {leaf.dotted!r}, n, 'length', 'a multiple of {counter.step}', {leaf.pos})")
        c(f"n_{counter.field} = {times_over('n', counter.unit, counter.element_bytes, '//')}")

    def read_word(self, c: Code) -> None:
        c(f"w = int.from_bytes(d, {self.m.wire.order!r})")
        used = sum(leaf.field.bits or 0 for leaf in self.leaves)
        shift, pad = self.m.padding()
        padding = ((1 << pad) - 1) << shift
        if padding:  # bits after the record that fill the last byte must be zero
            c(f"if w & {padding:#x}:")
            c(f"    raise _dec({self.m.name!r}, 'padding', w & {padding:#x}, 'reserved', '0', {used})")
        for leaf, shift in self.word_shifts():
            self.extract(c, leaf, "w", shift)

    def read_chunks(self, c: Code) -> None:
        segments = segments_of(self.chunks())
        names = []
        for n, seg in enumerate(segments):
            # a field that fills its own struct item is unpacked straight into its variable
            vars_ = [region(ch.repeat) if ch.repeat is not None else ch.leaves[0][0].var if ch.lone and ch.code != "s"
                     else f"c{seg.start}_{k}" for k, ch in enumerate(seg.chunks)]
            names.extend(zip(vars_, seg.chunks))
            c(f"{', '.join(vars_)}, = _S_{self.fn}_{n}.unpack_from(d, {seg.start})")
        self.unpack_chunks(c, names)

    def unpack_chunks(self, c: Code, names: list[tuple[str, Chunk]]) -> None:
        """Set each leaf's raw value from the struct items unpacked into `names`."""
        for var, chunk in names:
            if chunk.repeat is not None:
                continue  # read by the array's loop
            if chunk.lone:
                leaf = chunk.leaves[0][0]
                if chunk.code == "s":
                    order = leaf.field.byte_order or self.view.p.framing.byte_order
                    read = f"int.from_bytes({var}, {order!r}{', signed=True' if chunk.signed else ''})"
                    if self.only_checked(leaf):
                        raw = self.view.fixed_raw(leaf.field) % (1 << (8 * chunk.nbytes))
                        self.const_items[leaf.var] = (var, raw.to_bytes(chunk.nbytes, order), read)
                    else:
                        c(f"{leaf.var} = {read}")
                continue
            if chunk.code == "s":
                c(f"{var} = int.from_bytes({var}, {chunk.order!r})")
            if chunk.other:  # the same bytes read in the other byte order
                c(f"{var}x = int.from_bytes({var}.to_bytes({chunk.nbytes}, {chunk.order!r}), {chunk.other_order!r})")
                for leaf, shift in chunk.other:
                    self.extract(c, leaf, f"{var}x", shift)
            used = 0
            for leaf, shift in chunk.leaves:
                used |= ((1 << leaf.field.bits) - 1) << shift
            padding = 0 if chunk.free else ((1 << (8 * chunk.nbytes)) - 1) & ~used
            if padding:  # bits after the record that fill the last byte must be zero
                c(f"if {var} & {padding:#x}:")
                c(f"    raise _dec({self.m.name!r}, 'padding', {var} & {padding:#x}, 'reserved', '0', "
                  f"{self.m.bits})")
            for leaf, shift in chunk.leaves:
                self.extract(c, leaf, var, shift)

    def extract(self, c: Code, leaf: Leaf, var: str, shift: int) -> None:
        bits = leaf.field.bits
        if not bits:
            return
        raw = f"({var} >> {shift}) & {(1 << bits) - 1:#x}" if shift else f"{var} & {(1 << bits) - 1:#x}"
        if leaf.field.kind == "float":  # a float among bit fields (placed by start bit): its IEEE 754 bits
            c(f"{leaf.var} = _float_of_bits({raw}, {bits})")
            self.view.calls.use("_float_of_bits")
            return
        c(f"{leaf.var} = {raw}")
        if leaf.field.kind == "int":
            c(f"if {leaf.var} & {1 << (bits - 1):#x}:")
            c(f"    {leaf.var} -= {1 << bits:#x}")

    # -- the text form of a bits protocol (a text exchange file) --------------------------
    def text_form_functions(self) -> str:
        """The exchange-file form: the raw wire values in decimal, a signed field as its
        bit pattern (as the C writes it), so every token is a plain unsigned number."""
        sep = self.view.p.framing.text_form.separator
        names = ", ".join(x.var for x in self.leaves)
        c = Code()
        c(f"def _encode_text_{self.fn}(m: {self.cls}) -> str:")
        c(f"    {names}, = _raw_{self.fn}(m)")
        c(f"    return {sep!r}.join(map(str, ({''.join(self.unsigned(x) + ', ' for x in self.leaves)})))")
        c("")
        c(f"def _decode_text_{self.fn}(tokens: list[int]) -> {self.cls}:")
        c.indent()
        c(f"if len(tokens) != {len(self.leaves)}:")
        c(f"    raise _dec({self.m.name!r}, None, len(tokens), 'count', '{len(self.leaves)} values', 0)")
        c(f"{names}, = tokens")
        # Text carries any integer: each must fit its width, then a signed one is sign-extended.
        for leaf in self.leaves:
            f, var = leaf.field, leaf.var
            if f.range is None or f.kind == "int":
                top = (1 << f.bits) - 1
                c(f"if {var} > {top}:")
                c(f"    raise _dec({self.m.name!r}, {leaf.dotted!r}, {var}, 'range', '0..{top}', 0)")
            if f.kind == "int":
                c(f"if {var} & {1 << (f.bits - 1):#x}:")
                c(f"    {var} -= {1 << f.bits:#x}")
        c(f"return _build_{self.fn}({names}, text_form=True)")
        return c.text()

    # -- text framing ----------------------------------------------------------------------
    @property
    def text_leaves(self) -> tuple[Leaf, ...]:
        """The values of the line's body: all but the prefix field."""
        return tuple(leaf for leaf in self.leaves if not leaf.field.prefix)

    def prefix_check(self, c: Code, var: str, coder: str, at: str) -> None:
        """The prefix field's value: its length of uppercase letters, one of its values if listed."""
        f = self.m.prefix_field
        where = f"{self.m.name!r}, {f.name!r}"
        if coder == "_enc":
            c(f"if not isinstance({var}, str):")
            c(f"    raise _enc({where}, {var}, 'type', 'a string')")
            c(f"if len({var}) != {f.length}:")
            c(f"    raise _enc({where}, {var}, 'length', '{f.length} characters')")
        c(f"if _PREFIX_VALUE_RE.fullmatch({var}) is None:")
        c(f"    raise {coder}({where}, {var}, 'text', 'uppercase letters A-Z'{at})")
        if f.values:
            c(f"if {var} not in {tuple(f.values)!r}:")
            c(f"    raise {coder}({where}, {var}, 'values', {' '.join(f.values)!r}{at})")

    def text_encode_function(self) -> str:
        fr = self.view.p.framing
        c = Code()
        c(f"def _encode_{self.fn}(m: {self.cls}) -> {self.output}:")
        c.indent()
        self.view.rule_checks(c, self.m, "m", "_enc")
        head = ""
        if self.m.prefix_field is not None:  # written before the id
            c(f"h = m.{self.m.prefix_field.name}")
            self.prefix_check(c, "h", "_enc", "")
            head = "h + "
        outs: list[str] = []  # the text of each field, joined once at the end
        places = self.m.text_places
        least = places.least
        if any(leaf.field.keep_spelling for leaf in self.text_leaves):
            c("sp = m._spelling or {}  # the text each number was read from, with its raw value and value")
        for n, leaf in enumerate(self.text_leaves):
            f = leaf.field
            where = f"{self.m.name!r}, {leaf.dotted!r}"
            if f.optional and f.const is not None:
                pass  # no member: a constant that a line may leave empty is always written
            elif f.optional:
                c(f"if m.{leaf.dotted} is not None:")
                c.indent()
            if f.kind in ("char", "str") and f.enum is None and f.const is not None:
                out = repr(f.const)  # not a member: written as the schema spells it
            elif f.kind in ("char", "str") and f.enum is None:
                v = leaf.var
                c(f"{v} = m.{leaf.dotted}")
                c(f"if not isinstance({v}, str){f' or len({v}) != 1' if f.kind == 'char' else ''}:")
                c(f"    raise _enc({where}, {v}, 'type', {'one character' if f.kind == 'char' else 'a string'!r})")
                forbidden = "" if f.to_end else fr.separator
                c(f"if not {'_REST_OK' if f.to_end else '_TEXT_OK'}.fullmatch({v}):  # else look closer")
                c(f"    bad = _text_problem({v}, {forbidden!r}, {fr.trim})")
                self.view.calls.use("_text_problem")
                c("    if bad:")
                c(f"        raise _enc({where}, {v}, 'text', bad, {f.rule!r})")
                if f.max_length is not None:
                    c(f"if len({v}) > {f.max_length}:")
                    c(f"    raise _enc({where}, {v}, 'length', 'at most {f.max_length} characters')")
                out = v
            else:
                if f.keep_spelling:  # the very value decoded: its text as received, checked then
                    k = "k_" + leaf.var[2:]
                    c(f"{k} = sp.get({f.name!r})")
                    c(f"if {k} is not None and {k}[2] is m.{leaf.dotted}:")
                    c(f"    t{n} = {k}[1]")
                    c("else:")
                    c.indent()
                self.view.encode_leaf(c, self.m, leaf)
                if f.kind == "float":
                    out = self.view.float_text(leaf)
                elif f.enum is not None and f.enum.kind == "char":
                    out = leaf.var  # checked: its value's text, or a member, a str of its value
                elif f.fixed_spelling:
                    out = f"_fixed({leaf.var}, {f.decimals or 0}, {f.width or 0})"
                else:
                    out = f"str({leaf.var})"
                if f.keep_spelling:  # as received, while the field holds the value it reads as
                    c(f"t{n} = ({k}[1] if {k} is not None and {k}[0] == {leaf.var} else {out})")
                    c.dedent()
                    out = f"t{n}"
            if f.optional and f.const is None:  # absent: an empty value, or none at all at the end of the line
                if out != f"t{n}":
                    c(f"t{n} = {out}")
                c.dedent()
                c("else:")
                c(f"    t{n} = {'None' if n >= least else repr('')}")
                out = f"t{n}"
            outs.append(out)
        if places.varies:
            c(f"p: list[Any] = [{', '.join(outs)}]")
            if self.m.keeps_places:  # as many values as the line it was decoded from, if it was
                c(f"k = m._places if m._places is not None and {least} <= m._places <= {places.total} else {places.written}")
            else:
                c(f"k = {places.written}  # the values always written")
            c("while len(p) > k and p[-1] is None:  # absent values at the end are left out, separators and all")
            c("    p.pop()")
            last = places.total - 1
            for n in range(least, places.total):
                leaf = self.text_leaves[n]
                if n == last and n >= places.written and not self.m.keeps_places:
                    break  # the last value is in the line only when present
                c(f"if len(p) > {n} and p[{n}] is None:")
                if leaf.field.kind != "str":
                    c(f"    p[{n}] = ''")
                    continue
                if n < last:  # an empty value would read as an empty str: the line ends before it
                    c(f"    if any(x is not None for x in p[{n + 1}:]):")
                    c(f"        raise _enc({self.m.name!r}, {leaf.dotted!r}, None, 'count', 'present, as a later value is')")
                c(f"    del p[{n}:]")
        sep = repr(fr.separator)
        values = f"{sep}.join(p)" if places.varies else f"{sep}.join(({''.join(x + ', ' for x in outs)}))"
        if fr.line_checksum:  # _line adds the start marker, the checksum and the terminator
            c(f"return _line({head}{self.m.ids[0] + fr.prefix_separator!r} + {values})")
        elif head:
            c(f"return {fr.start!r} + {head}{self.m.ids[0] + fr.prefix_separator!r} + {values} + {fr.terminator!r}")
        else:
            c(f"return {fr.start + self.m.ids[0] + fr.prefix_separator!r} + {values} + {fr.terminator!r}")
        return c.text()

    @property
    def prefix_var(self) -> str:
        return next(leaf.var for leaf in self.leaves if leaf.field.prefix)

    def text_syntax(self) -> str:
        """An expression for the regular expression a well-formed body matches: every number
        well-formed, every text value printable without separators or spaces. A body that
        matches needs no per-token syntax checks; one that does not takes the checked path,
        which names the first bad token. Stricter than the checks it stands for, never looser."""
        sep = repr(re.escape(self.view.p.framing.separator))
        out, closing = [], ""
        least = self.m.text_places.least
        for n, leaf in enumerate(self.text_leaves):
            f = leaf.field
            if f.kind == "float":
                tok = "_FINITE_RE"
            elif f.fixed_spelling:
                tok = "_FIXED_RE"
            elif f.kind in ("uint", "int") or (f.enum is not None and f.enum.kind == "int"):
                tok = "_INT_RE"
            elif f.kind == "char":
                tok = "_CHAR_RE"
            else:
                tok = "_REST_RE" if f.to_end else "_TEXT_RE"
            if n >= least:  # the line may end before it
                out.append("'(?:'")
                closing += ")?"
            if n:
                out.append(sep)
            out.append(f"'(?:' + {tok} + ')?'" if f.optional and f.kind != "str" else tok)
        if closing:
            out.append(repr(closing))
        return " + ".join(out)

    @staticmethod
    def text_classes(fr) -> dict:
        """Character classes of text values: printable ASCII without space, terminator and
        separator (the last field, which runs to the end, may hold separators)."""
        def ranges(banned: set) -> str:
            codes = [x for x in range(0x21, 0x7f) if chr(x) not in banned]
            runs, start = [], codes[0]
            for a, b in zip(codes, codes[1:] + [None]):
                if b != a + 1:
                    runs.append(re.escape(chr(start)) + ("-" + re.escape(chr(a)) if a > start else ""))
                    start = b
            return "[" + "".join(runs) + "]"
        base = set(fr.terminator)
        return {"char": ranges(base | set(fr.separator)), "rest": ranges(base)}

    def text_decode_function(self) -> str:
        fr = self.view.p.framing
        c = Code()
        c(f"def _decode_{self.fn}(head: str, body: str, base: int) -> {self.cls}:")
        c.indent()
        values: dict[tuple, str] = {}
        pf = self.m.prefix_field
        if pf is None:
            c("del head  # the prefix is the id alone")
        else:  # the prefix's value before the id, which dispatch found
            c(f"{self.prefix_var} = head[:{pf.length}]")
            self.prefix_check(c, self.prefix_var, "_dec", f", {len(fr.start)}")
            values[(pf.name,)] = self.prefix_var
        total = len(self.text_leaves)
        required = self.m.text_places.least  # a line may end after this many values
        last_to_end = bool(self.text_leaves) and self.text_leaves[-1].field.to_end
        if total == 0:
            c("t = []")
            c("if body.strip():")
            c(f"    raise _dec({self.m.name!r}, None, body, 'count', 'no fields', base)")
        elif last_to_end:
            c(f"t = body.split({fr.separator!r}, {total - 1})" + (" if body else []" if not required else ""))
        else:
            # every value optional: an empty body holds none (not one empty value)
            c(f"t = body.split({fr.separator!r})" + (" if body else []" if not required else ""))
        c(f"if not {required} <= len(t) <= {total}:")
        c(f"    raise _dec({self.m.name!r}, None, len(t), 'count', {f'{required}..{total} fields' if required != total else f'{total} fields'!r}, base)")
        if total:
            c(f"ok = _SYNTAX_{self.fn}.fullmatch(body) is not None  # well-formed: token syntax checks are skipped")
        kept = any(leaf.field.keep_spelling for leaf in self.text_leaves)
        if kept:
            c("sp: dict[str, tuple[Any, str, Any]] = {}  # each number's text, with its raw value and value")
        for n, leaf in enumerate(self.text_leaves):
            f = leaf.field
            at = f"{self.m.name!r}, {leaf.dotted!r}"
            where = f"_token_offset(t, base, {n})"  # computed only for an error
            lazy = f"t, base, {n}"  # what a parser computes it from, for an error
            held = f"t[{n}].strip()" if fr.trim else f"t[{n}]"
            if f.optional and f.kind == "str" and f.const is None:  # an empty value is an empty str
                c(f"if len(t) > {n}:")
                c.indent()
            elif f.optional:  # an empty value is an absent one; every line holds the first `required`
                c(f"if len(t) > {n} and {held}:" if n >= required else f"if {held}:")
                c.indent()
            tok = f"(t[{n}] if ok else t[{n}].strip())" if fr.trim else f"t[{n}]"
            slow_tok = f"t[{n}].strip()" if fr.trim else f"t[{n}]"
            if f.keep_spelling:  # kept whole, never cut short
                c(f"if len(t[{n}]) > {SPELLING_MAX}:")
                c(f"    raise _dec({at}, t[{n}], 'length', 'a number of at most {SPELLING_MAX} characters', {where})")
            if f.kind == "float":
                c(f"{leaf.var} = float(t[{n}]) if ok else _parse_float({slow_tok}, {at}, {lazy})")
                self.view.calls.use("_parse_float")
            elif f.fixed_spelling:  # any spelling, rounded to the field's decimals
                c(f"{leaf.var} = _fixed_of(t[{n}], {f.decimals or 0}) if ok else "
                  f"_parse_fixed({slow_tok}, {f.decimals or 0}, {at}, {lazy})")
            elif f.kind in ("uint", "int") or (f.enum is not None and f.enum.kind == "int"):
                c(f"{leaf.var} = int(t[{n}]) if ok else _parse_int({slow_tok}, {at}, {lazy})")
                self.view.calls.use("_parse_int")
            elif f.kind == "char":
                c(f"{leaf.var} = {tok}")
                c(f"if len({leaf.var}) != 1:")
                c(f"    raise _dec({at}, {leaf.var}, 'type', 'one character', {where})")
            else:
                c(f"{leaf.var} = {tok}")
            if f.kind in ("char", "str") and f.enum is None:
                # what a writer may not emit, a reader does not accept either
                c("if not ok:")
                c(f"    bad = _text_problem({leaf.var}, {'' if f.to_end else fr.separator!r}, {fr.trim})")
                self.view.calls.use("_text_problem")
                c("    if bad:")
                c(f"        raise _dec({at}, {leaf.var}, 'text', bad, {where}, {f.rule!r})")
                if f.max_length is not None:
                    c(f"if len({leaf.var}) > {f.max_length}:")
                    c(f"    raise _dec({at}, {leaf.var}, 'length', 'at most {f.max_length} characters', {where})")
            expr = self.view.decode_leaf(c, self.m, leaf, where, finite_if="ok")
            if f.keep_spelling:  # with the value object itself: encode knows it unchanged by identity
                if expr is not None and expr != leaf.var and not expr.isidentifier():
                    c(f"d_{leaf.var[2:]} = {expr}")
                    expr = f"d_{leaf.var[2:]}"
                c(f"sp[{f.name!r}] = ({leaf.var}, t[{n}], {expr or leaf.var})")
            if f.optional:
                c.dedent()
                c("else:")
                c(f"    {leaf.var} = None")
                if expr and expr.isidentifier() and expr != leaf.var:  # bound on both branches
                    c(f"    {expr} = None")
                elif expr != leaf.var:
                    expr = f"(None if {leaf.var} is None else {expr})"
            values[leaf.path] = expr if expr is not None else leaf.var
        self.construct(c, self.m.layout, (), values)
        if kept:
            c("o._spelling = sp")
        if self.m.keeps_places:
            c("o._places = len(t)  # written back with as many values")
        self.view.rule_checks(c, self.m, "o", "_dec")
        c("return o")
        return c.text()


def sizes_range(least: int, most: int, step: int) -> str:
    """Python for the frame sizes least..most in steps of `step`."""
    return f"range({least}, {most + 1}{f', {step}' if step != 1 else ''})"


def sizes_literal(sizes: list[int]) -> str:
    """Python for a list of sorted sizes: a run of three or more consecutive ones is a range,
    so that a counted array's many sizes cost no more text than its few."""
    runs: list[list[int]] = []
    for n in sizes:
        if runs and runs[-1][-1] + 1 == n:
            runs[-1].append(n)
        else:
            runs.append([n])
    items = [f"*range({run[0]}, {run[-1] + 1})" if len(run) > 2 else ", ".join(map(str, run)) for run in runs]
    return f"[{', '.join(items)}]"


def module_view(p: Protocol) -> dict:
    """Everything the module template needs, computed."""
    view = ModuleView(p)
    codes = [MessageCode(view, m) for m in p.messages]
    fr = p.framing
    functions: list[str] = []
    structs: list[tuple[str, str]] = []
    syntaxes: list[tuple[str, str]] = []
    for mc in codes:
        if fr.kind == "text":
            functions += [mc.text_encode_function(), mc.text_decode_function()]
            if mc.text_leaves:
                syntaxes.append((mc.fn, mc.text_syntax()))
            continue
        functions += [mc.encode_bytes_function(), mc.decode_bytes_function()]
        if fr.text_form:
            functions += [mc.raw_function(), mc.build_function(), mc.text_form_functions()]
        structs += mc.structs()
    facts = {
        "p": p, "view": view, "codes": codes, "functions": functions, "structs": structs,
        "syntaxes": syntaxes, "text_classes": MessageCode.text_classes(fr) if fr.kind == "text" else {},
        "text_float": TEXT_FLOAT, "line": text_line_facts(p),
        "fixed": any(x.field.fixed_spelling for m in p.messages for x in m.wire.leaves),
        "has_gaps": any(m.shortening and m.shortening.gaps or any(f.multiplexed_by for f in m.layout)
                        for m in p.messages),
        "classes": view.dataclasses(),
        "dispatch": view.dispatch_table(), "sequences": [view.sequence_view(s) for s in p.sequences],
        "stream": view.stream_view(), "encoding": view.encoding_view(), "stuffing": stuffing_view(p),
        # frames sent otherwise than the layout describes them: encoders and decoders wrap the frame's own
        "wrapped": bool(p.framing.encoding or p.framing.stuffing),
        "decode_overloads": view.decode_signature(), "trailer": trailer_view(p),
        "kept_spellings": any(f.keep_spelling for m in p.messages for f in m.layout) or any(m.keeps_places for m in p.messages),
        "can": can_view(p),
        "open_enums": any(e.open for e in p.enums),
    }
    for cs in facts["stuffing"].get("checksums", ()):  # computed again over a frame as sent
        view.checksum_function(cs["cs"])
    facts["checksums"] = view.checksum_functions()  # those called, once every caller is written
    facts["needs"] = _template_calls(facts, view.calls).closure()
    return facts


def _template_calls(facts: dict, calls: Calls) -> Calls:
    """`calls` with what the template's own parts call, under the conditions that write them."""
    p, fr, stream = facts["p"], facts["p"].framing, facts["stream"]
    text_form = facts["dispatch"]["kind"] == "bits" and fr.text_form  # decode_text and decode_lines
    if fr.kind == "text" or text_form:
        calls.use("re")
    if text_form:
        calls.use("_int_of", "Iterator")
    if p.enums or p.flags:
        calls.use("enum")
    if facts["structs"] or calls.names & {"_float_of_bits", "_bits_of_float"}:  # their tables are structs
        calls.use("struct")
    if stream and not facts["encoding"] and stream.get("by_key") and stream["by_key"].get("counted"):
        calls.use("Literal")  # the byte order of a count field
    return calls


def _bit_reversed_hqx(p) -> bool:
    """A reflected CRC-16 of poly 0x1021, which crc_hqx computes over bit-reversed bytes."""
    return p.width == 16 and p.poly == 0x1021 and p.refin and p.refout


def _stdlib_crc(p, name: str = "") -> Optional[tuple[str, list[str]]]:
    """(import, body lines computing the CRC of `data`) for a CRC the standard library
    computes in C: binascii.crc_hqx is poly 0x1021 unreflected from any start value,
    zlib.crc32 is poly 0x04C11DB7 reflected and inverted on the way in and out. Poly 0x1021
    reflected (X.25, MAVLink's MCRF4XX, KERMIT) is crc_hqx of the bytes bit-reversed, its
    result bit-reversed: reflecting every byte in and the register out is the whole of a
    reflected CRC. None for any other CRC."""
    def out(value: str, xorout: int) -> str:
        return f"{value} ^ {xorout:#x}" if xorout else value
    if p.width == 16 and p.poly == 0x1021 and not p.refin and not p.refout:
        return "from binascii import crc_hqx as _crc_hqx", [f"return {out(f'_crc_hqx(data, {p.init:#x})', p.xorout)}"]
    if _bit_reversed_hqx(p):
        table = f"_BITS_REVERSED_{name}"
        # bytes and bytearray translate themselves; anything else is copied to bytes first
        return ("from binascii import crc_hqx as _crc_hqx",
                [f"x = _crc_hqx((data if isinstance(data, (bytes, bytearray)) else bytes(data)).translate({table}), {p.init:#x})",
                 f"return {out(f'({table}[x & 0xFF] << 8 | {table}[x >> 8])', p.xorout)}  # x bit-reversed"])
    if p.width == 32 and p.poly == 0x04C11DB7 and p.refin and p.refout:
        start = reflect(p.init, 32) ^ 0xFFFFFFFF
        return ("from zlib import crc32 as _crc32",
                [f"return {out(f'_crc32(data, {start:#x})', 0xFFFFFFFF ^ p.xorout)}"])
    return None


def _checksum_code(cs, function: bool = True) -> str:
    """A checksum's function over any bytes, after the tables it reads; `function` False:
    a CRC's byte table alone, which the straight-line code of its fixed lengths reads."""
    name = _checksum_name(cs)
    c = Code()
    fast = _stdlib_crc(cs.crc, name) if cs.algorithm == "crc" else None
    if fast:
        p = cs.crc
        c(f"# {p.name if p.name != 'custom' else 'CRC'}: width={p.width} poly={p.poly:#x} init={p.init:#x} "
          f"refin={p.refin} refout={p.refout} xorout={p.xorout:#x}, computed by the standard library in C")
        c(fast[0])
        if _bit_reversed_hqx(cs.crc):  # a table of each byte bit-reversed, its own so that CRCs never share names
            c(f"_BITS_REVERSED_{name} = bytes(int(f'{{b:08b}}'[::-1], 2) for b in range(256))")
        c("")
        c("")
        c(f"def _checksum_{name}(data: _Buffer) -> int:")
        for line in fast[1]:
            c(f"    {line}")
    elif cs.algorithm == "crc":
        p = cs.crc
        mask = (1 << p.width) - 1
        c(f"# {p.name if p.name != 'custom' else 'CRC'}: width={p.width} poly={p.poly:#x} init={p.init:#x} "
          f"refin={p.refin} refout={p.refout} xorout={p.xorout:#x}")
        _table_literal(c, name, p)
        if not function:
            return c.text()
        if p.refin:
            # Reflected algorithm: shift right with the reflected polynomial.
            init = reflect(p.init, p.width)
            c(f"def _checksum_{name}(data: _Buffer) -> int:")
            c(f"    reg = {init:#x}")
            c(f"    table = _TABLE_{name}")
            c("    for byte in data:")
            c("        reg = table[(reg ^ byte) & 0xFF] ^ (reg >> 8)")
            if not p.refout:
                c(f"    reg = int(format(reg, '0{p.width}b')[::-1], 2)")
            c(f"    return reg ^ {p.xorout:#x}")
        else:
            shift = p.width - 8
            c(f"def _checksum_{name}(data: _Buffer) -> int:")
            if p.width >= 8:
                c(f"    reg = {p.init:#x}")
                c(f"    table = _TABLE_{name}")
                c("    for byte in data:")
                c(f"        reg = table[((reg >> {shift}) ^ byte) & 0xFF] ^ ((reg << 8) & {mask:#x})")
            else:
                c(f"    reg = {p.init << (8 - p.width):#x}")
                c(f"    table = _TABLE_{name}")
                c("    for byte in data:")
                c("        reg = table[reg ^ byte]")
                c(f"    reg >>= {8 - p.width}")
            if p.refout:
                c(f"    reg = int(format(reg, '0{p.width}b')[::-1], 2)")
            c(f"    return reg ^ {p.xorout:#x}")
    elif cs.algorithm == "sum":
        c(f"def _checksum_{name}(data: _Buffer) -> int:")
        c(f"    return {_final_step(cs, f'sum(data) % {cs.modulo}')}")
    elif cs.algorithm == "xor":
        c(f"def _checksum_{name}(data: _Buffer) -> int:")
        c("    x = 0")
        c("    for byte in data:")
        c("        x ^= byte")
        c(f"    return {_final_step(cs, f'x % {cs.modulo}')}")
    elif cs.algorithm == "fletcher":
        _fletcher_code(c, cs, name)
    elif cs.algorithm == "internet":
        _internet_code(c, cs, name)
    else:
        c(f"def _checksum_{name}(data: _Buffer) -> int:")
        flip = " ^ 1" if cs.parity == "odd" else ""
        c(f"    return int.from_bytes(data, 'big').bit_count() & 1{flip}")
    return c.text()


def crc_byte_table(p) -> list[int]:
    """The 256-entry table of a table-driven CRC: the register after each byte alone from
    zero; reflected CRCs shift right by the reflected polynomial, widths under 8 run on a
    left-aligned 8-bit register."""
    table = []
    for byte in range(256):
        if p.refin:
            reg = byte
            for _ in range(8):
                reg = (reg >> 1) ^ reflect(p.poly, p.width) if reg & 1 else reg >> 1
        elif p.width >= 8:
            mask, top = (1 << p.width) - 1, 1 << (p.width - 1)
            reg = byte << (p.width - 8)
            for _ in range(8):
                reg = ((reg << 1) ^ p.poly) & mask if reg & top else (reg << 1) & mask
        else:
            reg = byte << (8 - p.width)
            for _ in range(8):
                reg = ((reg << 1) ^ (p.poly << (8 - p.width))) & 0xFF if reg & 0x80 else (reg << 1) & 0xFF
        table.append(reg)
    return table


def _table_literal(c: Code, name: str, p) -> None:
    """The byte table as a constant: nothing is computed when the module is imported."""
    table = crc_byte_table(p)
    digits = (max(p.width, 8) + 3) // 4
    c(f"_TABLE_{name}: tuple[int, ...] = (")
    for row in range(0, 256, 8):
        c("    " + " ".join(f"{x:#0{digits + 2}x}," for x in table[row:row + 8]))
    c(")")
    c("")
    c("")


def _final_step(cs, value: str) -> str:
    """A sum's or xor's value finished by its complement and xorout."""
    mask = (1 << cs.width) - 1 if cs.width else 0
    if cs.complement == "ones":
        value = f"({value}) ^ {mask:#x}"
    elif cs.complement == "twos":
        value = f"-({value}) & {mask:#x}"
    return f"({value}) ^ {cs.xorout:#x}" if cs.xorout is not None else value


def _fletcher_code(c: Code, cs, name: str) -> None:
    """Two running sums, A of the data and B of A after each step, reduced at the end
    (a sum's residue does not depend on when it is taken); Fletcher-8 steps through
    nibbles, high nibble first."""
    half = cs.width // 2
    c(f"# Fletcher-{cs.width}: sums modulo {cs.modulo}, value (B << {half}) | A")
    c(f"def _checksum_{name}(data: _Buffer) -> int:")
    c("    a = b = 0")
    c("    for byte in data:")
    if cs.width == 16:
        c("        a += byte")
        c("        b += a")
    else:
        c("        a += byte >> 4")
        c("        b += a")
        c("        a += byte & 0xF")
        c("        b += a")
    c(f"    return (b % {cs.modulo}) << {half} | a % {cs.modulo}")


def _internet_code(c: Code, cs, name: str) -> None:
    """RFC 1071: the words summed in one go, the carries out of 16 bits folded back in
    (end-around carry), then the sum's one's complement."""
    big = cs.word_order == "big"
    c(f"# The internet checksum (RFC 1071): 16-bit words, {cs.word_order}-endian, an odd byte padded with 0")
    c(f"def _checksum_{name}(data: _Buffer) -> int:")
    c("    n = len(data)")
    c(f"    total: int = sum(struct.unpack_from(f\"{'>' if big else '<'}{{n >> 1}}H\", data))")
    c("    if n & 1:")
    c("        total += data[n - 1]" + (" << 8" if big else ""))
    c("    while total >> 16:")
    c("        total = (total & 0xFFFF) + (total >> 16)")
    c("    return ~total & 0xFFFF")


def _positional_crc_code(name: str, lengths: list[int]) -> str:
    """A CRC over a fixed number of bytes without a loop. A CRC is affine in its data:
    crc(d) = crc(zeros) ^ XOR of one table lookup per byte, the table chosen by the
    byte's distance from the end, so each length gets straight-line code."""
    c = Code()
    longest = max(lengths)
    c(f"def _tables_{name}(longest: int) -> tuple[list[int], tuple[tuple[int, ...], ...]]:")
    c("    zeros = [_checksum_" + name + "(bytes(n)) for n in range(longest + 1)]")
    c("    tables = tuple(tuple(_checksum_" + name + "(bytes((b,)) + bytes(k)) ^ zeros[k + 1] for b in range(256))")
    c("                   for k in range(longest))")
    c("    return zeros, tables")
    c(f"_ZEROS_{name}, _AT_{name} = _tables_{name}({longest})")
    for k in range(longest):
        c(f"_AT{k}_{name} = _AT_{name}[{k}]")
    for n in lengths:
        c("")
        c("")
        c(f"def _checksum_{name}_{n}(data: _Buffer, start: int) -> int:")
        names = [f"b{i}" for i in range(n)]
        c(f"    {', '.join(names)}, = data[start:start + {n}]")
        terms = [f"_ZEROS_{name}[{n}]"] + [f"_AT{n - 1 - i}_{name}[b{i}]" for i in range(n)]
        lines = [" ^ ".join(terms[k:k + 4]) for k in range(0, len(terms), 4)]
        c(f"    return ({lines[0]}")
        for line in lines[1:]:
            c(f"            ^ {line}")
        c("            )")
    return c.text()


def _pairwise_crc_code(cs, name: str, lengths: list[int]) -> str:
    """A CRC of 16 bits or more over a fixed number of bytes, two bytes per step from a
    65,536-entry table (built once from the byte table): half the steps of a byte loop,
    each a single lookup, unrolled for each length."""
    p = cs.crc
    width, mask = p.width, (1 << p.width) - 1

    def reflected(expr: str) -> str:  # generated code that bit-reverses expr
        return f"int(format({expr}, '0{width}b')[::-1], 2)"
    c = Code()
    pairs = _pair_table_halves(p)
    for half, values in zip(("HIGH", "LOW"), pairs):
        c(f"_{half}16_{name}: tuple[int, ...] = (")
        for row in range(0, 256, 8):
            c("    " + " ".join(f"{x:#0{(width + 3) // 4 + 2}x}," for x in values[row:row + 8]))
        c(")")
    c(f"_TABLE16_{name}: tuple[int, ...] = ()  # built by the first checksum, not at import")
    c("")
    c("")
    c(f"def _table16_{name}() -> tuple[int, ...]:")
    c('    """The register after two bytes is linear in them: the entry of (high, low) is the')
    c('    entry of (high, 0) xor that of (0, low), so 65,536 entries come from 512 constants."""')
    c(f"    global _TABLE16_{name}")
    c(f"    _TABLE16_{name} = tuple([h ^ low for h in _HIGH16_{name} for low in _LOW16_{name}])")
    c(f"    return _TABLE16_{name}")
    init = reflect(p.init, width) if p.refin else p.init
    for n in lengths:
        words, odd = divmod(n, 2)
        c("")
        c("")
        c(f"_WORDS_{name}_{n} = struct.Struct({('<' if p.refin else '>') + f'{words}H' + ('B' if odd else '')!r})")
        c("")
        c("")
        c(f"def _checksum_{name}_{n}(data: _Buffer, start: int) -> int:")
        c.indent()
        names = [f"w{i}" for i in range(words)] + (["b"] if odd else [])
        c(f"words: tuple[int, ...] = _WORDS_{name}_{n}.unpack_from(data, start)")
        c(f"{', '.join(names)}, = words")
        c(f"t = _TABLE16_{name} or _table16_{name}()")
        c(f"r: int = {init:#x}")
        for w in names[:words]:
            if width == 16:
                c(f"r = t[r ^ {w}]")
            elif p.refin:
                c(f"r = t[(r ^ {w}) & 0xFFFF] ^ (r >> 16)")
            else:
                c(f"r = t[(r >> {width - 16}) ^ {w}] ^ ((r << 16) & {mask:#x})")
        if odd:
            if p.refin:
                c(f"r = _TABLE_{name}[(r ^ b) & 0xFF] ^ (r >> 8)")
            else:
                c(f"r = _TABLE_{name}[((r >> {width - 8}) ^ b) & 0xFF] ^ ((r << 8) & {mask:#x})")
        if p.refin != p.refout:
            c(f"r = {reflected('r')}")
        c(f"return r ^ {p.xorout:#x}" if p.xorout else "return r")
        c.dedent()
    return c.text()


def _pair_table_halves(p) -> tuple[list[int], list[int]]:
    """The two-byte table's entries for the pairs (x, 0) and (0, x), indexed as the
    generated code indexes it: the 16-bit word the pair reads as."""
    t, width, mask = crc_byte_table(p), p.width, (1 << p.width) - 1

    def entry(x: int) -> int:
        if p.refin:  # the low byte of each little-endian word goes in first
            return t[(t[x & 0xFF] ^ (x >> 8)) & 0xFF] ^ (t[x & 0xFF] >> 8)
        return t[((t[x >> 8] >> (width - 8)) ^ x) & 0xFF] ^ ((t[x >> 8] << 8) & mask)
    return [entry(x << 8) for x in range(256)], [entry(x) for x in range(256)]


# The longest fixed span a CRC gets straight-line code for: beyond it the code would grow
# with the wire (a 64 KiB frame, a line per byte), so the CRC's loop serves it.
STRAIGHT_LINE_CRC_BYTES = 1024


def _straight_line_crc(cs, size: int) -> bool:
    """Whether a CRC over `size` fixed bytes is computed by code written for that length."""
    return cs.algorithm == "crc" and not _stdlib_crc(cs.crc) and size <= STRAIGHT_LINE_CRC_BYTES


def _fixed_span_crc_code(cs, name: str, lengths: list[int]) -> str:
    return _pairwise_crc_code(cs, name, lengths) if cs.crc.width >= 16 else _positional_crc_code(name, lengths)


class ModuleView(PythonView):
    """The module-level parts: checksum functions, dispatch, streams, sequences."""

    def __init__(self, protocol: Protocol):
        super().__init__(protocol)
        self.sums: dict[str, Any] = {}  # checksum name → the checksum, for each one the code calls
        self.spans: dict[str, set[int]] = {}  # checksum name → the lengths of its straight-line calls

    def checksum_function(self, cs, size: Optional[int] = None) -> str:
        """The name of the function computing `cs` over any bytes, or over `size` bytes by
        code written for that length; noted as called."""
        name = _checksum_name(cs)
        self.sums[name] = cs
        if size is None:
            self.calls.use(f"_checksum_{name}")
            return f"_checksum_{name}"
        self.spans.setdefault(name, set()).add(size)
        if cs.crc.width < 16:  # its tables are built from the function over any bytes
            self.calls.use(f"_checksum_{name}")
        return f"_checksum_{name}_{size}"

    def checksum_functions(self) -> list[str]:
        """The code of each checksum function the module calls, in the order the messages
        first use them."""
        order = dict.fromkeys(_checksum_name(x.field.checksum) for m in self.p.messages for x in m.wire.leaves
                              if x.field.checksum and x.field.checksum.over == "bytes")
        names = [n for n in order if n in self.sums] + sorted(set(self.sums) - set(order))
        out = []
        for name in names:
            cs, lengths = self.sums[name], sorted(self.spans.get(name, ()))
            general = f"_checksum_{name}" in self.calls.names
            pairs = bool(lengths) and cs.crc.width >= 16
            if general or pairs and any(n % 2 for n in lengths):  # an odd byte takes the byte table
                out.append(_checksum_code(cs, general))
            if general and cs.algorithm == "internet" or pairs:
                self.calls.use("struct")
        for name in names:
            if name in self.spans:
                out.append(_fixed_span_crc_code(self.sums[name], name, sorted(self.spans[name])))
        return out

    def zeroed_checksum_call(self, cs, buf: str, at: int, cut: bool = False) -> str:
        """The value an encoder sends for a checksum that covers itself, at byte `at`: its
        coverage computed with the field's two bytes as zeros."""
        start, end = cs.byte_span
        less = " - cut" if cut else ""
        return (f"{self.checksum_function(cs)}(b''.join(({buf}[{start}:{at}], bytes(2), "
                f"{buf}[{at + 2}:{end}{less}])))")

    def checksum_call(self, cs, buf: str, start: int, end: int, extra: Optional[int] = None, cut: bool = False) -> str:
        """The call that computes checksum cs over buf[start:end], then over the
        message's extra byte when the checksum takes one. `cut`: the coverage ends
        `cut` bytes early, with a payload cut short."""
        # a join takes any bytes-like part, and copies once
        if cut:
            if cs.extra:
                return f"{self.checksum_function(cs)}(b''.join(({buf}[{start}:{end} - cut], {bytes([extra])!r})))"
            return f"{self.checksum_function(cs)}({buf}[{start}:{end} - cut])"
        if cs.extra:
            data, size = f"b''.join(({buf}[{start}:{end}], {bytes([extra])!r}))", end - start + 1
            if _straight_line_crc(cs, size):
                return f"{self.checksum_function(cs, size)}({data}, 0)"
            return f"{self.checksum_function(cs)}({data})"
        if _straight_line_crc(cs, end - start):  # straight-line code for this length
            return f"{self.checksum_function(cs, end - start)}({buf}, {start})"
        return f"{self.checksum_function(cs)}({buf}[{start}:{end}])"

    def dispatch_table(self) -> dict:
        facts = dispatch_facts(self.p)
        if facts["kind"] == "bytes":
            # each message's frame sizes as a range: a counted array's are as many as its elements
            keys = [(value, sizes_range(facts["least"].get(name, size), size, facts["steps"].get(name, 1)), direction, name)
                    for value, size, direction, name in facts["frames"]]
            facts = dict(facts, value_expr=self.read_expr("d", "", facts), sized_frames=keys, raw_key=None)
            if facts["bytes"] > 1 and not facts["shift"] and facts["mask"] == (1 << (8 * facts["bytes"])) - 1:
                # a key of whole bytes is looked up by the bytes themselves, no number read
                facts["raw_key"] = {"slice": f"d[{facts['first']}:{facts['last']}]", "bytes": facts["bytes"],
                                    "order": facts["byte_order"]}
        if facts["kind"] == "bits" and self.p.framing.max_bits:  # the word form: a left-aligned int
            facts = dict(facts, word_limit=1 << self.p.framing.max_bits,
                         word_shift=self.p.framing.max_bits - facts["head_bits"])
        return facts

    def decode_signature(self) -> str:
        """The def line of module-level decode, after an overload for each direction where
        the direction narrows the messages it returns (frames dispatched by id or prefix)."""
        lines = []
        if dispatch_facts(self.p)["kind"] in ("bytes", "text"):
            for d in self.p.directions:
                classes = [self.class_name(m) for m in self.p.messages if m.direction == d.name]
                if classes:
                    returned = f"Union[{', '.join(classes)}]" if len(classes) > 1 else classes[0]
                    self.calls.use("overload", "Literal")
                    lines += ["@overload", f"def decode(data: _Input, direction: Literal[{d.name!r}]) -> {returned}: ...",
                              "", ""]
        if lines:
            lines += ["@overload", "def decode(data: _Input, direction: Optional[str] = None) -> AnyMessage: ...", "", ""]
        if self.p.framing.trailer:  # a key verifies the trailer's signature
            lines = [x.replace(") -> ", ", key: Optional[_Buffer] = None) -> ") if x.startswith("def ") else x
                     for x in lines]
            return "\n".join(lines + ["def decode(data: _Input, direction: Optional[str] = None, "
                                       "key: Optional[_Buffer] = None) -> AnyMessage:"])
        return "\n".join(lines + ["def decode(data: _Input, direction: Optional[str] = None) -> AnyMessage:"])

    def encoding_view(self) -> dict:
        """The link's byte stuffing as Python literals, or {} without one."""
        facts = encoding_facts(self.p)
        if not facts:
            return facts
        delimiter, escape = bytes((facts["delimiter"],)), bytes((facts["escape"] or 0,))
        escaped = dict((original, escape + bytes((code,))) for code, original in facts["escaped"])
        return dict(facts, delimiter_literal=repr(delimiter), escape_literal=repr(escape),
                    escaped_delimiter=repr(escaped.get(facts["delimiter"], b"")),
                    escaped_escape=repr(escaped.get(facts["escape"], b"")),
                    mapped_literal=repr(bytes(facts["mapped"])),
                    escaped_table="{" + ", ".join(f"{code:#x}: {original:#x}" for code, original in facts["escaped"]) + "}")

    def stream_view(self) -> dict:
        facts = stream_facts(self.p)
        if facts:
            facts = dict(facts, sync_literal=repr(facts["sync_bytes"]), accepted_literal=sizes_literal(facts["accepted"]))
        if facts.get("length"):
            length = facts["length"]
            facts = dict(facts, length=dict(length, value_expr=self.read_expr("buf", "pos + ", dict(length, first=length["at"]))))
        if facts.get("by_key"):
            key = facts["by_key"]
            facts = dict(facts, by_key=dict(key, value_expr=self.read_expr("buf", "pos + ", dict(key, first=key["at"]))))
        return facts

    @staticmethod
    def read_expr(buf: str, base: str, where: dict) -> str:
        """The integer in bytes first..last of `buf` (after `base`), shifted and masked: a
        whole multi-byte field is read in its byte order, bits inside bytes big-endian."""
        first, last, shift, mask = where["first"], where["last"], where["shift"], where["mask"]
        if last - first == 1:
            value = f"{buf}[{base}{first}]"
        else:
            value = f"int.from_bytes({buf}[{base}{first}:{base}{last}], {where.get('byte_order', 'big')!r})"
        if shift:
            value = f"({value} >> {shift})"
        if shift or mask != (1 << (8 * (last - first))) - 1:
            value = f"({value} & {mask:#x})"
        return value

    def sequence_view(self, s: Sequence) -> dict:
        classes: list[dict] = []

        def item_spec(item: SequenceItem, owner: str) -> str:
            if item.message:
                cls = camel(item.message)
                mode = "count" if item.count else "repeat" if item.repeat else "one"
                return f"({item.name!r}, {mode!r}, {item.message!r}, {item.count!r}, None)"
            cls = owner + camel(item.name)
            children = ", ".join(item_spec(c, cls) for c in item.items)
            classes.append({"name": cls, "fields": [(c.name, annotation(c, cls)) for c in item.items],
                            "names": lit(tuple(c.name for c in item.items)),
                            "doc": str(item.doc or f"The {item.name} of a {s.name}.")})
            mode = "repeat" if item.repeat else "one"
            return f"({item.name!r}, {mode!r}, {cls}, {item.count!r}, ({children},))"

        def annotation(item: SequenceItem, owner: str) -> str:
            inner = camel(item.message) if item.message else owner + camel(item.name)
            return f"list[{inner}]" if item.repeat or item.count else inner

        cls = camel(s.name)
        spec = ", ".join(item_spec(i, cls) for i in s.items)
        classes.append({"name": cls, "fields": [(i.name, annotation(i, cls)) for i in s.items],
                        "names": lit(tuple(i.name for i in s.items)),
                        "doc": str(s.doc or f"A {s.name} sequence.")})
        rules = []
        for r in s.rules:
            rules.append(f"({r.kind!r}, {tuple(r.path.split('.'))!r}, "
                         f"{r.start if r.kind == 'consecutive' else tuple((r.to or r.of or '').split('.')) if r.kind in ('equal', 'member') else r.key!r}, "
                         f"{r.id!r})")
        return {"name": s.name, "cls": cls, "classes": classes, "spec": f"({spec},)",
                "rules": f"({', '.join(rules)}{',' if rules else ''})", "doc": str(s.doc or s.name)}
