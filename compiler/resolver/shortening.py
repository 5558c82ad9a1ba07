"""Frames shorter than their message: extension fields left off the end, and MAVLink 2's
truncation of the payload's trailing zero bytes. The decoder puts the missing bytes
back as zeros, so everything after this works on the whole frame; only the length
field and a checksum that ends with the payload count the bytes actually sent."""
from __future__ import annotations

from typing import Optional

from ..model import Field, Framing, Shortening
from .base import ResolverBase

PAYLOAD = ("payload", "payload")


class ShorteningMixin(ResolverBase):
    def shortening(self, name: str, layout: tuple[Field, ...], framing: Framing, path: tuple) -> Optional[Shortening]:
        """How much of the payload a frame of this message may leave off, or None."""
        own = tuple(f for f in layout if not f.from_envelope and not f.is_payload)  # placed
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
        marker = next(f for f in layout if f.is_payload)
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

    def check_spans_end_with_payload(self, name: str, layout: tuple[Field, ...], counter: Field,
                                     payload: tuple[int, int], path: tuple) -> None:
        """A checksum or length that covers the payload's end counts the bytes sent, so its
        coverage must end where the payload does: bytes after a cut payload move."""
        start, end = payload
        for f in layout:
            if f.length_of and f is not counter:
                self.error(path, f"message {name!r}: {f.name!r} is a second length field; a frame that may "
                                 f"be cut short has one, {counter.name!r}, which counts the payload sent",
                           "drop the other length field")
            span = f.checksum.byte_span if f.checksum else None
            if span is not None and span[1] > start and span[1] != end:
                self.error(path, f"message {name!r}: {f.name!r} covers bytes past the start of a payload "
                                 "that may be cut short, and does not end with it",
                           "end its coverage with the payload (`to: payload`) or before it")
