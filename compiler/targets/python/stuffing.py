"""Pattern stuffing (`framing.stuffing`) spelt in Python: the statements that make a
frame's length fields and checksums count it as sent, and that check a frame as
received, from the wire facts of `stuffing_facts`."""
from __future__ import annotations

from ..wire import checksum_name, stuffing_facts


def _slice(where: dict) -> str:
    """The bytes of a field placed from the frame's start (`at`) or end (`back`), in `b` of
    `n` bytes."""
    if "at" in where:
        return f"{where['at']}:{where['at'] + where['bytes']}"
    return f"n - {where['back']}:n - {where['back'] - where['bytes']}" if where["back"] > where["bytes"] \
        else f"n - {where['back']}:n"


def _covered(cs: dict, buf: str) -> str:
    end = f"n - {cs['end_back']}" if "end_back" in cs else str(cs["end"])
    return f"_checksum_{checksum_name(cs['cs'])}({buf}[{cs['start']}:{end}])"


def stuffing_view(p) -> dict:
    """The literals and statements of the Python pattern stuffing, or {} without it."""
    facts = stuffing_facts(p)
    if not facts:
        return facts
    recount, verify = [], []
    for f in facts["lengths"]:  # `added` is negative when stuffed bytes are removed
        at = _slice(f)
        recount += [f"v = int.from_bytes(b[{at}], {f['byte_order']!r}) + added",
                    "if v < 0:",
                    f"    raise _dec(None, {f['name']!r}, v - added, 'length', f'at least {{-added}}: the stuffed "
                    f"bytes it counts', {8 * f['at']})",
                    f"b[{at}] = v.to_bytes({f['bytes']}, {f['byte_order']!r})"]
    for cs in facts["checksums"]:
        at = _slice(cs)
        if cs["cs"].covers_self:  # counted as zero while computed
            recount.append(f"b[{at}] = bytes({cs['bytes']})")
        recount.append(f"b[{at}] = {_covered(cs, 'b')}.to_bytes({cs['bytes']}, {cs['byte_order']!r})")
        verify.append(f"got = int.from_bytes(d[{at}], {cs['byte_order']!r})")
        if cs["cs"].covers_self:  # RFC 1071's receiver check: with the field, the sum is all ones
            verify += [f"if {_covered(cs, 'd')}:",
                       "    z = bytearray(d)",
                       f"    z[{at}] = bytes({cs['bytes']})",
                       f"    raise _dec(None, {cs['name']!r}, got, 'checksum', hex({_covered(cs, 'z')}), "
                       f"({at.split(':')[0]}) * 8)"]
            continue
        verify += [f"x = {_covered(cs, 'd')}",
                   "if got != x:",
                   f"    raise _dec(None, {cs['name']!r}, got, 'checksum', hex(x), ({at.split(':')[0]}) * 8)"]
    # a length field sits before the stuffed bytes (the resolver's rule): placed from the start
    pattern = facts["pattern"]
    return dict(facts, pattern_literal=repr(pattern), stuffed_literal=repr(pattern + bytes((facts["insert"],))),
                pattern_hex=pattern.hex(" ").upper(), insert_hex=f"{facts['insert']:02X}",
                recount=recount, verify=verify)
