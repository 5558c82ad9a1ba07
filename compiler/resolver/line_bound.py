"""The longest line a text stream reader holds: a message's line with each value
as long as its decoders read it, so that a line longer than any message can be
is refused as soon as it outgrows the bound, by the Python and the C stream
readers alike, rather than buffered without end."""
from __future__ import annotations

from ..model import SPELLING_MAX, Framing, Message

FLOAT_TEXT = 26  # room the C encoder keeps for a float's shortest spelling


def value_room(field) -> int:
    """The characters of one value: a char one, a str its most, a number the longest
    the encoder writes or SPELLING_MAX, as a receiver may spell it otherwise (0008)."""
    if field.kind == "char":
        return 1
    if field.kind == "str":
        return field.max_length or 0
    return max(FLOAT_TEXT if field.kind == "float" else 0, field.width or 0, SPELLING_MAX)


def message_line_max(framing: Framing, m: Message) -> int:
    """The longest line of message `m`, its start, prefix, separators, checksum and terminator included."""
    values = [leaf.field for leaf in m.wire.leaves if not leaf.field.prefix]
    ident = m.ids[0] if m.ids and isinstance(m.ids[0], str) else ""  # another id is refused at its line
    n = len(framing.start) + len(ident) + len(framing.prefix_separator) + len(framing.terminator)
    if framing.line_checksum:
        n += len(framing.line_checksum.suffix) + 2
    if m.prefix_field is not None:
        n += m.prefix_field.length or 0
    n += max(0, len(values) - 1) * len(framing.separator)
    return n + sum(map(value_room, values))


def line_max(framing: Framing, messages: tuple[Message, ...]) -> int:
    """The stream readers' bound: the longest line any message can have."""
    return max((message_line_max(framing, m) for m in messages), default=0)
