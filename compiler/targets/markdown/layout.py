"""Where each field of a message sits on the wire, as the docs show it: the
layout diagram (a table in the style of a seed document's `name|name|…` tables) and
the field table (offset, width, type, range, unit, values, default, meaning)."""
from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Optional

from ...model import Field, Message, Presence, Protocol, field_at
from .placement import placed_type
from .text import DecisionLinker, anchor, cell, code, en, number, originals


@dataclass(frozen=True)
class Slot:
    """A field with its dotted path and its bit offset from the first bit sent."""

    path: str
    field: Field
    offset: Optional[int]  # None in text framings
    index: int  # 1-based position among the top-level fields (text framings: field number)
    depth: int

    @property
    def span_name(self) -> str:
        """The name the layout diagram gives it: an array as its elements, `ch[0..15]`."""
        if self.field.count is None:
            return self.path
        last = self.field.count if self.field.varies else self.field.count - 1
        return self.path[:self.path.rindex("[")] + f"[0..{last}]"


def array_suffix(f: Field) -> str:
    """`[16]` after an array of 16, `[0..125]` after one whose count another field gives."""
    if f.count is None:
        return ""
    return f"[0..{f.count}]" if f.varies else f"[{f.count}]"


def slots(m: Message) -> list[Slot]:
    """Every field of the frame in wire order, groups followed by their members;
    a group sits where its first member does."""
    out: list[Slot] = []
    top = [0]  # the top-level places so far: a field's number in the table
    first_bit: dict[tuple, Optional[int]] = {}
    for leaf in m.wire.leaves:
        for n in range(1, len(leaf.path) + 1):
            first_bit.setdefault(leaf.path[:n], leaf.pos)

    def walk(fields: tuple[Field, ...], prefix: tuple, shown: str, depth: int) -> None:
        """prefix: the path of the first element of each array on the way, as the leaves spell it."""
        for f in fields:
            if f.is_payload:
                continue
            path = prefix + (f.name,)
            name = f"{shown}.{f.name}" if shown else f.name
            offset = f.bit_offset if f.bit_offset is not None or m.bits is None else first_bit.get(path)
            # a text line's prefix field sits before the id, at no place of the body
            if depth == 0 and not f.prefix:
                top[0] += 1
            index = top[0] + (1 if f.prefix else 0) if depth == 0 else 0
            out.append(Slot(name + array_suffix(f), f, offset, index, depth))
            if f.kind == "group":  # an array's members shown once, at its first element
                walk(f.fields, path + ((0,) if f.count is not None else ()),
                     name + ("[i]" if f.count is not None else ""), depth + 1)

    walk(m.layout, (), "", 0)
    return out


def bit_span(offset: int, bits: int) -> str:
    return str(offset) if bits == 1 else f"{offset}–{offset + bits - 1}"


def offset_text(slot: Slot) -> str:
    """The diagram's offset of a field: its bits from the first bit sent, or a placed field's start bit."""
    if slot.field.start_bit is not None:
        return f"start bit {slot.field.start_bit}"
    return bit_span(slot.offset, slot.field.bits)


def position(p: Protocol, slot: Slot) -> str:
    """Where a reader finds the field: word bits (31 = MSB) or bytes (B0 first sent),
    bits in a byte numbered 7 (MSB) to 0, from the field's first bit to its last."""
    f, offset = slot.field, slot.offset
    if offset is None or f.bits is None:
        return ""
    fr = p.framing
    if fr.kind == "bits" and fr.word_bits:
        high = fr.word_bits - 1 - offset
        low = high - f.bits + 1
        return str(high) if f.bits == 1 else f"{high}–{low}"
    first, last = offset // 8, (offset + f.bits - 1) // 8
    lsb_first = f.byte_order == "little" if f.start_bit is not None else fr.bit_order == "lsb_first"
    if offset % 8 == 0 and f.bits % 8 == 0 and (f.start_bit is None or first == last):
        return f"B{first}" if first == last else f"B{first}–B{last}"
    if lsb_first:  # the field's low bit first, counting up
        start, end = offset % 8, (offset + f.bits - 1) % 8
    else:
        start, end = 7 - offset % 8, 7 - (offset + f.bits - 1) % 8
    if first == last:
        return f"B{first} bit {start}" if f.bits == 1 else f"B{first} bits {start}–{end}"
    return f"B{first} bit {start} – B{last} bit {end}"


def presence_text(cond: Presence) -> str:
    """A condition in the docs' words: "`parts` has `gps`", "`kind` is `run` or 4"."""
    if cond.has is not None:
        return f"`{cond.field}` has `{cond.has}`"
    return f"`{cond.field}` is " + " or ".join(f"`{v}`" if isinstance(v, str) else number(v) for v in cond.equals)


def type_text(p: Protocol, f: Field) -> str:
    if f.multiplexed_by:
        said = " and ".join(f"`{x.field}` is {x.values_text}" for x in f.multiplexed_by.chain)
        return f"{type_text(p, replace(f, multiplexed_by=None))}, if {said}"
    if f.present_if:
        return f"{type_text(p, replace(f, present_if=None))}, if {presence_text(f.present_if)}"
    if f.varies and f.kind == "bytes":
        return f"0…{f.length} bytes"
    if f.varies:
        return f"0…{f.count} × {type_text(p, f.element)}"
    if f.count is not None:
        return f"{f.count} × {type_text(p, f.element)}"
    kind = f.kind
    if kind == "group":
        text = "group"
    elif kind in ("uint", "int", "float"):
        text = {"uint": "u", "int": "i", "float": "f"}[kind] + str(f.bits)
        if f.start_bit is not None:
            text += " " + placed_type(f.byte_order)
        elif p.framing.kind == "bytes" and f.bits and f.bits > 8:
            order = f.byte_order or p.framing.byte_order
            text += " LE" if order == "little" else " BE"
    elif kind == "bool":
        text = "bool"
    elif kind == "char":
        text = "char"
    elif kind == "str" and f.prefix:
        text = f"{f.length} uppercase letters A–Z, before the id"
    elif kind == "str":
        text = "string"
        if f.max_length is not None:
            text += f" ≤ {f.max_length} chars"
        if f.to_end:
            text += ", to the terminator"
    elif kind == "bytes":
        length = f.length_param or f.length
        text = f"{length} bytes"
    else:
        text = kind
    if p.framing.kind == "text" and kind in ("uint", "int"):
        spelling = [f"{f.decimals} decimal{'' if f.decimals == 1 else 's'}" if f.decimals is not None else "",
                    f"{f.width} wide, zero-padded" if f.width is not None else ""]
        text = "integer (" + ", ".join([text] + [x for x in spelling if x]) + ")"
    if p.framing.kind == "text" and kind == "float":
        text = "decimal (" + text + ")"
    if f.type_name:
        text += f" · type {f.type_name}"
    return text


def range_text(p: Protocol, f: Field) -> str:
    """The allowed values in the units the user sees, and how they map to the wire
    (an array's: those of each element)."""
    f = f.element
    if f.const is not None:
        value = f"{f.const:#04x}" if isinstance(f.const, int) and not isinstance(f.const, bool) and f.bits and f.bits >= 8 else number(f.const)
        if f.length_of is not None and f.length_adjust:  # the count is not the bytes alone
            sign = "+" if f.length_adjust > 0 else "−"
            return f"= {value} (bytes {f.length_of[0]} … {f.length_of[1]} {sign} {abs(f.length_adjust)})"
        return f"= {value}"
    if f.reserved:
        return "0 (reserved)"
    if f.checksum is not None:
        return "computed (see [Checksum](#checksum))"
    if f.length_of is not None:
        return f"= bytes {f.length_of[0]} … {f.length_of[1]}"
    if f.one_hot and f.range:
        return f"level {number(f.range[0])}–{number(f.range[1])}, sent as 1 << level; 0 = absent"
    parts = []
    if f.range is not None:
        parts.append(f"{number(f.range[0])} … {number(f.range[1])}")
    elif f.raw_range is not None and not f.closed_enum and f.flags is None and f.kind != "bool":
        parts.append(f"{number(f.raw_range[0])} … {number(f.raw_range[1])}")
    if f.offset:
        parts.append(f"sent as value − {number(f.offset)}")
    if f.scale is not None:
        parts.append(f"step {number(f.scale)}")
    if f.kind == "float" and (f.bits == 32 or p.framing.kind != "text"):
        parts.append(f"IEEE-754 binary{f.bits}")
    if f.kind == "float" and not f.finite:  # the framing section says how a NaN is sent
        parts[-1] += " or NaN, ±∞"
    if f.kind == "float" and f.bits == 64 and not parts:
        parts.append("any decimal number")
    return "; ".join(parts)


def values_text(f: Field) -> str:
    out = []
    if f.enum is not None:
        out.append(f"enum [{f.enum.name}](#{anchor('enum', f.enum.name)})" + (", other values kept as numbers"
                                                                            if f.enum.open else ""))
    if f.flags is not None:
        out.append(f"flags [{f.flags.name}](#{anchor('flags', f.flags.name)})")
    if f.exactly_one:
        out.append("exactly one bit set")
    if f.kind == "bool":
        out.append("0 false, 1 true")
    if f.optional and f.const is not None:
        out.append("optional: always written; a reader also takes it empty or left out at the end")
    elif f.optional:
        out.append("optional")
    return "; ".join(out)


def default_text(f: Field) -> str:
    if not f.has_default:
        return ""
    value = f.default
    if value is None:
        return "absent"
    if f.enum is not None:
        member = next((x for x in f.enum.members if x.name == value or x.value == value), None)
        return member.name if member else str(value)
    return number(value)


def meaning(f: Field, linker: DecisionLinker) -> str:
    """English title and doc, the original-language wording beside them, the decision."""
    parts = []
    title, doc = en(f.title), en(f.doc)
    if not title and not doc and (f.enum or f.flags):
        doc = en((f.enum or f.flags).doc)
    if title:
        parts.append(f"**{cell(title)}**")
    if doc and doc != title:
        parts.append(cell(doc))
    by_lang: dict[str, list[str]] = {}
    for lang, text in originals(f.title) + originals(f.doc):
        by_lang.setdefault(lang, []).append(cell(text))
    for lang, texts in by_lang.items():
        parts.append(f"*{lang}:* " + " — ".join(texts))
    if f.extension and not f.optional:  # text extensions are told in the values column
        parts.append("*extension:* a frame may end before it; it then reads as 0")
    text = linker.link(" <br>".join(parts))
    if f.rule and f.rule not in linker.cited(text):
        text += (" " if text else "") + f"({linker.ref(f.rule)})"
    return text


def diagram(p: Protocol, m: Message) -> Optional[dict]:
    """Columns of the layout diagram: top-level fields with width, offset and position."""
    top = [s for s in slots(m) if s.depth == 0]
    if p.framing.kind == "text":
        return None
    cols = [{"name": s.span_name, "bits": s.field.bits, "offset": offset_text(s),
             "position": position(p, s)} for s in top]
    return {"columns": cols, "word": bool(p.framing.word_bits), "bytes": p.framing.kind == "bytes"}


def text_line(p: Protocol, m: Message) -> str:
    """The shape of a text message: `%:move,speed,…[,data];`."""
    fr = p.framing
    top = [s for s in slots(m) if not s.depth and not s.field.prefix]
    head = "".join(f"<{s.path}>" for s in slots(m) if s.field.prefix)  # NMEA's `<talker>GGA`
    body = ""
    for i, s in enumerate(top):
        if i >= m.text_places.least:  # a line may end before it
            body += f"[{fr.separator}{s.path}]" if i else f"[{s.path}]"
        else:  # `[name]`: may be empty
            body += (fr.separator if i else "") + (f"[{s.path}]" if s.field.optional else s.path)
    checksum = fr.line_checksum.suffix + "hh" if fr.line_checksum else ""
    return shown(f"{fr.start}{head}{m.ids[0]}{fr.prefix_separator}{body}{checksum}{fr.terminator}")


def shown(text: str) -> str:
    """Line text with its control characters spelled as escapes (`\\r\\n`), as a reader types them."""
    return text.encode("unicode_escape").decode("ascii") if not text.isprintable() else text


def field_rows(p: Protocol, m: Message, linker: DecisionLinker) -> list[dict]:
    rows = []
    for s in slots(m):
        f = s.field
        name = ("&nbsp;&nbsp;&nbsp;&nbsp;" * s.depth) + code(s.path)
        rows.append({
            "path": s.path, "name": name,
            "bits": "" if f.bits is None or p.framing.kind == "text" else str(f.bits),
            "offset": (f"start bit {f.start_bit}" if f.start_bit is not None else str(s.offset))
            if s.offset is not None else "",
            "index": "prefix" if f.prefix else str(s.index) if s.depth == 0 else "",
            "position": position(p, s),
            "type": cell(type_text(p, f)), "range": range_text(p, f),
            "unit": cell(f.unit or ""), "kinds": "; ".join(x for x in (values_text(f), place_text(p, m, s)) if x),
            "default": cell(default_text(f)),
            "meaning": meaning(f, linker),
        })
    return rows


def place_text(p: Protocol, m: Message, s: Slot) -> str:
    """Text framing: for an extension field, or one with its own keep_empty, whether a line
    may end before it and what a writer does with its absent value (the line's shape shows
    the rest)."""
    f, tp = s.field, m.text_places
    if tp is None or s.depth or not (f.extension or f.keep_empty is not None):
        return ""
    n = s.index - 1  # its place in the body
    said = ["may be missing: a line may end before it" + (" (an older writer's line)" if f.extension else "")
            if n >= tp.least else ""]
    said.append("absent: an empty place" if n < tp.written else "absent: left out at the end of a line")
    return ", ".join(x for x in said if x)


def payload_note(p: Protocol, m: Message) -> str:
    """Positions depend on a link parameter when a field's length is one (data of a per-link length),
    and on the payload's length when a frame may carry less than the whole payload."""
    sh = m.shortening
    if sh is not None and sh.gaps:
        said = []
        for gap in sh.gaps:
            ct = gap.counter
            if ct is None:
                said.append(f"`{gap.field}` is sent only when {presence_text(gap.presence)}")
                continue
            if gap.fills_rest:
                what = "bytes" if field_at(m.layout, ct.field).kind == "bytes" else "elements"
                said.append(f"`{ct.field}` fills the rest of the payload (at most {ct.most} {what})")
                continue
            says = "elements" if ct.unit_bytes is None else "bytes" if ct.unit_bytes == 1 else f"{ct.unit_bytes}-byte units"
            holds = ("bytes", "") if field_at(m.layout, ct.field).kind == "bytes" else ("elements", f"it counts {says}, ")
            said.append(f"`{ct.field}` holds as many {holds[0]} as `{ct.count_field}` says ({holds[1]}at most "
                        f"{ct.most_value})")
        length = f" (`{sh.length_field}` counts the payload bytes sent)" if sh.length_field else ""
        return (f"Positions are those of the largest frame. {'; '.join(said)}. A frame carries only those "
                f"bytes{length}, and what follows moves up by the bytes left off.")
    if sh is not None:
        start, end = sh.payload
        why = "its trailing zero bytes are not sent" if sh.trailing_zeros else "its extension fields may be left off"
        return (f"Positions are those of the whole frame. The payload (B{start}–B{end - 1}) may be cut short, "
                f"to {sh.least} byte{'s' if sh.least != 1 else ''}: {why}, `{sh.length_field}` counts the payload "
                "bytes sent, and what follows the payload moves up by the bytes left off. A decoder reads "
                "the bytes left off as zeros.")
    for s in slots(m):
        if s.field.length_param:
            param = next((x for x in p.parameters if x.name == s.field.length_param), None)
            if param is not None and param.default is not None:
                return (f"Positions assume `{param.name}` = {number(param.default)} (its default); "
                        f"`{s.path}` is `{param.name}` bytes long and every byte after it moves with it.")
    return ""


def field_columns(p: Protocol, rows: list[dict]) -> list[tuple[str, str, str]]:
    """(key, heading, alignment) of the field table: the framing's place columns,
    then the descriptive ones that have a value in at least one row."""
    fr = p.framing
    if fr.kind == "text":
        place = [("index", "#", "--:")]
    else:
        where = "word bits" if fr.word_bits else ("bytes" if fr.kind == "bytes" else "byte bits")
        place = [("bits", "bits", "--:"), ("offset", "offset", "--:"), ("position", where, "---")]
    optional = [("type", "type"), ("range", "range"), ("unit", "unit"), ("kinds", "values"),
                ("default", "default")]
    shown = [(key, title, "---") for key, title in optional if any(r[key] for r in rows)]
    return [("name", "field", "---")] + place + shown + [("meaning", "meaning", "---")]
