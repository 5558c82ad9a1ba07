"""The libraries users would otherwise pick, driven the way their docs show.

Each codec takes and returns the library's own form (a tuple of raw values for
bitstruct, a dict or Container for construct and cantools, a MAVLink message
object for pymavlink) and validates only what the library itself validates;
the checksums the libraries cannot compute (ROUTE-D1 sum, CAR-D2 parity) are
computed by the wrapper, so every codec produces the same bytes as codeword.
"""

from pathlib import Path

import bitstruct.c as bitstruct_c
import cantools
import construct as cs
from pymavlink.dialects.v20 import common as mavlink2

DBC = Path(__file__).resolve().parent / "route_car.dbc"

ROUTE_FIELDS = ("hdr", "ns", "nl", "no", "na", "dl", "rc", "dr", "cm", "cs")
CAR_FIELDS = ("accept_ir", "forward_words", "motor_enable", "motor_direction", "motor_speed",
              "motor_duration", "led_led", "led_duration", "ultrasonic_enable", "ultrasonic_radius",
              "ultrasonic_duration", "voice", "body_sensor", "reserved_bits", "parity")


def route_checksum(raw):
    """ROUTE-D1: sum of the other fields' wire values mod 8 (na as sent, minus 10)."""
    return (raw["hdr"] + raw["ns"] + raw["nl"] + raw["no"] + raw["na"] + raw["dl"] + raw["rc"]
            + raw["dr"] + raw["cm"]) & 7


def car_parity(raw):
    """CAR-D2: even parity over the 31 other bits (a count of set bits, not a sum of values)."""
    return sum(raw[k].bit_count() for k in CAR_FIELDS[:-1]) & 1


# -- bitstruct (C extension) --------------------------------------------------------------
_ROUTE_BITS = bitstruct_c.compile("u2u3u3u3u3u3u2u3u4u3p3")
_CAR_BITS = bitstruct_c.compile("u1u1u1u2u2u2u2u2u1u2u2u1u1u11u1")


def bitstruct_route_encode(raw):
    hdr, ns, nl, no, na, dl, rc, dr, cm = raw
    return _ROUTE_BITS.pack(hdr, ns, nl, no, na, dl, rc, dr, cm,
                            (hdr + ns + nl + no + na + dl + rc + dr + cm) & 7)


def bitstruct_route_decode(data):
    return _ROUTE_BITS.unpack(data)


def bitstruct_car_encode(raw):
    return _CAR_BITS.pack(*raw, sum(v.bit_count() for v in raw) & 1)


def bitstruct_car_decode(data):
    return _CAR_BITS.unpack(data)


# -- construct ----------------------------------------------------------------------------
_ROUTE_CONSTRUCT = cs.BitStruct(*(name / cs.BitsInteger(width) for name, width in zip(
    ROUTE_FIELDS, (2, 3, 3, 3, 3, 3, 2, 3, 4, 3))), cs.Padding(3))
_CAR_CONSTRUCT = cs.BitStruct(*(name / cs.BitsInteger(width) for name, width in zip(
    CAR_FIELDS, (1, 1, 1, 2, 2, 2, 2, 2, 1, 2, 2, 1, 1, 11, 1))))


def construct_route_encode(raw):
    return _ROUTE_CONSTRUCT.build(dict(raw, cs=route_checksum(raw)))


def construct_route_decode(data):
    return _ROUTE_CONSTRUCT.parse(data)


def construct_car_encode(raw):
    return _CAR_CONSTRUCT.build(dict(raw, parity=car_parity(raw)))


def construct_car_decode(data):
    return _CAR_CONSTRUCT.parse(data)


# -- cantools (DBC in bench/route_car.dbc) -------------------------------------------------
_DB = cantools.database.load_file(str(DBC))
_ROUTE_DBC = _DB.get_message_by_name("RouteObject")
_CAR_DBC = _DB.get_message_by_name("CarMasterControl")


def cantools_route_encode(values):
    """values: logical values (na is the marker number; the DBC offset subtracts 10)."""
    raw = dict(values, na=values["na"] - 10)
    return _ROUTE_DBC.encode(dict(values, cs=route_checksum(raw)))


def cantools_route_decode(data):
    return _ROUTE_DBC.decode(data)


def cantools_car_encode(raw):
    return _CAR_DBC.encode(dict(raw, parity=car_parity(raw)))


def cantools_car_decode(data):
    return _CAR_DBC.decode(data)


# -- pymavlink: ATTITUDE, a 28-byte payload, 40 bytes as a MAVLink 2 frame -------------------
def mavlink():
    """A MAVLink 2 connection object with no file (system 1, component 1)."""
    return mavlink2.MAVLink(None, srcSystem=1, srcComponent=1)


ATTITUDE_VALUES = dict(time_boot_ms=123456, roll=0.25, pitch=-0.5, yaw=3.140625,
                       rollspeed=0.01, pitchspeed=-0.02, yawspeed=0.125)


def pymavlink_attitude_encode(mav, values):
    return mav.attitude_encode(**values).pack(mav)


def pymavlink_attitude_decode(mav, frame):
    return mav.decode(frame)  # frame: a bytearray, as parse_buffer passes it
