"""Which messages the accelerator serves, and the tag that pairs a Python module with
its accelerator (kept apart from the view: the Python target needs both)."""
from __future__ import annotations

import hashlib
from typing import Optional

from ... import __version__
from ...model import Field, Message, Protocol, field_at
from ..wire import stream_facts


# What a module asks of its accelerator (bind, method, DECODES, ENCODES): raised with each
# change to it, so that a module never loads one built for another
INTERFACE = 2


def source_tag(p: Protocol) -> str:
    """What a Python module and its accelerator must both have been made from: the same
    schema with the same codeword, for the same interface. A module finds a stale
    accelerator by it and leaves it."""
    return hashlib.sha256(f"{p.sha256} {__version__} {INTERFACE}".encode()).hexdigest()[:16]


def serves(p: Protocol) -> bool:
    return any(servable(p, m) for m in p.messages)


def runs_streams(p: Protocol) -> bool:
    """Whether the accelerator also decodes the frames of a byte stream (an unstuffed one,
    where the C decoder finds frames as the Python StreamDecoder does). A stuffed frame
    goes through the Python StreamDecoder, which unstuffs it and hands the frame to the
    compiled message decoders."""
    return serves(p) and p.framing.kind == "bytes" and not p.framing.encoding and not p.framing.stuffing \
        and bool(stream_facts(p))


def servable(p: Protocol, m: Message) -> bool:
    """Whether every value of the message is built in C exactly as Python builds it."""
    if p.framing.kind == "text":  # text lines (of any number of values) are Python's to split
        return False
    return all(_field_servable(m, f, top=True) for f in m.layout if f.is_member)


def _field_servable(m: Message, f: Field, top: bool) -> bool:
    if f.optional or f.one_hot:  # a presence flag C keeps and Python reads otherwise
        return False
    # a value a frame may leave out, or an array it carries in part: the C struct says
    # which and how many from a raw integer the decoder kept (top-level fields only, as
    # Python reads them)
    if (f.present_if or f.multiplexed_by or f.varies) and not top:
        return False
    if f.present_if and not _raw_member(field_at(m.layout, f.present_if.field), unsigned=True):
        return False
    if f.multiplexed_by and not all(_raw_member(field_at(m.layout, x.field)) for x in f.multiplexed_by.chain):
        return False
    if f.kind == "group":
        return all(_field_servable(m, x, top=False) for x in f.fields if x.is_member)
    f = f.element
    if f.kind == "bool":
        return f.bits == 1  # Python reads `raw == 1`, C `raw != 0`
    if f.kind in ("float", "bytes"):
        return True
    if f.kind not in ("uint", "int") or f.decimals:
        return False
    if f.enum is not None:
        return f.enum.kind != "char" and f.scale is None and not f.offset
    if f.flags is not None:
        return f.scale is None and not f.offset
    numbers = [x for x in (f.scale, f.offset) if x is not None]
    if f.scale is None:  # C keeps raw + offset as an integer, Python adds them
        return all(isinstance(x, int) for x in numbers)
    return all(isinstance(x, (int, float)) and not isinstance(x, bool) for x in numbers)


def _raw_member(f: Optional[Field], unsigned: bool = False) -> bool:
    """Whether the C struct holds the field's raw wire integer, as Python tests it."""
    return f is not None and f.count is None and f.kind in (("uint",) if unsigned else ("uint", "int")) \
        and f.scale is None and not f.offset and not f.decimals
