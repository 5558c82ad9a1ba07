"""Fields: types, widths, scale and offset, ranges, constants and values."""
from __future__ import annotations

import math
from dataclasses import replace
from typing import Any, Optional

from .. import binary32
from ..model import Field, Multiplex, Presence
from ..text_prefix import is_prefix_value
from .text import text
from .base import MAX_ARRAY_COUNT, MAX_BYTES_LENGTH, MAX_SCALED_BITS, ResolverBase

MAX_PREFIX_LENGTH = 8  # a prefix field (NMEA's talker is 2)


def leaf_count(f: Field) -> int:
    """How many wire values a field holds: a group's members', an array's times its count."""
    each = sum(leaf_count(s) for s in f.fields) if f.kind == "group" else 1
    return each * (f.count or 1)


class FieldsMixin(ResolverBase):
    @staticmethod
    def int_fits(value: Any, kind: str, bits: int) -> bool:
        if isinstance(value, bool):
            value = int(value)
        if bits < 1:
            return True  # a width with no values: its own error is reported at the type
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
        counted_by = None
        if isinstance(length, dict):  # bytes whose length an earlier field gives: max_length at most
            counted_by, length = self.counted_length(name, kind, f, path, allow_payload)
        if kind == "bytes" and length is None and f.get("to_end") and isinstance(f.get("max_length"), int):
            length = f["max_length"]  # the most the rest of the payload holds
        if kind == "bytes":
            if length is None:
                self.error(path, f"bytes field {name!r} needs a `length`: a number, `{{from: <field>}}` "
                                 "with max_length, or to_end with max_length")
                length = 1
            if not 0 < length <= MAX_BYTES_LENGTH:
                key = "max_length" if counted_by or f.get("to_end") else "length"
                self.error(path + (key,), f"field {name!r}: {key} {length} is outside 1..{MAX_BYTES_LENGTH}",
                           f"give {key} between 1 and {MAX_BYTES_LENGTH}")
                length = 1
            bits = 8 * length
        elif kind == "str" and (length is not None or f.get("max_length") is not None) \
                and not 0 < (length if length is not None else f["max_length"]) <= MAX_BYTES_LENGTH:
            key = "length" if length is not None else "max_length"  # 0 is a size given, not one left out
            self.error(path + (key,), f"field {name!r}: {key} {f[key]} is outside 1..{MAX_BYTES_LENGTH}",
                       f"give {key} between 1 and {MAX_BYTES_LENGTH}")
        elif length is not None and kind != "str" and counted_by is None:
            self.error(path + ("length",), f"field {name!r}: `length` applies to bytes and str fields")
        field = Field(
            name=name, kind=kind, loc=loc, bits=bits, doc=text(f.get("doc")),
            title=text(f.get("title")), type_name=type_name, unit=f.get("unit"),
            const=f.get("const"), reserved=bool(f.get("reserved")), default=f.get("default"),
            has_default="default" in f,
            range=tuple(f["range"]) if "range" in f else None,
            values=tuple(f["values"]) if "values" in f else None, enum=enum, flags=flags,
            scale=f.get("scale", float(f"1e-{f['decimals']}") if f.get("decimals") else None),
            offset=f.get("offset"), one_hot=bool(f.get("one_hot")),
            decimals=f.get("decimals"), width=f.get("width"),
            exactly_one=bool(f.get("exactly_one")), byte_order=f.get("byte_order"),
            length=length if kind in ("bytes", "str") else None, length_param=length_param,
            max_length=f.get("max_length"), optional=bool(f.get("optional")),
            to_end=bool(f.get("to_end")), dispatch=bool(f.get("dispatch")) or bool(f.get("by_direction")) and allow_payload,
            by_direction=tuple(f.get("by_direction", {}).items()),
            length_of=(f["length_of"]["from"], f["length_of"]["to"]) if "length_of" in f else None,
            length_adjust=f["length_of"].get("adjust", 0) if "length_of" in f else 0,
            checksum=self.resolve_checksum(f["checksum"], path + ("checksum",), bits, f.get("byte_order"))
            if "checksum" in f else None,
            fields=sub_fields, message=text(f.get("message")), rule=f.get("rule"),
            extension=bool(f.get("extension")), counted_by=counted_by, start_bit=f.get("start_bit"),
            prefix=bool(f.get("prefix")), keep_empty=f.get("keep_empty"), mavlink_name=f.get("mavlink_name"),
            finite=f.get("finite", True) is not False,
            multiplexed_by=self.multiplex_of(f, path),
            count_unit=1 if counted_by is not None else None, present_if=self.condition_of(f, path, allow_payload))
        if field.by_direction:
            self.check_by_direction(field, path, allow_payload)
        self.check_field(field, path)
        if field.kind == "str" and field.length and field.max_length is None:
            field = replace(field, max_length=field.length)  # a fixed length is also the most it holds
        if isinstance(f.get("count"), dict):
            field = self.counted_array(field, f, path, allow_payload)
        elif "count" in f:
            field = self.array_of(field, f["count"], path, allow_payload)
        elif field.to_end and self.framing_kind != "text":
            field = self.rest_of_payload(field, f, path, allow_payload)
        if "max_count" in f and not isinstance(f.get("count"), dict) and not (field.to_end and field.count):
            self.error(path + ("max_count",), f"field {name!r}: max_count is for an array whose count "
                                              "another field gives", "drop it, or write `count: {from: <field>}`")
        return field

    def condition_of(self, f: dict, path: tuple, in_envelope: bool) -> Optional[Presence]:
        """`present_if: {field, has | equals}`: the field is sent only when an earlier field
        says so (bound to that field, and checked, by the message)."""
        spec = f.get("present_if")
        if spec is None:
            return None
        where = path + ("present_if",)
        if self.framing_kind != "bytes" or in_envelope:
            self.error(where, f"field {f['name']!r}: present_if applies to message fields of bytes framing",
                       "drop present_if")
            return None
        equals = spec.get("equals", ())
        return Presence(spec["field"], has=spec.get("has"),
                         equals=tuple(equals) if isinstance(equals, list) else (equals,) if "equals" in spec else ())

    def multiplex_of(self, f: dict, path: tuple) -> Optional[Multiplex]:
        """`multiplexed_by: {field, values}`: the values as sorted, merged ranges (bound to the
        multiplexor, and checked, where the message places its fields)."""
        spec = f.get("multiplexed_by")
        if spec is None:
            return None
        where = path + ("multiplexed_by",)
        if f.get("start_bit") is None:
            self.error(where, f"field {f['name']!r}: multiplexed_by applies to a field placed by start_bit",
                       "give the message payload_bytes and its fields start_bit, or use present_if")
            return None
        ranges = []
        for i, v in enumerate(spec["values"]):
            lo, hi = (v, v) if isinstance(v, int) else (int(x) for x in v.split(".."))
            if lo > hi:
                self.error(where + ("values", i), f"field {f['name']!r}: the range {v!r} ends before it starts",
                           f"write it {hi}..{lo}")
                continue  # the other values still keep it apart from the fields it shares bits with
            ranges.append((lo, hi))
        merged: list[tuple[int, int]] = []
        for lo, hi in sorted(ranges):
            if merged and lo <= merged[-1][1] + 1:
                merged[-1] = (merged[-1][0], max(hi, merged[-1][1]))
            else:
                merged.append((lo, hi))
        return Multiplex(spec["field"], tuple(merged))

    def counted_length(self, name: str, kind: str, f: dict, path: tuple, in_envelope: bool) -> tuple:
        """`length: {from: n}` with `max_length` on a bytes field: 0..max_length bytes whose
        length an earlier field gives (checked by the message, as a counted array is)."""
        lpath = path + ("length",)
        if kind != "bytes":
            self.error(lpath, f"field {name!r}: a length another field gives is for bytes fields",
                       "give a fixed `length`, or `max_length` for text")
        elif "max_length" not in f:
            self.error(lpath, f"field {name!r}: bytes whose length another field gives need `max_length`, "
                              "the most bytes a frame carries", "add max_length: <bytes>")
        elif self.framing_kind != "bytes":
            self.error(lpath, f"field {name!r}: a length another field gives is for bytes framing",
                       "give a fixed `length`")
        elif "count" in f:
            self.error(lpath, f"field {name!r}: bytes whose length another field gives cannot be an array",
                       "drop `count`, or give a fixed `length`")
        elif in_envelope:
            self.error(lpath, f"field {name!r}: a length another field gives applies to message fields, "
                              "not to the framing's layout", "move the field into the messages")
        else:
            return f["length"]["from"], f["max_length"]
        return None, 1

    def rest_of_payload(self, field: Field, f: dict, path: tuple, in_envelope: bool) -> Field:
        """`to_end: true` in a bytes framing: bytes (up to max_length) or an array (up to
        max_count) that fills what the frame holds after the fields before it."""
        name, where = field.name, path + ("to_end",)
        if self.framing_kind != "bytes" or in_envelope:
            self.error(where, f"field {name!r}: to_end applies to message fields of text and bytes framings",
                       "drop to_end")
        elif field.kind == "bytes":
            if "max_length" not in f:
                self.error(where, f"field {name!r}: bytes that fill the rest of the payload need `max_length`",
                           "add max_length: <bytes>")
            else:
                return replace(field, count_unit=1)
        elif "max_count" not in f:
            self.error(where, f"field {name!r}: an array that fills the rest of the payload needs `max_count`",
                       "add max_count: <elements>")
        else:
            array = self.array_of(field, f["max_count"], path, in_envelope, "max_count")
            return array
        return replace(field, to_end=False)

    def counted_array(self, element: Field, f: dict, path: tuple, in_envelope: bool) -> Field:
        """`count: {from: n, unit: elements|bytes}` with `max_count`: an array of at most
        max_count elements whose count an earlier field gives (checked by the message)."""
        name, cpath = element.name, path + ("count",)
        if "max_count" not in f:
            self.error(cpath, f"field {name!r}: an array whose count another field gives needs "
                              "`max_count`, the most elements a frame carries", "add max_count: <elements>")
            return element
        if self.framing_kind != "bytes":
            self.error(cpath, f"field {name!r}: a count another field gives is for bytes framing",
                       "give a fixed `count`")
            return element
        if element.kind == "bytes":
            self.error(cpath, f"field {name!r}: an array whose count another field gives holds numbers "
                              "or groups, not bytes", "use bytes with `length: {from: <field>}`, or a fixed `count`")
            return element
        array = self.array_of(element, f["max_count"], path, in_envelope, "max_count")
        if array.count is None:
            return element
        unit = f["count"].get("unit", "elements")
        unit = None if unit == "elements" else 1 if unit == "bytes" else unit
        if unit is not None and (element.bits // 8 * array.count) % unit:
            size = element.bits // 8
            self.error(cpath + ("unit",), f"field {name!r}: {array.count} elements of {size} byte"
                                          f"{'s' if size != 1 else ''} are not a whole number of {unit}-byte units",
                       "choose max_count so that the most elements fill whole units")
            return element
        return replace(array, counted_by=f["count"]["from"], count_unit=unit)

    def array_of(self, element: Field, count: int, path: tuple, in_envelope: bool, key: str = "count") -> Field:
        """The field as an array of `count` elements, each checked as the field alone was;
        `bits` becomes the whole array's, as a group's is the sum of its members'."""
        name, cpath = element.name, path + (key,)
        if not 1 <= count <= MAX_ARRAY_COUNT:
            self.error(cpath, f"field {name!r}: count {count} is outside 1..{MAX_ARRAY_COUNT}",
                       "an array holds at least one element")
            return element
        if self.framing_kind == "text":
            self.error(cpath, f"field {name!r}: count applies to binary framings; a text line holds "
                              "one value per field", "declare each value as a field of its own")
            return element
        if in_envelope:
            self.error(cpath, f"field {name!r}: count applies to message fields, not to the "
                              "framing's layout", "move the array into the messages")
            return element
        set_by_codec = [key for key, on in (("const", element.const is not None), ("checksum", element.checksum),
                                            ("dispatch", element.dispatch), ("length_of", element.length_of),
                                            ("reserved", element.reserved)) if on]
        if set_by_codec:
            self.error(cpath, f"field {name!r}: an array cannot be `{set_by_codec[0]}`: the codec "
                              "sets such a field as one value", "drop `count`, or make it a member field")
            return element
        elements = count * leaf_count(element)
        if elements > MAX_ARRAY_COUNT:
            self.error(cpath, f"field {name!r}: {count} elements of {leaf_count(element)} values each "
                              f"are {elements} values, more than {MAX_ARRAY_COUNT}",
                       "split the array over several messages")
            return element
        if element.bits is not None and count * element.bits > 8 * MAX_BYTES_LENGTH:
            self.error(cpath, f"field {name!r}: {count} elements of {element.bits} bits are "
                              f"{count * element.bits // 8} bytes, more than {MAX_BYTES_LENGTH}",
                       "split the array over several messages")
            return element
        return replace(element, count=count, bits=None if element.bits is None else count * element.bits)

    def check_by_direction(self, f: Field, path: tuple, in_envelope: bool) -> None:
        if not in_envelope or self.framing_kind != "bytes":
            self.error(path + ("by_direction",), f"field {f.name!r}: by_direction is for the envelope of "
                                                 "bytes framing", "drop it, or move the field to framing.layout")
        if f.const is not None:
            self.error(path + ("const",), f"field {f.name!r}: give `const` or `by_direction`, not both")
        for direction, value in f.by_direction:
            if direction not in self.data.get("directions", {}):
                self.error(path + ("by_direction", direction), f"field {f.name!r}: unknown direction {direction!r}",
                           "declare it under `directions`")
            if not self.int_fits(value, f.kind, f.bits or 0):
                self.error(path + ("by_direction", direction), f"field {f.name!r}: {value} does not fit "
                                                               f"{f.bits} bits")

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
        if f.start_bit is not None:
            pass  # a field placed by start_bit takes either byte order at any width (placement.py)
        elif f.byte_order and bits is not None and bits % 8 and bits > 8:
            self.error(path + ("byte_order",), f"field {name!r}: byte_order applies to fields of whole "
                                               f"bytes, not to {bits} bits",
                       "drop it: a field that crosses bytes follows the bit order (little-endian with "
                       "`bit_order: lsb_first`, big-endian with msb_first); where the framing's "
                       "`byte_order` differs, set the framing's to the bits' order and give the other "
                       "`byte_order` to the whole-byte fields that keep it")
        elif f.byte_order and (bits is None or bits % 8 or bits <= 8):
            self.error(path + ("byte_order",), f"field {name!r}: byte_order needs a multi-byte field")
        if f.reserved and kind not in ("uint", "int"):
            self.error(path + ("reserved",), f"field {name!r}: reserved bits are an unsigned integer")
        if f.optional and self.framing_kind != "text":
            self.error(path, f"field {name!r}: optional applies to text framing")
        if f.decimals is not None or f.width is not None:
            self.check_fixed_spelling(f, path)
        if f.extension:
            self.check_extension(f, path)
        if f.keep_empty is not None:
            self.check_keep_empty(f, path)
        if f.prefix:
            self.check_prefix_field(f, path)
        if f.to_end and kind != "str" and self.framing_kind == "text":
            self.error(path + ("to_end",), f"field {name!r}: to_end applies to str fields")
        elif f.to_end and kind == "str" and self.framing_kind != "text":
            self.error(path + ("to_end",), f"field {name!r}: a str field is for text framing",
                       "use bytes with to_end and max_length")
        if kind == "str" and f.length is None and f.max_length is None:
            self.error(path, f"field {name!r}: a str field needs `max_length` (or a fixed `length`)",
                       "C decoders keep the text in a buffer of that size")
        if kind == "float" and f.range is not None and self.framing_kind == "text":
            self.error(path + ("range",), f"field {name!r}: a text float cannot have a range yet",
                       "use an integer with a scale, which can")
        if not f.finite:
            self.check_not_finite(f, path)
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
                if not (math.isfinite(raw_lo) and math.isfinite(raw_hi)):  # scaled past a double
                    self.error(path + ("range",), f"field {name!r}: range [{lo}, {hi}] does not fit {bits} bits",
                               "widen the field or narrow the range")
                elif f.scale is None and f.offset is None and not (float(lo).is_integer() and float(hi).is_integer()):
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

    def check_prefix_field(self, f: Field, path: tuple) -> None:
        """A value written in the line's prefix before the message's id (NMEA's talker): a
        str of a fixed length of uppercase letters, so a reader finds where the id starts."""
        if self.framing_kind != "text":
            self.error(path + ("prefix",), f"field {f.name!r}: prefix fields are for text framing",
                       "drop `prefix`")
        elif f.kind != "str" or f.length is None or not 1 <= f.length <= MAX_PREFIX_LENGTH:
            self.error(path + ("prefix",), f"field {f.name!r}: a prefix field is a str of a fixed `length` "
                       f"(1..{MAX_PREFIX_LENGTH}) of uppercase letters", "write type: str, length: 2")
        elif f.optional or f.const is not None or f.to_end or f.has_default or f.count is not None:
            self.error(path + ("prefix",), f"field {f.name!r}: a prefix field is always there and is given "
                       "(no optional, const, default, to_end or count)",
                       "a fixed prefix is part of the message's id")
        else:
            for i, v in enumerate(f.values or ()):
                if not isinstance(v, str) or not is_prefix_value(v, f.length):
                    self.error(path + ("values", i), f"field {f.name!r}: prefix value {v!r} is not "
                               f"{f.length} uppercase letters A-Z", "list values such as GP, GN")

    def check_extension(self, f: Field, path: tuple) -> None:
        """An extension field may be missing from a frame: in bytes framing it then reads as
        0 and is a plain value; in text framing (a line that ends before it) it is absent,
        so it must be optional."""
        if self.framing_kind == "bits":
            self.error(path + ("extension",), f"field {f.name!r}: extension fields are for bytes and text framing",
                       "drop `extension`")
        elif f.checksum or f.length_of or f.const is not None or f.reserved:
            self.error(path + ("extension",), f"field {f.name!r}: a checksum, length, const or reserved "
                                              "field cannot be an extension", "drop `extension`")
        elif self.framing_kind == "text" and not f.optional:
            self.error(path + ("extension",), f"field {f.name!r}: an extension field of a text line must be "
                                              "optional: a line that ends before it gives no value for it",
                       "add `optional: true`")
        elif self.framing_kind == "bytes" and f.has_default and f.default not in (0, 0.0, False) \
                and not isinstance(f.default, str):
            self.error(path + ("default",), f"field {f.name!r}: an extension field missing from a frame "
                                            f"reads as 0, so its default must be 0, not {f.default!r}",
                       "drop the default, or make it 0")

    def check_not_finite(self, f: Field, path: tuple) -> None:
        """`finite: false` lets a binary float hold NaN and the infinities (MAVLink sends NaN
        for "no value"). NaN is no number a range, a list of values or a constant could hold."""
        at = path + ("finite",)
        if f.kind != "float":
            self.error(at, f"field {f.name!r}: finite applies to float fields", "drop `finite`")
        elif self.framing_kind == "text":
            self.error(at, f"field {f.name!r}: a text float is a number as written; NaN and the "
                           "infinities have no spelling in a line", "drop `finite: false`")
        elif f.range is not None:
            self.error(at, f"field {f.name!r}: finite: false with a range; NaN is in no range",
                       "drop the range, or `finite: false`")
        elif f.values is not None:
            self.error(at, f"field {f.name!r}: finite: false with values; NaN equals no value",
                       "drop the values, or `finite: false`")
        elif f.const is not None:
            self.error(at, f"field {f.name!r}: finite: false on a constant, which is one finite number",
                       "drop `finite: false`")

    def check_keep_empty(self, f: Field, path: tuple) -> None:
        """A field's own keep_empty says what a writer does with its absent value at the end
        of a line: only an optional value of a text line is ever absent."""
        if self.framing_kind != "text":
            self.error(path + ("keep_empty",), f"field {f.name!r}: keep_empty is for text framing "
                                               "(a binary value always has its bits)", "drop `keep_empty`")
        elif not f.optional or f.const is not None or f.prefix:
            what = "constant" if f.const is not None else "prefix field" if f.prefix else "required value"
            self.error(path + ("keep_empty",), f"field {f.name!r}: keep_empty on a {what}, which is always "
                                               "written and so always has its place", "drop `keep_empty`")

    def check_fixed_spelling(self, f: Field, path: tuple) -> None:
        """`decimals` and `width` spell a text integer's raw value: 4807038 with decimals 3 is
        `4807.038`, 8 with width 2 is `08`. Written so, read in any spelling, in 32 bits."""
        key = "decimals" if f.decimals is not None else "width"
        if self.framing_kind != "text" or f.kind not in ("uint", "int") or f.enum or f.flags or f.one_hot:
            self.error(path + (key,), f"field {f.name!r}: {key} applies to integer fields of text framing",
                       "a float is written in its shortest form; use an integer with decimals")
            return
        if f.decimals and f.scale != float(f"1e-{f.decimals}"):
            self.error(path + ("scale",), f"field {f.name!r}: decimals {f.decimals} means scale "
                                          f"{float(f'1e-{f.decimals}')}, not {f.scale}",
                       "leave scale out: decimals sets it")
        lo, hi = f.raw_range or (0, 0)
        if lo < -(1 << 31) or hi > (1 << 31) - 1:
            self.error(path + ("type",), f"field {f.name!r}: {key} needs raw values of at most 32 bits "
                                         f"(signed); {f.type_name or f.kind} {f.bits} bits is wider",
                       "use i32, or u31 and narrower")

    def check_value(self, f: Field, value: Any, path: tuple, what: str) -> None:
        kind, bits = f.kind, f.bits
        if f.enum is not None:
            names = {m.name for m in f.enum.members}
            if value in names or value in f.enum.values:
                return
            if not (f.enum.open and what == "default"):  # an open enum's default may be any value of the width
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
        elif kind == "float":
            self.check_float_value(f, value, path, what)
        elif kind == "bool" and not isinstance(value, bool) and value not in (0, 1):
            self.error(path, f"field {f.name!r}: {what} {value!r} is not a bool")
        elif kind == "char" and not (isinstance(value, str) and len(value) == 1):
            self.error(path, f"field {f.name!r}: {what} {value!r} is not one character")
        elif kind == "str" and not isinstance(value, str):
            self.error(path, f"field {f.name!r}: {what} {value!r} is not a string")
        elif kind == "str" and f.max_length is not None and len(value) > f.max_length:
            self.error(path, f"field {f.name!r}: {what} {value!r} is longer than max_length {f.max_length}",
                       "shorten it or raise max_length")

    def check_float_value(self, f: Field, value: Any, path: tuple, what: str) -> None:
        """A float field's constant, default or allowed value: a finite number its width holds,
        within its range; a constant exactly, since decoders compare what they read with it."""
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            self.error(path, f"field {f.name!r}: {what} {value!r} is not a number")
        elif not math.isfinite(value):
            self.error(path, f"field {f.name!r}: {what} {value!r} is not a finite number")
        elif f.range and not f.range[0] <= value <= f.range[1]:
            self.error(path, f"field {f.name!r}: {what} {value} is outside its range {list(f.range)}")
        elif f.bits == 32 and abs(value) > binary32.LARGEST:
            self.error(path, f"field {f.name!r}: {what} {value} is beyond a binary32's range",
                       "make the field f64")
        elif f.bits == 32 and what == "const" and binary32.nearest(value) != value:
            self.error(path, f"field {f.name!r}: const {value!r} is no binary32 value; the nearest is "
                             f"{binary32.nearest(value)!r}", "write that value, or make the field f64")

    @staticmethod
    def to_raw(f: Field, value: float) -> float:
        raw = (value - (f.offset or 0)) / (f.scale or 1)
        if not math.isfinite(raw):  # past a double: beyond any field's width, so refused as not fitting
            return raw
        return math.floor(raw + 0.5) if f.scale else raw
