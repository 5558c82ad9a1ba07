"""Compare two protocol models and classify every change by what it does to
the wire: breaking (old and new codecs disagree on some bytes), compatible
(everything valid before is still valid and means the same) or docs-only."""
from __future__ import annotations

from dataclasses import dataclass, field, replace
from typing import Any, Optional

from ..fingerprint import fingerprint, wire_model
from ..model import Field, Leaf, Message, Protocol
from ..resolver.layout import leaves_of

BREAKING, COMPATIBLE, DOCS = "breaking", "compatible", "docs"
KINDS = (BREAKING, COMPATIBLE, DOCS)

# Field attributes whose change alters the bytes or what a decoder accepts;
# each is described on its own below when it changes.
_WIRE_ATTRS = ("kind", "const", "scale", "offset", "byte_order", "start_bit", "one_hot", "exactly_one", "reserved",
               "length", "length_param", "max_length", "to_end", "dispatch", "length_of", "length_adjust",
               "decimals", "width")


@dataclass
class Change:
    kind: str  # breaking | compatible | docs
    subject: str  # what changed: "field motor.enable", "message ack", "framing", …
    what: str
    messages: list[str] = field(default_factory=list)  # the messages it applies to, if any


@dataclass
class Diff:
    old: Protocol
    new: Protocol
    changes: list[Change]

    @property
    def old_fingerprint(self) -> str:
        return fingerprint(self.old)

    @property
    def new_fingerprint(self) -> str:
        return fingerprint(self.new)

    @property
    def breaking(self) -> bool:
        return any(c.kind == BREAKING for c in self.changes)

    def of_kind(self, kind: str) -> list[Change]:
        return [c for c in self.changes if c.kind == kind]


@dataclass(frozen=True)
class Placed:
    """A leaf field with its place in the frame: bit offset where every earlier
    width is fixed, otherwise its position among the fields."""

    path: str
    field: Field
    index: int
    bit: Optional[int]

    def place(self) -> str:
        if self.bit is None or self.field.bits is None:
            return f"position {self.index + 1}"
        if self.field.bits == 1:
            return f"bit {self.bit}"
        return f"bits {self.bit}–{self.bit + self.field.bits - 1}"


def placed_leaves(leaves: tuple[Leaf, ...]) -> dict[str, Placed]:
    return {leaf.dotted: Placed(leaf.dotted, leaf.field, i, leaf.pos) for i, leaf in enumerate(leaves)}


def _text(t) -> str:
    """Comparable form of a Text (English and translations)."""
    return "" if t is None else repr((t.en, t.translations))


def _same_wire(a: Any, b: Any) -> bool:
    return wire_model(a) == wire_model(b)


def _fmt(v: Any) -> str:
    if isinstance(v, tuple) and len(v) == 2:
        return f"{v[0]}..{v[1]}"
    return repr(v)


class _Collector:
    def __init__(self):
        self.changes: list[Change] = []

    def add(self, kind: str, subject: str, what: str, message: Optional[str] = None):
        for c in self.changes:  # one entry for a change shared by several messages
            if (c.kind, c.subject, c.what) == (kind, subject, what) and message and c.messages:
                if message not in c.messages:
                    c.messages.append(message)
                return
        self.changes.append(Change(kind, subject, what, [message] if message else []))


def compare(old: Protocol, new: Protocol) -> Diff:
    out = _Collector()
    _framing(old, new, out)
    _messages(old, new, out)
    _sequences(old, new, out)
    _parameters(old, new, out)
    _machines(old, new, out)
    _delivery(old, new, out)
    _docs(old, new, out)
    if fingerprint(old) != fingerprint(new) and not any(c.kind != DOCS for c in out.changes):
        # never report a wire change as harmless because no rule above names it
        out.add(BREAKING, "schema", "a wire-relevant part of the model changed (fingerprints differ)")
    order = {k: i for i, k in enumerate(KINDS)}
    changes = sorted(out.changes, key=lambda c: order[c.kind])
    return Diff(old, new, changes)


def _framing(old: Protocol, new: Protocol, out: _Collector) -> None:
    a, b = old.framing, new.framing
    for name in ("kind", "byte_order", "bit_order", "encoding", "accm", "truncate", "word_bits", "max_bits", "prefix_separator",
                 "separator", "terminator", "ignore_between", "trim", "float_format", "start", "line_checksum",
                 "keep_empty"):
        if getattr(a, name) != getattr(b, name):
            out.add(BREAKING, "framing", f"{name} changed from {getattr(a, name)!r} to {getattr(b, name)!r}")
    if _stuffing(a.stuffing) != _stuffing(b.stuffing):
        out.add(BREAKING, "framing", f"stuffing changed from {_stuffing(a.stuffing)} to {_stuffing(b.stuffing)}")
    if not _same_wire(a.text_form, b.text_form):
        out.add(BREAKING, "framing", "the text form changed")
    if a.envelope or b.envelope:
        _fields(placed_leaves(leaves_of(a.envelope)), placed_leaves(leaves_of(b.envelope)), out, "envelope", text=a.kind == "text")
    _trailer(a.trailer, b.trailer, out)


def _trailer_wire(t) -> tuple:
    """What a trailer puts on the wire: its flag's place, each field's bytes, the hash."""
    return (t.flag_byte, t.flag_mask, tuple((f.name, f.kind, f.bits, f.byte_order, f.signature) for f in t.fields))


def _trailer(a, b, out: _Collector) -> None:
    """A trailer added is compatible (an old frame leaves its flag clear, and the new
    decoders accept it); one removed or changed on the wire breaks."""
    if a is None and b is not None:
        out.add(COMPATIBLE, "framing", f"a trailer added, sent when {b.presence.says}")
    elif a is not None and b is None:
        out.add(BREAKING, "framing", f"the trailer sent when {a.presence.says} removed")
    elif a is not None and b is not None and _trailer_wire(a) != _trailer_wire(b):
        out.add(BREAKING, "framing", "the trailer's flag, fields or signature changed")


def _stuffing(st) -> str:
    """Pattern stuffing as the wire sees it (where the schema says it is aside)."""
    if st is None:
        return "none"
    return f"{st.insert:02X} after {st.pattern.hex(' ').upper()} in {st.covers[0]}..{st.covers[1]}"


def _messages(old: Protocol, new: Protocol, out: _Collector) -> None:
    before = {m.name: m for m in old.messages}
    after = {m.name: m for m in new.messages}
    for name, m in before.items():
        if name not in after:
            ids = f" (id {_ids(m)})" if m.ids else ""
            out.add(BREAKING, f"message {name}", f"removed{ids}")
    old_ids = {(m.direction, i) for m in old.messages for i in m.ids}
    for name, m in after.items():
        if name in before:
            _message(before[name], m, out, text=new.framing.kind == "text")
            continue
        reused = [i for i in m.ids if (m.direction, i) in old_ids]
        if reused:
            out.add(BREAKING, f"message {name}", f"added with id {', '.join(map(str, reused))}, "
                    "which an old message already uses")
        else:
            ids = f" with id {_ids(m)}" if m.ids else ""
            out.add(COMPATIBLE, f"message {name}", f"added{ids}")


def _message(a: Message, b: Message, out: _Collector, text: bool) -> None:
    subject = f"message {a.name}"
    if a.ids != b.ids:
        out.add(BREAKING, subject, f"id changed from {_ids(a)} to {_ids(b)}")
    if a.direction != b.direction:
        out.add(BREAKING, subject, f"direction changed from {a.direction} to {b.direction}")
    if a.crc_extra != b.crc_extra:
        out.add(BREAKING, subject, f"crc_extra changed from {a.crc_extra} to {b.crc_extra}")
    if a.role != b.role:
        out.add(BREAKING, subject, f"role changed from {a.role} to {b.role}")
    growth = extension_growth(a, b)
    if a.bits != b.bits and a.bits is not None and b.bits is not None and growth is None:
        out.add(BREAKING, subject, f"size changed from {a.bits} to {b.bits} bits")
    if not _same_wire(a.dispatch_key, b.dispatch_key) and a.ids == b.ids:
        out.add(BREAKING, subject, "how a decoder recognises it changed")
    recounted = _counts(a.layout, b.layout, out, a.name)
    _fields(_outside(placed_leaves(a.wire.leaves), recounted), _outside(placed_leaves(b.wire.leaves), recounted),
            out, a.name, text=text, growth=growth)
    if text:
        _places(a, b, out)
    _rules(a, b, out)
    if _text(a.title) != _text(b.title) or _text(a.doc) != _text(b.doc):
        out.add(DOCS, subject, "title or description changed")
    if [e.name for e in a.examples] != [e.name for e in b.examples] or \
            [(e.hex, e.text, e.values) for e in a.examples] != [(e.hex, e.text, e.values) for e in b.examples]:
        out.add(DOCS, subject, "examples changed")


def _keep(value: Optional[bool]) -> str:
    return "the framing's" if value is None else repr(value).lower()


def _places(a: Message, b: Message, out: _Collector) -> None:
    """How many values a text line carries: the fewest readers take, the most writers always
    write. Readers that take fewer, or writers that write more, are compatible; lines the
    other schema's readers refuse are not."""
    pa, pb = a.text_places, b.text_places
    subject = f"message {a.name}"
    if pa is None or pb is None or pa.total != pb.total:  # fields added or removed: told field by field
        return
    if pb.least > pa.least:
        out.add(BREAKING, subject, f"readers now need at least {pb.least} values in a line (took {pa.least})")
    elif pb.least < pa.least:
        out.add(COMPATIBLE, subject, f"readers now take a line of {pb.least} values or more (took {pa.least})")
    if pb.written < pa.least:
        out.add(BREAKING, subject, f"writers now end a line after {pb.written} values when the later ones are "
                                   f"absent, and readers of the old schema need {pa.least}")
    elif pb.written != pa.written:
        out.add(COMPATIBLE, subject, f"writers now always write {pb.written} values (wrote {pa.written})")
    if a.keeps_places != b.keeps_places:  # the same lines read and written; a decoded one writes back otherwise
        out.add(COMPATIBLE, subject, "a decoded line is now written back with as many values as it had (C member "
                                     "line_values)" if b.keeps_places else
                "a decoded line is no longer written back with as many values as it had")


def extension_growth(a: Message, b: Message) -> Optional[int]:
    """The bits `b` adds to `a` when they are extension fields at the end of its payload
    and a frame of `a` is one `b` accepts (its extensions left off); else None."""
    if b.shortening is None or a.bits is None or b.bits is None or b.bits <= a.bits or a.size not in b.sizes:
        return None
    old = {f.name for f in a.fields}
    added = [f for f in b.fields if f.name not in old]
    if [f.name for f in b.fields[:len(a.fields)]] != [f.name for f in a.fields] or \
            not all(f.extension for f in added) or len(added) != len(b.fields) - len(a.fields):
        return None
    return b.bits - a.bits


def _counts(before: tuple[Field, ...], after: tuple[Field, ...], out: _Collector, message: str,
            prefix: str = "") -> list[str]:
    """Arrays whose count changed, reported once each (not element by element); their paths."""
    changed = []
    # the envelope's payload marker holds no value: a field may be named `payload` too
    old = {f.name: f for f in before if not f.is_payload}
    for f in after:
        g = old.get(f.name)
        if g is None or f.is_payload:
            continue
        path = prefix + f.name
        if g.count != f.count:
            out.add(BREAKING, f"field {path}", f"count changed from {g.count or 'none'} to {f.count or 'none'}",
                    message)
            changed.append(path)
        elif f.kind == "group" and g.kind == "group":
            changed += _counts(g.fields, f.fields, out, message, path + ("[0]" if f.count else "") + ".")
    return changed


def _outside(placed: dict[str, Placed], arrays: list[str]) -> dict[str, Placed]:
    """The places not inside one of `arrays` (or where one of them was)."""
    return {path: x for path, x in placed.items()
            if not any(path == a or path.startswith(a + "[") or path.startswith(a + ".") for a in arrays)}


def _ids(m: Message) -> str:
    if m.id_fields:
        return ", ".join(f"{name}={value}" for name, value in m.id_fields)
    return ", ".join(map(repr, m.ids)) or "none"


def _fields(before: dict[str, Placed], after: dict[str, Placed], out: _Collector, message: str,
            text: bool, growth: Optional[int] = None) -> None:
    for path, old in before.items():
        if path not in after:
            out.add(BREAKING, f"field {path}", f"removed (was {old.place()}, {_width(old.field)})", message)
    last = max((p.index for p in after.values()), default=-1)
    for path, new in after.items():
        if path in before:
            _field(before[path], new, out, message, growth, text)
        elif text and new.field.extension:
            out.add(COMPATIBLE, f"field {path}", "added as an extension field: a line may end before it, "
                                                 "so the lines of the old schema still read", message)
        elif text and new.field.optional and new.index == last:
            out.add(COMPATIBLE, f"field {path}", "added as an optional last field", message)
        elif growth is not None and new.field.extension:
            out.add(COMPATIBLE, f"field {path}", f"added as an extension field at {new.place()}", message)
        else:
            out.add(BREAKING, f"field {path}", f"added at {new.place()} ({_width(new.field)})", message)


def _width(f: Field) -> str:
    return f"{f.bits} bit{'s' if f.bits != 1 else ''}" if f.bits is not None else f.kind


def _field(a: Placed, b: Placed, out: _Collector, message: str, growth: Optional[int] = None,
           text: bool = False) -> None:
    subject = f"field {b.path}"
    fa, fb = a.field, b.field
    if growth is not None:  # extensions added: what follows the payload moves, the length counts them
        fa = replace(fa, checksum=fa.checksum and replace(fa.checksum, byte_span=None),
                     const=fb.const if fb.length_of else fa.const)
        fb = replace(fb, checksum=fb.checksum and replace(fb.checksum, byte_span=None))
        if fb.from_envelope and a.bit is not None and b.bit == a.bit + growth:
            a = replace(a, bit=b.bit)

    def add(kind, what):
        out.add(kind, subject, what, message)

    if fa.bits != fb.bits:
        add(BREAKING, f"resized from {_width(fa)} to {_width(fb)}")
    moved = a.bit != b.bit if a.bit is not None and b.bit is not None else a.index != b.index
    if moved:
        add(BREAKING, f"moved from {a.place()} to {b.place()}")
    for name in _WIRE_ATTRS:
        va, vb = getattr(fa, name), getattr(fb, name)
        if va != vb:
            add(BREAKING, f"{name} changed from {va!r} to {vb!r}")
    if fa.present_if != fb.present_if:  # when a frame carries it, so where what follows sits
        old, new = (f.present_if.says if f.present_if else "always" for f in (fa, fb))
        add(BREAKING, f"sent when {old}, now {new}")
    old, new = (f.multiplexed_by.says if f.multiplexed_by else "always" for f in (fa, fb))
    if old != new:  # which multiplexor values carry it: frames of the others read it no more, or read other bits
        add(BREAKING, f"carried when {old}, now {new}")
    if fa.to_end != fb.to_end:
        add(BREAKING, "now fills the rest of the payload" if fb.to_end else "no longer fills the rest of the payload")
    if fa.extension != fb.extension:  # a text line may end before it: readers take more lines than before
        add(COMPATIBLE if text and fb.extension else BREAKING,
            "now an extension field" + (": a line may end before it" if text else "") if fb.extension
            else "no longer an extension field")
    if text and fa.keep_empty != fb.keep_empty:  # what it does to the line is told for the message
        add(COMPATIBLE, f"keep_empty changed from {_keep(fa.keep_empty)} to {_keep(fb.keep_empty)}")
    if fa.optional != fb.optional:
        add(COMPATIBLE if fb.optional else BREAKING,
            "now optional" if fb.optional else "now required")
    if fa.prefix != fb.prefix:  # read from the line's prefix before the id, or from its body
        add(BREAKING, "now written in the prefix before the id" if fb.prefix
            else "no longer written in the prefix before the id")
    if fa.keep_spelling != fb.keep_spelling:  # the same lines read and written; a decoded one writes back otherwise
        add(COMPATIBLE, f"now keeps the text it was read from (C member {fb.name}_spelling)" if fb.keep_spelling
            else f"no longer keeps the text it was read from (C member {fa.name}_spelling removed)")
    if not _same_wire(fa.checksum, fb.checksum):
        add(BREAKING, "checksum changed" if fa.checksum and fb.checksum else
            "checksum added" if fb.checksum else "checksum removed")
    _range(fa.range, fb.range, add)
    if fa.kind == fb.kind == "float" and fa.finite != fb.finite:  # as a range widened or narrowed
        add(COMPATIBLE if not fb.finite else BREAKING,
            "now holds NaN and the infinities too (widened)" if not fb.finite else "NaN and the infinities now refused")
    _value_set(fa.values, fb.values, "allowed values", add)
    if fa.enum or fb.enum:
        _members({m.value: m.name for m in fa.enum.members} if fa.enum else {},
                 {m.value: m.name for m in fb.enum.members} if fb.enum else {}, add)
    if fa.enum and fb.enum and fa.enum.open != fb.enum.open:
        add(COMPATIBLE if fb.enum.open else BREAKING,
            f"enum {fb.enum.name} now open: a value no member has decodes as its number" if fb.enum.open
            else f"enum {fb.enum.name} now closed: a value no member has is refused")
    if fa.flags or fb.flags:
        _members({m.bit: m.name for m in fa.flags.members} if fa.flags else {},
                 {m.bit: m.name for m in fb.flags.members} if fb.flags else {}, add, "flag bit")
    if fa.default != fb.default or fa.has_default != fb.has_default:
        add(COMPATIBLE, f"default changed from {fa.default!r} to {fb.default!r}")
    if (_text(fa.doc), _text(fa.title), _text(fa.message), fa.unit, fa.rule) != \
            (_text(fb.doc), _text(fb.title), _text(fb.message), fb.unit, fb.rule):
        add(DOCS, "description, title, unit or cited rule changed")


def _range(a, b, add) -> None:
    if a == b:
        return
    if a is None:
        add(BREAKING, f"range {_fmt(b)} added (narrowed)")
    elif b is None:
        add(COMPATIBLE, f"range {_fmt(a)} removed (widened)")
    elif b[0] > a[0] or b[1] < a[1]:
        add(BREAKING, f"range narrowed from {_fmt(a)} to {_fmt(b)}")
    else:
        add(COMPATIBLE, f"range widened from {_fmt(a)} to {_fmt(b)}")


def _value_set(a, b, what: str, add) -> None:
    if a == b:
        return
    sa, sb = set(a or ()), set(b or ())
    if a is not None and b is not None and sa == sb:  # the order of a list of allowed values means nothing
        add(COMPATIBLE, f"{what} reordered (the same set)")
    elif a is None or b is not None and not sa <= sb:
        add(BREAKING, f"{what} narrowed: {sorted(map(str, sa - sb)) or 'now restricted'}")
    else:
        add(COMPATIBLE, f"{what} widened: {sorted(map(str, sb - sa)) or 'no longer restricted'}")


def _members(a: dict, b: dict, add, noun: str = "value") -> None:
    for value, name in a.items():
        if value not in b:
            add(BREAKING, f"{noun} {value!r} ({name}) removed")
        elif b[value] != name:
            add(BREAKING, f"{noun} {value!r} renamed from {name} to {b[value]}")
    for value, name in b.items():
        if value not in a:
            add(COMPATIBLE, f"{noun} {value!r} ({name}) added in spare space")


def _rules(a: Message, b: Message, out: _Collector) -> None:
    ra = [wire_model(r) for r in a.rules]
    rb = [wire_model(r) for r in b.rules]
    for r in ra:
        if r not in rb:
            out.add(COMPATIBLE, f"message {a.name}", f"rule{_rule_id(r)} removed (accepts more)")
    for r in rb:
        if r not in ra:
            out.add(BREAKING, f"message {a.name}", f"rule{_rule_id(r)} added or changed (accepts less)")
    if ra == rb and [_text(r.message) for r in a.rules] != [_text(r.message) for r in b.rules]:
        out.add(DOCS, f"message {a.name}", "rule messages changed")


def _rule_id(rule: dict) -> str:
    return f" {rule['id']}" if rule.get("id") else ""


def _sequences(old: Protocol, new: Protocol, out: _Collector) -> None:
    before = {s.name: s for s in old.sequences}
    after = {s.name: s for s in new.sequences}
    for name in before.keys() - after.keys():
        out.add(BREAKING, f"sequence {name}", "removed")
    for name in sorted(after.keys() - before.keys()):
        out.add(COMPATIBLE, f"sequence {name}", "added")
    for name in sorted(before.keys() & after.keys()):
        a, b = before[name], after[name]
        if not _same_wire(a.items, b.items):
            out.add(BREAKING, f"sequence {name}", "items changed")
        ra, rb = wire_model(a.rules), wire_model(b.rules)
        if any(r not in ra for r in rb):
            out.add(BREAKING, f"sequence {name}", "rules added or changed (accepts less)")
        elif ra != rb:
            out.add(COMPATIBLE, f"sequence {name}", "rules removed (accepts more)")


def _parameters(old: Protocol, new: Protocol, out: _Collector) -> None:
    before = {p.name: p for p in old.parameters}
    after = {p.name: p for p in new.parameters}
    for name in before.keys() - after.keys():
        out.add(BREAKING, f"parameter {name}", "removed")
    for name in sorted(after.keys() - before.keys()):
        out.add(COMPATIBLE, f"parameter {name}", f"added (default {after[name].default!r})")
    for name in sorted(before.keys() & after.keys()):
        a, b = before[name], after[name]
        if a.default != b.default:
            out.add(BREAKING, f"parameter {name}", f"default changed from {a.default!r} to {b.default!r}")
        if a.range != b.range:
            out.add(BREAKING, f"parameter {name}", f"range changed from {_fmt(a.range)} to {_fmt(b.range)}")


def _machines(old: Protocol, new: Protocol, out: _Collector) -> None:
    before = {m.name: m for m in old.machines}
    after = {m.name: m for m in new.machines}
    for name in before.keys() - after.keys():
        out.add(BREAKING, f"machine {name}", "removed")
    for name in sorted(after.keys() - before.keys()):
        out.add(COMPATIBLE, f"machine {name}", "added")
    for name in sorted(before.keys() & after.keys()):
        if not _same_wire(before[name], after[name]):
            out.add(BREAKING, f"machine {name}", "states, events or transitions changed")


def _delivery(old: Protocol, new: Protocol, out: _Collector) -> None:
    """The delivery section names what the docs describe and the simulator drives;
    the machines' own changes are reported above, so any change here is docs-only."""
    a, b = old.delivery, new.delivery
    if a is None and b is None:
        return
    if a is None:
        out.add(DOCS, "delivery", f"added: the docs state the delivery guarantee of {b.sender} → {b.receiver}")
        return
    if b is None:
        out.add(DOCS, "delivery", "removed: the docs no longer state a delivery guarantee")
        return
    for name in ("sender", "receiver", "address", "timeout", "retry_limit", "request", "addresses"):
        if getattr(a, name) != getattr(b, name):
            out.add(DOCS, "delivery", f"{name} changed from {getattr(a, name)!r} to {getattr(b, name)!r}")
    if a.notes != b.notes:
        out.add(DOCS, "delivery", "the notes cited for the guarantee or its limits changed")


def _docs(old: Protocol, new: Protocol, out: _Collector) -> None:
    streams_a = {s.name: (s.data, s.events) for s in old.streams}
    streams_b = {s.name: (s.data, s.events) for s in new.streams}
    for name in sorted(streams_a.keys() | streams_b.keys()):
        if streams_a.get(name) != streams_b.get(name):
            what = "added" if name not in streams_a else "removed" if name not in streams_b else "changed"
            out.add(DOCS, f"stream {name!r}", what)
    if old.version != new.version:
        out.add(DOCS, "version", f"{old.version} → {new.version}")
    if _text(old.title) != _text(new.title) or _text(old.doc) != _text(new.doc):
        out.add(DOCS, "protocol", "title or description changed")
    notes_a = {n.id: _text(n.text) for n in old.notes}
    notes_b = {n.id: _text(n.text) for n in new.notes}
    for nid in notes_a:
        if nid not in notes_b:
            out.add(DOCS, f"note {nid}", "removed")
        elif notes_a[nid] != notes_b[nid]:
            out.add(DOCS, f"note {nid}", "changed")
    for nid in notes_b:
        if nid not in notes_a:
            out.add(DOCS, f"note {nid}", "added")
    versions_a = [h.version for h in old.history]
    for h in new.history:
        if h.version not in versions_a:
            out.add(DOCS, "history", f"version {h.version} added ({len(h.changes)} change(s) listed)")
