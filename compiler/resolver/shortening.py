"""Frames shorter than their message: extension fields left off the end, and MAVLink 2's
truncation of the payload's trailing zero bytes. The decoder puts the missing bytes
back as zeros, so everything after this works on the whole frame; only the length
field and a checksum that ends with the payload count the bytes actually sent."""
from __future__ import annotations

from typing import Optional

from dataclasses import replace

from ..model import Counter, Field, Framing, Gap, Shortening
from .base import ResolverBase
from .checksums import coverage



def element_bytes(counted: Field) -> int:
    """Bytes of one element of a counted field: a counted bytes field's elements are bytes."""
    return 1 if counted.kind == "bytes" else counted.element.bits // 8


class ShorteningMixin(ResolverBase):
    def shortening(self, name: str, layout: tuple[Field, ...], framing: Framing, path: tuple) -> Optional[Shortening]:
        """How much of the payload a frame of this message may leave off, or None."""
        own = tuple(f for f in layout if not f.from_envelope and not f.is_payload)  # placed
        gapped = [f for f in own if f.varies or f.present_if]
        if gapped:
            return self.gapped_shortening(name, layout, own, gapped, framing, path)
        first_extension = self.check_extensions_last(name, own, path)
        if first_extension is None and not framing.truncate:
            return None
        counter = self.payload_length(layout)
        if counter is None:
            where = ("framing", "truncate") if framing.truncate else path + ("fields", own.index(first_extension))
            self.error(where, f"message {name!r}: a frame that may be shorter than its message needs a "
                              "length field that counts the payload", "add to the framing's layout a field "
                                                                      "with length_of: {from: payload, to: payload}, or "
                                                                      "a range around the payload")
            return None
        marker = next((f for f in layout if f.is_payload), None)
        if marker is None:  # the layout's own error says so
            return None
        start = own[0].bit_offset if own else marker.bit_offset
        end = marker.bit_offset
        if start % 8 or end % 8 or counter.bit_offset % 8 or counter.bits % 8:
            self.error(path, f"message {name!r}: a payload that may be cut short must start and end on "
                             "byte boundaries, and its length field be whole bytes",
                       "add reserved bits to the layout")
            return None
        start, end = start // 8, end // 8
        if framing.truncate:
            least = min(1, end - start)  # MAVLink 2 keeps at least one byte
        elif first_extension.bit_offset % 8:
            self.error(path + ("fields", own.index(first_extension)),
                       f"message {name!r}: extension field {first_extension.name!r} must start on a byte "
                       "boundary: a frame without it ends there", "add reserved bits before it")
            return None
        else:
            least = first_extension.bit_offset // 8 - start
        if least == end - start:
            return None
        self.check_spans_end_with_payload(name, layout, counter, (start, end), path)
        return Shortening((start, end), least, counter.name, framing.truncate == "trailing_zeros")

    def gapped_shortening(self, name: str, layout: tuple[Field, ...], own: tuple[Field, ...],
                          gapped: list[Field], framing: Framing, path: tuple) -> Optional[Shortening]:
        """A payload with counted arrays (or bytes) and conditional fields: frames carry from
        none to all of each one's bytes, as an earlier field says."""
        gaps = []
        for f in gapped:
            gap = self.gap_of(name, f, framing, path + ("fields", own.index(f)))
            if gap is None:
                return None
            gaps.append(gap)
        where = path + ("fields", own.index(gapped[0]))
        if framing.truncate or any(f.extension for f in own):
            self.error(where, f"message {name!r}: a counted or conditional field and a frame cut short in "
                              "another way (truncate, extension fields) do not combine", "drop one of them")
            return None
        marker = next((f for f in layout if f.is_payload), None)
        if marker is None:  # the layout's own error says so
            return None
        start, end = own[0].bit_offset // 8, marker.bit_offset // 8
        length = self.payload_length(layout)
        rest = next((f for f, g in zip(gapped, gaps) if g.fills_rest), None)
        if rest is not None and rest is not own[-1]:
            self.error(path + ("fields", own.index(rest)), f"message {name!r}: {rest.name!r} fills the rest "
                                                          "of the payload, so it must be the last field",
                       f"move {rest.name!r} to the end, or count it with `count: {{from: <field>}}`")
            return None
        if length is None and not framing.encoding and (len(gaps) > 1 or gaps[0].presence or rest):
            self.error(where, f"message {name!r}: without a length field or a byte stuffing that ends frames, "
                              f"a stream decoder cannot tell where a frame with {gapped[-1].name!r} ends",
                       "add a length field that counts the payload")
            return None
        if length is None and not any(f.dispatch for f in framing.envelope):
            self.error(where, f"message {name!r}: with neither a length field nor a dispatch field, a stream "
                              f"decoder cannot tell where a frame with {gapped[0].name!r} ends",
                       "add a length field that counts the payload, or a dispatch field to the layout")
            return None
        self.check_nothing_moves(name, layout, gaps[0], (start, end), path)
        self.check_spans_end_with_payload(name, layout, length, (start, end), path, gaps[0].span[0])
        least = end - start - sum(g.size for g in gaps)
        return Shortening((start, end), least, None if length is None else length.name, gaps=tuple(gaps))

    @staticmethod
    def payload_length(layout: tuple[Field, ...]) -> Optional[Field]:
        """The length field whose coverage holds the whole payload: it counts the bytes sent."""
        marker = next((f for f in layout if f.is_payload), None)
        own = [f for f in layout if not f.from_envelope and not f.is_payload]
        if marker is None:
            return None
        start = own[0].bit_offset if own else marker.bit_offset
        for f in layout:
            span = coverage(layout, f.length_of) if f.length_of else None
            if span is not None and span[0] <= start and span[1] >= marker.bit_offset:
                return f
        return None

    def gap_of(self, name: str, f: Field, framing: Framing, where: tuple) -> Optional[Gap]:
        """The bytes of counted or conditional field `f`, which must be whole bytes."""
        element = f.element if f.varies else f
        if f.varies and f.present_if or f.present_if and (not f.is_member or f.extension):
            self.error(where, f"message {name!r}: {f.name!r} is conditional and "
                              f"{'counted' if f.counted_by else 'not a value the sender gives'}",
                       "make it one or the other")
            return None
        if f.bit_offset % 8 or (element.bits or 0) % 8:
            self.error(where, f"message {name!r}: {f.name!r} must start on a byte boundary and be whole bytes"
                              f"{' each element' if f.varies else ''}: a frame may leave it out",
                       "add reserved bits before it, or widen it")
            return None
        span = (f.bit_offset // 8, (f.bit_offset + f.bits) // 8)
        if f.varies:
            counter = Counter(f.name, f.counted_by, element_bytes(f), f.count or f.length, f.count_unit)
            return Gap(span, f.name, counter=counter)
        return Gap(span, f.name, presence=f.present_if)

    def check_nothing_moves(self, name: str, layout: tuple[Field, ...], first: Gap, payload: tuple[int, int],
                            path: tuple) -> None:
        """A length or checksum field sits before the first gap or after the payload: the
        bytes between move with what a frame leaves out."""
        for f in layout:
            if (f.length_of or f.checksum) and first.span[0] * 8 <= f.bit_offset < payload[1] * 8:
                self.error(path, f"message {name!r}: {f.name!r} follows {first.field!r}, which a frame may "
                                 "leave out, inside the payload", f"move {f.name!r} before {first.field!r} "
                                                                   "or into the framing's trailer")

    def bind_controls(self, name: str, own: tuple[Field, ...], path: tuple) -> tuple[Field, ...]:
        """Counted and conditional fields name an earlier field of the message: a count field
        becomes one the encoder sets; a condition learns the bits and values it tests."""
        self.refuse_nested_gaps(name, own, path)
        for i, f in enumerate(own):
            if f.counted_by:
                own = self.bind_count(name, own, f, path + ("fields", i, "count" if f.count else "length"))
            elif f.present_if:
                own = own[:i] + (self.bind_condition(name, own, f, path + ("fields", i, "present_if")),) + own[i + 1:]
        return own

    def refuse_nested_gaps(self, name: str, own: tuple[Field, ...], path: tuple) -> None:
        """Counted and conditional fields are fields of the message itself, not of a group."""
        def nested(fields: tuple[Field, ...]) -> Optional[Field]:
            for f in fields:
                if f.varies or f.present_if:
                    return f
                inner = nested(f.fields)
                if inner is not None:
                    return inner
            return None
        for i, f in enumerate(own):
            inner = nested(f.fields)
            if inner is not None:
                self.error(path + ("fields", i), f"message {name!r}: {inner.name!r} in group {f.name!r} is "
                                                 "counted or conditional; only a message's own fields may be",
                           f"move {inner.name!r} out of the group, into the message")

    def control_of(self, name: str, own: tuple[Field, ...], f: Field, control: str, where: tuple) -> Optional[Field]:
        """The earlier field of the message, outside any gap, that `f` names."""
        index = next((i for i, x in enumerate(own) if x.name == control), None)
        if index is None or index > own.index(f):
            self.error(where, f"message {name!r}: {f.name!r} depends on {control!r}, which is not an "
                              "earlier field of the message", "name an unsigned field declared before it")
            return None
        x = own[index]
        if x.counted_by or x.present_if or x.count is not None:
            self.error(where, f"message {name!r}: {f.name!r} depends on {control!r}, which is an array or "
                              "itself counted or conditional", "name a single field that every frame carries")
            return None
        return x

    def bind_count(self, name: str, own: tuple[Field, ...], counted: Field, where: tuple) -> tuple[Field, ...]:
        """The field that gives a counted field's length becomes one the encoder sets."""
        f = self.control_of(name, own, counted, counted.counted_by, where)
        if f is None:
            return own
        index = own.index(f)
        size = element_bytes(counted)
        if not size:  # elements narrower than a byte: refused where the field's bytes are found (gap_of)
            return own
        most = (counted.count or counted.length) * size // (counted.count_unit or size)
        problem = ("it is not an unsigned integer" if f.kind != "uint" else
                   "the codec sets it" if not f.is_member else
                   "it has checks or a scale of its own" if f.enum or f.flags or f.range or f.values or f.scale
                   or f.offset is not None or f.one_hot else
                   f"its {f.bits} bits do not hold {most}" if f.bits is None or most >= 1 << f.bits else None)
        if problem:
            self.error(where, f"message {name!r}: {f.name!r} cannot give the length of {counted.name!r}: "
                              f"{problem}", "make it a plain unsigned integer wide enough for the most elements")
            return own
        return own[:index] + (replace(f, counts=counted.name),) + own[index + 1:]

    def bind_condition(self, name: str, own: tuple[Field, ...], f: Field, where: tuple) -> Field:
        """The bits of the control field a condition tests, and the raw values that mean present."""
        cond = f.present_if
        x = self.control_of(name, own, f, cond.field, where)
        if x is None:
            return f
        if x.kind not in ("uint", "bool") or x.scale or x.offset is not None or not x.is_member:
            self.error(where, f"message {name!r}: {f.name!r} depends on {x.name!r}, which is not a plain "
                              "unsigned, enum, flags or bool field of the message", "name such a field")
            return f
        if cond.has is not None:
            flag = next((fl for fl in x.flags.members if fl.name == cond.has), None) if x.flags else None
            if flag is None:
                self.error(where, f"message {name!r}: {x.name!r} has no flag {cond.has!r}",
                           f"name a flag of {x.name!r}'s flag set, or use `equals`")
                return f
            mask = 1 << flag.bit
            return replace(f, present_if=replace(cond, mask=mask, values=(mask,)))
        values = []
        for v in cond.equals:
            member = next((e for e in x.enum.members if e.name == v), None) if x.enum and isinstance(v, str) else None
            raw = member.value if member is not None else v
            if isinstance(raw, bool) or not isinstance(raw, int) or not 0 <= raw < 1 << x.bits:
                self.error(where, f"message {name!r}: {f.name!r} is present when {x.name!r} is {v!r}, "
                                  f"which its {x.bits} bits cannot hold",
                           f"give a number in 0..{(1 << x.bits) - 1}" + (" or a member of its enum" if x.enum else ""))
                return f
            values.append(raw)
        return replace(f, present_if=replace(cond, mask=(1 << x.bits) - 1, values=tuple(values)))

    def check_extensions_last(self, name: str, own: tuple[Field, ...], path: tuple) -> Optional[Field]:
        """Extension fields come after every other field of the message: the first of them."""
        first = next((f for f in own if f.extension), None)
        if first is None:
            return None
        for i, f in enumerate(own[own.index(first):]):
            if not f.extension:
                self.error(path + ("fields", own.index(first) + i),
                           f"message {name!r}: field {f.name!r} follows extension field {first.name!r}; "
                           "extension fields must come last", f"mark {f.name!r} `extension: true`, or move it "
                                                              "before the extensions")
                break
        return first

    def check_spans_end_with_payload(self, name: str, layout: tuple[Field, ...], counter: Optional[Field],
                                     payload: tuple[int, int], path: tuple, first: Optional[int] = None) -> None:
        """A checksum or length that covers the payload's end counts the bytes sent, so its
        coverage must end where the payload does: bytes after a cut payload move."""
        start, end = payload
        for f in layout:
            span = coverage(layout, f.length_of) if f.length_of and f is not counter else None
            if span is not None and span[1] > start * 8 and counter is not None and span[0] <= start * 8 \
                    and span[1] >= end * 8:
                self.error(path, f"message {name!r}: {f.name!r} is a second length field; a frame that may "
                                 f"be cut short has one, {counter.name!r}, which counts the bytes sent",
                           "drop the other length field")
            elif span is not None and span[1] > start * 8 and span[0] < end * 8:
                self.error(path, f"message {name!r}: {f.name!r} counts part of a payload that may be cut "
                                 "short, but not all of it", "count from the payload's start (or before) "
                                                             "to its end (or after)")
            span = f.checksum.byte_span if f.checksum else None
            if span is not None and span[1] > start and span[1] != end:
                self.error(path, f"message {name!r}: {f.name!r} covers bytes past the start of a payload "
                                 "that may be cut short, and does not end with it",
                           "end its coverage with the payload (`to: payload`) or before it")
            elif span is not None and first is not None and span[0] > first and span[1] > first:
                self.error(path, f"message {name!r}: {f.name!r} starts its coverage after a field that a "
                                 "frame may leave out, so its first byte moves",
                           "start its coverage before the first counted or conditional field")
