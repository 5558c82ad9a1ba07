"""The `delivery` section: which two machines deliver application requests over
a lossy link, the parameters the lossy-link simulator sets, and the notes that
state the guarantee and its limits. Everything the simulator and the docs'
delivery section rely on is checked here, so neither needs to look again."""
from __future__ import annotations

from typing import Optional

from ..model import Delivery, DeliveryNotes, Event, Field, Machine, Message, field_at
from .base import ResolverBase

NOTE_KEYS = ("guarantee", "retry_limit", "restart")
# parameter key -> the roles whose machine must take it
PARAMETER_USERS = {"address": ("sender", "receiver"), "timeout": ("sender",), "retry_limit": ("sender",)}
# the simulator's devices: a sender and up to four receivers, at these addresses
# where the protocol admits them all, else at the lowest addresses it admits
PREFERRED_ADDRESSES = (1, 3, 4, 5, 6)
# how far above the lowest admitted address the search for others goes
ADDRESS_SEARCH = 1 << 16


class DeliveryMixin(ResolverBase):
    def delivery_error(self, key: tuple, message: str, hint: str) -> None:
        self.error(("delivery",) + key, f"delivery: {message}", hint)

    def resolve_delivery(self, raw: dict, machines: tuple[Machine, ...],
                         messages: tuple[Message, ...]) -> Optional[Delivery]:
        declared = {m.name: m for m in machines}
        pair = {role: self.delivery_machine(raw[role], role, declared) for role in ("sender", "receiver")}
        sender, receiver = pair["sender"], pair["receiver"]
        if sender is not None and sender is receiver:
            self.delivery_error(("receiver",), f"the receiver is the sender, {sender.name!r}",
                                "name two machines: one sends requests and resends them, the other executes them")
        request = args = None
        if sender is not None:
            by_name = {m.name: m for m in messages}
            request = self.delivery_request(sender, by_name)
            args = self.address_and_data(sender, request, by_name) if request else None
            if not any(e.timer for e in sender.events):
                self.delivery_error(("sender",), f"sender {sender.name!r} has no timer event",
                                    "the sender resends on its timer: declare an event with `timer: true`")
            elif not any(a.kind == "start_timer" and a.target == raw["timeout"] for a in sender.actions):
                self.delivery_error(("timeout",), f"sender {sender.name!r} starts no timer with parameter "
                                                  f"{raw['timeout']!r}",
                                    "name the parameter the sender's `start_timer` action takes")
        if receiver is not None and not any(a.kind == "execute" for a in receiver.actions):
            self.delivery_error(("receiver",), f"receiver {receiver.name!r} has no `execute` action",
                                "the receiver hands each new request to the application with `{execute: <field>}`")
        for role, machine in pair.items():
            if machine is not None:
                self.one_receive_event(role, machine)
        self.delivery_parameters(raw, pair)
        notes = self.delivery_notes(raw["notes"])
        if self.report.diagnostics:  # here or in the machines: nothing to build from
            return None
        addresses = self.device_addresses(raw["address"], (sender, receiver), request, args[0], by_name)
        if addresses is None:
            return None
        return Delivery(sender=sender.name, receiver=receiver.name, address=raw["address"],
                        timeout=raw["timeout"], retry_limit=raw["retry_limit"], request=request.name,
                        address_arg=args[0], data_arg=args[1], addresses=addresses, notes=notes,
                        loc=self.loc("delivery"))

    def delivery_machine(self, name: str, role: str, declared: dict[str, Machine]) -> Optional[Machine]:
        machine = declared.get(name)
        if machine is None:
            self.delivery_error((role,), f"unknown machine {name!r}",
                                f"name a machine under `machines` (declared: {', '.join(declared) or 'none'})")
        return machine

    def delivery_request(self, sender: Machine, messages: dict[str, Message]) -> Optional[Event]:
        """The sender's one application request event."""
        requests = [e for e in sender.events if e.request is not None]
        if len(requests) != 1:
            found = f"{len(requests)} ({', '.join(e.name for e in requests)})" if requests else "no"
            self.delivery_error(("sender",), f"sender {sender.name!r} has {found} application request "
                                             "events; the simulator sends through exactly one",
                                "keep one event with `request: <message>` and `args: [<address>, <data>]`")
            return None
        return requests[0] if requests[0].request in messages else None  # else the machine reported it

    def address_and_data(self, sender: Machine, request: Event,
                         messages: dict[str, Message]) -> Optional[tuple[str, str]]:
        """(address argument, data argument) of the request: an integer field that
        addresses the receiver and a bytes field the receiver executes."""
        kinds = {f.name: f.kind for f in messages[request.request].members}
        addresses = [a for a in request.args if kinds.get(a) in ("uint", "bool")]
        data = [a for a in request.args if kinds.get(a) == "bytes"]
        if len(request.args) != 2 or len(addresses) != 1 or len(data) != 1:
            self.error(("machines", sender.name, "events", request.name, "args"),
                       f"delivery: request event {request.name!r} of sender {sender.name!r} takes "
                       f"[{', '.join(request.args)}]; it needs two arguments: the receiver's address "
                       "(an integer field) and the data (a bytes field)",
                       "write `args: [<address field>, <data field>]`")
            return None
        return addresses[0], data[0]

    def device_addresses(self, parameter: str, machines: tuple[Machine, Machine], request: Event,
                         address_arg: str, messages: dict[str, Message]) -> Optional[tuple[int, ...]]:
        """The addresses the simulator gives its devices: values the address parameter's
        range admits and that every field an address is written to can carry. At least
        two, a sender's and a receiver's; else the schema is refused here."""
        fields = [field_at(messages[request.request].members, address_arg)]
        for machine in machines:
            for action in machine.actions:
                target = messages.get(action.target or "")
                for name, source in action.fields:
                    if target is not None and (source.kind, source.name) in (("param", parameter),
                                                                                ("request", address_arg)):
                        fields.append(field_at(target.members, name))
        fields = [f for f in fields if f is not None]
        low, high = self.parameters[parameter].integers or (0, ADDRESS_SEARCH)
        low = max(0, low)
        high = min([high, low + ADDRESS_SEARCH] + [(1 << f.bits) - 1 for f in fields if f.bits])

        def admitted(value: int) -> bool:
            return all(carries(f, value) for f in fields)

        if all(low <= a <= high and admitted(a) for a in PREFERRED_ADDRESSES):
            return PREFERRED_ADDRESSES
        found: list[int] = []
        value = low
        while value <= high and len(found) < len(PREFERRED_ADDRESSES):
            if admitted(value):
                found.append(value)
            value += 1
        if len(found) < 2:
            carried = ", ".join(sorted({f.name for f in fields}))
            self.delivery_error(("address",), f"parameter {parameter!r} admits "
                                f"{'only the address ' + str(found[0]) if found else 'no address'} that "
                                f"the fields it is written to ({carried}) can carry; a sender and a receiver "
                                "need two different addresses",
                                f"widen the range of {parameter!r} (and of those fields) to hold at least two values")
            return None
        return tuple(found)

    def one_receive_event(self, role: str, machine: Machine) -> None:
        receives = [e.name for e in machine.events if e.message is not None]
        if len(receives) != 1:
            found = f"{len(receives)} receive events ({', '.join(receives)})" if receives else "no receive event"
            self.delivery_error((role,), f"{role} {machine.name!r} has {found}; the simulator hands every "
                                         "packet a device hears to exactly one",
                                "keep one event with `message: <message>`")

    def delivery_parameters(self, raw: dict, pair: dict[str, Optional[Machine]]) -> None:
        if len({raw[key] for key in PARAMETER_USERS}) < len(PARAMETER_USERS):
            self.delivery_error((), "address, timeout and retry_limit name the same parameter twice",
                                "name three different parameters")
        for key, roles in PARAMETER_USERS.items():
            name = raw[key]
            if name not in self.parameters:
                self.delivery_error((key,), f"unknown parameter {name!r}", "declare it under `parameters`")
                continue
            for role in roles:
                machine = pair[role]
                if machine is not None and name not in machine.parameters:
                    self.delivery_error((key,), f"{role} {machine.name!r} does not take parameter {name!r}",
                                        "add it to the machine's `parameters`")

    def delivery_notes(self, raw: dict) -> DeliveryNotes:
        ids = [n["id"] for n in self.data.get("notes", [])]
        for key in NOTE_KEYS:
            if raw[key] not in ids:
                self.delivery_error(("notes", key), f"unknown note {raw[key]!r}",
                                    f"cite the id of a note under `notes` ({', '.join(ids) or 'none declared'})")
        return DeliveryNotes(**{key: raw[key] for key in NOTE_KEYS})


def carries(f: Field, value: int) -> bool:
    """Whether an integer field takes `value` as written: in its width, its range
    (of a field whose range counts raw values) and its listed values."""
    if f.kind == "bool":
        return value in (0, 1)
    if f.bits and not 0 <= value < 1 << f.bits:
        return False
    if f.range is not None and f.scale is None and f.offset is None and not f.range[0] <= value <= f.range[1]:
        return False
    if f.values is not None and value not in f.values:
        return False
    return f.enum is None or any(m.value == value for m in f.enum.members)
