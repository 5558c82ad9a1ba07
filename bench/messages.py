"""Python per-message cases: codeword, the hand-written floor and the peers.

A case holds, for each contender, an encode and a decode call with its input
bound (codeword's per-message entry points, `obj.encode()` and `Cls.decode()`,
like the hand-written functions, bound as methods or with `functools.partial`,
so neither pays for a lambda; mtv4 also has the dispatching `mtv4.decode`,
which is what pymavlink's `decode` does). A peer has a function that turns its
decode result into plain wire-level values; the hand-written floor has message
classes of its own, so its input object and its decoded object are compared
with codeword's field by field. The smoke test checks that every contender
produces the same bytes and reads back the same values (equal work).
"""

import dataclasses
import enum
from dataclasses import dataclass, field
from functools import partial
from typing import Any, Callable, Optional

from bench import handwritten as hw
from bench import peers
from bench.protocols import car, mtv4, route, tank, tr24


DISPATCHING = "codeword, any message (mtv4.decode)"


FLOOR = "hand-written"


@dataclass
class Contender:
    encode: Callable[[], Any]
    decode: Callable[[], Any]
    # decode result → values compared with the example's; None: not compared (another message)
    values: Optional[Callable[[Any], Any]] = None
    # the message object encode takes, when it is of the contender's own classes: it and the
    # decoded object are compared with codeword's field by field
    own_object: Any = None


@dataclass
class Case:
    key: str
    title: str
    wire: Any  # the expected frame, from the schema's hand-calculated example
    expected: Any  # the example's values, from the message object written out by hand
    contenders: dict[str, Contender] = field(default_factory=dict)
    bit_packed: bool = False
    message: Any = None  # codeword's message object of the example: what its encode takes


def _floor(own_object, encode, decode, wire):
    return Contender(partial(encode, own_object), partial(decode, wire), own_object=own_object)


def _route_case():
    # schemas/route.yaml example "second object of scene 3, seed line 13": 59 11 69 20
    obj = route.Object(ns=3, nl=1, no=0, na=14, dl=2, rc=3, dr=2, cm=4)
    wire = bytes.fromhex("59116920")
    raw = dict(hdr=1, ns=3, nl=1, no=0, na=4, dl=2, rc=3, dr=2, cm=4)
    raw_tuple = tuple(raw.values())
    logical = dict(raw, na=14)

    def of_object(o):
        return (o.ns, o.nl, o.no, o.na, o.dl, o.rc, o.dr, o.cm)

    def of_raw(r):
        r = dict(r)
        return (r["ns"], r["nl"], r["no"], r["na"] + 10, r["dl"], r["rc"], r["dr"], r["cm"])

    case = Case("route", "route object sentence (29 bits)", wire, of_object(obj), bit_packed=True, message=obj)
    case.contenders = {
        "codeword": Contender(obj.encode, partial(route.Object.decode, wire), of_object),
        FLOOR: _floor(hw.RouteObject(*of_object(obj)), hw.route_object_encode, hw.route_object_decode, wire),
        "bitstruct.c": Contender(lambda: peers.bitstruct_route_encode(raw_tuple),
                                 lambda: peers.bitstruct_route_decode(wire),
                                 lambda t: of_raw(zip(peers.ROUTE_FIELDS, t))),
        "construct": Contender(lambda: peers.construct_route_encode(raw),
                               lambda: peers.construct_route_decode(wire),
                               lambda c: of_raw((k, c[k]) for k in peers.ROUTE_FIELDS)),
        "cantools": Contender(lambda: peers.cantools_route_encode(logical),
                              lambda: peers.cantools_route_decode(wire),
                              lambda d: of_raw(dict(d, na=d["na"] - 10))),
    }
    return case


def _car_case():
    # schemas/car.yaml example "master drives forward at speed 2 for duration 3": 65 80 00 01
    obj = car.MasterControl(accept_ir=False, forward_words=True,
                            motor=car.ControlWordMotor(enable=True, direction=car.MotorDirection.forward,
                                                       speed=2, duration=3))
    wire = bytes.fromhex("65800001")
    floor = hw.CarMasterControl(False, True, hw.CarMotor(True, hw.MotorDirection.forward, 2, 3), hw.CarLed(),
                                hw.CarUltrasonic())
    raw = dict.fromkeys(peers.CAR_FIELDS[:-1], 0)
    raw.update(forward_words=1, motor_enable=1, motor_speed=2, motor_duration=3)
    raw_tuple = tuple(raw.values())

    def of_object(o):
        return (int(o.accept_ir), int(o.forward_words), int(o.motor.enable), int(o.motor.direction),
                o.motor.speed, o.motor.duration, o.led.led, o.led.duration, int(o.ultrasonic.enable),
                o.ultrasonic.radius, o.ultrasonic.duration, int(o.voice), int(o.body_sensor))

    def of_raw(r):
        r = dict(r)
        return tuple(r[k] for k in peers.CAR_FIELDS[:13])

    case = Case("car", "car master control word (32 bits)", wire, of_object(obj), bit_packed=True, message=obj)
    case.contenders = {
        "codeword": Contender(obj.encode, partial(car.MasterControl.decode, wire), of_object),
        FLOOR: _floor(floor, hw.car_master_encode, hw.car_master_decode, wire),
        "bitstruct.c": Contender(lambda: peers.bitstruct_car_encode(raw_tuple),
                                 lambda: peers.bitstruct_car_decode(wire),
                                 lambda t: of_raw(zip(peers.CAR_FIELDS, t))),
        "construct": Contender(lambda: peers.construct_car_encode(raw),
                               lambda: peers.construct_car_decode(wire),
                               lambda c: of_raw((k, c[k]) for k in peers.CAR_FIELDS)),
        "cantools": Contender(lambda: peers.cantools_car_encode(raw),
                              lambda: peers.cantools_car_decode(wire), of_raw),
    }
    return case


def mtv4_odometry_message():
    # schemas/mtv4.yaml example "all status bits, odometry overwritten"
    return mtv4.SetWheelsVelocitiesWithOdometry(
        group=2, robots=mtv4.Robots.robot12, status=mtv4.Status(7), vl=250, vr=-0.125, x=1.5,
        y=-0.25, th=3.140625)


MTV4_ODOMETRY_WIRE = bytes.fromhex(
    "aa 16 02 03 00 10 07 00 d0 07 ff ff 00 00 c0 3f 00 00 80 be 00 00 49 40 f7 eb")


def _mtv4_case():
    obj = mtv4_odometry_message()
    wire = MTV4_ODOMETRY_WIRE

    def of_object(o):
        return (o.group, int(o.robots), int(o.status), o.vl, o.vr, o.x, o.y, o.th)

    mav = peers.mavlink()
    mav_frame = bytearray(peers.pymavlink_attitude_encode(mav, peers.ATTITUDE_VALUES))

    case = Case("mtv4", "mtv4 SetWheelsVelocitiesWithOdometry (26-byte frame, CRC-16)", wire, of_object(obj), message=obj)
    case.contenders = {
        "codeword": Contender(obj.encode, partial(mtv4.SetWheelsVelocitiesWithOdometry.decode, wire), of_object),
        # what pymavlink's decode does: find the message from its id, then decode it
        DISPATCHING: Contender(lambda: mtv4.encode(obj), lambda: mtv4.decode(wire), of_object),
        FLOOR: _floor(hw.SetWheelsVelocitiesWithOdometry(2, hw.Robots.robot12, hw.Status(7), 250, -0.125, 1.5,
                                                         -0.25, 3.140625),
                      hw.mtv4_odometry_encode, hw.mtv4_odometry_decode, wire),
        # a different message of comparable size: its bytes are not compared
        "pymavlink ATTITUDE (40 B)": Contender(
            lambda: peers.pymavlink_attitude_encode(mav, peers.ATTITUDE_VALUES),
            lambda: peers.pymavlink_attitude_decode(mav, mav_frame), None),
    }
    return case


def _tank_case():
    # schemas/tank.yaml example "driving forward-left, fractional and negative readings"
    wire = "$:a,50,s,1.25,-0.5,0.01,-0.02,9.81,0,0,-1.5,23,-7,41.5,55.7558,37.6173,12.6,1,0,1;"
    obj = tank.Telemetry(
        move=tank.Move.forward_left, speed=50, value="s", lcurr=1.25, rcurr=-0.5, accx=0.01,
        accy=-0.02, accz=9.81, gyrox=0.0, gyroy=0.0, gyroz=-1.5, magx=23.0, magy=-7.0, magz=41.5,
        lan="55.7558", lon="37.6173", vbat=12.6, systemstatus=tank.SystemStatus.work, extid=0,
        extstatus=tank.ExtStatus.working)
    floor = hw.Telemetry(hw.Move.forward_left, 50, "s", 1.25, -0.5, 0.01, -0.02, 9.81, 0.0, 0.0, -1.5, 23.0, -7.0,
                         41.5, "55.7558", "37.6173", 12.6, hw.SystemStatus.work, 0, hw.ExtStatus.working)

    def of_object(o):
        return tuple(getattr(o, name) for name in tank.Telemetry.__slots__)

    case = Case("tank", "tank telemetry line (20 fields)", wire, of_object(obj), message=obj)
    case.contenders = {
        "codeword": Contender(obj.encode, partial(tank.Telemetry.decode, wire), of_object),
        FLOOR: _floor(floor, hw.tank_telemetry_encode, hw.tank_telemetry_decode, wire),
    }
    return case


def _tr24_case():
    # schemas/tr24.yaml example "the seed's command, seq 0, from ID 1 to ID 3"
    wire = bytes.fromhex("02 00 01 03 2c 00 00 00 00 00 00 03")
    obj = tr24.Command(seq=0, sender=1, receiver=3, data=bytes.fromhex("2c 00 00 00 00 00 00"))

    def of_object(o):
        return (o.seq, o.sender, o.receiver, o.data)

    case = Case("tr24", "tr24 command packet (12 bytes)", wire, of_object(obj), message=obj)
    case.contenders = {
        "codeword": Contender(obj.encode, partial(tr24.Command.decode, wire), of_object),
        FLOOR: _floor(hw.Tr24Command(*of_object(obj)), hw.tr24_command_encode, hw.tr24_command_decode, wire),
    }
    return case


def cases():
    return [_route_case(), _car_case(), _mtv4_case(), _tank_case(), _tr24_case()]


def differences(ours, reference, path=""):
    """Where `ours`, an object of another codec's classes, differs from codeword's object
    `reference`, field by field: groups field by field, enum and flag members by name and
    value, anything else by type and value."""
    out = []
    for f in dataclasses.fields(reference):
        where, want = f"{path}{f.name}", getattr(reference, f.name)
        if not hasattr(ours, f.name):
            out.append(f"{where}: missing")
            continue
        got = getattr(ours, f.name)
        if dataclasses.is_dataclass(want):
            out += differences(got, want, where + ".")
        elif isinstance(want, enum.Enum):
            if not isinstance(got, enum.Enum) or (got.name, got.value) != (want.name, want.value):
                out.append(f"{where}: {got!r}, codeword {want!r}")
        elif type(got) is not type(want) or got != want:
            out.append(f"{where}: {got!r}, codeword {want!r}")
    return out


def check(case):
    """Problems with a case: a contender whose bytes or decoded values differ from the
    schema example's, or whose own objects differ from codeword's."""
    problems = []
    codeword = case.contenders["codeword"]
    for name, c in case.contenders.items():
        if c.values is None and c.own_object is None:
            continue
        wire = c.encode()
        if wire != case.wire:
            problems.append(f"{case.key}/{name}: encodes {wire!r}, expected {case.wire!r}")
        if c.own_object is not None:
            problems += [f"{case.key}/{name}: input {d}" for d in differences(c.own_object, case.message)]
            problems += [f"{case.key}/{name}: decodes {d}" for d in differences(c.decode(), codeword.decode())]
            continue
        got = c.values(c.decode())
        if got != case.expected:
            problems.append(f"{case.key}/{name}: decodes to {got}, expected {case.expected}")
    return problems
