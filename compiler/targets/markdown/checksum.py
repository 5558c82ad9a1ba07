"""The checksum section: algorithm, parameters, coverage per message, and a
worked example recomputed step by step from a real example frame.

The worked example is computed here from the frame's bits, independently of
the generated codec, and must agree with the checksum the codec wrote.
"""
from __future__ import annotations

import types
from typing import Any, Optional

from ... import crc as crc_reference
from ...model import Checksum, Message, Protocol, shift_in
from .layout import Slot, position, slots
from .text import DecisionLinker, anchor, cell, en, number
from ..wire import checksum_name


def _bits_of(frame: bytes, offset: int, width: int, order: str = "big") -> int:
    """The `width` bits from frame bit `offset`, the frame read as one integer in
    `order` (its bit order: Framing.wire_order)."""
    return (int.from_bytes(frame, order) >> shift_in(order, 0, len(frame), offset, width)) & ((1 << width) - 1)


def _sent_value(p: Protocol, frame: bytes, slot: Slot) -> int:
    """A checksum field of whole bytes as sent, in its byte order; narrower ones as bits."""
    field = slot.field
    if slot.offset % 8 or field.bits % 8:
        return _bits_of(frame, slot.offset, field.bits, p.framing.wire_order)
    order = field.byte_order or p.framing.byte_order
    return int.from_bytes(frame[slot.offset // 8:(slot.offset + field.bits) // 8],
                          "big" if order == "big" else "little")


def _checksum_slot(m: Message) -> Optional[Slot]:
    return next((s for s in slots(m) if s.field.checksum is not None), None)


def _frame(p: Protocol, codec: types.ModuleType, m: Message) -> Optional[tuple[Any, bytes]]:
    """The first example of `m` with values, encoded by the codec, as a whole frame (the
    positions of a frame cut short are not those of the layout)."""
    for ex in m.examples:
        if not ex.errors and not ex.decode_only and ex.values is not None:
            frame = codec.encode(codec.from_dict(m.name, ex.values))
            if len(frame) == m.size:
                return ex, frame
    return None


def _coverage(p: Protocol, m: Message, cs: Checksum, slot: Slot) -> str:
    if cs.byte_span is not None:
        start, end = cs.byte_span
        return f"bytes B{start}–B{end - 1} ({end - start} bytes: {cs.covers[0]} … {cs.covers[1]})" if cs.covers \
            else f"bytes B{start}–B{end - 1}"
    others = [s.path for s in slots(m) if s.depth == 0 and s.path != slot.path and s.field.kind != "group"] + \
             [s.path for s in slots(m) if s.depth > 0]
    if cs.over == "bits" or cs.algorithm == "parity":
        return f"all {m.bits} bits of the word, the parity bit included"
    return "the wire values of every other field: " + ", ".join(others)


def _crc_steps(params, data: bytes) -> list[tuple[str, str]]:
    """The register after each byte (Rocksoft model, bit at a time)."""
    top, mask = 1 << (params.width - 1), (1 << params.width) - 1
    reg = params.init
    digits = (params.width + 3) // 4
    steps = [("init", f"0x{reg:0{digits}x}")]
    for byte in data:
        b = crc_reference.reflect(byte, 8) if params.refin else byte
        for i in range(7, -1, -1):
            feedback = bool(reg & top) ^ ((b >> i) & 1)
            reg = (reg << 1) & mask
            if feedback:
                reg ^= params.poly
        steps.append((f"{byte:02x}", f"0x{reg:0{digits}x}"))
    return steps


def _final_steps(cs: Checksum, bits: int, value: int) -> tuple[list[str], int]:
    """The lines of a sum's complement and xorout, and the finished value."""
    lines = []
    mask = (1 << bits) - 1
    if cs.complement == "ones":
        lines.append(f"one's complement in {bits} bits: {value} ⊕ {mask} = {value ^ mask}")
        value ^= mask
    elif cs.complement == "twos":
        finished = -value & mask
        lines.append(f"two's complement in {bits} bits: ({mask + 1} − {value}) mod {mask + 1} = {finished}")
        value = finished
    if cs.xorout is not None:
        lines.append(f"XOR with xorout {cs.xorout:#x}: {value} ⊕ {cs.xorout} = {value ^ cs.xorout}")
        value ^= cs.xorout
    return lines, value


def _fletcher_steps(cs: Checksum, data: bytes) -> tuple[list[tuple[str, tuple[str, str]]], int, int]:
    """Fletcher's two sums after each byte (Fletcher-16) or nibble (Fletcher-8), reduced
    at every step, and their final values."""
    a = b = 0
    digits = 2 if cs.width == 16 else 1
    steps = [("start", (f"0x{a:0{digits}x}", f"0x{b:0{digits}x}"))]
    for byte in data:
        blocks = [(f"{byte:02x}", byte)] if cs.width == 16 else \
            [(f"{byte:02x} high", byte >> 4), (f"{byte:02x} low", byte & 0xF)]
        for label, block in blocks:
            a = (a + block) % cs.modulo
            b = (b + a) % cs.modulo
            steps.append((label, (f"0x{a:0{digits}x}", f"0x{b:0{digits}x}")))
    return steps, a, b


def _internet_steps(cs: Checksum, data: bytes) -> tuple[list[tuple[str, tuple[str, str]]], int, int]:
    """RFC 1071's words (an odd byte padded with 00) and the sum after each, its carry
    out of 16 bits added back in; the plain total of the words, and the folded sum."""
    padded = data + bytes(len(data) % 2)
    total = folded = 0
    steps = []
    for i in range(0, len(padded), 2):
        word = int.from_bytes(padded[i:i + 2], cs.word_order)
        total += word
        folded += word
        folded = (folded & 0xFFFF) + (folded >> 16)
        steps.append((padded[i:i + 2].hex(" "), (f"0x{word:04x}", f"0x{folded:04x}")))
    return steps, total, folded


def _sent_bytes_line(p: Protocol, frame: bytes, slot: Slot) -> str:
    field = slot.field
    order = field.byte_order or p.framing.byte_order
    sent_bytes = frame[slot.offset // 8:(slot.offset + field.bits) // 8]
    return (f"sent {'high byte (B) first' if order == 'big' else 'low byte (A) first'} at "
            f"{position(p, slot)}: `{sent_bytes.hex(' ')}`")


def worked_example(p: Protocol, codec: types.ModuleType, m: Message, cs: Checksum, slot: Slot) -> Optional[dict]:
    found = _frame(p, codec, m)
    if found is None:
        return None
    ex, frame = found
    field = slot.field
    sent = _bits_of(frame, slot.offset, field.bits, p.framing.wire_order)
    view = {"message": f"[{m.name}](#{anchor('msg', m.name)})", "example": cell(ex.name), "frame": frame.hex(" "),
            "field": slot.path, "position": position(p, slot), "steps": [], "lines": []}
    if cs.algorithm == "crc":
        start, end = cs.byte_span
        extra = bytes([m.crc_extra]) if cs.extra else b""
        covered = frame[start:end] + extra
        steps = _crc_steps(cs.crc, covered)
        raw = int(steps[-1][1], 16)
        out = crc_reference.reflect(raw, cs.crc.width) if cs.crc.refout else raw
        result = out ^ cs.crc.xorout
        if result != crc_reference.compute(cs.crc, covered):
            raise AssertionError("worked CRC example disagrees with the reference implementation")
        digits = (cs.crc.width + 3) // 4
        order = field.byte_order or p.framing.byte_order
        sent_bytes = frame[slot.offset // 8:(slot.offset + field.bits) // 8]
        sent = _sent_value(p, frame, slot)
        view["steps"] = [(b, (r,)) for b, r in steps]
        view["steps_title"], view["steps_head"] = "CRC register after each byte", ("register",)
        view["lines"] = [
            f"covered bytes B{start}–B{end - 1}: `{frame[start:end].hex(' ')}`"
            + (f", then the message's crc_extra `{extra.hex()}`" if extra else ""),
            f"register after the last byte: `0x{raw:0{digits}x}`"
            + (f", reflected `0x{out:0{digits}x}`" if cs.crc.refout else "")
            + f"; XOR `0x{cs.crc.xorout:0{digits}x}` → CRC `0x{result:0{digits}x}`",
            f"sent {'high byte first' if order == 'big' else 'low byte first'} at {position(p, slot)}: "
            f"`{sent_bytes.hex(' ')}`",
        ]
    elif cs.algorithm in ("sum", "xor"):
        if cs.byte_span is not None:  # over the covered bytes, as sent
            start, end = cs.byte_span
            terms = [(f"B{start + i}", byte) for i, byte in enumerate(frame[start:end])]
            sent = _sent_value(p, frame, slot)
        else:  # over the wire values of every other field
            terms = [(x.dotted, _bits_of(frame, x.pos, x.bits, p.framing.wire_order)) for x in m.wire.leaves
                     if x.dotted != slot.path and x.field.bits is not None]  # each array element its own
        if cs.algorithm == "sum":
            total = sum(v for _, v in terms)
            result = total % cs.modulo if cs.modulo else total & ((1 << field.bits) - 1)
            how = f"{total} mod {cs.modulo or 1 << field.bits} = {result}"
            joined = " + ".join(str(v) for _, v in terms)
        else:
            result = 0
            for _, v in terms:
                result ^= v
            how = str(result)
            joined = " ⊕ ".join(str(v) for _, v in terms)
        finishing, result = _final_steps(cs, field.bits, result)
        view["lines"] = [
            ("covered bytes: " if cs.byte_span is not None else "wire values: ")
            + ", ".join(f"{name} = {v}" for name, v in terms),
            f"{joined} = {how}",
            *finishing,
            f"sent in `{slot.path}` ({position(p, slot) or 'bits ' + str(slot.offset)}): {sent}",
        ]
    elif cs.algorithm == "fletcher":
        start, end = cs.byte_span
        covered = frame[start:end]
        steps, a, b = _fletcher_steps(cs, covered)
        half = cs.width // 2
        result = (b << half) | a
        sent = _sent_value(p, frame, slot)
        digits = cs.width // 4
        view["steps"] = steps
        view["steps_title"] = "Sums after each " + ("byte" if cs.width == 16 else "nibble (high, then low)")
        view["steps_head"] = ("A", "B")
        view["lines"] = [
            f"covered bytes B{start}–B{end - 1}: `{covered.hex(' ')}`",
            f"A = sum of the {'bytes' if cs.width == 16 else 'nibbles, high nibble first'} mod {cs.modulo} "
            f"= {a}; B = sum of A after each step mod {cs.modulo} = {b}",
            f"(B << {half}) | A = `0x{result:0{digits}x}`",
            f"sent in `{slot.path}` ({position(p, slot)}): {sent}" if cs.width == 8 else
            _sent_bytes_line(p, frame, slot),
        ]
    elif cs.algorithm == "internet":
        start, end = cs.byte_span
        at = slot.offset // 8
        covered = frame[start:at] + bytes(2) + frame[at + 2:end] if cs.covers_self else frame[start:end]
        steps, total, folded = _internet_steps(cs, covered)
        result = ~folded & 0xFFFF
        sent = _sent_value(p, frame, slot)
        view["steps"] = steps
        view["steps_title"] = "The sum after each word (carry out of 16 bits added back)"
        view["steps_head"] = ("word", "sum")
        view["lines"] = [
            f"covered bytes B{start}–B{end - 1}: `{covered.hex(' ')}`"
            + (f", `{slot.path}` itself (B{at}–B{at + 1}) counted as `00 00`" if cs.covers_self else "")
            + (" and a pad byte `00`" if len(covered) % 2 else ""),
            f"{len(steps)} words, {cs.word_order}-endian, add to `0x{total:x}`; with each carry out "
            f"of 16 bits added back in (end-around carry), `0x{folded:04x}`",
            f"one's complement: `0x{result:04x}`",
            f"sent in `{slot.path}` ({position(p, slot)}): `0x{sent:04x}`",
        ]
        if cs.covers_self:  # RFC 1071's receiver check, on the bytes as sent
            check = _internet_steps(cs, frame[start:end])[2]
            view["lines"].append(f"a receiver sums the covered bytes as sent, `{frame[start:end].hex(' ')}`, "
                                 f"to `0x{check:04x}` (all ones: no error)")
            if check != 0xFFFF:
                raise AssertionError(f"worked internet example: the receiver's sum is {check:#x}, not all ones")
    elif cs.algorithm == "parity":
        word = int.from_bytes(frame, "big")
        others = bin(word).count("1") - sent
        result = others % 2 if cs.parity == "even" else 1 - others % 2
        view["lines"] = [
            f"word `0x{word:0{len(frame) * 2}x}` = `{word:0{8 * len(frame)}b}`",
            f"ones outside the parity bit: {others} → parity bit {result} makes the total "
            f"{others + result}, {'even' if cs.parity == 'even' else 'odd'}",
            f"sent in `{slot.path}` ({position(p, slot)}): {sent}",
        ]
    else:
        return None
    if result != sent:
        raise AssertionError(f"worked {cs.algorithm} example gives {result}, the frame carries {sent}")
    return view


def parameters(cs: Checksum) -> list[tuple[str, str]]:
    if cs.algorithm == "crc":
        c = cs.crc
        digits = (c.width + 3) // 4
        rows = [("name", c.name), ("width", str(c.width)), ("poly", f"0x{c.poly:0{digits}x}"),
                ("init", f"0x{c.init:0{digits}x}"), ("refin", str(c.refin).lower()),
                ("refout", str(c.refout).lower()), ("xorout", f"0x{c.xorout:0{digits}x}")]
        if c.check is not None:
            rows.append(("check (CRC of ASCII `123456789`)", f"0x{c.check:0{digits}x}"))
        if cs.extra:
            rows.append(("extra", "each message's crc_extra byte, after the covered bytes"
                                  + (" (derived from the message's definition as MAVLink's CRC_EXTRA)"
                                     if cs.extra == "mavlink" else "")))
        return rows
    if cs.algorithm == "sum":
        rows = [("algorithm", "sum of values"), ("modulo", number(cs.modulo) if cs.modulo else "field width")]
        if cs.complement:
            rows.append(("then", f"{'one' if cs.complement == 'ones' else 'two'}'s complement in the field's width"))
        return rows + _xorout_row(cs)
    if cs.algorithm == "xor":
        return [("algorithm", "xor")] + _xorout_row(cs)
    if cs.algorithm == "fletcher":
        half = cs.width // 2
        return [("algorithm", f"Fletcher-{cs.width}"),
                ("blocks", "bytes" if cs.width == 16 else "nibbles, high nibble first"),
                ("modulo", number(cs.modulo)),
                ("value", f"B in the high {'byte' if half == 8 else 'nibble'}, A in the low one")]
    if cs.algorithm == "parity":
        return [("algorithm", "parity"), ("parity", cs.parity)]
    if cs.algorithm == "internet":
        return [("algorithm", "internet checksum (RFC 1071)"),
                ("words", f"16 bits, {cs.word_order}-endian; an odd byte count padded with a zero byte"),
                ("sum", "one's complement: each carry out of 16 bits added back in"),
                ("value", "the sum's one's complement (every bit inverted)")] + (
                    [("itself", "inside its coverage, counted as 00 00 while computed; a receiver "
                                "checks that the covered bytes as sent sum to all ones (0xffff), "
                                "so 0xffff passes where 0x0000 is sent")] if cs.covers_self else [])
    return [("algorithm", cs.algorithm)]


def _title(cs: Checksum) -> str:
    if cs.algorithm == "internet":
        return "internet checksum (RFC 1071)"
    return f"Fletcher-{cs.width}" if cs.algorithm == "fletcher" else cs.algorithm


def _xorout_row(cs: Checksum) -> list[tuple[str, str]]:
    return [("then XOR with", f"0x{cs.xorout:x}")] if cs.xorout is not None else []


def checksum_sections(p: Protocol, codec: types.ModuleType, linker: DecisionLinker) -> list[dict]:
    """One section per distinct checksum (algorithm and parameters) of the protocol."""
    groups: dict[str, dict] = {}
    for m in p.messages:
        slot = _checksum_slot(m)
        if slot is None:
            continue
        cs = slot.field.checksum
        key = checksum_name(cs)
        group = groups.setdefault(key, {"title": cs.crc.name if cs.crc else _title(cs),
                                        "params": parameters(cs), "coverage": [], "worked": None,
                                        "field": slot.path, "doc": "", "decisions": []})
        order = slot.field.byte_order or p.framing.byte_order
        group["coverage"].append({
            "message": f"[{m.name}](#{anchor('msg', m.name)})", "covers": cell(_coverage(p, m, cs, slot)),
            "at": position(p, slot) or f"bits {slot.offset}–{slot.offset + slot.field.bits - 1}",
            "order": ("high byte first" if order == "big" else "low byte first")
            if slot.field.bits and slot.field.bits > 8 else "—"})
        text = " ".join(filter(None, [en(slot.field.doc), en(slot.field.title)]))
        cited = set(linker.cited(text)) | ({slot.field.rule} if slot.field.rule else set())
        group["decisions"] = sorted(set(group["decisions"]) | {c for c in cited if c in linker.ids})
        if not group["doc"]:
            group["doc"] = f"Field `{slot.path}`: " + linker.link(cell(en(slot.field.doc) or "the checksum")).rstrip(".") + "."
        if group["worked"] is None:
            group["worked"] = worked_example(p, codec, m, cs, slot)
    for group in groups.values():
        group["decisions"] = [linker.ref(d) for d in group["decisions"]]
    line = line_checksum_section(p)
    return list(groups.values()) + ([line] if line else [])


def line_checksum_section(p: Protocol) -> Optional[dict]:
    """The checksum of a text line (NMEA's `*hh`), worked out on the first example line."""
    cs = p.framing.line_checksum
    if cs is None:
        return None
    fr = p.framing
    what = "XOR" if cs.algorithm == "xor" else "sum modulo 256"
    section = {"title": f"Line checksum ({what})", "coverage": [], "decisions": [], "worked": None,
               "params": [("algorithm", cs.algorithm), ("covers", f"the characters after {fr.start!r} up to "
                                                                  f"{cs.suffix!r}" if fr.start else
                                                                  f"the line up to {cs.suffix!r}"),
                          ("written as", f"{cs.suffix} and two uppercase hex digits, before the terminator")],
               "doc": "Every line ends with its checksum, before the terminator."}
    for m in p.messages:
        ex = next((e for e in m.examples if e.text and not e.errors), None)
        if ex is None:
            continue
        line = ex.text
        body = line[len(fr.start):line.rindex(cs.suffix)]
        value, steps = 0, []
        for ch in body:
            value = value ^ ord(ch) if cs.algorithm == "xor" else (value + ord(ch)) % 256
            steps.append((cell(repr(ch)), (f"0x{value:02x}",)))
        sent = line[line.rindex(cs.suffix) + len(cs.suffix):][:2]
        if f"{value:02X}" != sent:
            raise AssertionError(f"worked line checksum gives {value:02X}, the example carries {sent}")
        section["worked"] = {
            "message": f"[{m.name}](#{anchor('msg', m.name)})", "example": cell(ex.name), "frame": cell(line.rstrip()),
            "steps": steps, "steps_title": f"{what} after each character", "steps_head": ("value",),
            "lines": [f"characters covered: `{cell(body)}` ({len(body)})",
                      f"{what} of their codes: `0x{value:02x}`, written `{cs.suffix}{value:02X}`"]}
        break
    return section
