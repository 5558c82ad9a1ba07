"""Every example with a peer library against it, in pure Python, on the same bytes.

Each example of examples/ whose users have a library of their own is decoded and
encoded by codeword's generated module (imported from generated/examples/python
with the accelerator off) and by that library, message by message, on frames the
library wrote. Before timing, each row checks that both sides read the same values
from the frames and write the same bytes back.

What each library's calls are (the way its docs and tests/test_example_*.py use it):
- pymavlink: `MAVLink.decode(bytearray)` of a whole frame (what `parse_buffer` passes
  it: the CRC checked, the message object made), and `msg.pack(mav)` to encode;
- pyubx2: `UBXReader.parse(frame, msgmode=...)`, and `UBXMessage(class, id, mode,
  **values).serialize()`: pyubx2 packs the payload when the message object is made, so
  an encode of values is both calls;
- pymodbus: the RTU framer's `handleFrame` (the CRC checked, the PDU decoded) and
  `buildFrame(pdu)`;
- scapy: `IP(raw)` with every field of the datagram read, and `bytes(packet)` of a
  packet whose checksums and lengths are left for scapy to compute;
- pynmea2: `pynmea2.parse(line, check=True)` followed by reading every field: pynmea2
  reads its fields when they are asked for, so reading them is part of its decode; and
  `msg.render(newline=...)`, which joins the texts it holds.
codeword's calls are the module's `decode(data)` (`decode(data, direction)` for Modbus,
whose ids repeat across directions) and `encode(message)`.
"""

from __future__ import annotations

import dataclasses
import os
import random
import struct
import sys
import time
from dataclasses import dataclass
from typing import Any, Callable

from bench import timing
from bench.protocols import ROOT

sys.path.insert(0, str(ROOT / "generated" / "examples" / "python"))
os.environ["CODEWORD_PURE_PYTHON"] = "1"
import ipv4  # noqa: E402
import mavlink1  # noqa: E402
import mavlink2  # noqa: E402
import modbus_rtu  # noqa: E402
import nmea0183  # noqa: E402
import ubx  # noqa: E402
import can_mixed  # noqa: E402
del os.environ["CODEWORD_PURE_PYTHON"]

# The targets: peer time / codeword time.
TARGETS = {("mavlink2", "decode"): 2.5, ("mavlink2", "encode"): 1.5,
           ("nmea0183 GGA", "decode"): 1.5, ("nmea0183 RMC", "decode"): 1.5}
PEER_MIN = 1.0  # every row, both ways


@dataclass
class Row:
    """One message of an example: a few frames both sides decode and write back."""
    example: str
    peer: str
    message: str
    ours_decode: Callable[[], Any]
    theirs_decode: Callable[[], Any]
    ours_encode: Callable[[], Any]
    theirs_encode: Callable[[], Any]
    problems: Callable[[], list[str]]  # where the two disagree; empty when they do the same work

    @property
    def key(self) -> str:
        return f"{self.example} {self.message}"


def _batch(fn, items):
    """A call doing `fn` on every item: one timed call per row."""
    def run():
        for item in items:
            fn(*item)
    return run


def _disagreements(where: str, pairs) -> list[str]:
    return [f"{where} {name}: codeword {ours!r}, peer {theirs!r}" for name, ours, theirs in pairs if ours != theirs]


# -- MAVLink 1 and 2: pymavlink --------------------------------------------------------
def _f32(x: float) -> float:
    return struct.unpack("<f", struct.pack("<f", x))[0]


def _mavlink_value(rng: random.Random, ctype: str):
    """A value of a MAVLink field type (the examples' messages have no arrays but text)."""
    if ctype == "char":
        return b"PARAM_%d" % rng.getrandbits(16)
    if ctype == "float":
        return _f32(rng.uniform(-1e4, 1e4))
    bits = int(ctype.strip("uint_t"))
    if ctype.startswith("uint"):
        return rng.getrandbits(bits)
    return rng.randint(-(1 << (bits - 1)), (1 << (bits - 1)) - 1)


def _mavlink_rows(example: str, mod, dialect) -> list[Row]:
    rng = random.Random(2)
    rows = []
    names = [cls.NAME for cls in mod.MESSAGES.values()]
    for name in names:
        cls = getattr(dialect, f"MAVLink_{name}_message")
        mav = dialect.MAVLink(None, srcSystem=42, srcComponent=190)
        messages = [cls(**{f: _mavlink_value(rng, t) for f, t in zip(cls.fieldnames, cls.fieldtypes)})
                    for _ in range(3)]
        frames = [bytes(m.pack(mav)) for m in messages]
        buffers = [(bytearray(f),) for f in frames]
        ours = [mod.decode(f) for f in frames]

        def problems(name=name, cls=cls, mav=mav, messages=messages, frames=frames, buffers=buffers, ours=ours):
            out = []
            for message, frame, (buf,), mine in zip(messages, frames, buffers, ours):
                theirs = mav.decode(bytearray(buf))
                pairs = []
                for field in cls.fieldnames:
                    a, b = getattr(mine, field), getattr(theirs, field)
                    if isinstance(a, bytes):  # pymavlink gives char arrays as text without the NULs
                        a, b = a.rstrip(b"\0").decode(), b.decode() if isinstance(b, bytes) else b
                    pairs.append((field, a, b))
                out += _disagreements(f"{example} {name}", pairs)
                if mod.encode(mine) != frame or bytes(message.pack(mav)) != frame:
                    out.append(f"{example} {name}: encodes differ")
            return out

        rows.append(Row(example, "pymavlink", name,
                        _batch(mod.decode, [(f,) for f in frames]), _batch(mav.decode, buffers),
                        _batch(mod.encode, [(m,) for m in ours]), _batch(lambda m, mav=mav: m.pack(mav), [(m,) for m in messages]),
                        problems))
    return rows


# -- UBX: pyubx2 ------------------------------------------------------------------------
def _ubx_rows() -> list[Row]:
    from pyubx2 import GET, POLL, SET, UBXMessage, UBXReader
    from pyubx2.ubxtypes_get import UBX_PAYLOADS_GET
    from pyubx2.ubxtypes_set import UBX_PAYLOADS_SET

    rng = random.Random(3)

    def value(spec, width):
        kind, scale = (spec, None) if isinstance(spec, str) else spec
        raw = rng.randint(-(1 << (width - 1)), (1 << (width - 1)) - 1) if kind[0] == "I" else rng.getrandbits(width)
        return raw * scale if scale else raw

    def values(definition, suffix=""):
        out = {}
        for name, spec in definition.items():
            if isinstance(spec, tuple) and isinstance(spec[1], dict):
                if spec[0].startswith("X"):  # bit fields: each its own attribute; reserved bits, which
                    # pyubx2 does not keep when it reads a frame, zero
                    out.update({k + suffix: 0 if k.startswith("reserved") else value(v, int(v[1:]))
                                for k, v in spec[1].items()})
                continue  # a repeated group: below
            kind = spec if isinstance(spec, str) else spec[0]
            out[name + suffix] = value(spec, 8 * int(kind[1:]))
        return out

    def keywords(cls, name, mode, blocks=0):
        table = UBX_PAYLOADS_SET if mode == SET else UBX_PAYLOADS_GET
        v = values(table[name])
        for spec in table[name].values():
            if isinstance(spec, tuple) and isinstance(spec[1], dict) and not spec[0].startswith("X"):
                v[spec[0]] = blocks
                for k in range(1, blocks + 1):
                    v.update(values(spec[1], f"_{k:02}"))
        return v

    cases = [("ACK-ACK", "ACK", GET, [0]), ("ACK-NAK", "ACK", GET, [0]), ("CFG-RATE", "CFG", SET, [0]),
             ("NAV-POSLLH", "NAV", GET, [0]), ("NAV-PVT", "NAV", GET, [0]), ("NAV-SAT", "NAV", GET, [1, 12])]
    rows = []
    for name, cls, mode, counts in cases:
        # what pyubx2 builds each frame of (not its attributes as it reads them: it truncates a
        # scaled value divided by its scale, so a value read may build another frame)
        kwargs = [keywords(cls, name, mode, n) for n in counts]
        frames = [UBXMessage(cls, name, mode, **kw).serialize() for kw in kwargs]
        ours = [ubx.decode(f) for f in frames]

        def problems(name=name, cls=cls, mode=mode, frames=frames, kwargs=kwargs, ours=ours):
            out = []
            for f, kw, mine in zip(frames, kwargs, ours):
                theirs = {k: v for k, v in vars(UBXReader.parse(f, msgmode=mode)).items() if not k.startswith("_")}
                mine_flat = _ubx_attributes(mine)
                pairs = [(k, mine_flat[k], theirs[k]) for k in sorted(set(mine_flat) & set(theirs))]
                out += _disagreements(f"ubx {name}", [(k, a, b) for k, a, b in pairs
                                                      if not (isinstance(b, float) and abs(a - b) <= 1e-9 * abs(b))])
                if len(pairs) < len(theirs) - 1:  # all but NAV-SAT's count, which is the list's length
                    out.append(f"ubx {name}: compared {len(pairs)} of pyubx2's {len(theirs)} values")
                if ubx.encode(mine) != f or UBXMessage(cls, name, mode, **kw).serialize() != f:
                    out.append(f"ubx {name}: encodes differ")
            return out

        rows.append(Row("ubx", "pyubx2", name,
                        _batch(ubx.decode, [(f,) for f in frames]),
                        _batch(lambda f, mode=mode: UBXReader.parse(f, msgmode=mode), [(f,) for f in frames]),
                        _batch(ubx.encode, [(m,) for m in ours]),
                        _batch(lambda kw, cls=cls, name=name, mode=mode: UBXMessage(cls, name, mode, **kw).serialize(),
                               [(kw,) for kw in kwargs]),
                        problems))
    return rows


def _ubx_attributes(message) -> dict:
    """A decoded message's values named as pyubx2 names them: the k-th element's members
    of an array of groups as `member_0k`."""
    out = {}
    for field in dataclasses.fields(message):
        value = getattr(message, field.name)
        if isinstance(value, list):
            for k, element in enumerate(value, start=1):
                out.update({f"{f.name}_{k:02}": getattr(element, f.name) for f in dataclasses.fields(element)})
        else:
            out[field.name] = value
    return out


# -- Modbus RTU: pymodbus ---------------------------------------------------------------
def _modbus_rows() -> list[Row]:
    from pymodbus.framer import FramerRTU
    from pymodbus.pdu import DecodePDU, ExceptionResponse
    from pymodbus.pdu.register_message import (ReadHoldingRegistersRequest, ReadHoldingRegistersResponse,
                                               WriteMultipleRegistersRequest, WriteMultipleRegistersResponse)

    framers = {"to_server": FramerRTU(DecodePDU(is_server=True)), "to_client": FramerRTU(DecodePDU(is_server=False))}
    rng = random.Random(4)
    regs = [rng.getrandbits(16) for _ in range(16)]
    cases = [("read_holding_registers", "to_server", ReadHoldingRegistersRequest(address=107, count=16, dev_id=17)),
             ("read_holding_registers_response", "to_client", ReadHoldingRegistersResponse(registers=regs, dev_id=17)),
             ("write_multiple_registers", "to_server",
              WriteMultipleRegistersRequest(address=1, registers=regs, dev_id=17)),
             ("write_multiple_registers_response", "to_client",
              WriteMultipleRegistersResponse(address=1, count=16, dev_id=17)),
             ("exception_response", "to_client", ExceptionResponse(3, 2, device_id=10))]
    rows = []
    for name, direction, pdu in cases:
        framer = framers[direction]
        frame = framer.buildFrame(pdu)
        mine = modbus_rtu.decode(frame, direction)

        def read(f, framer=framer):
            pdu = framer.handleFrame(f, 0, 0)[1]
            return pdu

        def problems(name=name, direction=direction, frame=frame, read=read, framer=framer, mine=mine):
            theirs = read(frame)
            out = _disagreements(f"modbus {name}", [("values", _modbus_ours(mine), _modbus_theirs(theirs))])
            if modbus_rtu.encode(mine) != frame or framer.buildFrame(theirs) != frame:
                out.append(f"modbus {name}: encodes differ")
            return out

        theirs = read(frame)
        rows.append(Row("modbus_rtu", "pymodbus", name,
                        _batch(modbus_rtu.decode, [(frame, direction)]), _batch(read, [(frame,)]),
                        _batch(modbus_rtu.encode, [(mine,)]), _batch(framer.buildFrame, [(theirs,)]), problems))
    return rows


def _modbus_ours(m) -> tuple:
    values = [getattr(m, f.name) for f in dataclasses.fields(m)]
    return tuple(int(v) if hasattr(v, "_value_") else tuple(v) if isinstance(v, list) else v for v in values)


def _modbus_theirs(pdu) -> tuple:
    """pymodbus's values in the order of the example's fields."""
    from pymodbus.pdu import ExceptionResponse
    name = type(pdu).__name__
    if isinstance(pdu, ExceptionResponse):  # the function code is a field of this message alone
        return pdu.dev_id, pdu.function_code, pdu.exception_code
    if name == "ReadHoldingRegistersRequest":
        return pdu.dev_id, pdu.address, pdu.count
    if name == "ReadHoldingRegistersResponse":
        return pdu.dev_id, tuple(pdu.registers)
    if name == "WriteMultipleRegistersRequest":
        return pdu.dev_id, pdu.address, pdu.count, tuple(pdu.registers)
    return pdu.dev_id, pdu.address, pdu.count


# -- IPv4: scapy ------------------------------------------------------------------------
def _ipv4_rows() -> list[Row]:
    from scapy.layers.inet import ICMP, IP, UDP
    from scapy.packet import Raw

    rng = random.Random(5)
    udp = bytes(IP(src="10.1.2.3", dst="192.168.7.9", id=4242, ttl=61, tos=0x28, flags="DF")
                / UDP(sport=5353, dport=53) / Raw(rng.randbytes(64)))
    icmp = bytes(IP(src="10.1.2.3", dst="192.168.7.9", id=4243, ttl=64) / ICMP(type=8, id=77, seq=9)
                 / Raw(rng.randbytes(56)))
    rows = []
    for name, raw, inner in (("udp", udp, UDP), ("icmp_echo_request", icmp, ICMP)):
        def theirs_decode(f, inner=inner):
            p = IP(f)
            q = p[inner]
            return (p.version, p.ihl, p.tos, p.len, p.id, p.flags, p.frag, p.ttl, p.proto, p.chksum, p.src, p.dst,
                    *(getattr(q, k) for k in ([f.name for f in q.fields_desc])), q.payload.load)

        def packet(f=raw, inner=inner):
            """The datagram as a scapy packet to build: lengths and checksums left to scapy
            (but UDP's, which codeword carries as a value)."""
            p = IP(f)
            del p.chksum, p.len
            if inner is ICMP:
                del p[ICMP].chksum
            return IP(bytes(p))  # a new packet of the same fields: no bytes cached
        built = packet()
        for layer in (built, built[inner]):
            for k in ("chksum", "len") if layer is built else (("chksum",) if inner is ICMP else ()):
                setattr(layer, k, None)
        mine = ipv4.decode(raw)

        def problems(name=name, raw=raw, mine=mine, built=built, theirs_decode=theirs_decode, inner=inner):
            theirs = theirs_decode(raw)
            ours = (mine.dscp << 2 | mine.ecn, mine.identification, mine.ttl, int.from_bytes(raw[12:16], "big"),
                    mine.data)
            want = (theirs[2], theirs[4], theirs[7], mine.src, theirs[-1])
            out = _disagreements(f"ipv4 {name}", [("values", ours, want)])
            if ipv4.encode(mine) != raw or bytes(built) != raw:
                out.append(f"ipv4 {name}: encodes differ")
            return out

        rows.append(Row("ipv4", "scapy", name, _batch(ipv4.decode, [(raw,)]), _batch(theirs_decode, [(raw,)]),
                        _batch(ipv4.encode, [(mine,)]), _batch(bytes, [(built,)]), problems))
    return rows


# -- NMEA 0183: pynmea2 -----------------------------------------------------------------
NMEA_LINES = {  # gpsd's "NMEA 0183 revealed", and a DGPS fix with every field of GGA
    "GGA": ["$GPGGA,123519,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,*47",
            "$GPGGA,040001,2246.08015,N,15755.97487,W,2,07,1.1,15.8,M,0.4,M,7.0,0133*79"],
    "RMC": ["$GPRMC,123519,A,4807.038,N,01131.000,E,022.4,084.4,230394,003.1,W*6A"],
    "VTG": ["$GPVTG,054.7,T,034.4,M,005.5,N,010.2,K*48"],
}

NMEA_NAMES = {"mode_indicator": "mode"}  # pynmea2's names that the example spells otherwise


def _nmea_rows() -> list[Row]:
    import pynmea2

    def theirs_decode(line):
        msg = pynmea2.parse(line, check=True)
        return [getattr(msg, f[1]) for f in msg.fields]

    rows = []
    for name, lines in NMEA_LINES.items():
        lines = [line + "\r\n" for line in lines]
        parsed = [pynmea2.parse(line, check=True) for line in lines]
        ours = [nmea0183.decode(line) for line in lines]

        def problems(name=name, lines=lines, parsed=parsed, ours=ours):
            out = []
            for line, theirs, mine in zip(lines, parsed, ours):
                pairs = []
                for (_, field, *_), text in zip(theirs.fields, theirs.data):
                    value = getattr(mine, NMEA_NAMES.get(field, field))
                    if hasattr(value, "_value_"):
                        value = value._value_
                    elif isinstance(value, (int, float)):
                        text = float(text)
                    pairs.append((field, "" if value is None else value, text))
                out += _disagreements(f"nmea0183 {name}", pairs)
                if nmea0183.encode(mine) != line or theirs.render(newline="\r\n") != line:
                    out.append(f"nmea0183 {name}: encodes differ")
            return out

        rows.append(Row("nmea0183", "pynmea2", name, _batch(nmea0183.decode, [(x,) for x in lines]),
                        _batch(theirs_decode, [(x,) for x in lines]), _batch(nmea0183.encode, [(m,) for m in ours]),
                        _batch(lambda m: m.render(newline="\r\n"), [(m,) for m in parsed]), problems))
    return rows


# -- CAN: cantools -----------------------------------------------------------------------
EXTENDED_FLAG = 0x80000000  # a frame id's extended flag, as SocketCAN's


def _can_rows() -> list[Row]:
    """examples/can_mixed.yaml against cantools loading examples/can_mixed.dbc: each side
    finds the message by its identifier (decode_can, Database.decode_message) and
    writes a frame's data from values (encode_can, Database.encode_message)."""
    import cantools
    db = cantools.database.load_file(str(ROOT / "examples" / "can_mixed.dbc"))
    rng = random.Random(8)
    rows = []
    for ref in db.messages:
        frame_id = ref.frame_id | (EXTENDED_FLAG if ref.is_extended_frame else 0)
        values = [_can_values(rng, ref) for _ in range(3)]
        datas = [ref.encode(v) for v in values]
        ours = [can_mixed.decode_can(frame_id, d) for d in datas]
        name = ours[0].NAME

        def problems(ref=ref, frame_id=frame_id, datas=datas, ours=ours):
            out = []
            for data, mine in zip(datas, ours):
                theirs = db.decode_message(ref.frame_id, data, decode_choices=False,
                                           force_extended_id=ref.is_extended_frame)
                pairs = [(k, getattr(mine, _snake(k)), v) for k, v in theirs.items()]
                out += _disagreements(f"can_mixed {ref.name}", pairs)
                if mine.encode_can() != (frame_id, data):
                    out.append(f"can_mixed {ref.name}: encodes differ")
            return out

        rows.append(Row("can_mixed", "cantools", name,
                        _batch(can_mixed.decode_can, [(frame_id, d) for d in datas]),
                        _batch(lambda d, ref=ref: db.decode_message(ref.frame_id, d, force_extended_id=ref.is_extended_frame),
                               [(d,) for d in datas]),
                        _batch(lambda m: m.encode_can(), [(m,) for m in ours]),
                        _batch(lambda v, ref=ref: db.encode_message(ref.frame_id, v, force_extended_id=ref.is_extended_frame),
                               [(v,) for v in values]),
                        problems))
    return rows


def _snake(name: str) -> str:
    """can_mixed's field for a DBC signal: BIT_J → bit_j, AverageRadius → average_radius."""
    if name.isupper():
        return name.lower()
    return "".join("_" + c.lower() if c.isupper() and i else c.lower() for i, c in enumerate(name))


def _can_values(rng: random.Random, ref) -> dict:
    """Values of the signals a frame carries, as cantools scales them (the multiplexors'
    values select signals the message has)."""
    out: dict = {}
    by_name = {s.name: s for s in ref.signals}

    def carried(s) -> bool:
        mux = by_name.get(s.multiplexer_signal)
        return mux is None or carried(mux) and out.get(mux.name) in s.multiplexer_ids

    for s in ref.signals:  # multiplexors first: a signal's carrying depends on theirs
        if s.is_multiplexer and s.multiplexer_signal is None:
            out[s.name] = rng.choice(sorted({v for x in ref.signals if x.multiplexer_signal == s.name
                                             for v in x.multiplexer_ids}))
    for s in ref.signals:
        if s.is_multiplexer and s.multiplexer_signal is not None and carried(s):
            out[s.name] = rng.choice(sorted({v for x in ref.signals if x.multiplexer_signal == s.name
                                             for v in x.multiplexer_ids}))
    for s in ref.signals:
        if s.name in out or not carried(s):
            continue
        if s.is_float:
            out[s.name] = _f32(rng.uniform(-1e3, 1e3))
            continue
        lo, hi = (-(1 << (s.length - 1)), (1 << (s.length - 1)) - 1) if s.is_signed else (0, (1 << s.length) - 1)
        out[s.name] = s.conversion.raw_to_scaled(rng.randint(lo, hi), decode_choices=False)
    return out


def rows() -> list[Row]:
    from pymavlink.dialects.v10 import common as v10
    from pymavlink.dialects.v20 import common as v20
    return (_mavlink_rows("mavlink2", mavlink2, v20) + _mavlink_rows("mavlink1", mavlink1, v10) + _ubx_rows()
            + _modbus_rows() + _ipv4_rows() + _nmea_rows() + _can_rows())


def check(all_rows) -> list[str]:
    return [p for row in all_rows for p in row.problems()]


def measure(repeats: int, target: float = timing.TARGET_SECONDS) -> tuple[list[Row], dict]:
    """Each row's four calls timed, interleaved: {(row key, side, op): median ns}."""
    all_rows = rows()
    problems = check(all_rows)
    if problems:
        raise AssertionError("codeword and its peers disagree:\n" + "\n".join(problems))
    calls = {}
    for row in all_rows:
        calls[(row.key, "codeword", "decode")] = row.ours_decode
        calls[(row.key, "peer", "decode")] = row.theirs_decode
        calls[(row.key, "codeword", "encode")] = row.ours_encode
        calls[(row.key, "peer", "encode")] = row.theirs_encode
    # CPU time of this process: on a shared machine a wall-clock call of a few microseconds
    # also counts the other processes' turns, which swamp the difference measured
    return all_rows, timing.interleaved(calls, repeats, target, clock=time.process_time)


def ratios(all_rows, ns) -> dict:
    """{(example or `example message`, op): peer time / codeword time}: each message, and
    each example's messages together."""
    out = {}
    for op in ("decode", "encode"):
        totals: dict[str, list[float]] = {}
        for row in all_rows:
            ours, theirs = ns[(row.key, "codeword", op)], ns[(row.key, "peer", op)]
            out[(row.key, op)] = theirs / ours
            t = totals.setdefault(row.example, [0.0, 0.0])
            t[0] += ours
            t[1] += theirs
        out.update({(example, op): theirs / ours for example, (ours, theirs) in totals.items()})
    return out


def _table(all_rows, ns, r) -> list[str]:
    lines = ["| example | peer | message | codeword decode ns | peer decode ns | decode × | codeword encode ns "
             "| peer encode ns | encode × |", "|---|---|---|---:|---:|---:|---:|---:|---:|"]
    for row in all_rows:
        d = [ns[(row.key, side, "decode")] for side in ("codeword", "peer")]
        e = [ns[(row.key, side, "encode")] for side in ("codeword", "peer")]
        lines.append(f"| {row.example} | {row.peer} | {row.message} | {d[0]:,.0f} | {d[1]:,.0f} | "
                     f"{r[(row.key, 'decode')]:.2f} | {e[0]:,.0f} | {e[1]:,.0f} | {r[(row.key, 'encode')]:.2f} |")
    return lines + ["", "`×` is the peer's time over codeword's: above 1, codeword is faster."]


def _targets(r, which, verdicts, met) -> list[str]:
    out = []
    for (what, op), target in TARGETS.items():
        if what.split()[0] in which:
            ok = r[(what, op)] >= target
            verdicts.append(ok)
            out.append(f"- {what} {op}: peer / codeword = {r[(what, op)]:.2f} (target ≥ {target}): {met(ok)}")
    return out


def nmea_report(all_rows, ns, verdicts: list, met: Callable[[bool], str]) -> list[str]:
    """Section 7: NMEA 0183 against pynmea2."""
    r = ratios(all_rows, ns)
    rows = [row for row in all_rows if row.example == "nmea0183"]
    lines = ["## 7. NMEA 0183 against pynmea2", "",
             "examples/nmea0183.yaml's generated module, pure Python, against pynmea2 on the same lines: "
             "`nmea0183.decode(line)` against `pynmea2.parse(line, check=True)` followed by reading every field "
             "pynmea2 lists (it reads a field when it is asked for, so reading them is part of its decode), "
             "and `nmea0183.encode(message)` against `msg.render()`, which joins the texts pynmea2 holds and "
             "appends their checksum; values and lines are checked equal first (`bench/examples.py`).", ""]
    lines += _table(rows, ns, r) + ["", "Targets:", ""] + _targets(r, {"nmea0183"}, verdicts, met)
    return lines


def report(all_rows, ns, verdicts: list, met: Callable[[bool], str]) -> list[str]:
    """Section 8: every example against its peer library."""
    r = ratios(all_rows, ns)
    intro = __doc__.split("\n\n", 1)[1].split("\n\n")[0].replace("\n", " ")
    lines = ["## 8. The examples against their peer libraries", "", intro, "",
             "Pure Python on both sides (`CODEWORD_PURE_PYTHON=1`), medians of interleaved rounds of the "
             "process's CPU time (a shared machine's other work left out); each row times the frames of one message "
             "(a few, for messages of several sizes), the calls and the checks are in `bench/examples.py`; "
             "an example's figure below is its messages' times summed.", ""]
    lines += _table(all_rows, ns, r) + ["", "Targets:", ""]
    lines += _targets(r, {"mavlink2"}, verdicts, met)
    for example in dict.fromkeys(row.example for row in all_rows):
        lines.append(f"- {example}, all its messages: decode × {r[(example, 'decode')]:.2f}, "
                     f"encode × {r[(example, 'encode')]:.2f}")
    slow = [f"{row.key} {op} ({r[(row.key, op)]:.2f})" for row in all_rows for op in ("decode", "encode")
            if r[(row.key, op)] < PEER_MIN]
    verdicts.append(not slow)
    lines.append(f"- every message of every example, decode and encode, peer / codeword ≥ {PEER_MIN}: "
                 f"{met(not slow)}" + (f"; below it: {', '.join(slow)}" if slow else ""))
    if any(k.startswith("nmea0183") for k in slow):
        lines.append("- where NMEA's encode misses: pynmea2 holds each field's text and only joins them; "
                     "codeword's encoder checks each value's type and range and writes its text (kept as "
                     "read, when unchanged), then both XOR the line")
    return lines
