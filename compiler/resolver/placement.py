"""Fields placed by start_bit, as a CAN DBC places its signals: a payload of a fixed
size, each field at its own start bit in its own byte order, unused bits between
them. Fields share bits only when no frame carries both: each is multiplexed
(`multiplexed_by`) and, at some multiplexor both depend on, for values the other is not."""
from __future__ import annotations

from dataclasses import replace
from typing import Optional

from ..model import Field, Framing, Multiplex
from .base import ResolverBase

# What a placed field may not be: each takes bits the payload's fixed layout cannot give.
NOT_PLACED = (("count", "an array"), ("counted_by", "a counted field"), ("present_if", "a conditional field"),
              ("checksum", "a checksum"), ("length_of", "a length field"), ("extension", "an extension field"),
              ("to_end", "a field filling the rest"), ("dispatch", "a dispatch field"))


def msb_position(start_bit: int) -> int:
    """A Motorola start bit (DBC's sawtooth numbering: bit 7 of byte 0 is 7, bit 0 of
    byte 1 is 8) as its place in the payload counted most significant bit first."""
    return 8 * (start_bit // 8) + 7 - start_bit % 8


def dbc_bits(f: Field) -> list[int]:
    """The DBC bit numbers (bit k = bit k % 8 of byte k // 8) a placed field covers,
    least significant first for little-endian, most significant first for big-endian."""
    if f.byte_order == "little":
        return list(range(f.start_bit, f.start_bit + f.bits))
    first = msb_position(f.start_bit)
    return [msb_position(q) for q in range(first, first + f.bits)]  # the map is its own inverse


def exclusive(a: Optional[Multiplex], b: Optional[Multiplex]) -> bool:
    """Whether no frame carries both of two fields so conditioned: some multiplexor both
    depend on selects them for disjoint values."""
    if a is None or b is None:
        return False
    theirs = {x.field: x.ranges for x in b.chain}
    return any(x.field in theirs and not any(lo <= h2 and l2 <= hi for lo, hi in x.ranges for l2, h2 in theirs[x.field])
               for x in a.chain)


def relative_offset(f: Field) -> int:
    """The field's first bit in the payload, counted in its own bit order."""
    return f.start_bit if f.byte_order == "little" else msb_position(f.start_bit)


class PlacementMixin(ResolverBase):
    def place_signals(self, name: str, own: tuple[Field, ...], payload_bytes: Optional[int],
                      framing: Framing, path: tuple) -> tuple[Field, ...]:
        """The message's own fields, those placed by start_bit with their byte order and their
        first bit counted from the payload's start; every rule of placement checked."""
        if payload_bytes is None:
            for f in own:
                self.refuse_nested(f, name)
                if f.start_bit is not None:
                    self.report.error(f.loc, f"message {name!r}: field {f.name!r} has a start_bit, but the "
                                             "message has no payload_bytes to place it in",
                                      "give the message `payload_bytes: <size>` and every field a start_bit, "
                                      "or drop start_bit to place the fields one after another")
            return own
        if framing.kind != "bytes":
            self.error(path + ("payload_bytes",), f"message {name!r}: payload_bytes places fields in a bytes "
                                                  f"framing's payload, not in {framing.kind} framing",
                       "drop payload_bytes and the fields' start_bit")
            return own
        if framing.truncate:
            self.error(path + ("payload_bytes",), f"message {name!r}: a payload placed by start_bit has a fixed "
                                                  "size, and the framing truncates trailing zeros",
                       "drop the framing's truncate, or place the fields one after another")
        if not own:
            self.error(path + ("payload_bytes",), f"message {name!r}: a payload placed by start_bit needs a field",
                       "give it at least one field with a start_bit")
        out: list[Field] = []
        taken: dict[int, list[Field]] = {}  # DBC bit -> the fields that hold it
        for f in own:
            f = self.bind_multiplexor(name, f, out)
            placed = self.placed_field(name, f, payload_bytes, framing, taken)
            out.append(placed)
        return tuple(out)

    def bind_multiplexor(self, name: str, f: Field, earlier: list[Field]) -> Field:
        """A multiplexed field's condition, with its multiplexor's own (extended multiplexing);
        the multiplexor is an earlier plain unsigned field whose bits hold every value named."""
        mux = f.multiplexed_by
        if mux is None:
            return f
        x = next((e for e in earlier if e.name == mux.field), None)
        problem = ("which is not an earlier field of the message" if x is None else
                   "which is not a plain unsigned integer" if x.kind != "uint" or x.scale is not None
                   or x.offset is not None or x.flags or x.enum or x.const is not None or x.reserved or not x.bits
                   else None)
        if problem:
            self.report.error(f.loc, f"message {name!r}: field {f.name!r} is multiplexed by {mux.field!r}, {problem}",
                              "name a placed unsigned field (no scale, offset, enum or flags) listed before it")
            return f  # refused: kept as written, so that no overlap is reported besides
        top = max((hi for _, hi in mux.ranges), default=0)
        if top >= 1 << x.bits:
            self.report.error(f.loc, f"message {name!r}: field {f.name!r} is present when {x.name!r} is {top}, "
                                     f"which its {x.bits} bits cannot hold",
                              f"give values in 0..{(1 << x.bits) - 1}")
            return f
        return replace(f, multiplexed_by=replace(mux, outer=x.multiplexed_by, most=(1 << x.bits) - 1))

    def placed_field(self, name: str, f: Field, payload_bytes: int, framing: Framing,
                     taken: dict[int, str]) -> Field:
        if f.start_bit is None:
            self.report.error(f.loc, f"message {name!r}: field {f.name!r} has no start_bit; in a message "
                                     "with payload_bytes every field is placed by its start bit",
                              "give it `start_bit: <bit>` (DBC numbering) and its `byte_order`")
            return f
        for key, what in NOT_PLACED:
            if getattr(f, key):
                self.report.error(f.loc, f"message {name!r}: field {f.name!r} is {what}; a field placed by "
                                         "start_bit is an integer or bool of its own bits",
                                  f"drop `{key}`, or place the message's fields one after another")
                return replace(f, bit_offset=0)
        if f.kind not in ("uint", "int", "bool", "float"):
            self.report.error(f.loc, f"message {name!r}: field {f.name!r} is {f.kind}; a field placed by "
                                     "start_bit is an integer, bool or float (a DBC signal)",
                              "give it an integer or float type, or place the message's fields one after another")
            return replace(f, bit_offset=0)
        if f.bits is None:  # a width the type refused: its own error says so
            return replace(f, bit_offset=0)
        f = replace(f, byte_order=f.byte_order or framing.byte_order)
        payload_bits = 8 * payload_bytes
        first = relative_offset(f)
        if f.start_bit >= payload_bits or first + f.bits > payload_bits:
            self.report.error(f.loc, f"message {name!r}: field {f.name!r} ({f.bits} bits, {f.byte_order}-endian, "
                                     f"start bit {f.start_bit}) runs outside the payload of {payload_bytes} bytes "
                                     f"(bits 0..{payload_bits - 1})",
                              "move the field, narrow it, or enlarge payload_bytes (a big-endian field runs "
                              "from its start bit down to bit 0 of its byte, then on from bit 7 of the next)")
            return replace(f, bit_offset=0)
        bits = dbc_bits(f)
        clash = next(((b, g) for b in bits for g in taken.get(b, ()) if not exclusive(f.multiplexed_by, g.multiplexed_by)),
                     None)
        if clash is not None:
            b, g = clash
            both = " and a frame may carry both" if f.multiplexed_by or g.multiplexed_by else ""
            self.report.error(f.loc, f"message {name!r}: field {f.name!r} overlaps field {g.name!r} at bit "
                                     f"{b} (byte {b // 8}, bit {b % 8}){both}",
                              "move one, or multiplex both by one multiplexor for different values "
                              "(multiplexed_by: {field: <multiplexor>, values: [...]})")
        for b in bits:
            taken.setdefault(b, []).append(f)
        return replace(f, bit_offset=first)

    def refuse_nested(self, f: Field, name: str) -> None:
        """start_bit places a message's own field: not a group's member, nor an envelope field."""
        for sub in f.fields:
            if sub.start_bit is not None:
                self.report.error(sub.loc, f"message {name!r}: field {sub.name!r} of group {f.name!r} has a "
                                           "start_bit; only a message's own fields are placed by start bit",
                                  "drop its start_bit, or make it a field of the message")
            self.refuse_nested(sub, name)
