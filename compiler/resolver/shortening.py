"""Frames shorter than their message: extension fields left off the end, and MAVLink 2's
truncation of the payload's trailing zero bytes. The decoder puts the missing bytes
back as zeros, so everything after this works on the whole frame; only the length
field and a checksum that ends with the payload count the bytes actually sent."""
from __future__ import annotations

from typing import Optional

from dataclasses import replace

from ..model import Counter, Field, Framing, Shortening
from .base import ResolverBase

PAYLOAD = ("payload", "payload")


def element_bytes(counted: Field) -> int:
    """Bytes of one element of a counted field: a counted bytes field's elements are bytes."""
    return 1 if counted.kind == "bytes" else counted.element.bits // 8


class ShorteningMixin(ResolverBase):
    def shortening(self, name: str, layout: tuple[Field, ...], framing: Framing, path: tuple) -> Optional[Shortening]:
        """How much of the payload a frame of this message may leave off, or None."""
        own = tuple(f for f in layout if not f.from_envelope and not f.is_payload)  # placed
        counted = next((f for f in own if f.counted_by), None)
        if counted is not None:
            return self.counted_shortening(name, layout, own, counted, framing, path)
        first_extension = self.check_extensions_last(name, own, path)
        if first_extension is None and not framing.truncate:
            return None
        counter = next((f for f in layout if f.length_of == PAYLOAD), None)
        if counter is None:
            where = ("framing", "truncate") if framing.truncate else path + ("fields", own.index(first_extension))
            self.error(where, f"message {name!r}: a frame that may be shorter than its message needs a "
                              "length field that counts the payload", "add to the framing's layout a field "
                                                                      "with length_of: {from: payload, to: payload}")
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

    def counted_shortening(self, name: str, layout: tuple[Field, ...], own: tuple[Field, ...], counted: Field,
                           framing: Framing, path: tuple) -> Optional[Shortening]:
        """A payload that ends with an array (or bytes) whose length an earlier field gives:
        frames carry from none of its elements to all of them."""
        where = path + ("fields", own.index(counted))
        if counted is not own[-1]:
            self.error(where, f"message {name!r}: {counted.name!r}, whose length {counted.counted_by!r} "
                              "gives, must be the last field of the message", f"move {counted.name!r} to the end")
            return None
        if framing.truncate or any(f.extension for f in own):
            self.error(where, f"message {name!r}: a counted field and a frame cut short in another way "
                              "(truncate, extension fields) do not combine", "drop one of them")
            return None
        element = counted.element
        start = own[0].bit_offset
        if start % 8 or counted.bit_offset % 8 or (element.bits or 0) % 8:
            self.error(where, f"message {name!r}: {counted.name!r} must start on a byte boundary and "
                              "its elements be whole bytes", "add reserved bits before it")
            return None
        end = (counted.bit_offset + counted.bits) // 8
        length = next((f for f in layout if f.length_of == PAYLOAD), None)
        fixed = next((f for f in layout if f.length_of and f.length_of != PAYLOAD), None)
        if fixed is not None:
            self.error(where, f"message {name!r}: {fixed.name!r} counts {fixed.length_of[0]}..{fixed.length_of[1]}, "
                              f"a span whose size changes with {counted.name!r}",
                       "count the payload alone: length_of: {from: payload, to: payload}")
            return None
        if length is None and not any(f.dispatch for f in framing.envelope):
            self.error(where, f"message {name!r}: with neither a length field nor a dispatch field, a stream "
                              f"decoder cannot tell where a frame with {counted.name!r} ends",
                       "add a length field that counts the payload, or a dispatch field to the layout")
            return None
        counter = Counter(counted.name, counted.counted_by, element_bytes(counted), counted.count or counted.length,
                          counted.counts_bytes)
        self.check_spans_end_with_payload(name, layout, length, (start // 8, end), path)
        return Shortening((start // 8, end), counted.bit_offset // 8 - start // 8,
                          None if length is None else length.name, counter=counter)

    def bind_count(self, name: str, own: tuple[Field, ...], path: tuple) -> tuple[Field, ...]:
        """The field that gives a counted field's length becomes one the encoder sets."""
        counted = next((f for f in own if f.counted_by), None)
        if counted is None:
            return own
        index = next((i for i, f in enumerate(own) if f.name == counted.counted_by), None)
        where = path + ("fields", own.index(counted), "count" if counted.count else "length")
        if index is None or index > own.index(counted):
            self.error(where, f"message {name!r}: {counted.name!r} takes its length from "
                              f"{counted.counted_by!r}, which is not an earlier field of the message",
                       "name a u8 or u16 field declared before it")
            return own
        f = own[index]
        most = (counted.count or counted.length) * (element_bytes(counted) if counted.counts_bytes else 1)
        problem = ("it is not an unsigned integer" if f.kind != "uint" or f.count is not None else
                   "the codec sets it" if not f.is_member else
                   "it has checks or a scale of its own" if f.enum or f.flags or f.range or f.values or f.scale
                   or f.offset is not None or f.one_hot else
                   f"its {f.bits} bits do not hold {most}" if f.bits is None or most >= 1 << f.bits else None)
        if problem:
            self.error(where, f"message {name!r}: {f.name!r} cannot give the length of {counted.name!r}: "
                              f"{problem}", "make it a plain unsigned integer wide enough for the most elements")
            return own
        return own[:index] + (replace(f, counts=counted.name),) + own[index + 1:]

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
                                     payload: tuple[int, int], path: tuple) -> None:
        """A checksum or length that covers the payload's end counts the bytes sent, so its
        coverage must end where the payload does: bytes after a cut payload move."""
        start, end = payload
        for f in layout:
            if f.length_of and f is not counter and counter is not None:
                self.error(path, f"message {name!r}: {f.name!r} is a second length field; a frame that may "
                                 f"be cut short has one, {counter.name!r}, which counts the payload sent",
                           "drop the other length field")
            elif f.length_of and counter is None:
                self.error(path, f"message {name!r}: {f.name!r} does not count the payload alone; in a "
                                 "frame that may be cut short a length field counts the payload sent",
                           "give it length_of: {from: payload, to: payload}")
            span = f.checksum.byte_span if f.checksum else None
            if span is not None and span[1] > start and span[1] != end:
                self.error(path, f"message {name!r}: {f.name!r} covers bytes past the start of a payload "
                                 "that may be cut short, and does not end with it",
                           "end its coverage with the payload (`to: payload`) or before it")
