"""The delivery pair as generated Python code: which classes the simulator builds
and which methods it calls, found with the Python target's own naming from the
schema's `delivery` section. Machine parameters other than the address, the
timeout and the retry limit, which the simulator sets, are passed by name: the
caller's value, else the schema's default."""
from __future__ import annotations

import types
from typing import Mapping, Optional

from ..model import Machine, Protocol, field_at
from ..targets.python.machines import EXECUTE_ARGUMENT, class_name, method_name


def receive_method(machine: Machine) -> str:
    """The method a machine takes packets with (the resolver allows one receive event)."""
    return method_name(next(e for e in machine.events if e.message is not None))


class Pair:
    """A protocol's sender and receiver machines in a generated module."""

    def __init__(self, p: Protocol, module: types.ModuleType, parameters: Optional[Mapping[str, int]] = None):
        if p.delivery is None:
            raise ValueError(f"{p.name} declares no `delivery` section: the simulator has no machines to drive")
        d = self.delivery = p.delivery
        sender, receiver = p.machine(d.sender), p.machine(d.receiver)
        self.sender_class = getattr(module, class_name(sender))
        self.receiver_class = getattr(module, class_name(receiver))
        self.idle = sender.initial  # no request outstanding
        self.send_method = method_name(sender.event(d.request))
        self.sender_receive = receive_method(sender)
        self.tick = method_name(next(e for e in sender.events if e.timer))
        self.receiver_receive = receive_method(receiver)
        values = other_parameters(p, (sender, receiver), parameters or {})
        self.sender_values = {n: values[n] for n in sender.parameters if n in values}
        self.receiver_values = {n: values[n] for n in receiver.parameters if n in values}
        data = field_at(p.message(sender.event(d.request).request).fields, d.data_arg)
        self.data_length = values[data.length_param] if data.length_param else data.length

    def new_sender(self, address: int, timeout: int, retry_limit: int):
        d = self.delivery
        return self.sender_class(**{d.address: address, d.timeout: timeout, d.retry_limit: retry_limit},
                                 **self.sender_values)

    def new_receiver(self, address: int, execute):
        return self.receiver_class(**{self.delivery.address: address, EXECUTE_ARGUMENT: execute},
                                   **self.receiver_values)

    def send(self, sender, now: int, address: int, data: bytes):
        """The application's request to `address`."""
        d = self.delivery
        return getattr(sender, self.send_method)(now, **{d.address_arg: address, d.data_arg: data})


def other_parameters(p: Protocol, machines: tuple[Machine, ...], given: Mapping[str, int]) -> dict[str, int]:
    """Values of the parameters the simulator does not set itself."""
    d = p.delivery
    names = list(dict.fromkeys(n for m in machines for n in m.parameters
                               if n not in (d.address, d.timeout, d.retry_limit)))
    unknown = sorted(set(given) - set(names))
    if unknown:
        raise ValueError(f"unknown parameter {unknown[0]!r}; the machines take {', '.join(names) or 'no others'}")
    defaults = {x.name: x.default for x in p.parameters}
    values = {}
    for name in names:
        value = given.get(name, defaults.get(name))
        if value is None:
            raise ValueError(f"parameter {name!r} has no default: give it a value")
        values[name] = value
    return values
