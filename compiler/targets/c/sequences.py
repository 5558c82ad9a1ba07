"""Sequences in C: a sequence's items as a flat grammar automaton and its
cross-message rules as loops over a decoded array; templates/c/sequence.h.j2
lays them out.

The generated Python (`_parse_items`, `_check_rules`) is the reference: the C
reports the error the Python lists first (the lowest unit index; at equal
index a message's own decode error before a grammar error, earlier rules
before later ones). Items become slots of one automaton driven by a switch in
a loop, so nesting costs no recursion:
- `one`: takes exactly that message;
- `repeat`: takes that message while it comes, then moves on;
- `count`: takes as many as an earlier sibling's field says;
- `loop`: the head of a repeated group, entered while the next message can
  start the group (Python's `_first`), left otherwise;
- `end`: accepts only the end of the input.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from ...model import Sequence, SequenceItem, SequenceRule, field_at
from ...diagnostics import Diagnostic, Loc, SchemaError
from .view import ERR, CView, comment



@dataclass
class Slot:
    pc: int
    mode: str  # one | repeat | count | loop | end
    note: str
    kind: str = ""  # the message's C kind constant (one, repeat, count)
    message: str = ""
    next: int = -1
    enter: int = -1  # loop: first slot of the group's items
    first: list[str] = field(default_factory=list)  # loop: kinds that start the group
    counter: int = -1  # count: index into the iterator's `left`
    group: int = -1  # loop: index into the iterator's `begin`
    sets: list[tuple[int, str]] = field(default_factory=list)  # one: (counter, member) taken from it


class SequenceView:
    def __init__(self, v: CView, s: Sequence):
        self.v, self.s, self.p = v, s, v.p
        self.slots: list[Slot] = []
        self.counters = 0
        self.groups: dict[str, int] = {}  # dotted item path of a repeated group -> index
        self.kind_slots: dict[str, list[int]] = {}

    def unsupported(self, message: str, loc: Loc | None = None) -> SchemaError:
        """A sequence the C target cannot express, reported against the schema."""
        return SchemaError([Diagnostic(loc or self.s.loc, message,
                                       "the C target needs fixed-size messages, counts in plain "
                                       "unsigned fields and rules over integer fields of messages "
                                       "that appear in one item")])

    # -- the automaton --------------------------------------------------------------------
    def kind(self, message: str) -> str:
        return self.v.upper("MSG", message)

    def add(self, mode: str, note: str, **kw) -> Slot:
        slot = Slot(len(self.slots), mode, comment(note), **kw)
        self.slots.append(slot)
        return slot

    def first(self, items: tuple[SequenceItem, ...]) -> list[str]:
        """Message kinds that can start the items (Python's `_first`)."""
        out: list[str] = []
        for item in items:
            for k in (self.first(item.items) if item.items else [self.kind(item.message)]):
                if k not in out:
                    out.append(k)
            if not item.repeat:
                break
        return out

    def emit(self, items: tuple[SequenceItem, ...], path: str) -> tuple[int, list[Slot]]:
        """Slots for the items in order: (entry pc, slots whose `next` follows them)."""
        entry, exits = -1, []
        taken: dict[str, Slot] = {}  # sibling `one` items a later `count` may read
        for item in items:
            dotted = f"{path}.{item.name}" if path else item.name
            if item.items and item.repeat:
                head = self.add("loop", f"{dotted}: repeated group", first=self.first(item.items),
                                group=len(self.groups))
                self.groups[dotted] = head.group
                inner, inner_exits = self.emit(item.items, dotted)
                head.enter = inner
                for s in inner_exits:
                    s.next = head.pc
                start, ends = head.pc, [head]
            elif item.items:
                start, ends = self.emit(item.items, dotted)
            else:
                mode = "count" if item.count else "repeat" if item.repeat else "one"
                slot = self.add(mode, f"{dotted}: {mode} {item.message}", kind=self.kind(item.message),
                                message=item.message)
                self.kind_slots.setdefault(item.message, []).append(slot.pc)
                if item.count:
                    slot.counter = self.counters
                    self.counters += 1
                    head, _, member = item.count.partition(".")
                    source = taken.get(head)
                    # Python reads the count from a sibling taken once; from anywhere else
                    # it finds no number and takes none, which `left` starting at 0 mirrors.
                    if source is not None:
                        self.count_field(source.message, member, item)
                        source.sets.append((slot.counter, f"m->as.{source.message}.{member}"))
                if mode == "one":
                    taken[item.name] = slot
                start, ends = slot.pc, [slot]
            for s in exits:
                s.next = start
            if entry < 0:
                entry = start
            exits = ends
        return entry, exits

    def count_field(self, message: str, member: str, item: SequenceItem) -> None:
        f = field_at(self.p.message(message).layout, member)
        if f is None or f.kind != "uint" or f.scale is not None or f.offset or f.optional:
            raise self.unsupported(f"sequence {self.s.name}: count {item.count!r} must be a plain "
                               "unsigned field for the C target", item.loc)

    # -- rules ------------------------------------------------------------------------------
    def leaf(self, dotted: str, rule: SequenceRule) -> tuple[str, list[str], str]:
        """(message, item names down to it, field path inside it; "" for the whole message)."""
        parts, items, names = dotted.split("."), self.s.items, []
        for i, part in enumerate(parts):
            item = next(it for it in items if it.name == part)
            names.append(part)
            if item.message:
                if len(self.kind_slots.get(item.message, [])) != 1:
                    raise self.unsupported(f"sequence {self.s.name}: rule {rule.kind} on {dotted!r} needs "
                                       f"{item.message!r} in one item only for the C target", rule.loc)
                return item.message, names, ".".join(parts[i + 1:])
            items = item.items
        raise self.unsupported(f"sequence {self.s.name}: rule path {dotted!r} names no message", rule.loc)

    def member(self, message: str, dotted: str, rule: SequenceRule) -> str:
        """The field as a C expression over `m[%s]`, widened so any two compare."""
        f = field_at(self.p.message(message).layout, dotted) if dotted else None
        if f is None or (f.kind not in ("uint", "int", "bool") and f.enum is None) or f.optional \
                or f.scale is not None:
            raise self.unsupported(f"sequence {self.s.name}: rule {rule.kind} compares {message}.{dotted}, "
                               "which the C target compares only as a plain integer, enum or bool", rule.loc)
        return f"(int64_t)m[%s].as.{message}.{dotted}"

    def rule_view(self, i: int, r: SequenceRule) -> dict:
        out = {"index": i, "kind": r.kind, "error": ERR[r.kind],
               "note": comment(f"{r.id + ': ' if r.id else ''}{r.kind} {r.path}")}
        message, names, inside = self.leaf(r.path, r)
        out["mkind"] = self.kind(message)
        if r.kind == "consecutive":
            out.update(value=self.member(message, inside, r), start=r.start)
        elif r.kind == "unique":
            out["keys"] = [self.member(message, f"{inside}.{k}" if inside else k, r) for k in r.key]
        else:
            other = r.to if r.kind == "equal" else r.of
            o_message, o_names, o_inside = self.leaf(other, r)
            if message == o_message:
                raise self.unsupported(f"sequence {self.s.name}: rule {r.kind} within one message", r.loc)
            common = 0
            while common < min(len(names), len(o_names)) and names[common] == o_names[common]:
                common += 1
            # Python compares within each instance of the common prefix; instances
            # are those of its innermost repeated group (-1: the whole sequence).
            group = next((self.groups[".".join(names[:k])] for k in range(common, 0, -1)
                          if ".".join(names[:k]) in self.groups), -1)
            out.update(value=self.member(message, inside, r), okind=self.kind(o_message),
                       other=self.member(o_message, o_inside, r), group=group)
        return out

    def view(self) -> dict:
        dispatch = self.v.dispatch()  # the head the C reads, as <proto>_find takes it
        sizes = {m.size for m in self.p.messages}
        if dispatch["kind"] not in ("none", "bits") or None in sizes:
            raise self.unsupported(f"sequence {self.s.name}: the C target splits sequences of fixed-size "
                               "messages only (bit-packed, or one size without dispatch)")
        if dispatch["kind"] == "none" and len(sizes) != 1:
            raise self.unsupported(f"sequence {self.s.name}: messages without dispatch need one size")
        _, exits = self.emit(self.s.items, "")
        end = self.add("end", "the end of the input")
        if end.pc > 255:
            raise self.unsupported(f"sequence {self.s.name}: more than 255 grammar slots for the C target")
        for s in exits:
            s.next = end.pc
        px = self.v.px
        return {
            "name": self.s.name, "doc": comment(self.s.doc or self.s.name), "fn": f"{px}_{self.s.name}",
            "msg_t": f"{px}_message_t", "find": f"{px}_find", "positional": dispatch["kind"] == "none",
            "unit_size": min(sizes), "head_bytes": dispatch.get("head_bytes", 0),
            "messages": [{"kind": self.kind(m.name), "name": m.name, "fn": f"{px}_{m.name}",
                          "size": m.size} for m in self.p.messages],
            "slots": self.slots, "counters": self.counters, "groups": len(self.groups),
            "rules": [self.rule_view(i, r) for i, r in enumerate(self.s.rules)],
        }


def sequences_view(v: CView) -> list[dict]:
    return [SequenceView(v, s).view() for s in v.p.sequences]
