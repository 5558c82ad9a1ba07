"""Markdown target: generated/docs/<protocol>.md for each schema and an index.

The pages are written for the people who implement or review a protocol:
tables and bit layouts, every example produced by the generated Python codec
(and checked against the schema's hand-written form), and every decision and
seed error from the schema's notes.
"""
from __future__ import annotations

import types
from typing import Optional

from ...can import identifier
from ...fingerprint import fingerprint, fingerprint32
from ...model import SPELLING_MAX, Message, Protocol
from .budget import longest_text_line, transport_views
from .checksum import checksum_sections
from .delivery import delivery_view
from .errors import error_claims
from .examples import message_example, sequence_example
from .multiplex import multiplexed_views
from .placement import payload_grid
from .layout import diagram, field_columns, field_rows, payload_note, shown, slots, text_line
from .stuffing import encoding_lines, pattern_lines
from .trailer import trailer_lines
from .machines import conditions, machine_view, sequence_view
from .site import mermaid_script
from .streams import stream_section
from .text import LANGUAGES, DecisionLinker, anchor, cell, code, en, link_msg, number, originals, with_original
from ..render import environment, tidy
from ..wire import stream_facts


def wire_fingerprint(p: Protocol) -> tuple[str, str]:
    """The schema's wire fingerprint as the generated codecs expose it: 16 hex
    digits, and the 32-bit word firmware reports."""
    return fingerprint(p), f"{fingerprint32(p):#010x}"


def direction_text(p: Protocol, name: Optional[str]) -> str:
    d = next((x for x in p.directions if x.name == name), None)
    return f"{d.source} → {d.target}" if d else ""


def can_spelled(can_id: int) -> str:
    """A CAN identifier as people write it: `0x123`, or `0x18FEF100` (extended)."""
    value, extended = identifier(can_id)
    return f"`0x{value:08X}` (extended)" if extended else f"`0x{value:03X}`"


def message_id(p: Protocol, m: Message) -> str:
    if m.id_fields:
        return ", ".join(f"{name} = `{value:#04x}`" for name, value in m.id_fields)
    if m.ids and p.framing.can:
        return ", ".join(can_spelled(v) for v in m.ids)
    if m.ids:
        return ", ".join(code(v) if isinstance(v, str) else f"`{v:#04x}`" for v in m.ids)
    if m.dispatch_key:
        return ", ".join(f"{name} = {number(value)}" for name, value in m.dispatch_key)
    return "by position"


def message_size(p: Protocol, m: Message) -> str:
    if p.framing.kind == "text":
        longest = longest_text_line(p, m)
        return f"≤ {longest} chars" if longest is not None else "unbounded"
    if p.framing.kind == "bits":
        return f"{m.bits} bits ({m.size} byte{'s' if m.size != 1 else ''})"
    if m.shortening:
        return f"{m.min_size}–{m.size} bytes"
    return f"{m.size} bytes"


def message_rules(p: Protocol, m: Message, linker: DecisionLinker) -> list[dict]:
    """Rules with their user-facing wording: the message's own, then field constraints that have one."""
    out = []
    for r in m.rules:
        when = conditions(r.when)
        text = ("when " + when + ": " if when else "") + conditions(r.require)
        out.append({"id": linker.ref(r.id), "text": cell(text), "message": cell(en(r.message)) if r.message else "",
                    "originals": [(l, cell(t)) for l, t in originals(r.message)]})
    for s in slots(m):
        f = s.field
        if f.message is None:
            continue
        out.append({"id": linker.ref(f.rule), "text": f"{code(s.path)}: {cell(_constraint(f))}",
                    "message": cell(en(f.message)), "originals": [(l, cell(t)) for l, t in originals(f.message)]})
    return out


def _constraint(f) -> str:
    if f.exactly_one:
        return "exactly one bit set"
    if f.values is not None:
        return "one of " + ", ".join(str(v) for v in f.values)
    if f.range is not None:
        return f"{number(f.range[0])} … {number(f.range[1])}"
    return "checked"


def message_view(p: Protocol, codec: types.ModuleType, m: Message, linker: DecisionLinker) -> dict:
    cited = set()
    for s in slots(m):
        if s.field.rule:
            cited.add(s.field.rule)
        cited.update(linker.cited(" ".join([en(s.field.doc), en(s.field.title)])))
    cited.update(r.id for r in m.rules if r.id)
    cited.update(linker.cited(en(m.doc)))
    rows = field_rows(p, m, linker)
    facts = [("Id", message_id(p, m)), ("Size", message_size(p, m))]
    if m.crc_extra is not None:
        facts.append(("CRC extra", f"`{m.crc_extra:#04x}` ({m.crc_extra}), the last byte the CRC takes"))
    if m.direction:
        facts.append(("Direction", f"{direction_text(p, m.direction)} (`{m.direction}`)"))
    if m.role:
        facts.append(("Role", m.role))
    if m.answered_by:
        facts.append(("Answered by", ", ".join(link_msg(a) for a in m.answered_by)))
    answers = [link_msg(x.name) for x in p.messages if m.name in x.answered_by]
    if answers:
        facts.append(("Answers", ", ".join(answers)))
    decisions = [linker.ref(x) for x in sorted(c for c in cited if c in linker.ids)]
    if decisions:
        facts.append(("Decisions", ", ".join(decisions)))
    return {
        "name": m.name, "anchor": anchor("msg", m.name), "facts": facts, "title": cell(with_original(m.title)) if m.title else "",
        "doc": linker.link(cell(en(m.doc))), "originals": [(l, cell(t)) for l, t in originals(m.doc)],
        "id": message_id(p, m), "direction": direction_text(p, m.direction), "role": m.role,
        "size": message_size(p, m), "answered_by": [link_msg(a) for a in m.answered_by],
        "diagram": diagram(p, m), "grid": payload_grid(m, {f.name for f in m.layout if not f.multiplexed_by}),
        "multiplexed": multiplexed_views(m), "line": text_line(p, m) if p.framing.kind == "text" else None,
        "fields": rows, "columns": field_columns(p, rows), "payload_note": payload_note(p, m),
        "rules": message_rules(p, m, linker),
        "examples": [message_example(p, codec, m, ex, linker) for ex in m.examples],
    }


def framing_view(p: Protocol, linker: DecisionLinker) -> dict:
    fr = p.framing
    view = {"kind": fr.kind, "lines": []}
    lines = view["lines"]
    if fr.kind == "bits":
        lines.append("Each message is one bit-packed record, most significant bit first: the first field "
                     "takes the high bits.")
        if fr.word_bits:
            lines.append(f"Every message is one {fr.word_bits}-bit word, sent "
                         + ("most significant byte first." if fr.byte_order == "big" else "least significant byte first."))
        if fr.max_bits:
            lines.append(f"A record is at most {fr.max_bits} bits. In a {fr.max_bits}-bit word it is left-aligned "
                         "(the first field in the top bits) and the low bits are zero; as bytes it is left-aligned "
                         "and zero-padded to whole bytes.")
        if p.self_identifying:
            keys = sorted({name for m in p.messages for name, _ in m.dispatch_key})
            lines.append("A decoder tells the messages apart by " + ", ".join(code(k) for k in keys)
                         + " (see the catalogue).")
        else:
            lines.append("Words carry no message type: what a word is follows from its position in a sequence "
                         "(see [Sequences](#sequences)).")
        if fr.text_form:
            tf = fr.text_form
            lines.append(f"Text form: one message a line, every field (constants and checksum included) as a "
                         f"decimal wire value, separated by {code(tf.separator) if tf.separator != ' ' else 'single spaces'}.")
            if tf.comment:
                lines.append(f"Blank lines and lines starting with {code(tf.comment)} are ignored.")
            if tf.checksum_unfilled is not None:
                lines.append(f"In the text form a checksum of {tf.checksum_unfilled} means \"not filled in\" and is "
                             "accepted by readers; writers always fill it in. In the bit form it must be correct.")
    elif fr.kind == "bytes":
        facts = stream_facts(p)
        if fr.can:
            lines.append(("CAN FD frames: up to 64 bytes of data, in the DLC steps 0–8, 12, 16, 20, 24, 32, 48 "
                          "and 64." if fr.can == "fd" else "Classic CAN frames: up to 8 bytes of data.")
                         + " A message is found by its arbitration identifier, standard (11-bit) or extended "
                         "(29-bit), and its data is its payload. In examples and vectors a frame is written as "
                         "the identifier in four bytes (bit 31 set for an extended one, as SocketCAN's `can_id`), "
                         "the data length in one byte, then the data; the generated codecs take and give the "
                         "identifier and the data apart (`decode_can`, `encode_can`).")
        lines.append("Every frame has the same envelope; each message fills its payload. Multi-byte fields are "
                     + ("little endian" if fr.byte_order == "little" else "big endian")
                     + " unless the field table says otherwise; bits within a byte are numbered 7 (MSB) to 0.")
        if fr.bit_order == "lsb_first":
            lines.append("Bit fields are packed least significant bit first: the frame is one little-endian bit "
                         "stream, each field starting at the lowest free bit of a byte, low bit first, and "
                         "continuing from bit 0 of the next byte.")
        if facts.get("sync") is not None:
            lines.append(f"A frame starts with the sync byte `{facts['sync']:#04x}`.")
        if facts.get("length"):
            at, overhead, last = facts["length"]["at"], facts["length"]["overhead"], facts["length"]["last"] - 1
            where = f"Byte B{at} holds" if at == last else f"Bytes B{at}–B{last} hold"
            lines.append(f"{where} the length: the frame is length + {overhead} bytes. Known frame sizes: "
                         + ", ".join(f"{lo}–{hi}" if lo != hi else str(lo) for lo, hi in facts["ranges"]) + " bytes.")
            if fr.truncate:
                lines.append("**Truncation.** A sender drops the trailing zero bytes of the payload, keeping at "
                             "least one, and the length says how many it sent; the checksum covers the frame as "
                             "sent. A decoder checks it, then puts the zeros back before it reads the fields.")
        else:
            lines.append("Frames have a fixed size for a link: " + ", ".join(str(s) for s in facts["sizes"])
                         + " bytes with the default parameters.")
        last = slots(p.messages[0])[-1].field
        after = fr.envelope[next(i for i, f in enumerate(fr.envelope) if f.is_payload) + 1:]
        if after and last.name == after[-1].name and isinstance(last.const, int):  # the envelope's end marker
            lines.append(f"A frame ends with `{last.const:#04x}`.")
        lines.extend(trailer_lines(p))
        if fr.encoding:
            lines.extend(encoding_lines(p))
        else:
            lines.extend(pattern_lines(p))
            lines.append("**Stream resynchronisation.** A stream decoder skips bytes up to the next sync byte"
                         + (", checks the length byte against the known frame sizes" if facts.get("length") else "")
                         + ", and decodes a whole frame. After a bad frame (of a size no message has, a wrong "
                         "checksum or constant, an unknown id) it reports the error, drops one byte and searches for the next sync byte, so "
                         "one damaged frame never hides the next good one. It holds at most one largest frame "
                         f"({facts['max']} bytes).")
    else:
        cs = fr.line_checksum
        lines.append(f"Every message is one ASCII line `{shown(fr.start)}<prefix>{shown(fr.prefix_separator)}<field>"
                     f"{shown(fr.separator)}<field>…{shown(cs.suffix) + 'hh' if cs else ''}{shown(fr.terminator)}`: "
                     "the prefix names the message, fields follow in table order."
                     + (" A field whose place is *prefix* is written in the prefix before the message's id "
                        "(NMEA's talker: `GN` in `GNGGA`)." if any(m.prefix_field for m in p.messages) else ""))
        if fr.start:
            lines.append(f"A line starts with {code(shown(fr.start))}.")
        if cs:
            what = "XOR" if cs.algorithm == "xor" else "sum modulo 256"
            after = f"after {code(shown(fr.start))}" if fr.start else "from the start of the line"
            lines.append(f"`hh` is the {what} of the characters {after} up to {code(shown(cs.suffix))}, "
                         "written as two uppercase hex digits; readers accept only that spelling.")
        if fr.trim:
            lines.append("Readers accept spaces around a value; writers emit none.")
        if fr.ignore_between:
            names = {"\r": "CR", "\n": "LF", " ": "space", "\t": "tab"}
            lines.append("A message ends at " + code(shown(fr.terminator)) + "; "
                         + "/".join(names.get(ch, ch) for ch in fr.ignore_between)
                         + " between messages is ignored, so a stream resynchronises at the next terminator.")
        lines.append("**Stream resynchronisation.** A stream decoder (Python's `StreamDecoder`, C's "
                     f"`{p.name}_scan` and `{p.name}_parser_feed`/`{p.name}_parser_next`) reads a line up to "
                     f"{code(shown(fr.terminator))} and decodes it whole; after a bad line it reports the error "
                     f"and reads the next. A line that reaches {fr.line_max} characters (the longest a message "
                     f"can have, each number in at most {SPELLING_MAX} characters) without its terminator is a "
                     "`length` error, and the rest of it is dropped through its terminator; at the end of the "
                     f"stream (`finish()`, `{p.name}_scan_finish`, `{p.name}_parser_finish`) an unterminated "
                     f"line is a `syntax` error. It holds at most one longest line ({fr.line_max} characters).")
        if fr.float_format == "shortest":
            lines.append("Decimal numbers are written in the shortest form that reads back to the same value "
                         "(1.0 is written `1`).")
        if any(x.field.fixed_spelling for m in p.messages for x in m.wire.leaves):
            lines.append("A number with `decimals` or `width` is written with exactly those decimals and at least "
                         "that width; readers take any spelling of it (`8` or `08`, `2.0` or `2`, more decimals "
                         "or a sign), and round further decimals to the field's step, halves away from zero.")
        if any(x.field.keep_spelling for m in p.messages for x in m.wire.leaves):
            lines.append("A decoded message keeps the text each number was received in (at most "
                         f"{SPELLING_MAX} characters; a longer one is a `length` error) and writes it back "
                         "unchanged while the value stays, so a line decoded and encoded again is the same "
                         "bytes; a changed value is written in its field's spelling.")
    if any(x.field.kind == "float" and not x.field.finite for m in p.messages for x in m.wire.leaves):
        lines.append("A float whose range says `or NaN, ±∞` holds NaN and the infinities too. A receiver takes "
                     "any NaN, whatever its sign and payload; a sender sends every NaN as the quiet NaN, "
                     "`0x7FC00000` in 32 bits and `0x7FF8000000000000` in 64 (in the field's byte order), so "
                     "that a message encodes to one frame.")
    lines.extend(claim["text"] for claim in error_claims(p))
    view["lines"] = [linker.link(x) for x in lines]
    return view


def protocol_view(p: Protocol, codec: types.ModuleType) -> dict:
    linker = DecisionLinker(p)
    languages = sorted({lang for lang, _ in p.title.translations} | {lang for n in p.notes for lang, _ in n.text.translations})
    directions = []
    for d in p.directions:
        carried = [link_msg(m.name) for m in p.messages if m.direction == d.name]
        directions.append({"name": d.name, "route": f"{d.source} → {d.target}", "messages": carried,
                           "doc": cell(en(d.doc)), "originals": [(l, cell(t)) for l, t in originals(d.doc)]})
    overview = bool(en(p.doc) or p.roles or p.directions or p.transports or p.parameters)
    contents = ["[All protocols](index.md)"] + (["[Overview](#overview)"] if overview else [])
    contents.append("[Messages](#message-catalogue)")
    if p.enums or p.flags:
        contents.append("[Enumerations and flags](#enumerations-and-flags)")
    contents += ["[Checksum](#checksum)", "[Framing](#framing)"]
    if p.sequences:
        contents.append("[Sequences](#sequences)")
    delivery = delivery_view(p, codec, linker)
    if p.machines:
        contents.append("[State machines](#state-machines)")
    if delivery:
        contents.append("[Delivery guarantee](#delivery)")
    if p.notes:
        contents.append("[Spec notes](#spec-notes)")
    if p.history:
        contents.append("[Version history](#version-history)")
    enum_users: dict[str, list[str]] = {}  # each enum's messages, in the schema's order: one pass over them
    for m in p.messages:
        for name in dict.fromkeys(s.field.enum.name for s in slots(m) if s.field.enum is not None):
            enum_users.setdefault(name, []).append(m.name)
    return {
        "p": p, "name": p.name, "title": cell(en(p.title)), "contents": contents, "overview": overview,
        "title_originals": [(LANGUAGES.get(l, l), cell(t)) for l, t in originals(p.title)],
        "languages": [LANGUAGES.get(l, l) for l in languages],
        "doc": linker.link(cell(en(p.doc))), "doc_originals": [(LANGUAGES.get(l, l), cell(t)) for l, t in originals(p.doc)],
        "fingerprint": wire_fingerprint(p),
        "roles": [{"name": r.name, "doc": cell(en(r.doc)), "originals": [(l, cell(t)) for l, t in originals(r.doc)]}
                  for r in p.roles],
        "directions": directions,
        "transports": transport_views(p, codec),
        "parameters": [{"name": x.name, "default": number(x.default) if x.default is not None else "per device",
                        "range": f"{number(x.range[0])} … {number(x.range[1])}" if x.range else "",
                        "unit": cell(x.unit or ""), "doc": linker.link(cell(en(x.doc)))} for x in p.parameters],
        "messages": [message_view(p, codec, m, linker) for m in p.messages],
        "enums": [{"name": e.name, "anchor": anchor("enum", e.name), "doc": cell(with_original(e.doc)), "open": e.open,
                   "wire": f"u{e.bits}" if e.bits else ("char" if e.kind == "char" else "integer"),
                   "members": [{"value": code(x.value) if isinstance(x.value, str) else str(x.value),
                                "name": code(x.name), "doc": cell(en(x.doc)),
                                "original": "; ".join(cell(t) for _, t in originals(x.doc))} for x in e.members],
                   "used_by": [link_msg(name) for name in enum_users.get(e.name, [])]}
                  for e in p.enums],
        "flags": [{"name": fl.name, "anchor": anchor("flags", fl.name), "doc": cell(with_original(fl.doc)),
                   "bits": fl.bits, "mask": f"0x{fl.mask:0{(fl.bits + 3) // 4}x}",
                   "members": [{"bit": b.bit, "value": f"0x{1 << b.bit:0{(fl.bits + 3) // 4}x}", "name": code(b.name),
                                "doc": cell(en(b.doc)), "original": "; ".join(cell(t) for _, t in originals(b.doc))}
                               for b in fl.members]}
                  for fl in p.flags],
        "checksums": checksum_sections(p, codec, linker),
        "framing": framing_view(p, linker),
        "streams": stream_section(p, linker) if p.streams else None,
        "sequences": [dict(sequence_view(s, linker),
                           examples=[sequence_example(p, codec, s, ex, linker) for ex in s.examples])
                      for s in p.sequences],
        "machines": [machine_view(p, m, linker) for m in p.machines],
        "delivery": delivery,
        "notes": [{"id": cell(n.id), "anchor": anchor("note", n.id), "text": linker.link(cell(en(n.text))),
                   "originals": [(l, cell(t)) for l, t in originals(n.text)]} for n in p.notes],
        "history": [{"version": cell(h.version), "date": cell(h.date), "author": cell(h.author),
                     "changes": [(cell(en(c)), "; ".join(cell(t) for _, t in originals(c))) for c in h.changes]}
                    for h in p.history],
    }


def render(p: Protocol, codec: types.ModuleType) -> dict[str, str]:
    """The protocol's page; `codec` is its generated Python module, its examples checked."""
    text = environment().get_template("docs/protocol.md.j2").render(**protocol_view(p, codec))
    return {f"docs/{p.name}.md": tidy(text, max_blank=1)}


def index_row(p: Protocol) -> dict:
    return {"name": p.name, "title": cell(en(p.title)), "file": f"{p.name}.md",
            "originals": "; ".join(cell(t) for _, t in originals(p.title)),
            "framing": p.framing.kind, "transports": ", ".join(t.name for t in p.transports),
            "messages": len(p.messages), "version": p.version or "", "source": p.source,
            "schema": p.file}


def render_index(protocols: list[Protocol]) -> dict[str, str]:
    rows = [index_row(p) for p in sorted(protocols, key=lambda x: x.name)]
    env = environment()
    text = env.get_template("docs/index.md.j2").render(protocols=rows)
    style = env.get_template("docs/codeword.css").render()
    return {"docs/index.md": tidy(text, max_blank=1), "docs/codeword.css": style, **mermaid_script(protocols)}
