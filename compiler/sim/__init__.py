"""A lossy shared radio channel for the generated tr24 machines.

One master device and up to four slaves share one channel, as in the seed
(three beacons, two locators). Every packet is heard by every other device;
for each listener the channel independently loses it (per direction: commands
master→slave, replies slave→master), duplicates it, or flips one bit in it, in
which case the listener's radio finds a CRC mismatch and drops it, as the
tr24a module does. Each copy is delayed by a bounded random time, never
overtaking an earlier packet on the same sender→listener path.

Everything is driven by one seeded random.Random, so a seed names a run; the
run's inputs and outputs are recorded as a trace (`Trace`) that a C driver can
replay against the generated C machines.

The machines come from the committed generated/python/tr24.py unless a module
is passed (the docs build passes the codec it has just rendered).
"""
from __future__ import annotations

import binascii
import heapq
import importlib.util
import random
import sys
from dataclasses import dataclass, field
from functools import lru_cache
from pathlib import Path

GENERATED = Path(__file__).resolve().parents[2] / "generated" / "python" / "tr24.py"
MASTER_ID = 1
SLAVE_IDS = (3, 4, 5, 6)  # the seed's example addresses a slave with ID 3


def load_tr24():
    """The committed generated module, imported without the compiler."""
    name = "sim_generated_tr24"
    if name not in sys.modules:
        spec = importlib.util.spec_from_file_location(name, GENERATED)
        module = importlib.util.module_from_spec(spec)
        sys.modules[name] = module  # dataclasses look their module up while the class is built
        spec.loader.exec_module(module)
    return sys.modules[name]


@dataclass(frozen=True)
class Link:
    """Channel behaviour; loss rates per direction, the rest for both."""

    p_fwd: float = 0.0  # a command is lost
    p_ack: float = 0.0  # a reply is lost
    duplicate: float = 0.0  # a copy arrives twice
    corrupt: float = 0.0  # one bit flipped: the radio's CRC drops it
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


def reply_for(command: bytes, slave_id: int) -> bytes:
    """What a slave's application answers: each byte plus the slave's ID, so a
    reply names both its command and the slave that ran it."""
    return bytes(command).translate(_plus(slave_id))


@lru_cache(maxsize=None)
def _plus(n: int) -> bytes:
    """The byte table that adds n to every byte, modulo 256."""
    return bytes((b + n) & 0xFF for b in range(256))


@dataclass
class Stats:
    commands: int = 0
    delivered: int = 0
    failed: int = 0
    command_packets: int = 0  # transmissions by the master
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
    """One master device (a master machine per slave: the sequence bit belongs to a
    link) and `slaves` slave devices; the application sends `commands` commands,
    one at a time, each to a random slave, with random data."""

    def __init__(self, seed: int, link: Link, *, slaves: int = 1, data_length: int = 7,
                 timeout: int = 20, retry_limit: int = 0, module=None, trace: bool = False):
        link.check()
        if not 1 <= slaves <= len(SLAVE_IDS):
            raise ValueError(f"slaves must be in 1..{len(SLAVE_IDS)}")
        self.tr24 = module or load_tr24()
        self.rng = random.Random(seed)
        self.link = link
        self.data_length = data_length
        self.slave_ids = SLAVE_IDS[:slaves]
        self.masters = {sid: self.tr24.MasterMachine(own_id=MASTER_ID, data_length=data_length, timeout=timeout,
                                                     retry_limit=retry_limit) for sid in self.slave_ids}
        self.slaves = {sid: self.tr24.SlaveMachine(own_id=sid, data_length=data_length,
                                                   execute=lambda data, sid=sid: reply_for(data, sid))
                       for sid in self.slave_ids}
        self.devices = (MASTER_ID,) + self.slave_ids
        self.listeners = {d: tuple(x for x in self.devices if x != d) for d in self.devices}
        self.queue: list = []
        self.order = 0
        self.last_arrival: dict[tuple[int, int], int] = {}
        self.scheduled: dict[int, int] = {}  # machine id -> deadline a tick is queued for
        self.stats = Stats()
        self.trace = Trace() if trace else None
        # what the property checks: commands per slave in order, what each slave ran
        self.issued: dict[int, list[bytes]] = {sid: [] for sid in self.slave_ids}
        self.executed: dict[int, list[bytes]] = {sid: [] for sid in self.slave_ids}
        self.outcomes: list[tuple[int, bytes, str, bytes | None]] = []  # slave, command, delivered|failed, reply
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
        if sender == MASTER_ID:
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
        sid = self.rng.choice(self.slave_ids)
        byte = self.rng.getrandbits
        tail = bytes([byte(8) for _ in range(max(0, self.data_length - 4))])
        data = (number.to_bytes(4, "big") + tail)[:self.data_length] if self.data_length >= 4 else \
            bytes([byte(8) for _ in range(self.data_length)])
        self.issued[sid].append(data)
        self.pending = (sid, data)
        master = self.masters[sid]
        if self.trace is None:
            out = master.send(self.now, sid, data)
        else:
            out = self.call(f"m{sid}", "send", master.send, sid, data)
        self.handle(MASTER_ID, out, master)

    def finish_command(self, sid: int, out) -> None:
        for reply in out.delivered:
            self.stats.delivered += 1
            self.outcomes.append((sid, self.pending[1], "delivered", reply))
        for _ in out.failed:
            self.stats.failed += 1
            self.outcomes.append((sid, self.pending[1], "failed", None))

    def run(self, commands: int, time_limit: int | None = None) -> Stats:
        """Send `commands` commands; stop when all are answered or failed, or at `time_limit`."""
        # Untraced runs (the docs' efficiency table) call the machines directly.
        traced = self.trace is not None
        queue, masters, handle = self.queue, self.masters, self.handle
        sid_of = {id(m): sid for sid, m in masters.items()}
        self.next_command(commands)
        while queue:
            time, _, kind, args = heapq.heappop(queue)
            if time_limit is not None and time > time_limit:
                break
            self.now = time
            if kind == "tick":
                device, machine = args
                sid = device if device != MASTER_ID else sid_of[id(machine)]
                out = self.call(f"m{sid}", "tick", machine.tick) if traced else machine.tick(time)
                handle(MASTER_ID, out, machine)
                if out.failed:
                    self.finish_command(sid, out)
                    self.next_command(commands)
                continue
            listener, data, check = args
            if binascii.crc_hqx(data, CRC_INIT) != check:
                self.stats.corrupted += 1  # the radio drops it
                continue
            if listener == MASTER_ID:
                for sid, master in masters.items():
                    out = self.call(f"m{sid}", "receive", master.receive, data) if traced \
                        else master.receive(time, data)
                    handle(MASTER_ID, out, master)
                    if out.delivered:
                        self.finish_command(sid, out)
                        self.next_command(commands)
            else:
                slave = self.slaves[listener]
                out = self.call(f"s{listener}", "receive", slave.receive, data) if traced \
                    else slave.receive(time, data)
                self.executed[listener].extend(out.executed)
                handle(listener, out)
        return self.stats

    def idle(self) -> bool:
        return all(m.state == "idle" for m in self.masters.values())


def trace_lines(out) -> list[str]:
    return ([f"sent {p.hex()}" for p in out.sent] + [f"delivered {d.hex()}" for d in out.delivered]
            + [f"executed {d.hex()}" for d in out.executed] + [f"failed {r}" for r in out.failed]
            + [f"dropped {d.hex()}" for d in out.dropped])


def efficiency(p_fwd: float, p_ack: float, commands: int = 20000, seed: int = 1,
               module=None) -> tuple[float, float]:
    """(measured, theoretical) transmissions per delivered command over a link with
    these loss rates, no duplication or corruption, and a timeout longer than any
    round trip; theory: attempts are independent and one succeeds when both the
    command and its reply arrive, so their number is geometric with mean
    1/((1-p_fwd)(1-p_ack))."""
    sim = Simulation(seed, Link(p_fwd=p_fwd, p_ack=p_ack, delay=(1, 4)), timeout=10, module=module)
    stats = sim.run(commands)
    return stats.command_packets / stats.delivered, 1.0 / ((1.0 - p_fwd) * (1.0 - p_ack))


def efficiency_table(rates=(0.0, 0.1, 0.3, 0.5), commands: int = 20000, seed: int = 1,
                     module=None) -> list[dict]:
    """Rows for the docs: the same loss rate p in both directions."""
    rows = []
    for p in rates:
        measured, theory = efficiency(p, p, commands, seed, module)
        rows.append({"p": p, "measured": measured, "theory": theory,
                     "error": abs(measured - theory) / theory})
    return rows
