"""Byte layout of the packets a machine builds and reads, with link-time data lengths.

The codecs fix a `bytes` field's length at its parameter's default; a machine
takes the length as a link parameter, so it packs and unpacks with offsets that
depend on it. Every target reads the same `PacketLayout`: bytes framing, fields of
at most 8 bits packed MSB first inside whole bytes, whole-byte data fields.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Optional

from ...model import Machine, Message, Protocol


class MachineTargetError(ValueError):
    """A machine uses a packet shape the machine targets cannot generate; loc is where the
    schema asks for it, when known."""

    def __init__(self, message: str, loc=None):
        super().__init__(message)
        self.loc = loc


@dataclass(frozen=True)
class Offset:
    """`base` bytes plus `lengths` link data lengths (by parameter name)."""

    base: int
    lengths: tuple[str, ...] = ()

    def plus(self, n: int) -> "Offset":
        return Offset(self.base + n, self.lengths)

    def plus_length(self, param: str) -> "Offset":
        return Offset(self.base, self.lengths + (param,))

    def expr(self, name_of) -> str:
        """The offset as an expression; `name_of(param)` spells a parameter in the target."""
        parts = [name_of(p) for p in self.lengths]
        if self.base or not parts:
            parts.append(str(self.base))
        return " + ".join(parts)


@dataclass(frozen=True)
class BitPart:
    field: str
    shift: int
    mask: int  # of the value, before the shift
    const: Optional[int]  # constant (incl. reserved = 0) or None for a member field


@dataclass(frozen=True)
class Slot:
    """One byte of bit fields, or a run of data bytes (`length` fixed or a parameter)."""

    at: Offset
    parts: tuple[BitPart, ...] = ()
    data_field: Optional[str] = None
    length: Optional[int] = None
    length_param: Optional[str] = None

    @property
    def const_mask(self) -> int:
        return sum(p.mask << p.shift for p in self.parts if p.const is not None)

    @property
    def const_value(self) -> int:
        return sum(p.const << p.shift for p in self.parts if p.const is not None)


@dataclass(frozen=True)
class PacketLayout:
    message: str
    slots: tuple[Slot, ...]
    size: Offset  # whole packet
    members: tuple[str, ...]  # fields the machine supplies or reads, in wire order
    data_members: tuple[str, ...]  # the members that are bytes

    def length_params(self) -> tuple[str, ...]:
        return self.size.lengths


def packet_layout(p: Protocol, m: Message) -> PacketLayout:
    if p.framing.kind != "bytes":
        raise MachineTargetError(f"{p.name}: machines need bytes framing, not {p.framing.kind}")
    slots: list[Slot] = []
    at = Offset(0)
    pending: list[BitPart] = []
    used = 0
    members, data_members = [], []
    for leaf in m.wire.leaves:
        f = leaf.field
        if f.is_payload or f.kind == "payload":
            continue
        if f.kind == "bytes":
            if used:
                raise MachineTargetError(f"{m.name}.{f.name}: data bytes must start on a byte boundary", f.loc)
            if f.length_param is None and f.length is None:
                raise MachineTargetError(f"{m.name}.{f.name}: data bytes need a fixed or parameter length", f.loc)
            slots.append(Slot(at, data_field=f.name, length=None if f.length_param else f.length,
                              length_param=f.length_param))
            at = at.plus_length(f.length_param) if f.length_param else at.plus(f.length)
            members.append(f.name)
            data_members.append(f.name)
            continue
        if f.kind not in ("uint", "bool") or f.bits is None or f.bits > 8:
            raise MachineTargetError(f"{m.name}.{f.name}: machines handle unsigned fields of at most 8 bits", f.loc)
        const = 0 if f.reserved else f.const
        if f.dispatch and const is None:
            const = m.dispatch_key and dict(m.dispatch_key).get(f.name)
        pending.append(BitPart(f.name, 8 - used - f.bits, (1 << f.bits) - 1, const))
        if const is None:
            members.append(f.name)
        used += f.bits
        if used > 8:
            raise MachineTargetError(f"{m.name}.{f.name}: a field crosses a byte boundary", f.loc)
        if used == 8:
            slots.append(Slot(at, tuple(pending)))
            at, pending, used = at.plus(1), [], 0
    if used:
        raise MachineTargetError(f"{m.name}: the packet does not end on a byte boundary")
    return PacketLayout(m.name, tuple(slots), at, tuple(members), tuple(data_members))


def machine_messages(machine: Machine) -> tuple[tuple[str, ...], tuple[str, ...]]:
    """(messages the machine builds, messages it receives), in declaration order."""
    built = tuple(dict.fromkeys(a.target for a in machine.actions if a.kind == "keep"))
    received = tuple(dict.fromkeys(e.message for e in machine.events if e.message))
    return built, received


def max_packet(p: Protocol, layout: PacketLayout) -> int:
    """Largest packet size over the parameters' ranges (or defaults)."""
    total = layout.size.base
    for name in layout.size.lengths:
        param = next(x for x in p.parameters if x.name == name)
        total += int(param.range[1] if param.range else param.default)
    return total
