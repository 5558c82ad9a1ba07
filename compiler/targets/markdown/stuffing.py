"""The framing section's byte stuffing: what the encoding does, and one frame
before and after it. A small reference encoder of its own, for the docs only: the
codecs' agreement with published frames is what the tests check."""
from __future__ import annotations

from ...model import Protocol
from .text import code
from ..escape import md_text
from ..wire import ENCODINGS, encoding_facts, stuffing_facts

DEMO = bytes((0x01, 0xC0, 0x7E, 0x00, 0xDB, 0x7D, 0x02))  # every special byte of every encoding


def stuff(encoding: str, frame: bytes, mapped: tuple[int, ...] = ()) -> bytes:
    """The frame as the encoding sends it, delimiters included."""
    if encoding == "cobs":
        out = bytearray()
        code_at, code = 0, 1
        out.append(0)
        for byte in frame:
            if code == 0xFF:  # a full block closes only when more follows
                out[code_at], code_at, code = code, len(out), 1
                out.append(0)
            if byte == 0:
                out[code_at], code_at, code = code, len(out), 1
                out.append(0)
            else:
                out.append(byte)
                code += 1
        out[code_at] = code
        return bytes(out) + b"\x00"
    facts = ENCODINGS[encoding]
    codes = {original: code for code, original in facts["escaped"]}
    codes.update({c: c ^ 0x20 for c in mapped})  # HDLC: the control characters of its map
    body = b"".join(bytes((facts["escape"], codes[b])) if b in codes else bytes((b,)) for b in frame)
    delimiter = bytes((facts["delimiter"],))
    return delimiter + body + delimiter


def unstuff(encoding: str, wire: bytes, mapped: tuple[int, ...] = ()) -> bytes:
    """The frame a well-formed encoded frame holds (HDLC: its mapped control characters
    that arrive unescaped dropped)."""
    facts = ENCODINGS[encoding]
    body = wire[:-1]
    if encoding == "cobs":
        out, pos = bytearray(), 0
        while pos < len(body):
            code = body[pos]
            out += body[pos + 1:pos + code]
            pos += code
            if code < 0xFF and pos < len(body):
                out.append(0)
        return bytes(out)
    body = body[1:] if body[:1] == bytes((facts["delimiter"],)) else body
    body = bytes(b for b in body if b not in mapped)
    originals = dict(facts["escaped"])
    out, pos = bytearray(), 0
    while pos < len(body):
        if body[pos] == facts["escape"]:
            out.append(originals.get(body[pos + 1], body[pos + 1] ^ 0x20))
            pos += 2
        else:
            out.append(body[pos])
            pos += 1
    return bytes(out)


def spaced(data: bytes) -> str:
    return " ".join(f"{b:02X}" for b in data)


def encoding_lines(p: Protocol) -> list[str]:
    """The framing section's paragraphs on the encoding, or none without one."""
    facts = encoding_facts(p)
    if not facts:
        return []
    kind = facts["kind"]
    example = next((ex.hex for m in p.messages for ex in m.examples if ex.hex and ex.values is not None), None)
    mapped = facts["mapped"]
    frame = unstuff(kind, example, mapped) if example else DEMO
    wire = example or stuff(kind, DEMO, mapped)
    lines = [f"**Encoding: {facts['name']}.** The frame above, its lengths and checksums computed over "
             "its own bytes, is stuffed on the link: every encoder and decoder of this protocol reads and "
             "writes the stuffed bytes."]
    if kind == "cobs":
        lines.append("COBS removes every `00` byte: each block is a code byte *n* and *n* − 1 non-zero bytes, "
                     "followed by a `00` in the frame unless *n* is `FF` or the block is the last; `00` ends "
                     "the frame.")
    else:
        (first, of_first), (second, of_second) = facts["escaped"]
        lines.append(f"Each frame is sent between two delimiters `{facts['delimiter']:02X}`; inside it "
                     f"`{of_first:02X}` is sent as `{facts['escape']:02X} {first:02X}` and `{of_second:02X}` as "
                     f"`{facts['escape']:02X} {second:02X}`. A decoder accepts a frame without its leading "
                     "delimiter" + (", and any byte after the escape `7D` (the byte XOR `20`), so a peer "
                     "may escape control characters too." if kind == "hdlc" else
                     "; `DB` followed by any byte but `DC` or `DD` is an error."))
    if mapped:
        lines.append(f"Its async control character map (accm `0x{facts['accm']:08X}`, RFC 1662 §7.1) escapes "
                     "the control characters " + ", ".join(f"`{c:02X}`" for c in mapped)
                     + " too: each is sent as `7D` and the character XOR `20`. A decoder drops any of them "
                     "that arrives unescaped, wherever it comes (even after `7D`): equipment on the way "
                     "may have added it (RFC 1662 §4.2). A stream decoder drops them as they arrive: a "
                     "stretch of them alone between two delimiters is empty, like idle flags, and they "
                     "count as no skipped byte.")
    lines.append(f"{'An example frame' if example else 'A frame'}: `{spaced(frame)}` is sent as "
                 f"`{spaced(wire)}`. Buffers: a frame takes at most {facts['wire_max']} bytes encoded "
                 f"(the largest frame is {facts['frame_max']} bytes).")
    lines.append("**Stream resynchronisation.** A stream decoder splits the stream at each delimiter and "
                 "unstuffs and decodes the bytes between two delimiters. When they hold no frame (a bad "
                 "escape, more bytes than the largest frame, a bad frame) it reports one error for them and "
                 "goes on after the next delimiter, so a damaged frame never hides the next good one.")
    return lines


def pattern_lines(p: Protocol) -> list[str]:
    """The framing section's paragraphs on pattern stuffing, with a worked frame: the
    schema's first example whose stuffed bytes hold the pattern, or none without stuffing."""
    facts = stuffing_facts(p)
    if not facts:
        return []
    st = p.framing.stuffing
    pattern, stuffed = st.pattern, st.pattern + bytes((st.insert,))
    lines = [f"**Pattern stuffing: {code(facts['name'])}.** In the bytes from `{st.covers[0]}` through "
             f"`{st.covers[1]}` (from byte {st.head} of a frame to {st.tail} bytes before its end) the sender inserts "
             f"`{st.insert:02X}` after every `{spaced(pattern)}`, and the receiver removes the `{st.insert:02X}` that "
             f"follows each `{spaced(pattern)}` there. The pattern is found in the bytes meant, from the first stuffed byte on, and occurrences "
             "never overlap. Length fields that count the stuffed bytes count them as sent, inserted bytes "
             "included, and checksums are computed over the frame as sent: an encoder stuffs the frame, then "
             "sets its lengths and checksums; a decoder checks its checksums over the bytes received, then "
             "removes the inserted bytes, and a pattern there without its inserted byte is the error `escape`. Every encoder and decoder of this protocol reads and writes the "
             "frame as sent; the field offsets of an error past a stuffed byte count the frame without it."]
    for m in p.messages:
        for ex in m.examples:
            wire = bytes(ex.hex) if ex.hex and ex.values is not None else b""
            body = wire[st.head:len(wire) - st.tail]
            if stuffed in body:
                lines.append(f"A worked frame, {md_text(ex.name or m.name)}: the stuffed bytes "
                             f"`{spaced(body.replace(stuffed, pattern))}` are sent as `{spaced(body)}`, and the "
                             f"whole frame as `{spaced(wire)}`.")
                break
        else:
            continue
        break
    lines.append(f"Buffers: a frame takes at most {facts['wire_max']} bytes as sent (the largest frame is "
                 f"{facts['frame_max']} bytes before stuffing).")
    return lines
