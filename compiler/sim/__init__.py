"""A lossy shared channel for a protocol's delivery pair: the sender and receiver
machines its schema's `delivery` section names, as the generated Python module
has them (see pair.py).

One sender device and up to four receiver devices share one channel, a sender
machine per receiver; their addresses are the schema's (`Delivery.addresses`). Every packet is heard by every other device; for each
listener the channel independently loses it (per direction: commands
sender→receiver, replies receiver→sender), duplicates it, or flips one bit in
it, in which case the listener's link layer finds a CRC mismatch and drops it.
Each copy is delayed by a bounded random time, never overtaking an earlier
packet on the same sender→listener path.

Everything is driven by one seeded random.Random, so a seed names a run; the
run's inputs and outputs are recorded as a trace (`Trace`) that a C driver can
replay against the generated C machines.
"""
from __future__ import annotations

import binascii
import heapq
import random
import types
from dataclasses import dataclass, field
from functools import lru_cache, partial
from typing import Mapping, Optional

from ..model import Protocol
from .pair import Pair

@dataclass(frozen=True)
class Link:
    """Channel behaviour; loss rates per direction, the rest for both."""

    p_fwd: float = 0.0  # a command is lost
    p_ack: float = 0.0  # a reply is lost
    duplicate: float = 0.0  # a copy arrives twice
    corrupt: float = 0.0  # one bit flipped: the listener's CRC check drops it
    delay: tuple[int, int] = (1, 5)  # ticks, inclusive

    def check(self) -> None:
        for name in ("p_fwd", "p_ack"):
            if not 0.0 <= getattr(self, name) <= 0.5:
                raise ValueError(f"{name} must be in 0..0.5")
        for name in ("duplicate", "corrupt"):
            if not 0.0 <= getattr(self, name) < 1.0:
                raise ValueError(f"{name} must be in 0..1")
        if not 0 <= self.delay[0] <= self.delay[1]:
            raise ValueError("delay must be (min, max) with 0 <= min <= max")


def reply_for(command: bytes, address: int) -> bytes:
    """What a receiver's application answers: each byte plus the receiver's
    address, so a reply names both its command and the receiver that ran it."""
    return bytes(command).translate(_plus(address))


@lru_cache(maxsize=None)
def _plus(n: int) -> bytes:
    """The byte table that adds n to every byte, modulo 256."""
    return bytes((b + n) & 0xFF for b in range(256))


@dataclass
class Stats:
    commands: int = 0
    delivered: int = 0
    failed: int = 0
    command_packets: int = 0  # transmissions by the sender
    reply_packets: int = 0
    lost: int = 0
    corrupted: int = 0
    duplicated: int = 0


@dataclass
class Trace:
    """Every machine input in order and, per input, the outputs it produced."""

    inputs: list[tuple[int, str, str, str]] = field(default_factory=list)  # time, machine, kind, hex
    outputs: list[list[str]] = field(default_factory=list)

    def script(self) -> str:
        """The inputs alone, one per line: what a driver of other machines replays."""
        return "".join(f"{t} {machine} {kind} {data}".rstrip() + "\n" for t, machine, kind, data in self.inputs)

    def text(self) -> str:
        """Each input followed by its outputs, indented."""
        lines = []
        for (t, machine, kind, data), outs in zip(self.inputs, self.outputs):
            lines.append(f"{t} {machine} {kind} {data}".rstrip())
            lines.extend("  " + line for line in outs)
        return "".join(line + "\n" for line in lines)


CRC_INIT = 0xFFFF


def crc(packet: bytes) -> int:
    return binascii.crc_hqx(packet, CRC_INIT)


class Simulation:
    """One sender device (a sender machine per receiver: the state that tells
    commands apart belongs to a link) and `receivers` receiver devices; the
    application sends `commands` commands, one at a time, each to a random
    receiver, with random data. `parameters` gives the machines' other
    parameters by name; those left out take the schema's defaults."""

    def __init__(self, protocol: Protocol, module: types.ModuleType, seed: int, link: Link, *,
                 receivers: int = 1, timeout: int = 20, retry_limit: int = 0,
                 parameters: Optional[Mapping[str, int]] = None, trace: bool = False):
        link.check()
        self.pair = pair = Pair(protocol, module, parameters)
        sender_address, *receiver_addresses = protocol.delivery.addresses
        if not 1 <= receivers <= len(receiver_addresses):
            raise ValueError(f"receivers must be in 1..{len(receiver_addresses)}: the address parameter "
                             f"{protocol.delivery.address!r} admits {len(receiver_addresses) + 1} device addresses")
        self.rng = random.Random(seed)
        self.link = link
        self.data_length = pair.data_length
        self.sender_address = sender_address
        self.receiver_ids = tuple(receiver_addresses[:receivers])
        self.senders = {rid: pair.new_sender(sender_address, timeout, retry_limit) for rid in self.receiver_ids}
        self.receivers = {rid: pair.new_receiver(rid, partial(reply_for, address=rid)) for rid in self.receiver_ids}
        self.devices = (sender_address,) + self.receiver_ids
        self.listeners = {d: tuple(x for x in self.devices if x != d) for d in self.devices}
        self.queue: list = []
        self.order = 0
        self.last_arrival: dict[tuple[int, int], int] = {}
        self.scheduled: dict[int, int] = {}  # machine id -> deadline a tick is queued for
        self.stats = Stats()
        self.trace = Trace() if trace else None
        # what the property checks: commands per receiver in order, what each receiver ran
        self.issued: dict[int, list[bytes]] = {rid: [] for rid in self.receiver_ids}
        self.executed: dict[int, list[bytes]] = {rid: [] for rid in self.receiver_ids}
        self.outcomes: list[tuple[int, bytes, str, bytes | None]] = []  # receiver, command, delivered|failed, reply
        self.pending: tuple[int, bytes] | None = None
        self.now = 0

    # -- scheduling ----------------------------------------------------------------
    def at(self, time: int, kind: str, *args) -> None:
        self.order += 1
        heapq.heappush(self.queue, (time, self.order, kind, args))

    def transmit(self, sender: int, packet: bytes) -> None:
        # The docs build runs this some 50,000 times: attributes are read once.
        link, rng, stats, last_arrival = self.link, self.rng, self.stats, self.last_arrival
        chance = rng.random
        if sender == self.sender_address:
            loss = link.p_fwd
            stats.command_packets += 1
        else:
            loss = link.p_ack
            stats.reply_packets += 1
        check = binascii.crc_hqx(packet, CRC_INIT)
        now, (slowest, fastest) = self.now, link.delay
        for listener in self.listeners[sender]:
            if chance() < loss:
                stats.lost += 1
                continue
            copies = 2 if chance() < link.duplicate else 1
            stats.duplicated += copies - 1
            for _ in range(copies):
                data = packet
                if chance() < link.corrupt:
                    bit = rng.randrange(8 * len(packet))
                    data = bytearray(packet)
                    data[bit // 8] ^= 1 << (bit % 8)
                    data = bytes(data)
                path = (sender, listener)
                arrival = max(now + rng.randint(slowest, fastest), last_arrival.get(path, 0))
                last_arrival[path] = arrival
                self.order += 1
                heapq.heappush(self.queue, (arrival, self.order, "arrive", (listener, data, check)))

    # -- machine calls, traced -----------------------------------------------------
    # Trace names: m<address> is the sender machine for the receiver at that
    # address, s<address> the receiver; kinds are send, receive and tick.
    def call(self, name: str, kind: str, fn, *args):
        out = fn(self.now, *args)
        if self.trace is not None:
            data = args[-1].hex() if args and isinstance(args[-1], bytes) else ""
            if kind == "send":
                data = f"{args[0]:02x}{args[1].hex()}"
            self.trace.inputs.append((self.now, name, kind, data))
            self.trace.outputs.append(trace_lines(out))
        return out

    def handle(self, device: int, out, machine=None) -> None:
        for packet in out.sent:
            self.transmit(device, packet)
        # one tick per new deadline; a stale tick would find nothing to do anyway
        if machine is not None:
            deadline = machine.deadline
            if deadline is not None and self.scheduled.get(id(machine)) != deadline:
                self.scheduled[id(machine)] = deadline
                self.at(deadline, "tick", device, machine)

    # -- the application -----------------------------------------------------------
    def next_command(self, count: int) -> None:
        if self.stats.commands >= count:
            return
        number = self.stats.commands
        self.stats.commands += 1
        rid = self.rng.choice(self.receiver_ids)
        byte = self.rng.getrandbits
        tail = bytes([byte(8) for _ in range(max(0, self.data_length - 4))])
        data = (number.to_bytes(4, "big") + tail)[:self.data_length] if self.data_length >= 4 else \
            bytes([byte(8) for _ in range(self.data_length)])
        self.issued[rid].append(data)
        self.pending = (rid, data)
        sender = self.senders[rid]
        if self.trace is None:
            out = self.pair.send(sender, self.now, rid, data)
        else:
            out = self.call(f"m{rid}", "send", partial(self.pair.send, sender), rid, data)
        self.handle(self.sender_address, out, sender)

    def finish_command(self, rid: int, out) -> None:
        for reply in out.delivered:
            self.stats.delivered += 1
            self.outcomes.append((rid, self.pending[1], "delivered", reply))
        for _ in out.failed:
            self.stats.failed += 1
            self.outcomes.append((rid, self.pending[1], "failed", None))

    def run(self, commands: int, time_limit: int | None = None, event_limit: int | None = None) -> Stats:
        """Send `commands` commands; stop when all are answered or failed, at `time_limit`,
        or after `event_limit` events (machines that never finish a command tick forever)."""
        # Untraced runs (the docs' efficiency table) call the machines directly.
        traced = self.trace is not None
        queue, senders, handle, pair = self.queue, self.senders, self.handle, self.pair
        rid_of = {id(m): rid for rid, m in senders.items()}
        take_reply = {rid: getattr(m, pair.sender_receive) for rid, m in senders.items()}
        take_command = {rid: getattr(m, pair.receiver_receive) for rid, m in self.receivers.items()}
        self.next_command(commands)
        events = 0
        while queue:
            time, _, kind, args = heapq.heappop(queue)
            if time_limit is not None and time > time_limit:
                break
            events += 1
            if event_limit is not None and events > event_limit:
                break
            self.now = time
            if kind == "tick":
                _, machine = args  # only senders have a timer
                rid = rid_of[id(machine)]
                tick = getattr(machine, pair.tick)
                out = self.call(f"m{rid}", "tick", tick) if traced else tick(time)
                handle(self.sender_address, out, machine)
                if out.failed:
                    self.finish_command(rid, out)
                    self.next_command(commands)
                continue
            listener, data, check = args
            if binascii.crc_hqx(data, CRC_INIT) != check:
                self.stats.corrupted += 1  # the listener's CRC check drops it
                continue
            if listener == self.sender_address:
                for rid, sender in senders.items():
                    receive = take_reply[rid]
                    out = self.call(f"m{rid}", "receive", receive, data) if traced else receive(time, data)
                    handle(self.sender_address, out, sender)
                    if out.delivered:
                        self.finish_command(rid, out)
                        self.next_command(commands)
            else:
                receive = take_command[listener]
                out = self.call(f"s{listener}", "receive", receive, data) if traced else receive(time, data)
                self.executed[listener].extend(out.executed)
                handle(listener, out)
        return self.stats

    def idle(self) -> bool:
        """Whether no command is outstanding: every sender in its initial state."""
        return all(m.state == self.pair.idle for m in self.senders.values())


def trace_lines(out) -> list[str]:
    return ([f"sent {p.hex()}" for p in out.sent] + [f"delivered {d.hex()}" for d in out.delivered]
            + [f"executed {d.hex()}" for d in out.executed] + [f"failed {r}" for r in out.failed]
            + [f"dropped {d.hex()}" for d in out.dropped])


def efficiency(protocol: Protocol, module: types.ModuleType, p_fwd: float, p_ack: float,
               commands: int = 20000, seed: int = 1) -> tuple[float, float]:
    """(measured, theoretical) transmissions per delivered command over a link with
    these loss rates, no duplication or corruption, and a timeout longer than any
    round trip; theory: attempts are independent and one succeeds when both the
    command and its reply arrive, so their number is geometric with mean
    1/((1-p_fwd)(1-p_ack)). The timeout and the retry limit (0: none) are taken
    as near those as the schema's parameter ranges allow, and each packet's delay
    kept short enough that a round trip ends before the timeout."""
    d = protocol.delivery
    timeout = within(protocol, d.timeout, EFFICIENCY_TIMEOUT)
    slowest = min(EFFICIENCY_DELAY, (timeout - 1) // 2) if timeout > 0 else 0
    link = Link(p_fwd=p_fwd, p_ack=p_ack, delay=(min(1, slowest), slowest))
    sim = Simulation(protocol, module, seed, link, timeout=timeout,
                     retry_limit=within(protocol, d.retry_limit, 0))
    stats = sim.run(commands, event_limit=commands * EVENTS_PER_COMMAND)
    if stats.delivered + stats.failed < commands or not stats.delivered:
        raise Undelivered(f"over a simulated link losing {p_fwd:.0%} of commands and {p_ack:.0%} of replies, "
                          f"the machines deliver {stats.delivered} and fail {stats.failed} of "
                          f"{stats.commands} commands issued out of {commands} "
                          f"in {commands * EVENTS_PER_COMMAND:,} events")
    return stats.command_packets / stats.delivered, 1.0 / ((1.0 - p_fwd) * (1.0 - p_ack))


# The measurement's timeout and longest packet delay, in ticks: a round trip takes
# at most twice the delay, less than the timeout.
EFFICIENCY_TIMEOUT = 10
EFFICIENCY_DELAY = 4


def within(protocol: Protocol, parameter: str, wanted: int) -> int:
    """`wanted`, or the nearest integer the parameter's range admits."""
    span = next(x for x in protocol.parameters if x.name == parameter).integers
    return wanted if span is None else min(max(wanted, span[0]), span[1])


# A command takes a few events per attempt (send, receive, reply, receive, tick);
# at half the packets lost its attempts average 4 and rarely pass 40.
EVENTS_PER_COMMAND = 500


class Undelivered(Exception):
    """Delivery machines that do not finish their commands over a simulated link."""


LOSSLESS_COMMANDS = 200


def efficiency_table(protocol: Protocol, module: types.ModuleType, rates=(0.0, 0.1, 0.3, 0.5),
                     commands: int = 20000, seed: int = 1) -> list[dict]:
    """Rows for the docs: the same loss rate p in both directions."""
    rows = []
    for rate in rates:
        # without loss every command is delivered at its first attempt: a short run shows it
        count = commands if rate else min(commands, LOSSLESS_COMMANDS)
        measured, theory = efficiency(protocol, module, rate, rate, count, seed)
        rows.append({"p": rate, "measured": measured, "theory": theory,
                     "error": abs(measured - theory) / theory})
    return rows
