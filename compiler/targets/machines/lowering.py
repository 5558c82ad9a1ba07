"""Machines lowered to target code: guards become expressions, actions statements.

Each target spells names, operators and statements its own way (a subclass);
the walk over states, events and rows is shared so that every target runs the
same rows in the same order: the first row whose guard holds wins.
"""
from __future__ import annotations

from dataclasses import dataclass

from ...model import Action, Condition, Event, Machine, Protocol, Source
from .packets import MachineTargetError, PacketLayout, machine_messages, packet_layout


@dataclass(frozen=True)
class Row:
    guard: str  # target expression; "" = always
    body: tuple[str, ...]  # statements, the state change last
    to: str


@dataclass(frozen=True)
class Case:
    """What one state does with one event."""

    state: str
    kind: str  # ignore | error | rows
    rows: tuple[Row, ...] = ()


@dataclass(frozen=True)
class EventCode:
    event: Event
    cases: tuple[Case, ...]
    packet: PacketLayout | None  # receive events: the message the packet must be


class _Words(dict):
    """The words an action's spelling uses ({var}, {value}, {mask}, …), each worked out
    only when the spelling names it."""

    def __init__(self, lowering: "Lowering", a: Action):
        super().__init__()
        self.lowering, self.a = lowering, a

    def __missing__(self, key: str) -> object:
        value = self[key] = self.lowering.action_word(key, self.a)
        return value


class Lowering:
    """Spell a machine in one target; subclasses fill in the spelling.

    SPELLING gives the statements of each simple action kind as format strings over
    the words of action_word; a kind whose statements need more is a method
    lower_<kind>(action)."""

    SPELLING: dict[str, str | tuple[str, ...]] = {}

    def __init__(self, p: Protocol, machine: Machine):
        self.p = p
        self.m = machine
        built, received = machine_messages(machine)
        self.layouts = {name: packet_layout(p, p.message(name)) for name in built + received}

    # -- spelling, per target -------------------------------------------------------------
    def var(self, name: str) -> str: raise NotImplementedError
    def param(self, name: str) -> str: raise NotImplementedError
    def packet(self, name: str) -> str: raise NotImplementedError
    def request(self, name: str) -> str: raise NotImplementedError
    def result(self, name: str) -> str: raise NotImplementedError
    def state_value(self, name: str) -> str: raise NotImplementedError
    def zero_bytes(self, message: str, field: str) -> str: raise NotImplementedError
    def goto(self, state: str) -> str: raise NotImplementedError
    AND = " and "

    # -- shared ---------------------------------------------------------------------------
    def action(self, a: Action, event: Event) -> list[str]:
        lower = getattr(self, f"lower_{a.kind}", None)
        if lower is not None:
            return lower(a)
        spelled = self.SPELLING.get(a.kind)
        if spelled is None:
            raise MachineTargetError(f"{self.m.name}.{a.name}: action kind {a.kind!r} has no spelling here")
        words = _Words(self, a)
        return [line.format_map(words) for line in ((spelled,) if isinstance(spelled, str) else spelled)]

    def action_word(self, key: str, a: Action) -> object:
        """A word of an action's spelling."""
        words = {"var": lambda: self.var(a.target), "value": lambda: self.source(a.value),
                 "mask": lambda: (1 << self.var_bits(a.target)) - 1, "param": lambda: self.param(a.target),
                 "packet": lambda: self.packet(a.target), "result": lambda: self.result(a.target),
                 "target": lambda: a.target, "machine": lambda: self.m.name}
        return words[key]()

    def var_bits(self, name: str) -> int:
        return next(v.bits for v in self.m.variables if v.name == name)

    def source(self, s: Source, message: str | None = None, field: str | None = None) -> str:
        if s.kind == "const":
            if message and field in self.layouts[message].data_members:
                return self.zero_bytes(message, field)
            return str(s.value)
        return {"var": self.var, "param": self.param, "packet": self.packet,
                "request": self.request, "result": self.result}[s.kind](s.name)

    def key(self, name: str, event: Event) -> str:
        if event.message:
            return self.packet(name)
        if any(v.name == name for v in self.m.variables):
            return self.var(name)
        return self.param(name)

    def condition(self, c: Condition, event: Event) -> str:
        left = self.key(c.path, event)
        op = c.op
        if op.endswith("_var"):
            right = self.var(c.value)
        elif op.endswith("_param"):
            right = self.param(c.value)
        elif op == "in":
            return "(" + self.OR.join(f"{left} == {v}" for v in c.value) + ")"
        elif op == "range":
            return f"({c.value[0]} <= {left}{self.AND}{left} <= {c.value[1]})"
        else:
            right = str(c.value)
        symbol = {"eq": "==", "ne": "!=", "lt": "<", "ge": ">="}[op.split("_")[0]]
        return f"{left} {symbol} {right}"

    OR = " or "

    def guard(self, conditions: tuple[Condition, ...], event: Event) -> str:
        return self.AND.join(self.condition(c, event) for c in conditions)

    def events(self) -> list[EventCode]:
        out = []
        for event in self.m.events:
            cases = []
            for state in self.m.states:
                handler = next(h for h in state.handlers if h.event == event.name)
                if handler.kind != "transitions":
                    cases.append(Case(state.name, handler.kind))
                    continue
                rows = []
                for t in handler.transitions:
                    body: list[str] = []
                    for name in t.actions:
                        body.extend(self.action(self.m.action(name), event))
                    if t.to != state.name:
                        body.append(self.goto(t.to))
                    rows.append(Row(self.guard(t.guard, event), tuple(body), t.to))
                cases.append(Case(state.name, "rows", tuple(rows)))
            out.append(EventCode(event, tuple(cases),
                                 self.layouts[event.message] if event.message else None))
        return out

    def uses(self, kind: str) -> bool:
        return any(a.kind == kind for a in self.m.actions)
