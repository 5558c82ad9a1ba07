"""Hand-written Python codecs for the benchmarked messages: the practical floor.

Each one is what a careful engineer writes by hand with `int.from_bytes` and
shifts, `struct` and `str.split`: it checks what the wire cannot guarantee
(ranges narrower than a field's width, constants, checksums, finiteness) and
takes and returns the same message objects as the generated codec, so the two
do the same work. Layouts are from ../shared/PROTOCOLS.md, as in the schemas.
"""

import math
import struct

from bench.protocols import car, mtv4, route, tank, tr24

_isfinite = math.isfinite


# -- route: object sentence, 29 bits MSB first, left-aligned in 4 bytes (ROUTE-D4) ----------
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
    return route.Object(ns=ns, nl=nl, no=no, na=na + 10, dl=dl, rc=rc, dr=dr, cm=cm)


# -- car: master control word, 32 bits big-endian, even parity in bit 31 (CAR-D2) ----------
_DIRECTIONS = tuple(car.MotorDirection)


def car_master_encode(m):
    mo, led, us = m.motor, m.led, m.ultrasonic
    if m.accept_ir or not m.forward_words:
        raise ValueError("CAR-R1/CAR-R2")
    if not (0 <= mo.speed <= 3 and 0 <= mo.duration <= 3 and 0 <= led.led <= 3
            and 0 <= led.duration <= 3 and 0 <= us.radius <= 3 and 0 <= us.duration <= 3):
        raise ValueError("control word field out of range")
    word = (1 << 30 | mo.enable << 29 | int(mo.direction) << 27 | mo.speed << 25
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
    return car.MasterControl(
        accept_ir=False, forward_words=True,
        motor=car.ControlWordMotor(enable=w >> 29 & 1 == 1, direction=_DIRECTIONS[w >> 27 & 3],
                                   speed=w >> 25 & 3, duration=w >> 23 & 3),
        led=car.ControlWordLed(led=w >> 21 & 3, duration=w >> 19 & 3),
        ultrasonic=car.ControlWordUltrasonic(enable=w >> 18 & 1 == 1, radius=w >> 16 & 3,
                                             duration=w >> 14 & 3),
        voice=w >> 13 & 1 == 1, body_sensor=w >> 12 & 1 == 1)


# -- mtv4: SetWheelsVelocitiesWithOdometry, 26 bytes, CRC-16/CMS over bytes 1..23 ----------
_ODO = struct.Struct("<BBBBHHhhfff")


def _crc16_table():
    table = []
    for byte in range(256):
        reg = byte << 8
        for _ in range(8):
            reg = ((reg << 1) ^ 0x8005) & 0xffff if reg & 0x8000 else (reg << 1) & 0xffff
        table.append(reg)
    return tuple(table)


_CRC_TABLE = _crc16_table()


def crc16_cms(data):
    """CRC-16/CMS (poly 0x8005, init 0xffff, no reflection): MTV4-D1."""
    reg, table = 0xffff, _CRC_TABLE
    for byte in data:
        reg = table[(reg >> 8) ^ byte] ^ (reg << 8 & 0xffff)
    return reg


def _finite32(v):
    return _isfinite(v) and -3.4028234663852886e38 <= v <= 3.4028234663852886e38


def mtv4_odometry_encode(m):
    robots, status = int(m.robots), int(m.status)
    if not (0 <= m.group <= 15 and 0 < robots <= 0xffff and not robots & (robots - 1)
            and 0 <= status <= 7 and -4096 <= m.vl <= 4095.875 and -4096 <= m.vr <= 4095.875
            and _finite32(m.x) and _finite32(m.y) and _finite32(m.th)):
        raise ValueError("set_wheels_velocities_with_odometry field out of range")
    body = _ODO.pack(0xAA, 22, m.group, m.radio_crc_flag << 7 | 3, robots, status,
                     math.floor(m.vl * 8 + 0.5), math.floor(m.vr * 8 + 0.5), m.x, m.y, m.th)
    return body + crc16_cms(body[1:]).to_bytes(2, "big")


def mtv4_odometry_decode(d):
    if len(d) != 26:
        raise ValueError("frame is 26 bytes")
    sync, length, group, cmd, robots, status, vl, vr, x, y, th = _ODO.unpack_from(d)
    if (sync != 0xAA or length != 22 or group > 15 or cmd & 0x7f != 3 or not robots
            or robots & (robots - 1) or status & ~7):
        raise ValueError("bad frame")
    if not (_isfinite(x) and _isfinite(y) and _isfinite(th)):
        raise ValueError("not finite")
    if int.from_bytes(d[24:26], "big") != crc16_cms(d[1:24]):
        raise ValueError("bad CRC")
    return mtv4.SetWheelsVelocitiesWithOdometry(
        group=group, radio_crc_flag=cmd >> 7, robots=mtv4.Robots(robots), status=mtv4.Status(status),
        vl=vl * 0.125, vr=vr * 0.125, x=x, y=y, th=th)


# -- tank: telemetry line `$:<20 comma-separated fields>;` (TANK-D3, TANK-D5) --------------
_MOVES = {m.value: m for m in tank.Move}
_STATUS = tuple(tank.SystemStatus)
_EXT = tuple(tank.ExtStatus)


def _fmt(v):
    text = repr(float(v))
    return text[:-2] if text.endswith(".0") else text


def _clean(s):
    if "," in s or ";" in s or len(s) > 32 or s != s.strip() or not s.isascii():
        raise ValueError("bad text field")
    return s


def tank_telemetry_encode(m):
    if not 0 <= m.speed <= 100 or not 0 <= m.extid <= 255 or len(m.value) != 1:
        raise ValueError("telemetry field out of range")
    floats = (m.lcurr, m.rcurr, m.accx, m.accy, m.accz, m.gyrox, m.gyroy, m.gyroz, m.magx, m.magy,
              m.magz)
    if not all(map(_isfinite, floats)) or not _isfinite(m.vbat):
        raise ValueError("not finite")
    return "$:%s,%d,%s,%s,%s,%s,%s,%d,%d,%d;" % (
        m.move.value, m.speed, _clean(m.value), ",".join(map(_fmt, floats)), _clean(m.lan),
        _clean(m.lon), _fmt(m.vbat), m.systemstatus, m.extid, m.extstatus)


def tank_telemetry_decode(line):
    if not line.startswith("$:") or not line.endswith(";"):
        raise ValueError("not a telemetry line")
    t = line[2:-1].split(",")
    if len(t) != 20:
        raise ValueError("telemetry has 20 fields")
    f = [float(x) for x in t[3:14]]
    vbat, speed, extid = float(t[16]), int(t[1]), int(t[18])
    status, ext = int(t[17]), int(t[19])
    if not all(map(_isfinite, f)) or not _isfinite(vbat) or not 0 <= speed <= 100 \
            or not 0 <= extid <= 255 or not 0 <= status < len(_STATUS) or not 0 <= ext < len(_EXT) \
            or len(t[2]) != 1:
        raise ValueError("telemetry field out of range")
    return tank.Telemetry(
        move=_MOVES[t[0]], speed=speed, value=_clean(t[2]), lcurr=f[0], rcurr=f[1], accx=f[2],
        accy=f[3], accz=f[4], gyrox=f[5], gyroy=f[6], gyroz=f[7], magx=f[8], magy=f[9], magz=f[10],
        lan=_clean(t[14]), lon=_clean(t[15]), vbat=vbat, systemstatus=_STATUS[status], extid=extid,
        extstatus=_EXT[ext])


# -- tr24: command packet, 12 bytes: start, service, sender, receiver, 7 data, stop -------
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
    return tr24.Command(seq=service, sender=sender, receiver=receiver, data=data)
