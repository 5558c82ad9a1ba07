"""Python target, machines: one sans-IO class per machine, appended to the codec module.

The caller passes the current time, received packets and application requests;
each call returns an `Outputs` with the packets to send, the data delivered,
the commands executed and the failures. No clock, socket or thread inside.
"""
from __future__ import annotations

from ...model import Action, Event, Machine, Protocol
from ..machines.lowering import Lowering
from ..machines.packets import PacketLayout, machine_messages, packet_layout


# The constructor keyword of a machine that executes requests: the application's
# function from request data to reply data.
EXECUTE_ARGUMENT = "execute"


def class_name(machine: Machine) -> str:
    return "".join(part.capitalize() for part in machine.name.split("_")) + "Machine"


def method_name(event: Event) -> str:
    """send(…) for requests, receive(…) for packets, tick(…) for the timer."""
    if event.timer:
        return "tick"
    return event.name


def byte_expr(slot, value_of) -> str:
    parts = [value_of(bp.field) if bp.shift == 0 else f"{value_of(bp.field)} << {bp.shift}"
             for bp in slot.parts if bp.const is None]
    if slot.const_value or not parts:
        parts.insert(0, str(slot.const_value))
    return " | ".join(parts)


def pack_function(layout: PacketLayout) -> dict:
    """`_machine_pack_<m>(lengths…, members…)`: the packet's bytes."""
    pieces, run = [], []
    for slot in layout.slots:
        if slot.data_field:
            if run:
                pieces.append("_bytes((" + ", ".join(run) + ",))")
                run = []
            pieces.append(slot.data_field)
        else:
            run.append(byte_expr(slot, lambda name: name))
    if run:
        pieces.append("_bytes((" + ", ".join(run) + ",))")
    data = {slot.data_field for slot in layout.slots if slot.data_field}
    return {"name": f"_machine_pack_{layout.message}",
            "args": ", ".join(f"{name}: {'bytes' if name in data else 'int'}" for name in layout.members),
            "expr": " + ".join(pieces)}


def unpack_function(layout: PacketLayout) -> dict:
    """`_machine_unpack_<m>(lengths…, b)`: the member values, or None if b is not this message."""
    def at(slot) -> str:
        return slot.at.expr(lambda name: name)

    checks = [f"_len(b) != {layout.size.expr(lambda name: name)}"]
    values = {}
    for slot in layout.slots:
        if slot.data_field:
            end = slot.at.plus_length(slot.length_param) if slot.length_param else slot.at.plus(slot.length)
            values[slot.data_field] = f"_bytes(b[{at(slot)}:{end.expr(lambda name: name)}])"
            continue
        if slot.const_mask == 0xff:
            checks.append(f"b[{at(slot)}] != {slot.const_value:#04x}")
        elif slot.const_mask:
            checks.append(f"b[{at(slot)}] & {slot.const_mask:#04x} != {slot.const_value:#04x}")
        for bp in slot.parts:
            if bp.const is None:
                v = f"b[{at(slot)}]" if bp.shift == 0 else f"(b[{at(slot)}] >> {bp.shift})"
                values[bp.field] = v if bp.mask == 0xff >> bp.shift else f"{v} & {bp.mask:#x}"
    data = {slot.data_field for slot in layout.slots if slot.data_field}
    return {"name": f"_machine_unpack_{layout.message}",
            "args": ", ".join([f"{name}: int" for name in layout.length_params()] + ["b: Union[bytes, bytearray]"]),
            "checks": checks, "types": ", ".join("bytes" if name in data else "int" for name in layout.members),
            "values": [values[name] for name in layout.members]}


class PythonLowering(Lowering):
    def var(self, name): return f"self.{name}"
    def param(self, name): return f"self.{name}"
    def packet(self, name): return f"p_{name}"
    def request(self, name): return name
    def result(self, name): return f"r_{name}"
    def goto(self, state): return f"self.state = {state!r}"

    def zero_bytes(self, message, field):
        slot = next(s for s in self.layouts[message].slots if s.data_field == field)
        return f"_bytes({self.param(slot.length_param)})" if slot.length_param else f"_bytes({slot.length})"

    SPELLING = {
        "set": "{var} = {value}",
        "flip": "{var} ^= 1",
        "increment": "{var} = ({var} + 1) & {mask:#x}",
        "transmit": "out.sent.append(self.kept)",
        "start_timer": "self.deadline = now + {param}",
        "stop_timer": "self.deadline = None",
        "deliver": "out.delivered.append({packet})",
        "execute": ("out.executed.append({packet})", "{result} = self._execute_checked({packet})"),
        "fail": "out.failed.append({target!r})",
    }

    def lower_keep(self, a: Action) -> list[str]:
        given = dict(a.fields)
        args = [self.source(given[n], a.target, n) for n in self.layouts[a.target].members]
        return [f"self.kept = _machine_pack_{a.target}({', '.join(args)})"]


def branches(case) -> list[dict]:
    """if/elif/else heads with their bodies for the rows of one case."""
    out = []
    for i, row in enumerate(case.rows):
        if not row.guard:
            head = "else:" if i else None
        else:
            head = ("elif " if i else "if ") + row.guard + ":"
        out.append({"head": head, "body": list(row.body) or ["pass"]})
    return out


def parameter_views(p: Protocol, machine: Machine) -> list[dict]:
    out = []
    for name in machine.parameters:
        param = next(x for x in p.parameters if x.name == name)
        out.append({"name": name, "default": param.default, "range": param.range,
                    "doc": param.doc or name})
    # required ones first, so the signature reads naturally
    return sorted(out, key=lambda v: v["default"] is not None)


def argument_checks(p: Protocol, event: Event, machine: Machine) -> list[dict]:
    checks = []
    message = p.message(event.request)
    for arg in event.args:
        f = next(x for x in message.members if x.name == arg)
        if f.kind == "bytes":
            size = f.length_param or str(f.length)
            checks.append({"name": arg, "bytes": True, "size": f"self.{size}" if f.length_param else size})
        else:
            checks.append({"name": arg, "bytes": False, "max": (1 << f.bits) - 1})
    return checks


def machine_view(p: Protocol, machine: Machine) -> dict:
    low = PythonLowering(p, machine)
    events = []
    for code in low.events():
        e = code.event
        view = {"name": e.name, "method": method_name(e), "doc": e.doc or e.name, "timer": e.timer,
                "args": "", "checks": [], "unpack": None, "cases": []}
        if e.request:
            view["checks"] = argument_checks(p, e, machine)
            types = {c["name"]: "Union[bytes, bytearray]" if c["bytes"] else "int" for c in view["checks"]}
            view["args"] = "".join(f", {a}: {types[a]}" for a in e.args)
        if code.packet:
            view["args"] = ", packet: Union[bytes, bytearray]"
            lengths = [low.param(n) for n in code.packet.length_params()]
            view["unpack"] = {"fn": f"_machine_unpack_{code.packet.message}",
                              "args": ", ".join(lengths + ["packet"]),
                              "names": ", ".join(low.packet(n) for n in code.packet.members)}
        for case in code.cases:
            view["cases"].append({"state": case.state, "kind": case.kind, "branches": branches(case)})
        events.append(view)
    return {"cls": class_name(machine), "name": machine.name, "doc": machine.doc or machine.name,
            "states": [s.name for s in machine.states], "initial": machine.initial,
            "variables": machine.variables, "params": parameter_views(p, machine),
            "events": events, "executes": low.uses("execute"), "execute_argument": EXECUTE_ARGUMENT,
            "timer": any(e.timer for e in machine.events),
            "execute_size": execute_size(low)}


def execute_size(low: PythonLowering) -> str | None:
    """The expected length of the application's result, as an expression."""
    for a in low.m.actions:
        if a.kind == "execute":
            message = next(e.message for e in low.m.events if e.message)
            slot = next(s for s in low.layouts[message].slots if s.data_field == a.target)
            return low.param(slot.length_param) if slot.length_param else str(slot.length)
    return None


def machines_view(p: Protocol) -> dict:
    """Everything the machines template needs; empty when the schema declares none."""
    if not p.machines:
        return {"machines": [], "packers": [], "unpackers": []}
    built, received = set(), set()
    for m in p.machines:
        b, r = machine_messages(m)
        built.update(b)
        received.update(r)
    ordered = [m.name for m in p.messages]
    return {"machines": [machine_view(p, m) for m in p.machines],
            "packers": [pack_function(packet_layout(p, p.message(n))) for n in ordered if n in built],
            "unpackers": [unpack_function(packet_layout(p, p.message(n))) for n in ordered if n in received]}
