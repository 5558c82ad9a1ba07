"""Promela target: generated/promela/<protocol>.pml, the declared machines as a
model for the SPIN model checker.

One proctype per machine, running the same rows in the same order as the
generated code (the first row whose guard holds wins). What the model abstracts:

- Packets travel on one channel per message; a send may be lost, or arrive
  twice, but packets never overtake each other (a FIFO that drops and repeats).
  A corrupted packet is dropped by the receiving end's CRC check, so it is a
  loss.
- Data bytes carry a command number (1..CMDS, cycling) instead of L bytes: the
  application asks to send the next number, the executing side checks that it
  runs every number once and in order, and the delivering side checks that the
  reply carries the number of the outstanding command.
- A timer may expire at any time while it runs: an early timeout only adds
  resends, which the channel could produce anyway.
- Parameters with a default take it (overridable with -D<NAME>=value); a
  parameter without one is a device identity, distinct per machine.
- A request's data argument is the command number; its other arguments address
  the machine that receives the request's message.
"""
from __future__ import annotations

from ...diagnostics import Diagnostic, Loc, SchemaError
from ...model import Action, Event, Machine, Protocol
from ..machines.lowering import Lowering
from ..machines.packets import MachineTargetError, machine_messages
from ..render import environment, tidy

CHANNEL_CAPACITY = 4  # a packet, its duplicate and resends in flight
COMMAND_NUMBERS = 4  # more than the two a one-bit sequence number tells apart


def macro(name: str) -> str:
    return name.upper()


def restart_macro(machine: Machine) -> str:
    """The -D flag name that lets a machine restart at any time."""
    return f"{macro(machine.name)}_RESTART"


class PromelaLowering(Lowering):
    AND = " && "
    OR = " || "

    def var(self, name): return f"{self.m.name}_{name}"
    def param(self, name): return f"{self.m.name}_{name}"
    def packet(self, name): return f"{self.m.name}_p_{name}"
    def request(self, name): return f"{self.m.name}_q_{name}"
    def result(self, name): return f"{self.m.name}_x_{name}"
    def state_value(self, name): return f"{self.m.name}_{name}"
    def goto(self, state): return f"{self.m.name}_state = {self.state_value(state)}"
    def zero_bytes(self, message, field): return "0"

    def kept(self, field: str) -> str:
        return f"{self.m.name}_kept_{field}"

    def kept_message(self) -> str | None:
        built, _ = machine_messages(self.m)
        if len(built) > 1:
            raise MachineTargetError(f"{self.m.name}: the Promela model keeps one message per machine, "
                                     f"not {', '.join(built)}")
        return built[0] if built else None

    SPELLING = {
        "set": "{var} = {value}",
        "flip": "{var} = 1 - {var}",
        "increment": "{var} = ({var} + 1) & {mask}",
        "start_timer": "{machine}_timer = true",
        "stop_timer": "{machine}_timer = false",
        "deliver": "app_deliver({packet})",
        "execute": "app_execute({packet}, {result})",
        "fail": "app_fail()",
    }

    def lower_keep(self, a: Action) -> list[str]:
        given = dict(a.fields)
        return [f"{self.kept(n)} = {self.source(given[n], a.target, n)}" for n in self.layouts[a.target].members]

    def lower_transmit(self, a: Action) -> list[str]:
        message = self.kept_message()
        members = self.layouts[message].members
        return [f"transmit_{message}({', '.join(self.kept(n) for n in members)})"]


def variable_type(bits: int) -> str:
    return "bit" if bits == 1 else "byte" if bits <= 8 else "short" if bits <= 15 else "int"


def exclusive_rows(rows) -> list[dict]:
    """Promela's `if` picks any true guard; each row's guard also denies the
    earlier ones, so the first matching row wins as in the generated code."""
    out, earlier = [], []
    for row in rows:
        if not row.guard:
            guard = "else" if earlier else "true"
        else:
            guard = " && ".join([f"({row.guard})"] + [f"!({g})" for g in earlier])
        out.append({"guard": guard, "body": list(row.body) or ["skip"]})
        if not row.guard:
            break
        earlier.append(row.guard)
    if out and out[-1]["guard"] not in ("else", "true"):
        out.append({"guard": "else", "body": ["skip"]})
    return out


def identity_params(p: Protocol) -> dict[tuple[str, str], int]:
    """(machine, parameter) -> value for parameters without a default: distinct per machine."""
    out = {}
    for i, m in enumerate(p.machines, start=1):
        for name in m.parameters:
            param = next(x for x in p.parameters if x.name == name)
            if param.default is None:
                out[(m.name, name)] = i
    return out


def parameter_views(p: Protocol, machine: Machine, identities) -> list[dict]:
    out = []
    for name in machine.parameters:
        param = next(x for x in p.parameters if x.name == name)
        if param.default is None:
            out.append({"name": f"{machine.name}_{name}", "value": str(identities[(machine.name, name)]),
                        "doc": "device identity, distinct per machine"})
        else:
            out.append({"name": f"{machine.name}_{name}", "value": macro(name), "doc": ""})
    return out


def link_parameters(p: Protocol) -> list[dict]:
    """Parameters with a default, as macros a -D option can override."""
    used = {n for m in p.machines for n in m.parameters}
    return [{"macro": macro(x.name), "default": int(x.default), "name": x.name}
            for x in p.parameters if x.name in used and x.default is not None]


def receiver_of(p: Protocol, message: str) -> Machine:
    for m in p.machines:
        if any(e.message == message for e in m.events):
            return m
    raise MachineTargetError(f"no machine receives {message!r}: its packets would go nowhere")


def request_values(p: Protocol, low: PromelaLowering, event: Event, identities) -> list[str]:
    """Statements giving the request's arguments: the next command number for data,
    the receiving machine's identity for anything else."""
    message = p.message(event.request)
    target = receiver_of(p, message.name)
    statements = []
    for arg in event.args:
        f = next(x for x in message.members if x.name == arg)
        if f.kind == "bytes":
            statements.append(f"app_request({low.request(arg)})")
            continue
        ident = [v for (m, _), v in identities.items() if m == target.name]
        if not ident:
            raise MachineTargetError(f"{low.m.name}.{event.name}: {arg} must address {target.name}, "
                                     "which has no identity parameter")
        statements.append(f"{low.request(arg)} = {ident[0]}")
    return statements


def event_view(p: Protocol, low: PromelaLowering, code, identities) -> dict:
    e = code.event
    asked = e.message is None and not e.timer  # the application's: a request, with or without values
    cases = []
    for case in code.cases:
        if case.kind == "rows":
            cases.append({"state": low.state_value(case.state), "rows": exclusive_rows(case.rows)})
        elif case.kind == "error" and not asked:
            # a packet or a timer the machine cannot take is a model error
            refused = f"assert(false) /* {e.name} refused in {case.state} */"
            cases.append({"state": low.state_value(case.state), "rows": [{"guard": "true", "body": [refused]}]})
    view = {"name": e.name, "cases": cases, "enable": "", "prelude": [], "receive": None}
    if asked:
        # the application only asks where the machine accepts the request
        view["enable"] = " || ".join(f"{low.var('state')} == {c['state']}" for c in cases) or "false"
        view["prelude"] = request_values(p, low, e, identities) if e.request else []
    elif e.timer:
        view["enable"] = f"{low.m.name}_timer"
        view["prelude"] = [f"{low.m.name}_timer = false"]
    else:
        members = code.packet.members
        view["receive"] = f"{code.packet.message}_ch?{', '.join(low.packet(n) for n in members)}"
    return view


def machine_view(p: Protocol, machine: Machine, identities) -> dict:
    low = PromelaLowering(p, machine)
    kept = low.kept_message()
    if kept is not None:
        receiver_of(p, kept)  # a packet sent is a packet some machine of the model receives
    received = [e.message for e in machine.events if e.message]
    request_args = []
    for e in machine.events:
        if e.request:
            request_args.extend(low.request(a) for a in e.args)
    results = [low.result(a.target) for a in machine.actions if a.kind == "execute"]
    packet_fields = [low.packet(n) for n in dict.fromkeys(
        n for msg in received for n in low.layouts[msg].members)]
    return {
        "name": machine.name,
        "restart": restart_macro(machine),
        "restart_guard": f"!{machine.name}_timer" if any(e.timer for e in machine.events) else "true",
        "states": [{"name": low.state_value(s.name), "value": i} for i, s in enumerate(machine.states)],
        "initial": low.state_value(machine.initial),
        "variables": [{"name": low.var(v.name), "type": variable_type(v.bits), "initial": v.initial}
                      for v in machine.variables],
        "kept": [low.kept(n) for n in low.layouts[kept].members] if kept else [],
        "timer": any(e.timer for e in machine.events),
        "locals": packet_fields + request_args + results,
        "params": parameter_views(p, machine, identities),
        "events": [event_view(p, low, code, identities) for code in low.events()],
    }


def channel_views(p: Protocol) -> list[dict]:
    names = [m.name for m in p.messages]
    used = sorted({e.message for m in p.machines for e in m.events if e.message}, key=names.index)
    out = []
    for name in used:
        low = PromelaLowering(p, receiver_of(p, name))
        members = low.layouts[name].members
        out.append({"message": name, "capacity": CHANNEL_CAPACITY, "members": members,
                    "types": ", ".join("byte" for _ in members)})
    return out


def render(p: Protocol) -> dict[str, str]:
    if not p.machines:
        return {}
    identities = identity_params(p)
    try:
        view = {"p": p, "channels": channel_views(p), "params": link_parameters(p),
                "machines": [machine_view(p, m, identities) for m in p.machines],
                "commands": COMMAND_NUMBERS}
    except MachineTargetError as exc:  # a shape the model cannot express: report it against the schema
        raise SchemaError([Diagnostic(p.machines[0].loc if p.machines else Loc(p.file, 1, 1),
                                      f"no Promela model: {exc}",
                                      "the Promela target handles one kept message per machine "
                                      "and packets received by some machine")]) from exc
    text = environment().get_template("promela/protocol.pml.j2").render(**view)
    return {f"promela/{p.name}.pml": tidy(text, max_blank=1)}
