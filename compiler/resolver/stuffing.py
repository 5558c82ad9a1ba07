"""Pattern stuffing (`framing.stuffing`): a byte inserted after each occurrence of a
pattern in a span of the frame, and the rules that let every receiver read it back one
way and every length field and checksum count the frame as sent."""
from __future__ import annotations

from dataclasses import replace
from typing import Optional

from ..model import Field, Framing, Message, PatternStuffing
from .base import ResolverBase

# The longest pattern: real buses use two to four bytes
MAX_PATTERN = 16
# A stuffed frame's length is an `int` of 16 bits in C on AVR
MAX_STUFFED_FRAME = 32767


def pattern_problem(pattern: bytes, insert: int) -> Optional[str]:
    """Why a receiver could not read the pattern's stuffing back one way, or None.

    A pattern that overlaps itself (`AA AA`: AA AA AA holds it twice) is found once or
    twice depending on whether a receiver looks at the bytes sent or the bytes meant; and
    an inserted byte that could begin an occurrence, or continue the part of one that the
    pattern ends with, would make the bytes sent hold an occurrence the sender never saw.
    Without both, the occurrences in the bytes sent are exactly the sender's, each followed
    by the inserted byte."""
    for k in range(1, len(pattern)):
        if pattern[:k] == pattern[-k:]:
            return (f"the pattern {pattern.hex(' ').upper()} overlaps itself ({pattern[:k].hex(' ').upper()} both "
                    "starts and ends it), so a run of it holds occurrences a receiver may count differently")
    # an inserted byte inside an occurrence would follow a part of the pattern that also ends
    # it: a border, refused above; so only one that begins the pattern can be misread
    if pattern[0] == insert:
        return (f"the inserted byte {insert:02X} begins the pattern {pattern.hex(' ').upper()}, so the bytes "
                "sent could hold an occurrence the sender never saw")
    return None


class StuffingMixin(ResolverBase):
    def resolve_stuffing(self, fr: dict, framing: Framing, messages: tuple[Message, ...]) -> Framing:
        """The framing with its pattern stuffing, once the messages' sizes are known."""
        st = fr.get("stuffing")
        if st is None or framing.kind != "bytes" or not framing.envelope:
            return framing
        path = ("framing", "stuffing")
        ok = True
        if framing.encoding:
            self.error(path, f"framing: `stuffing` and `encoding: {framing.encoding}` both stuff the frame",
                       "keep one: an encoding wraps the whole frame, stuffing inserts bytes in a span of it")
            ok = False
        if framing.truncate:
            self.error(path, "framing: `stuffing` does not combine with `truncate`",
                       "drop one of them")
            ok = False
        pattern = self.stuffing_pattern(st["after"], path + ("after",))
        if pattern is not None:
            problem = pattern_problem(pattern, st["insert"])
            if problem:
                self.error(path + ("after",), f"framing.stuffing: {problem}",
                           "choose a pattern and inserted byte a receiver reads back one way "
                           "(Dynamixel's FF FF FD with FD)")
                pattern = None
        span = self.stuffing_span(framing.envelope, st["covers"], path + ("covers",))
        if pattern is None or span is None or not ok:
            return framing
        first, last = span
        env = framing.envelope
        head_bits = sum(f.bits or 0 for f in env[:first])
        tail_bits = sum(f.bits or 0 for f in env[last + 1:])
        if head_bits % 8 or tail_bits % 8:
            self.error(path + ("covers",), "framing.stuffing: the stuffed bytes must start and end on a byte "
                                           "boundary", "move the span's ends to whole bytes")
            return framing
        stuffing = PatternStuffing(pattern=pattern, insert=st["insert"],
                                   covers=(st["covers"]["from"], st["covers"]["to"]),
                                   head=head_bits // 8, tail=tail_bits // 8, loc=self.loc(*path))
        inside = [f for f in env[first:last + 1] if not f.is_payload]
        if not self.stuffing_fields_ok(env, inside, messages, span, path) \
                or not self.stuffing_sizes_ok(stuffing, env, span, messages, path):
            return framing
        return replace(framing, stuffing=stuffing)

    def stuffing_pattern(self, text: str, path: tuple) -> Optional[bytes]:
        try:
            pattern = bytes.fromhex(text)
        except ValueError:
            self.error(path, f"framing.stuffing: after {text!r} is not a pattern of hex bytes",
                       'write it as hex bytes: "FF FF FD"')
            return None
        if not pattern:
            self.error(path, "framing.stuffing: the pattern is empty", 'give the bytes to look for: "FF FF FD"')
            return None
        if len(pattern) > MAX_PATTERN:
            self.error(path, f"framing.stuffing: a pattern of {len(pattern)} bytes; at most {MAX_PATTERN}")
            return None
        return pattern

    def stuffing_span(self, env: tuple[Field, ...], covers: dict, path: tuple) -> Optional[tuple[int, int]]:
        """The layout indices of the span's first and last items, or None after an error."""
        index = {("payload" if f.is_payload else f.name): i for i, f in enumerate(env)}
        payload = index["payload"]
        ends = []
        for key in ("from", "to"):
            name = covers[key]
            if name not in index:
                self.error(path + (key,), f"framing.stuffing: {key} {name!r} is no field of the layout",
                           "name a layout field, or `payload`")
                return None
            ends.append(index[name])
        first, last = ends
        if first > last:
            self.error(path + ("from",), f"framing.stuffing: {covers['from']!r} comes after {covers['to']!r}",
                       "name the span's first field in `from` and its last in `to`")
            return None
        if not first <= payload <= last:
            self.error(path + ("from",) if first > payload else path + ("to",),
                       f"framing.stuffing: the span {covers['from']}..{covers['to']} does not hold the payload",
                       "stuffing covers the message's fields: start at or before `payload`, end at or after it")
            return None
        return first, last

    def stuffing_fields_ok(self, env: tuple[Field, ...], inside: list[Field], messages: tuple[Message, ...],
                           span: tuple[int, int], path: tuple) -> bool:
        """Length fields and checksums sit outside the stuffed bytes, in whole bytes, and count
        either none of them or all of them."""
        first, last = span
        index = {("payload" if f.is_payload else f.name): i for i, f in enumerate(env)}
        own = [f for m in messages for f in m.fields if f.checksum or f.length_of]
        for f in inside + own:
            if f.checksum or f.length_of:
                self.error(path + ("covers",), f"framing.stuffing: {'checksum' if f.checksum else 'length'} "
                                               f"field {f.name!r} lies inside the stuffed bytes",
                           "stuffing would change it after it was computed: end the span before it or start it after")
                return False
        counted = False
        for i, f in enumerate(env):
            if not (f.checksum or f.length_of):
                continue
            whole = sum(x.bits or 0 for x in env[:i]) % 8 == 0 and (f.bits or 0) % 8 == 0
            if f.length_of:
                if f.length_of[0] not in index or f.length_of[1] not in index:
                    continue  # a length of fields the envelope lacks: reported where the length is read
                lo, hi = index[f.length_of[0]], index[f.length_of[1]]
                if hi < first or lo > last:
                    continue
                if not (lo <= first and hi >= last):
                    self.error(path + ("covers",), f"framing.stuffing: length field {f.name!r} counts part of the "
                                                   "stuffed bytes", "a length counts all of them or none")
                    return False
                if i > last:
                    self.error(path + ("covers",), f"framing.stuffing: length field {f.name!r} comes after the "
                                                   "stuffed bytes it counts",
                               "a stream decoder reads the length before them to find the frame's end")
                    return False
                if not whole or (f.bits or 0) > 32:
                    self.error(path + ("covers",), f"framing.stuffing: length field {f.name!r} must be whole bytes "
                                                   "(at most 4) to count stuffed bytes")
                    return False
                counted = True
                continue
            cs = f.checksum
            if cs.over != "bytes" or cs.extra or not whole:
                self.error(path + ("covers",), f"framing.stuffing: checksum {f.name!r} must be over bytes, in whole "
                                               "bytes, without `extra`, to be computed over the frame as sent")
                return False
            if cs.covers[0] not in index or cs.covers[1] not in index:
                return False  # a coverage naming no field of the layout: reported where the checksum is resolved
            lo, hi = index[cs.covers[0]], index[cs.covers[1]]
            if hi < first:
                continue  # before the stuffed bytes: computed again only if it covers a length
            if not (lo <= first and hi >= last):
                self.error(path + ("covers",), f"framing.stuffing: checksum {f.name!r} covers part of the "
                                               "stuffed bytes",
                           "a checksum over stuffed bytes covers them all, from before them to after them")
                return False
        if not counted:
            self.error(path + ("covers",), "framing.stuffing: no length field counts the stuffed bytes",
                       "add a length field before them whose `length_of` covers them: a stream decoder finds "
                       "where a stuffed frame ends by it")
        return counted

    def stuffing_sizes_ok(self, st: PatternStuffing, env: tuple[Field, ...], span: tuple[int, int],
                          messages: tuple[Message, ...], path: tuple) -> bool:
        """The pattern fits the stuffed bytes of some frame, every length field counts the largest
        stuffed frame, and that frame's size fits C's `int`."""
        longest = max((m.size or 0) - st.head - st.tail for m in messages)
        if longest < len(st.pattern):
            self.error(path + ("after",), f"framing.stuffing: the pattern of {len(st.pattern)} bytes never fits the "
                                          f"stuffed bytes, at most {longest} in any frame",
                       "a pattern that cannot be found stuffs nothing: drop `stuffing` or shorten the pattern")
            return False
        lengths = [f.name for f in env if f.length_of]
        for m in messages:
            extra = st.most_inserted((m.size or 0) - st.head - st.tail)
            if (m.size or 0) + extra > MAX_STUFFED_FRAME:
                self.error(path, f"framing.stuffing: message {m.name!r} may take {(m.size or 0) + extra} bytes "
                                 f"stuffed; a stuffed frame holds at most {MAX_STUFFED_FRAME}",
                           "its length is an `int` of 16 bits in C on AVR")
                return False
            for f in m.layout:
                if f.name in lengths and f.from_envelope and isinstance(f.const, int) \
                        and f.const + extra > (1 << (f.bits or 0)) - 1:
                    self.error(path, f"framing.stuffing: length field {f.name!r} ({f.bits} bits) cannot count "
                                     f"the largest stuffed frame of message {m.name!r} ({f.const + extra})",
                               "widen the length field or shorten the message")
                    return False
        return True
