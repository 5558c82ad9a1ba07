"""Hand-written Python codecs for the benchmarked messages: the floor codeword is held to.

Each is what a competent engineer writes by hand for one message, knowing the
fast idioms: a precompiled `struct.Struct` or one `int.from_bytes` and shifts,
`str.split` and one compiled regular expression for a text line, enum and flag
values looked up in tables built at import, a CRC-16 that takes two bytes a
lookup from a 65,536-entry table built at import (constructed here on its own,
not taken from codeword), and its own message classes: plain classes with
`__slots__` and a positional `__init__`. Decode returns them, encode takes them.
Layouts are from ../shared/PROTOCOLS.md, as in the schemas.

Each checks the rules codeword's generated codec checks on that message, no
fewer:

- route object (ROUTE-D1, D3, D6): encode checks every field's range (na
  10..17, dl and dr 1..5, cm 1..15, the others their width); decode checks the
  padding bits, the header constant, dl, dr and cm, and the 3-bit checksum.
- car master control word (CAR-D1, D2, CAR-R1, R2): encode checks the two
  cross-field rules (accept_ir false, forward_words true), that each flag is
  0 or 1, the direction is one of its four values and each 2-bit field in
  0..3; decode checks the reserved bits, the parity and the two rules.
- mtv4 SetWheelsVelocitiesWithOdometry (MTV4-D1, D3..D6): encode checks group
  0..15, radio_crc_flag 0..1, exactly one robot bit, only the 3 status bits,
  vl and vr in -4096..4095.875, x, y and th finite binary32 values; decode
  checks the CRC-16/CMS, sync, length, group, command, exactly one robot
  bit, the status bits and that x, y and th are finite.
- tank telemetry line (TANK-D3..D6): encode checks the move and the two
  status enums, speed 0..100, extid 0..255, value one character, each text
  printable ASCII with no separator or terminator and no whitespace around
  it, lan and lon at most 32 characters, each double finite and of at most 15
  significant digits (zero or at least 1e-307 in magnitude), written in its
  shortest form; decode checks ASCII, the prefix and terminator (CR/LF around
  the line ignored), 20 fields, whitespace around a value trimmed, each
  token's syntax and the same value rules.
- tr24 command (TR24-D1, D3): encode checks seq 0..1, sender and receiver
  0..255 and 7 bytes of data; decode checks start, stop, the reserved bits
  and the type bit.

Like codeword's, every rule broken is a ValueError. What the floor leaves out
is codeword's own API: its error objects (field, offset, decision), the
per-field type checks on encode (Python itself refuses most wrong types
here: a str in a shift, a float in a `struct` integer), a tank line given as
bytes, `to_dict`. Those are codeword's costs, not the message's.
"""

import enum
import math
import re
import struct

_isfinite = math.isfinite


class _Message:
    __slots__ = ()

    def __repr__(self):
        fields = ", ".join(f"{name}={getattr(self, name)!r}" for name in self.__slots__)
        return f"{type(self).__name__}({fields})"


# -- route: object sentence, 29 bits MSB first, left-aligned in 4 bytes (ROUTE-D4) ----------
class RouteObject(_Message):
    __slots__ = ("ns", "nl", "no", "na", "dl", "rc", "dr", "cm")

    def __init__(self, ns, nl, no, na, dl, rc, dr, cm):
        self.ns = ns
        self.nl = nl
        self.no = no
        self.na = na
        self.dl = dl
        self.rc = rc
        self.dr = dr
        self.cm = cm


def route_object_encode(m):
    ns, nl, no, na, dl, rc, dr, cm = m.ns, m.nl, m.no, m.na, m.dl, m.rc, m.dr, m.cm
    if not (0 <= ns <= 7 and 0 <= nl <= 7 and 0 <= no <= 7 and 10 <= na <= 17 and 1 <= dl <= 5
            and 0 <= rc <= 3 and 1 <= dr <= 5 and 1 <= cm <= 15):
        raise ValueError("object field out of range")
    na -= 10  # ROUTE-D6: the wire carries the marker number minus 10
    cs = (1 + ns + nl + no + na + dl + rc + dr + cm) & 7  # ROUTE-D1
    word = (1 << 27 | ns << 24 | nl << 21 | no << 18 | na << 15 | dl << 12 | rc << 10 | dr << 7
            | cm << 3 | cs)
    return (word << 3).to_bytes(4, "big")


def route_object_decode(d):
    if len(d) != 4:
        raise ValueError("object is 4 bytes")
    w = int.from_bytes(d, "big")
    if w & 7:
        raise ValueError("padding bits set")
    w >>= 3
    ns, nl, no, na = w >> 24 & 7, w >> 21 & 7, w >> 18 & 7, w >> 15 & 7
    dl, rc, dr, cm, cs = w >> 12 & 7, w >> 10 & 3, w >> 7 & 7, w >> 3 & 15, w & 7
    if w >> 27 != 1 or not (1 <= dl <= 5 and 1 <= dr <= 5 and cm):
        raise ValueError("bad object")
    if cs != (1 + ns + nl + no + na + dl + rc + dr + cm) & 7:
        raise ValueError("bad checksum")
    return RouteObject(ns, nl, no, na + 10, dl, rc, dr, cm)


# -- car: master control word, 32 bits big-endian, even parity in bit 31 (CAR-D2) ----------
class MotorDirection(enum.IntEnum):
    forward = 0
    left = 1
    right = 2
    random = 3


_DIRECTIONS = tuple(MotorDirection)


class CarMotor(_Message):
    __slots__ = ("enable", "direction", "speed", "duration")

    def __init__(self, enable=False, direction=MotorDirection.forward, speed=0, duration=0):
        self.enable = enable
        self.direction = direction
        self.speed = speed
        self.duration = duration


class CarLed(_Message):
    __slots__ = ("led", "duration")

    def __init__(self, led=0, duration=0):
        self.led = led
        self.duration = duration


class CarUltrasonic(_Message):
    __slots__ = ("enable", "radius", "duration")

    def __init__(self, enable=False, radius=0, duration=0):
        self.enable = enable
        self.radius = radius
        self.duration = duration


class CarMasterControl(_Message):
    __slots__ = ("accept_ir", "forward_words", "motor", "led", "ultrasonic", "voice", "body_sensor")

    def __init__(self, accept_ir, forward_words, motor, led, ultrasonic, voice=False, body_sensor=False):
        self.accept_ir = accept_ir
        self.forward_words = forward_words
        self.motor = motor
        self.led = led
        self.ultrasonic = ultrasonic
        self.voice = voice
        self.body_sensor = body_sensor


_BITS = (0, 1)


def car_master_encode(m):
    mo, led, us = m.motor, m.led, m.ultrasonic
    if m.accept_ir != 0 or m.forward_words != 1:  # CAR-R1, CAR-R2 (False == 0, True == 1)
        raise ValueError("accept_ir must be false and forward_words true")
    if (mo.enable not in _BITS or us.enable not in _BITS or m.voice not in _BITS
            or m.body_sensor not in _BITS or mo.direction not in _DIRECTIONS):
        raise ValueError("flag or direction out of range")
    if not (0 <= mo.speed <= 3 and 0 <= mo.duration <= 3 and 0 <= led.led <= 3
            and 0 <= led.duration <= 3 and 0 <= us.radius <= 3 and 0 <= us.duration <= 3):
        raise ValueError("control word field out of range")
    word = (1 << 30 | mo.enable << 29 | mo.direction << 27 | mo.speed << 25
            | mo.duration << 23 | led.led << 21 | led.duration << 19 | us.enable << 18
            | us.radius << 16 | us.duration << 14 | m.voice << 13 | m.body_sensor << 12)
    return (word | word.bit_count() & 1).to_bytes(4, "big")


def car_master_decode(d):
    if len(d) != 4:
        raise ValueError("control word is 4 bytes")
    w = int.from_bytes(d, "big")
    if w.bit_count() & 1:
        raise ValueError("bad parity")
    if w & 0xffe or w >> 30 != 1:  # reserved bits; accept_ir = 0 and forward_words = 1
        raise ValueError("bad control word")
    return CarMasterControl(
        False, True,
        CarMotor(w & 0x20000000 != 0, _DIRECTIONS[w >> 27 & 3], w >> 25 & 3, w >> 23 & 3),
        CarLed(w >> 21 & 3, w >> 19 & 3),
        CarUltrasonic(w & 0x40000 != 0, w >> 16 & 3, w >> 14 & 3),
        w & 0x2000 != 0, w & 0x1000 != 0)


# -- mtv4: SetWheelsVelocitiesWithOdometry, 26 bytes, CRC-16/CMS over bytes 1..23 ----------
class Robots(enum.IntFlag):
    """bit n = robot n of the group (MTV4-D3)"""
    robot0 = 1 << 0
    robot1 = 1 << 1
    robot2 = 1 << 2
    robot3 = 1 << 3
    robot4 = 1 << 4
    robot5 = 1 << 5
    robot6 = 1 << 6
    robot7 = 1 << 7
    robot8 = 1 << 8
    robot9 = 1 << 9
    robot10 = 1 << 10
    robot11 = 1 << 11
    robot12 = 1 << 12
    robot13 = 1 << 13
    robot14 = 1 << 14
    robot15 = 1 << 15


class Status(enum.IntFlag):
    speed_control = 1
    power_amplifiers = 2
    overwrite_odometry = 4


# one robot bit: a lookup both checks "exactly one" and gives the flag value
_ONE_ROBOT = {1 << n: Robots(1 << n) for n in range(16)}
_STATUSES = tuple(Status(v) for v in range(8))


class SetWheelsVelocitiesWithOdometry(_Message):
    __slots__ = ("group", "robots", "status", "vl", "vr", "x", "y", "th", "radio_crc_flag")

    def __init__(self, group, robots, status, vl, vr, x, y, th, radio_crc_flag=0):
        self.group = group
        self.robots = robots
        self.status = status
        self.vl = vl
        self.vr = vr
        self.x = x
        self.y = y
        self.th = th
        self.radio_crc_flag = radio_crc_flag


def _crc16_cms_tables():
    """CRC-16/CMS (poly 0x8005, init 0xffff, not reflected, no final xor; MTV4-D1):
    the byte table, and the pair table that runs two bytes a lookup. The register after
    the bytes h, l from register r depends only on r ^ (h << 8 | l), so the pair table's
    entry x is the register after two zero bytes from register x."""
    byte = []
    for b in range(256):
        reg = b << 8
        for _ in range(8):
            reg = (reg << 1 ^ 0x8005 if reg & 0x8000 else reg << 1) & 0xffff
        byte.append(reg)
    # first zero byte from x = h << 8 | l: byte[h] ^ l << 8; the second shifts that out
    pair = tuple(byte[byte[h] >> 8 ^ low] ^ (byte[h] << 8 & 0xffff) for h in range(256) for low in range(256))
    return tuple(byte), pair


_CRC_BYTE, _CRC_PAIR = _crc16_cms_tables()
_CRC_PAIRS = struct.Struct(">11H")  # bytes 1..22 of the frame; byte 23 ends the span


def crc16_cms(frame):
    """CRC-16/CMS over bytes 1..23 of an mtv4 odometry frame."""
    reg, pair = 0xffff, _CRC_PAIR
    for p in _CRC_PAIRS.unpack_from(frame, 1):
        reg = pair[reg ^ p]
    return _CRC_BYTE[reg >> 8 ^ frame[23]] ^ (reg << 8 & 0xffff)


_ODO = struct.Struct("<BBBBHHhhfff")  # bytes 0..23; the CRC follows, big-endian
_F32_MAX = 3.4028234663852886e38


def mtv4_odometry_encode(m):
    robots, status, x, y, th = m.robots, m.status, m.x, m.y, m.th
    # a comparison chain is false for NaN as well as out of range
    if not (0 <= m.group <= 15 and 0 <= m.radio_crc_flag <= 1 and robots in _ONE_ROBOT
            and 0 <= status <= 7 and -4096 <= m.vl <= 4095.875 and -4096 <= m.vr <= 4095.875
            and -_F32_MAX <= x <= _F32_MAX and -_F32_MAX <= y <= _F32_MAX and -_F32_MAX <= th <= _F32_MAX):
        raise ValueError("set_wheels_velocities_with_odometry field out of range")
    body = _ODO.pack(0xAA, 22, m.group, m.radio_crc_flag << 7 | 3, robots, status,
                     math.floor(m.vl * 8 + 0.5), math.floor(m.vr * 8 + 0.5), x, y, th)
    return body + crc16_cms(body).to_bytes(2, "big")


def mtv4_odometry_decode(d):
    if len(d) != 26:
        raise ValueError("frame is 26 bytes")
    sync, length, group, cmd, robots, status, vl, vr, x, y, th = _ODO.unpack_from(d)
    if d[24] << 8 | d[25] != crc16_cms(d):
        raise ValueError("bad CRC")
    one_robot = _ONE_ROBOT.get(robots)
    if sync != 0xAA or length != 22 or group > 15 or cmd & 0x7f != 3 or one_robot is None or status > 7:
        raise ValueError("bad frame")
    if not (_isfinite(x) and _isfinite(y) and _isfinite(th)):
        raise ValueError("not finite")
    return SetWheelsVelocitiesWithOdometry(group, one_robot, _STATUSES[status], vl * 0.125, vr * 0.125,
                                           x, y, th, cmd >> 7)


# -- tank: telemetry line `$:<20 comma-separated fields>;` (TANK-D3..D6) --------------------
class Move(str, enum.Enum):
    forward = "f"
    back = "b"
    left = "l"
    right = "r"
    forward_left = "a"
    forward_right = "c"
    back_left = "d"
    back_right = "e"


class SystemStatus(enum.IntEnum):
    stop = 0
    work = 1
    shutdown = 2
    eco = 3
    e_mode = 4
    error = 5
    exception = 6


class ExtStatus(enum.IntEnum):
    disconnected = 0
    working = 1
    initialisation = 2
    exception = 3
    unknown = 4
    error = 5


_MOVES = {m.value: m for m in Move}
_MOVE_TEXT = {m: m.value for m in Move}
_SYSTEM_STATUSES = tuple(SystemStatus)
_EXT_STATUSES = tuple(ExtStatus)

_FLOATS = ("lcurr", "rcurr", "accx", "accy", "accz", "gyrox", "gyroy", "gyroz", "magx", "magy", "magz")


class Telemetry(_Message):
    __slots__ = ("move", "speed", "value") + _FLOATS + ("lan", "lon", "vbat", "systemstatus", "extid",
                                                         "extstatus")

    def __init__(self, move, speed, value, lcurr, rcurr, accx, accy, accz, gyrox, gyroy, gyroz, magx, magy,
                 magz, lan, lon, vbat, systemstatus, extid, extstatus):
        self.move = move
        self.speed = speed
        self.value = value
        self.lcurr = lcurr
        self.rcurr = rcurr
        self.accx = accx
        self.accy = accy
        self.accz = accz
        self.gyrox = gyrox
        self.gyroy = gyroy
        self.gyroz = gyroz
        self.magx = magx
        self.magy = magy
        self.magz = magz
        self.lan = lan
        self.lon = lon
        self.vbat = vbat
        self.systemstatus = systemstatus
        self.extid = extid
        self.extstatus = extstatus


# A well-formed line needs no per-token checks: a printable character other than space and
# the separator and terminator; an integer of at most 20 digits; a number of at most 15
# digits and a point with an exponent of at most two digits, so at most 15 significant
# digits, finite, and zero or at least 1e-113 in magnitude.
_CHAR = r"[!-+\--:<-~]"
_INT = r"[+-]?[0-9]{1,20}"
_SHORT_NUMBER = r"[+-]?(?=[0-9.]{1,15}(?![0-9.]))(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][+-]?[0-9]{1,2})?"
_TELEMETRY_LINE = re.compile(",".join([_CHAR, _INT, _CHAR] + [_SHORT_NUMBER] * 11
                                      + [_CHAR + "*", _CHAR + "*", _SHORT_NUMBER, _INT, _INT, _INT]))
_TEXT = re.compile(_CHAR + "*")
_INT_TOKEN = re.compile(r"[+-]?[0-9]+")
_NUMBER_TOKEN = re.compile(r"[+-]?(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][+-]?[0-9]+)?")


def _significant_digits(number_text):
    mantissa = number_text.lower().partition("e")[0]
    return len(mantissa.lstrip("+-").replace(".", "").strip("0"))


def _number(v):
    """The shortest text of a finite double of at most 15 significant digits (TANK-D6)."""
    if not _isfinite(v) or (v and -1e-307 < v < 1e-307):
        raise ValueError("number not finite or too small")
    text = repr(float(v))
    if text.endswith(".0"):
        text = text[:-2]
    if len(text) > 15 and _significant_digits(text) > 15:  # 16 digits need 16 characters
        raise ValueError("more than 15 significant digits")
    return text


def _text(s):
    """Printable ASCII, no separator or terminator, no whitespace around it (TANK-D5)."""
    if _TEXT.fullmatch(s) is None and (not s.isascii() or not s.isprintable() or "," in s or ";" in s
                                       or s != s.strip()):
        raise ValueError("bad text field")
    return s


def tank_telemetry_encode(m):
    move = _MOVE_TEXT.get(m.move)
    if move is None or m.systemstatus not in _SYSTEM_STATUSES or m.extstatus not in _EXT_STATUSES:
        raise ValueError("telemetry enum out of range")
    if not 0 <= m.speed <= 100 or not 0 <= m.extid <= 255 or len(m.value) != 1 or len(m.lan) > 32 \
            or len(m.lon) > 32:
        raise ValueError("telemetry field out of range")
    return "$:%s,%d,%s,%s,%s,%s,%s,%d,%d,%d;" % (
        move, m.speed, _text(m.value),
        ",".join(map(_number, (m.lcurr, m.rcurr, m.accx, m.accy, m.accz, m.gyrox, m.gyroy, m.gyroz, m.magx,
                               m.magy, m.magz))),
        _text(m.lan), _text(m.lon), _number(m.vbat), m.systemstatus, m.extid, m.extstatus)


def _checked_int(token):
    if _INT_TOKEN.fullmatch(token) is None:
        raise ValueError("not a decimal integer")
    return token


def _checked_number(token):
    if _NUMBER_TOKEN.fullmatch(token) is None:
        raise ValueError("not a decimal number")
    digits, value = _significant_digits(token), float(token)
    if digits > 15 or (digits and -1e-307 < value < 1e-307) or not _isfinite(value):
        raise ValueError("number beyond 15 significant digits or not finite")
    return token


def _checked_tokens(tokens):
    """The tokens of a line the fast pattern refused, trimmed and checked one by one."""
    t = [token.strip() for token in tokens]
    for i in (1, 17, 18, 19):
        _checked_int(t[i])
    for i in range(3, 14):
        _checked_number(t[i])
    _checked_number(t[16])
    for i in (2, 14, 15):
        _text(t[i])
    return t


def _telemetry_body(line):
    if not line.isascii():
        raise ValueError("not ASCII")
    line = line.strip("\r\n")  # TANK-D4
    if line[:2] == "$:" and line[-1:] == ";":
        return line[2:-1]
    prefix, colon, rest = line.partition(":")
    if not colon or prefix.strip() != "$" or not rest.endswith(";"):
        raise ValueError("not a telemetry line")
    return rest[:-1]


def tank_telemetry_decode(line):
    body = _telemetry_body(line)
    t = body.split(",")
    if len(t) != 20:
        raise ValueError("telemetry has 20 fields")
    if _TELEMETRY_LINE.fullmatch(body) is None:
        t = _checked_tokens(t)
    move, speed, value, lan, lon, extid = _MOVES.get(t[0]), int(t[1]), t[2], t[14], t[15], int(t[18])
    status, ext = int(t[17]), int(t[19])
    if move is None or not 0 <= speed <= 100 or len(value) != 1 or len(lan) > 32 or len(lon) > 32 \
            or not 0 <= extid <= 255 or not 0 <= status <= 6 or not 0 <= ext <= 5:
        raise ValueError("telemetry field out of range")
    return Telemetry(move, speed, value, float(t[3]), float(t[4]), float(t[5]), float(t[6]), float(t[7]),
                     float(t[8]), float(t[9]), float(t[10]), float(t[11]), float(t[12]), float(t[13]), lan, lon,
                     float(t[16]), _SYSTEM_STATUSES[status], extid, _EXT_STATUSES[ext])


# -- tr24: command packet, 12 bytes: start, service, sender, receiver, 7 data, stop -------
class Tr24Command(_Message):
    __slots__ = ("seq", "sender", "receiver", "data")

    def __init__(self, seq, sender, receiver, data):
        self.seq = seq
        self.sender = sender
        self.receiver = receiver
        self.data = data


_TR24 = struct.Struct("<BBBB7sB")


def tr24_command_encode(m):
    if not (0 <= m.seq <= 1 and 0 <= m.sender <= 255 and 0 <= m.receiver <= 255) or len(m.data) != 7:
        raise ValueError("command field out of range")
    return _TR24.pack(2, m.seq, m.sender, m.receiver, m.data, 3)


def tr24_command_decode(d):
    if len(d) != 12:
        raise ValueError("packet is 12 bytes")
    start, service, sender, receiver, data, stop = _TR24.unpack_from(d)
    if start != 2 or stop != 3 or service & 0xfe:  # TR24-D1: reserved bits and type 0
        raise ValueError("bad packet")
    return Tr24Command(service, sender, receiver, data)
