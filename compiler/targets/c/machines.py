"""C target, machines: a struct and sans-IO step functions per machine.

No heap: a machine holds its kept packet in a fixed buffer sized for the
largest data length. Time is an unsigned 32-bit tick passed in by the caller
(wrap-around safe). Each step fills a `<p>_machine_out_t`: at most one packet
to send, one delivery, one execution and one failure (the generator checks that
no transition produces more).
"""
from __future__ import annotations

from ...model import Action, Machine, Protocol, length_argument
from ..machines.lowering import Lowering
from ..machines.packets import MachineTargetError, PacketLayout, machine_messages, max_packet, packet_layout


def ctype(bits: int) -> str:
    return "uint8_t" if bits <= 8 else "uint16_t" if bits <= 16 else "uint32_t"


def param_ctype(p: Protocol, name: str) -> str:
    param = next(x for x in p.parameters if x.name == name)
    return ctype(int(param.range[1]).bit_length()) if param.range else "uint32_t"


class CLowering(Lowering):
    AND = " && "
    OR = " || "

    def __init__(self, p: Protocol, machine: Machine, px: str):
        super().__init__(p, machine)
        self.px = px

    def var(self, name): return f"m->{name}"
    def param(self, name): return f"m->{name}"
    def packet(self, name): return f"p_{name}"
    def request(self, name): return name
    def result(self, name): return f"r_{name}"
    def goto(self, state): return f"m->state = {self.state_const(state)};"
    def zero_bytes(self, message, field): return "NULL"

    def state_const(self, state: str) -> str:
        return f"{self.px.upper()}_{self.m.name.upper()}_{state.upper()}"

    def data_length(self, message: str, field: str) -> str:
        slot = next(s for s in self.layouts[message].slots if s.data_field == field)
        return self.param(slot.length_param) if slot.length_param else f"{slot.length}u"

    def received(self) -> str:
        return next(e.message for e in self.m.events if e.message)

    SPELLING = {
        "set": "{var} = ({ctype})({value});",
        "flip": "{var} ^= 1u;",
        "increment": "{var} = ({ctype})(({var} + 1u) & {mask:#x}u);",
        "transmit": ("memcpy(out->sent, m->kept, m->kept_len);", "out->sent_len = m->kept_len;"),
        "start_timer": ("m->timer_on = true;", "m->deadline = now + {param};"),
        "stop_timer": "m->timer_on = false;",
        "fail": 'out->failed = "{target}";',
    }

    def action_word(self, key: str, a: Action) -> object:
        if key == "ctype":  # a variable's own width
            return ctype(self.var_bits(a.target))
        return super().action_word(key, a)

    def lower_keep(self, a: Action) -> list[str]:
        layout = self.layouts[a.target]
        given = dict(a.fields)
        args = ["m->kept"] + [self.param(n) for n in layout.length_params()]
        args += [self.source(given[n], a.target, n) for n in layout.members]
        return [f"m->kept_len = {self.px}_machine_pack_{a.target}({', '.join(args)});"]

    def lower_deliver(self, a: Action) -> list[str]:
        size = self.data_length(self.received(), a.target)
        sink = "delivered" if a.kind == "deliver" else "executed"
        return [f"memcpy(out->{sink}, {self.packet(a.target)}, {size});", f"out->{sink}_len = {size};"]

    def lower_execute(self, a: Action) -> list[str]:
        size = self.data_length(self.received(), a.target)
        r = self.result(a.target)
        return self.lower_deliver(a) + [
            f"if (m->execute != NULL) m->execute(m->execute_ctx, {self.packet(a.target)}, {size}, {r});",
            f"else memset({r}, 0, {size});"]


def check_single_outputs(machine: Machine) -> None:
    for state in machine.states:
        for h in state.handlers:
            for t in h.transitions:
                kinds = [machine.action(a).kind for a in t.actions]
                for kind in ("transmit", "deliver", "execute", "fail"):
                    if kinds.count(kind) > 1:
                        raise MachineTargetError(f"{machine.name}: state {state.name}: more than one {kind} in a step", machine.loc)


def pack_view(p: Protocol, layout: PacketLayout, px: str) -> dict:
    name = lambda n: n  # noqa: E731 - parameters are plain arguments here
    params = [f"{param_ctype(p, n)} {n}" for n in layout.length_params()]
    members = []
    for n in layout.members:
        members.append(f"const uint8_t *{n}" if n in layout.data_members else f"uint8_t {n}")
    lines = []
    for slot in layout.slots:
        at = slot.at.expr(name)
        if slot.data_field:
            size = slot.length_param or f"{slot.length}u"
            lines.append(f"if ({slot.data_field} != NULL) memcpy(b + {at}, {slot.data_field}, {size});")
            lines.append(f"else memset(b + {at}, 0, {size});")
            continue
        # each shifted part cast back to a byte: a uint8_t shifts as an int, which would
        # meet an unsigned constant in `|` as a signed value
        parts = [bp.field if bp.shift == 0 else f"(uint8_t)({bp.field} << {bp.shift})"
                 for bp in slot.parts if bp.const is None]
        if slot.const_value or not parts:
            parts.insert(0, f"{slot.const_value:#04x}u")
        lines.append(f"b[{at}] = (uint8_t)({' | '.join(parts)});")
    unpack = [f"if (n != (size_t)({layout.size.expr(name)})) return false;"]
    for slot in layout.slots:
        at = slot.at.expr(name)
        if slot.data_field:
            unpack.append(f"*{slot.data_field} = b + {at};")
            continue
        if slot.const_mask == 0xff:
            unpack.insert(1, f"if (b[{at}] != {slot.const_value:#04x}u) return false;")
        elif slot.const_mask:
            unpack.insert(1, f"if ((b[{at}] & {slot.const_mask:#04x}u) != {slot.const_value:#04x}u) return false;")
        for bp in slot.parts:
            if bp.const is None:
                v = f"b[{at}]" if bp.shift == 0 else f"(b[{at}] >> {bp.shift})"
                unpack.append(f"*{bp.field} = {v};" if bp.mask == 0xff >> bp.shift
                              else f"*{bp.field} = (uint8_t)({v} & {bp.mask:#x}u);")
    out_members = [f"const uint8_t **{n}" if n in layout.data_members else f"uint8_t *{n}" for n in layout.members]
    return {"message": layout.message, "size": layout.size.expr(name),
            "pack_args": ", ".join(["uint8_t *b"] + params + members), "pack": lines,
            "unpack_args": ", ".join(["const uint8_t *b", "size_t n"] + params + out_members), "unpack": unpack}


def machine_view(p: Protocol, machine: Machine, px: str) -> dict:
    check_single_outputs(machine)
    low = CLowering(p, machine, px)
    events = []
    for code in low.events():
        e = code.event
        args, checks, prologue = [], [], []
        if e.request:
            message = p.message(e.request)
            for arg in e.args:
                f = next(x for x in message.members if x.name == arg)
                if f.kind == "bytes":
                    args += [f"const uint8_t *{arg}", f"size_t {length_argument(arg)}"]
                    size = low.param(f.length_param) if f.length_param else f"{f.length}u"
                    checks.append(f"{arg} == NULL || {length_argument(arg)} != {size}")
                else:
                    args.append(f"{ctype(f.bits)} {arg}")
                    if f.bits < 8:
                        checks.append(f"{arg} > {(1 << f.bits) - 1}u")
        if code.packet:
            args += ["const uint8_t *packet", "size_t len"]
            layout = code.packet
            for n in layout.members:
                prologue.append(f"const uint8_t *p_{n} = NULL;" if n in layout.data_members else f"uint8_t p_{n} = 0u;")
            outs = ", ".join(f"&p_{n}" for n in layout.members)
            lengths = "".join(", " + low.param(n) for n in layout.length_params())
            prologue.append(f"if (packet == NULL || !{px}_machine_unpack_{layout.message}(packet, len{lengths}, {outs})) {{")
            prologue.append("    out->dropped = true;")
            prologue.append("    return 0;")
            prologue.append("}")
            for a in machine.actions:  # what the application returns, for each field it executes
                if a.kind == "execute":
                    prologue.append(f"uint8_t {low.result(a.target)}[{px.upper()}_MACHINE_MAX_DATA];")
        cases = []
        for case in code.cases:
            branches = []
            for i, row in enumerate(case.rows):
                head = None if not row.guard and i == 0 else \
                    ("} else {" if not row.guard else (f"if ({row.guard}) {{" if i == 0 else f"}} else if ({row.guard}) {{"))
                branches.append({"head": head, "body": list(row.body)})
            closes = any(b["head"] for b in branches)
            cases.append({"const": low.state_const(case.state), "kind": case.kind, "branches": branches,
                          "close": closes})
        name = "tick" if e.timer else e.name
        events.append({"fn": f"{px}_{machine.name}_{name}", "doc": e.doc or e.name, "timer": e.timer,
                       "args": "".join(", " + a for a in args), "checks": checks, "prologue": prologue,
                       "cases": cases})
    params = []
    for n in machine.parameters:
        rng, t = next(x for x in p.parameters if x.name == n).range, param_ctype(p, n)
        limit = (1 << {"uint8_t": 8, "uint16_t": 16, "uint32_t": 32}[t]) - 1
        checks = []  # only the bounds the C type does not already enforce
        if rng and rng[0] > 0:
            checks.append(f"{n} < {int(rng[0])}u")
        if rng and rng[1] < limit:
            checks.append(f"{n} > {int(rng[1])}u")
        params.append({"name": n, "ctype": t, "checks": checks})
    return {"t": f"{px}_{machine.name}_t", "name": machine.name, "fn": f"{px}_{machine.name}",
            "doc": machine.doc or machine.name,
            "states": [(low.state_const(s.name), s.doc or s.name) for s in machine.states],
            "initial": low.state_const(machine.initial),
            "variables": [(ctype(v.bits), v.name, v.initial, v.doc if hasattr(v, "doc") else "")
                          for v in machine.variables],
            "params": params, "events": events, "executes": low.uses("execute"),
            "timer": any(e.timer for e in machine.events)}


def data_size(p: Protocol, slot) -> int:
    """The most bytes a data field holds: its fixed length, or its parameter's largest value."""
    if slot.length_param is None:
        return slot.length
    param = next(x for x in p.parameters if x.name == slot.length_param)
    return int(param.range[1] if param.range else param.default)


def machines_view(p: Protocol) -> dict:
    if not p.machines:
        return {"machines": []}
    px = p.name.lower()
    built, received = [], []
    for m in p.machines:
        b, r = machine_messages(m)
        built += [n for n in b if n not in built]
        received += [n for n in r if n not in received]
    layouts = {n: packet_layout(p, p.message(n)) for n in built + received}
    max_size = max(max_packet(p, layout) for layout in layouts.values())
    data = [data_size(p, slot) for layout in layouts.values() for slot in layout.slots if slot.data_field]
    ordered = [m.name for m in p.messages if m.name in layouts]
    return {"machines": [machine_view(p, m, px) for m in p.machines], "PX": px.upper(), "px": px,
            "max_packet": max_size, "max_data": max(data, default=1),
            "packets": [dict(pack_view(p, layouts[n], px), build=n in built, read=n in received)
                        for n in ordered]}
