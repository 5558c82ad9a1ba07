"""Resolve and check the `machines` of a schema: states, events, guards and actions.

A machine is checked as a whole before any backend sees it: every name it uses
(state, event, variable, parameter, packet field, action) must be declared, every
value must fit the width it is compared with or stored in, every state must be
reachable and able to act, and every event must be handled in every state.
"""
from __future__ import annotations

from typing import Any, Optional

from .text import text
from ..model import (EVENT_LOCALS, EVENT_PARAMETERS, MACHINE_FUNCTIONS, MACHINE_MEMBERS,
                     PACKET_PARAMETERS, Action, Condition, Event, Field, Handler, Machine, Message, Source,
                     State, Transition, Variable, length_argument)

ACTION_KINDS = ("set", "flip", "increment", "keep", "transmit", "start_timer", "stop_timer",
                "deliver", "execute", "fail")


def bits_for(high: int) -> int:
    """Unsigned bits needed to hold 0..high."""
    return max(1, int(high).bit_length())


class MachineResolver:
    """Checks one machine against the resolved messages and parameters of its protocol."""

    def __init__(self, resolver, name: str, raw: dict, messages: tuple[Message, ...]):
        self.r = resolver
        self.name = name
        self.raw = raw
        self.path = ("machines", name)
        self.messages = {m.name: m for m in messages}
        self.variables: dict[str, Variable] = {}
        self.events: dict[str, Event] = {}
        self.actions: dict[str, Action] = {}

    def error(self, path: tuple, message: str, hint: str = "") -> None:
        self.r.error(self.path + path, f"machine {self.name!r}: {message}", hint)

    # -- widths ------------------------------------------------------------------------
    def parameter_bits(self, name: str) -> Optional[int]:
        param = self.r.parameters.get(name)
        if param is None or param.range is None:
            return None
        return bits_for(param.range[1])

    def field_of(self, message: Optional[str], name: str) -> Optional[Field]:
        m = self.messages.get(message or "")
        if m is None:
            return None
        return next((f for f in m.members if f.name == name and f.count is None), None)

    # -- declarations ------------------------------------------------------------------
    def resolve_declarations(self) -> None:
        raw = self.raw
        listed = raw.get("parameters", [])
        for i, p in enumerate(listed):
            if p in listed[:i]:
                self.error(("parameters", i), f"parameter {p!r} is listed twice", "list each parameter once")
            elif p not in self.r.parameters:
                self.error(("parameters",), f"unknown parameter {p!r}", "declare it under `parameters`")
        for vn, v in raw.get("variables", {}).items():
            vpath = ("variables", vn)
            self.r.check_name(vn, self.path + vpath, "variable")
            kind, bits = self.r.scalar_type(v["type"], self.path + vpath + ("type",))
            if kind not in ("uint", "bool") or not bits:
                self.error(vpath + ("type",), f"variable {vn!r}: type must be unsigned",
                           "use u1 … u32")
                bits = 8
            initial = v.get("initial", 0)
            if not self.r.int_fits(initial, "uint", bits):
                self.error(vpath + ("initial",),
                           f"variable {vn!r}: initial value {initial} does not fit {v['type']}",
                           "widen the variable or change the initial value")
            self.variables[vn] = Variable(vn, bits, initial)
        self.check_member_names()
        timers = []
        for en, e in raw["events"].items():
            epath = ("events", en)
            self.check_event_name(en, bool(e.get("timer")))
            self.check_packet_names(e.get("message"))
            for key in ("message", "request"):
                self.check_length_parameters(e.get(key), epath + (key,))
            if "message" in e and e["message"] not in self.messages:
                self.error(epath + ("message",), f"event {en!r}: unknown message {e['message']!r}",
                           "name a message under `messages`")
            if "message" in e and ("request" in e or e.get("timer")):
                self.error(epath, f"event {en!r}: a receive event is neither a request nor a timer",
                           "split it into separate events")
            if e.get("timer"):
                timers.append(en)
            request = e.get("request")
            if request is not None and request not in self.messages:
                self.error(epath + ("request",), f"event {en!r}: unknown message {request!r}",
                           "name a message under `messages`")
            if e.get("args") and request is None:
                self.error(epath + ("args",), f"event {en!r}: `args` needs `request`",
                           "name the message whose fields the arguments are")
            for arg in e.get("args", []):
                if request in self.messages and self.field_of(request, arg) is None:
                    self.error(epath + ("args",), f"event {en!r}: {request!r} has no field {arg!r}",
                               "arguments are fields of the request's message")
            self.check_argument_names(en, request, e.get("args", []), epath + ("args",))
            self.events[en] = Event(en, e.get("message"), bool(e.get("timer")), self.r_text(e.get("doc")),
                                    request, tuple(e.get("args", [])))
        if len(timers) > 1:
            self.error(("events",), f"{len(timers)} timer events ({', '.join(timers)}); a machine has one timer",
                       "keep one event with `timer: true`")
        for an, a in raw.get("actions", {}).items():
            self.actions[an] = self.resolve_action(an, a)
            if self.actions[an].kind in ("start_timer", "stop_timer") and not timers:
                self.error(("actions", an), f"action {an!r} uses a timer, but no event is the timer's",
                           "add an event with `timer: true` and handle it in every state")
        kept = [an for an, a in self.actions.items() if a.kind == "keep"]
        for an, a in self.actions.items():
            if a.kind == "transmit" and not kept:
                self.error(("actions", an), f"action {an!r} transmits the kept packet, but no action keeps one",
                           "add an action `keep: <message>` with the packet's fields and run it before")

    def check_argument_names(self, event: str, request: Optional[str], args: list, path: tuple) -> None:
        """The generated event function takes its own parameters and, after each bytes
        argument, that argument's length: an argument named like either would be declared twice."""
        lengths = {length_argument(a): a for a in args
                   if (f := self.field_of(request, a)) is not None and f.kind == "bytes"}
        for i, arg in enumerate(args):
            if arg in EVENT_PARAMETERS + EVENT_LOCALS:
                self.error(path + (i,), f"event {event!r}: argument {arg!r} has the name of a parameter or "
                                        f"local every event function has ({', '.join(EVENT_PARAMETERS + EVENT_LOCALS)})",
                           f"rename the field {arg!r} of {request!r}")
            elif arg in lengths:
                self.error(path + (i,), f"event {event!r}: argument {arg!r} has the name of the length the "
                                        f"event function takes after the bytes argument {lengths[arg]!r}",
                           f"rename the field {arg!r} of {request!r}")

    def check_member_names(self) -> None:
        """Variables and parameters are members of the generated machine, beside the ones
        every machine has; the constructor takes the parameters beside its own arguments;
        the packers take the length parameters beside their buffer."""
        for i, p in enumerate(self.raw.get("parameters", [])):
            if p in MACHINE_MEMBERS + PACKET_PARAMETERS:
                self.error(("parameters", i), f"parameter {p!r} has a name the generated machine uses "
                                              f"({', '.join(MACHINE_MEMBERS + PACKET_PARAMETERS)})",
                           f"rename the parameter {p!r}")
        for vn in self.raw.get("variables", {}):
            if vn in MACHINE_MEMBERS:
                self.error(("variables", vn), f"variable {vn!r} has a name the generated machine uses "
                                              f"({', '.join(MACHINE_MEMBERS)})", f"rename the variable {vn!r}")
            elif vn in self.raw.get("parameters", []):
                self.error(("variables", vn), f"variable {vn!r} has the name of a parameter of the machine",
                           f"rename the variable {vn!r}")

    def check_event_name(self, en: str, timer: bool) -> None:
        """An event is a function (C) and a method (Python) of the machine, beside its own and
        its members; the timer event's is always `tick`."""
        taken = [n for n in MACHINE_FUNCTIONS if not (timer and n == "tick")] + list(MACHINE_MEMBERS)
        if en in taken:
            self.error(("events", en), f"event {en!r} has the name of a function or member every "
                                       f"machine has ({', '.join(taken)})", f"rename the event {en!r}")
        elif en in self.raw.get("variables", {}) or en in self.raw.get("parameters", []):
            self.error(("events", en), f"event {en!r} has the name of a variable or parameter of the machine",
                       f"rename the event {en!r}")

    def check_packet_names(self, message: str) -> None:
        """The packer and unpacker of a message take its fields beside their buffer and the
        parameters its length depends on: a field so named would be declared twice."""
        m = self.messages.get(message)
        checked = self.r.machine_packets_checked  # once per protocol: every machine shares its packers
        if m is None or message in checked:
            return
        checked.add(message)
        lengths = {f.length_param for f in m.members if f.kind == "bytes" and f.length_param}
        for f in m.members:
            if f.name in PACKET_PARAMETERS or f.name in lengths:
                what = "a parameter the packet's length depends on" if f.name in lengths else \
                    f"a parameter of the functions that pack and unpack it ({', '.join(PACKET_PARAMETERS)})"
                self.r.error(self.field_path(message, f.name), f"field {f.name!r} of {message!r}, which "
                             f"machine {self.name!r} sends or receives, has the name of {what}",
                             f"rename the field {f.name!r}")

    def check_length_parameters(self, message: Optional[str], path: tuple) -> None:
        """A machine that packs or unpacks a message whose bytes a link parameter sizes
        takes that parameter: its code reads the length from it."""
        m = self.messages.get(message or "")
        if m is None:
            return
        taken = self.raw.get("parameters", [])
        for f in m.members:
            if f.kind == "bytes" and f.length_param and f.length_param not in taken:
                self.error(path, f"message {message!r} has {f.name!r} sized by parameter {f.length_param!r}, "
                                 f"which machine {self.name!r} does not take",
                           f"add {f.length_param!r} to the machine's `parameters`")
                return

    def field_path(self, message: str, name: str) -> tuple:
        """The path of a field's name in the document: in its message or in the envelope."""
        data = self.r.data
        for where in (("messages", message, "fields"), ("framing", "layout")):
            items = data
            for key in where:
                items = items.get(key, {}) if isinstance(items, dict) else {}
            for i, f in enumerate(items if isinstance(items, list) else []):
                if isinstance(f, dict) and f.get("name") == name:
                    return where + (i, "name")
        return ("messages", message)

    @staticmethod
    def r_text(value: Any):
        return text(value)

    # -- actions -----------------------------------------------------------------------
    def resolve_source(self, raw: Any, path: tuple) -> Source:
        if isinstance(raw, float):  # 3.0 passes the JSON Schema's `integer`
            self.error(path, f"{raw!r} is not an integer", f"write {int(raw)}" if raw.is_integer() else
                       "machine values are integers")
            return Source("const", None, int(raw) if raw.is_integer() else 0)
        if isinstance(raw, int):
            return Source("const", None, raw)
        kind, value = next(iter(raw.items()))
        if kind == "const":
            return Source("const", None, value)
        if kind == "var" and value not in self.variables:
            self.error(path, f"unknown variable {value!r}", "declare it under `variables`")
        if kind == "param":
            self.check_parameter(value, path)
        return Source(kind, value)

    def check_parameter(self, name: str, path: tuple) -> None:
        if name not in self.r.parameters:
            self.error(path, f"unknown parameter {name!r}", "declare it under `parameters`")
        elif name not in self.raw.get("parameters", []):
            self.error(path, f"parameter {name!r} is not listed in the machine's `parameters`",
                       "add it to the machine's `parameters`")

    def resolve_action(self, name: str, a: dict) -> Action:
        path = ("actions", name)
        self.r.check_name(name, self.path + path, "action")
        kind = next(k for k in ACTION_KINDS if k in a)
        extra = set(a) - {kind, "doc"} - ({"value"} if kind == "set" else set()) \
            - ({"fields"} if kind == "keep" else set())
        if extra:
            self.error(path, f"action {name!r}: {', '.join(sorted(extra))} does not go with {kind!r}",
                       "an action does one thing; split it")
        target = a[kind]
        value, fields = None, ()
        if kind in ("set", "flip", "increment"):
            var = self.variables.get(target)
            if var is None:
                self.error(path + (kind,), f"action {name!r}: unknown variable {target!r}",
                           "declare it under `variables`")
            elif kind == "flip" and var.bits != 1:
                self.error(path + (kind,), f"action {name!r}: flips {target!r}, which is {var.bits} bits wide",
                           "flip works on one-bit variables; declare it u1")
            if kind == "set":
                value = self.resolve_source(a["value"], path + ("value",))
        elif kind == "keep":
            self.check_packet_names(target)
            self.check_length_parameters(target, path + ("keep",))
            if target not in self.messages:
                self.error(path + ("keep",), f"action {name!r}: unknown message {target!r}",
                           "name a message under `messages`")
            else:
                arrays = [f.name for f in self.messages[target].members if f.count is not None]
                if arrays:
                    self.error(path + ("keep",), f"action {name!r}: {target!r} has the array {arrays[0]!r}, "
                                                 "and a machine's values are single numbers",
                               "keep a message without arrays")
                members = [f.name for f in self.messages[target].members]
                for fn in a["fields"]:
                    if fn not in members:
                        self.error(path + ("fields", fn), f"action {name!r}: {target!r} has no field {fn!r}",
                                   f"its fields are {', '.join(members)}")
                missing = [fn for fn in members if fn not in a["fields"]]
                if missing:
                    self.error(path + ("fields",), f"action {name!r}: no value for {', '.join(missing)}",
                               "give every field of the message a value")
            fields = tuple((fn, self.resolve_source(s, path + ("fields", fn))) for fn, s in a["fields"].items())
        elif kind == "start_timer":
            self.check_parameter(target, path + ("start_timer",))
        return Action(name, kind, None if kind == "stop_timer" else target, value, fields,
                      self.r_text(a.get("doc")))

    def source_bits(self, source: Source, event: Event, path: tuple) -> tuple[str, Optional[int]]:
        """(kind, bits) of a source in the context of one event: 'int' or 'bytes'.
        Reports a source the event cannot supply."""
        if source.kind == "const":
            return "const", None
        if source.kind == "var":
            var = self.variables.get(source.name)
            return "int", var.bits if var else None
        if source.kind == "param":
            return "int", self.parameter_bits(source.name)
        if source.kind in ("packet", "result"):
            if event.message is None:
                self.error(path, f"event {event.name!r} receives no packet to take {source.name!r} from",
                           "packet values exist only in receive events")
                return "int", None
            f = self.field_of(event.message, source.name)
            if f is None:
                self.error(path, f"message {event.message!r} has no field {source.name!r}",
                           "name a field of the received message")
                return "int", None
            return ("bytes" if f.kind == "bytes" else "int"), f.bits
        if source.kind == "request":
            if source.name not in event.args:
                self.error(path, f"event {event.name!r} has no argument {source.name!r}",
                           "request values exist only in request events that declare them in `args`")
                return "int", None
            f = self.field_of(event.request, source.name)
            return ("bytes" if f is not None and f.kind == "bytes" else "int"), f.bits if f else None
        return "int", None

    def check_store(self, source: Source, event: Event, width: Optional[int], is_bytes: bool,
                    what: str, path: tuple) -> None:
        kind, bits = self.source_bits(source, event, path)
        if kind == "const":
            if is_bytes and source.value != 0:
                self.error(path, f"{what}: a bytes field takes only the constant 0 (all zero bytes)",
                           "write {const: 0}")
            elif not is_bytes and width and not self.r.int_fits(source.value, "uint", width):
                self.error(path, f"{what}: {source.value} does not fit {width} bits", "use a smaller value")
            return
        if (kind == "bytes") != is_bytes:
            self.error(path, f"{what}: cannot store {'bytes' if kind == 'bytes' else 'a number'} in "
                             f"{'bytes' if is_bytes else 'a number'}", "take the value from a field of the same kind")
        elif not is_bytes and width and bits and bits > width:
            self.error(path, f"{what}: a {bits}-bit value does not fit {width} bits",
                       "widen the target or store a narrower value")

    def check_action_in(self, action: Action, event: Event, executed: bool, path: tuple) -> None:
        """Check that `event` supplies what `action` needs."""
        here = path + (action.name,)
        if action.kind == "set" and action.value and action.target in self.variables:
            var = self.variables[action.target]
            self.check_store(action.value, event, var.bits, False, f"action {action.name!r}", here)
        elif action.kind == "keep" and action.target in self.messages:
            for fn, source in action.fields:
                f = self.field_of(action.target, fn)
                if f is None:
                    continue
                if source.kind == "result" and not executed:
                    self.error(here, f"action {action.name!r} takes the result before `execute`",
                               "put the execute action first")
                self.check_store(source, event, f.bits, f.kind == "bytes",
                                 f"action {action.name!r}, field {fn!r}", here)
        elif action.kind in ("deliver", "execute"):
            if event.message is None:
                self.error(here, f"action {action.name!r} needs a received packet; event {event.name!r} has none",
                           "deliver and execute belong to receive events")
            elif self.field_of(event.message, action.target) is None:
                self.error(here, f"action {action.name!r}: message {event.message!r} has no field {action.target!r}",
                           "name a field of the received message")

    # -- guards ------------------------------------------------------------------------
    def resolve_guard(self, key: str, raw: Any, event: Event, path: tuple) -> Condition:
        op, operand = next(iter(raw.items())) if isinstance(raw, dict) else ("eq", raw)
        if event.message is not None:
            f = self.field_of(event.message, key)
            if f is None:
                self.error(path, f"guard names {key!r}, which is not a field of {event.message!r}",
                           "in a receive event guard keys are fields of the received message")
                return Condition(key, op, operand)
            width = f.bits
        elif key in self.variables:
            width = self.variables[key].bits
        elif key in self.r.parameters:
            self.check_parameter(key, path)
            width = self.parameter_bits(key)
        else:
            self.error(path, f"guard names {key!r}, which is neither a variable nor a parameter",
                       "guard keys of this event are variables or parameters")
            return Condition(key, op, operand)
        if op.endswith("_var"):
            var = self.variables.get(operand)
            if var is None:
                self.error(path, f"guard names unknown variable {operand!r}", "declare it under `variables`")
            elif width and var.bits != width:
                self.error(path, f"guard compares {key!r} ({width} bits) with variable {operand!r} ({var.bits} bits)",
                           "compare values of the same width")
        elif op.endswith("_param"):
            self.check_parameter(operand, path)
            pbits = self.parameter_bits(operand)
            if op.startswith(("eq", "ne")) and width and pbits and pbits > width:
                self.error(path, f"guard compares {key!r} ({width} bits) with parameter {operand!r} "
                                 f"({pbits} bits)", "narrow the parameter's range")
        else:
            values = operand if op in ("in", "range") else [operand]
            for v in values:
                if not isinstance(v, int) or isinstance(v, bool) or (width and not self.r.int_fits(v, "uint", width)):
                    self.error(path, f"guard value {v!r} does not fit {key!r} ({width} bits)",
                               "compare with a value the field or variable can hold")
        return Condition(key, op, operand)

    # -- states ------------------------------------------------------------------------
    def resolve_states(self) -> tuple[tuple[State, ...], dict[str, set[str]]]:
        states = self.raw["states"]
        edges: dict[str, set[str]] = {s: set() for s in states}
        resolved = []
        for sn, st in states.items():
            self.r.check_name(sn, self.path + ("states", sn), "state")
            on = st.get("on", {})
            for en in self.events:
                if en not in on:
                    self.error(("states", sn), f"state {sn!r} does not handle event {en!r}",
                               f"handle it, or write `{en}: ignore` or `{en}: error`")
            handlers = []
            for en, h in on.items():
                hp = ("states", sn, "on", en)
                event = self.events.get(en)
                if event is None:
                    self.error(hp, f"state {sn!r}: unknown event {en!r}", "declare it under `events`")
                    continue
                if h in ("ignore", "error"):
                    handlers.append(Handler(en, h))
                    continue
                rows = h if isinstance(h, list) else [h]
                transitions = []
                for i, t in enumerate(rows):
                    tp = hp + ((i,) if isinstance(h, list) else ())
                    if t["to"] not in states:
                        self.error(tp + ("to",), f"state {sn!r}: transition to unknown state {t['to']!r}",
                                   "declare the state under `states`")
                    else:
                        edges[sn].add(t["to"])
                    if not t.get("guard") and i < len(rows) - 1:
                        self.error(tp, f"state {sn!r}, event {en!r}: a row without a guard hides the rows after it",
                                   "the first matching row wins; put the unguarded row last")
                    guard = tuple(self.resolve_guard(k, v, event, tp + ("guard", k))
                                  for k, v in t.get("guard", {}).items())
                    executed = False
                    for j, an in enumerate(t.get("actions", [])):
                        action = self.actions.get(an)
                        if action is None:
                            known = ", ".join(self.actions) or "none"
                            self.error(tp + ("actions", j), f"unknown action {an!r}",
                                       f"define it under the machine's `actions` (defined: {known})")
                            continue
                        self.check_action_in(action, event, executed, tp + ("actions", j))
                        executed = executed or action.kind == "execute"
                    transitions.append(Transition(t["to"], guard, tuple(t.get("actions", []))))
                handlers.append(Handler(en, "transitions", tuple(transitions)))
            resolved.append(State(sn, self.r_text(st.get("doc")), tuple(handlers)))
        return tuple(resolved), edges

    def check_graph(self, states: tuple[State, ...], edges: dict[str, set[str]]) -> None:
        initial = self.raw["initial"]
        final = self.raw.get("final", [])
        for i, fn in enumerate(final):
            if fn not in edges:
                self.error(("final", i), f"final state {fn!r} is not declared", "declare it under `states`")
        reachable, todo = set(), [initial]
        while todo:
            s = todo.pop()
            if s in reachable or s not in edges:
                continue
            reachable.add(s)
            todo.extend(edges[s])
        for st in states:
            if st.name not in reachable:
                self.error(("states", st.name), f"state {st.name!r} is unreachable from {initial!r}",
                           "add a transition to it or delete it")
            # A state where every event is ignored or an error can never act again.
            if st.name not in final and not any(h.transitions for h in st.handlers):
                self.error(("states", st.name), f"state {st.name!r} has no way out",
                           "add a transition or list it under `final`")

    def resolve(self) -> Machine:
        raw = self.raw
        self.r.check_name(self.name, self.path, "machine")
        self.resolve_declarations()
        if raw["initial"] not in raw["states"]:
            self.error(("initial",), f"initial state {raw['initial']!r} is not declared",
                       "declare it under `states`")
        states, edges = self.resolve_states()
        self.check_graph(states, edges)
        return Machine(self.name, self.r.loc(*self.path), raw.get("role"), self.r_text(raw.get("doc")),
                       tuple(raw.get("parameters", [])), tuple(self.variables.values()),
                       tuple(self.events.values()), raw["initial"], tuple(raw.get("final", [])),
                       states, tuple(self.actions.values()))
