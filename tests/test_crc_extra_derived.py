"""`extra: mavlink`: the compiler derives each message's crc_extra from its definition
as MAVLink derives CRC_EXTRA (its name, then each base field's type, name and array
length, extensions left out), so a hand-edited schema cannot keep a stale value: a
declared value that differs is an error naming both, at its line. Expected values come
from pymavlink's generated dialect (mavgen's CRC_EXTRA) and from frames pymavlink packed."""
from __future__ import annotations

import os
import random

import pytest

os.environ["MAVLINK20"] = "1"  # before pymavlink is imported: its v2 framing
from pymavlink.dialects.v20 import common as mavlink2  # noqa: E402  (a test extra)

from codeword import crc  # noqa: E402
from codeword.build import compile_schema  # noqa: E402
from codeword.cli import main  # noqa: E402
from codeword.resolver.crc_extra import x25  # noqa: E402

HEAD = """codeword: 1
protocol: mavx
title: MAVLink 1 framing, crc_extra derived
source: https://mavlink.io/en/guide/serialization.html#crc_extra
framing:
  kind: bytes
  byte_order: little
  layout:
    - {name: stx, type: u8, const: 0xFE}
    - {name: len, type: u8, length_of: {from: payload, to: payload}}
    - {name: seq, type: u8}
    - {name: sysid, type: u8}
    - {name: compid, type: u8}
    - {name: msgid, type: u8, dispatch: true}
    - {payload: true}
    - name: checksum
      type: u16
      checksum: {algorithm: CRC-16/MCRF4XX, covers: {from: len, to: payload}, extra: mavlink}
messages:
"""

# HEARTBEAT as MAVLink defines it, `type` kept under another name; the example was packed
# by pymavlink (MAVLink 1)
HEARTBEAT = """  heartbeat:
    id: 0
    fields:
      - {name: custom_mode, type: u32}
      - {name: kind, type: u8, mavlink_name: type}
      - {name: autopilot, type: u8}
      - {name: base_mode, type: u8}
      - {name: system_status, type: u8}
      - {name: mavlink_version, type: u8}
    examples:
      - hex: "fe 09 00 01 01 00 03 00 00 00 02 03 51 04 03 14 a9"
        values: {seq: 0, sysid: 1, compid: 1, custom_mode: 3, kind: 2, autopilot: 3, base_mode: 81,
                 system_status: 4, mavlink_version: 3}
"""

# PARAM_VALUE: a char[16] array; its codeword name differs and mavlink_name gives MAVLink's
PARAM = """  value_of_param:
    id: 22
    mavlink_name: PARAM_VALUE
    fields:
      - {name: param_value, type: f32}
      - {name: param_count, type: u16}
      - {name: param_index, type: u16}
      - {name: param_id, type: bytes, length: 16}
      - {name: param_type, type: u8}
"""

# GPS_RAW_INT: its extension fields take no part
GPS = """  gps_raw_int:
    id: 24
    fields:
      - {name: time_usec, type: u64}
      - {name: lat, type: i32}
      - {name: lon, type: i32}
      - {name: alt, type: i32}
      - {name: eph, type: u16}
      - {name: epv, type: u16}
      - {name: vel, type: u16}
      - {name: cog, type: u16}
      - {name: fix_type, type: u8}
      - {name: satellites_visible, type: u8}
      - {name: alt_ellipsoid, type: i32, extension: true}
      - {name: h_acc, type: u32, extension: true}
      - {name: v_acc, type: u32, extension: true}
      - {name: vel_acc, type: u32, extension: true}
      - {name: hdg_acc, type: u32, extension: true}
      - {name: yaw, type: u16, extension: true}
"""


def write(tmp_path, body: str):
    path = tmp_path / "mavx.yaml"
    path.write_text(HEAD + body, encoding="utf-8")
    return path


def lint_errors(path, capsys) -> list[str]:
    assert main(["lint", str(path)]) == 1
    return [line for line in capsys.readouterr().err.splitlines() if ": error: " in line or "hint:" in line]


def test_x25_is_crc16_mcrf4xx():
    params = crc.lookup("CRC-16/MCRF4XX")
    rng = random.Random(7)
    for n in (0, 1, 9, 64):
        data = bytes(rng.randrange(256) for _ in range(n))
        assert x25(data) == crc.compute(params, data)


def test_each_crc_extra_is_mavgens(tmp_path):
    p = compile_schema(write(tmp_path, HEARTBEAT + PARAM + GPS))  # the heartbeat example is checked by the build
    got = {m.name: m.crc_extra for m in p.messages}
    assert got == {"heartbeat": mavlink2.MAVLink_heartbeat_message.crc_extra,
                   "value_of_param": mavlink2.MAVLink_param_value_message.crc_extra,
                   "gps_raw_int": mavlink2.MAVLink_gps_raw_int_message.crc_extra}
    assert got == {"heartbeat": 50, "value_of_param": 220, "gps_raw_int": 24}


def test_a_declared_value_is_checked(tmp_path, capsys):
    ok = write(tmp_path, HEARTBEAT.replace("    id: 0\n", "    id: 0\n    crc_extra: 50\n"))
    assert compile_schema(ok).message("heartbeat").crc_extra == 50
    stale = write(tmp_path, HEARTBEAT.replace("    id: 0\n", "    id: 0\n    crc_extra: 51\n"))
    assert lint_errors(stale, capsys) == [
        f"{stale}:22:5: error: message 'heartbeat': crc_extra 51 is not 50, MAVLink's CRC_EXTRA of its definition "
        "(HEARTBEAT: uint32_t custom_mode, uint8_t type, uint8_t autopilot, uint8_t base_mode, uint8_t system_status, "
        "uint8_t mavlink_version)",
        "  hint: write crc_extra: 50, or drop it: the CRC derives it (`extra: mavlink`)"]


def test_a_field_mavlink_has_no_type_for_is_an_error_at_its_line(tmp_path, capsys):
    path = write(tmp_path, HEARTBEAT.replace("{name: autopilot, type: u8}", "{name: autopilot, type: u4}\n"
                                                                            "      - {name: pad, type: u4}"))
    errors = lint_errors(path, capsys)
    assert errors[0] == (f"{path}:25:9: error: message 'heartbeat': field 'autopilot' has no MAVLink type, so the "
                         "message's crc_extra cannot be derived (`extra: mavlink`)")


@pytest.mark.parametrize("where, line", [("message", 21), ("field", 25)])
def test_mavlink_name_is_read_only_by_a_crc_that_derives(tmp_path, capsys, where, line):
    """With `extra: message` the crc_extra is declared: a mavlink_name would say nothing."""
    body = HEARTBEAT.replace("    id: 0\n", "    id: 0\n    crc_extra: 50\n")
    if where == "message":
        body = body.replace(", mavlink_name: type}", "}").replace("    id: 0\n", "    mavlink_name: HEARTBEAT\n    id: 0\n")
    path = tmp_path / "mavx.yaml"
    path.write_text((HEAD + body).replace("extra: mavlink}", "extra: message}"), encoding="utf-8")
    errors = lint_errors(path, capsys)
    assert errors[0].startswith(f"{path}:{line}:") and "mavlink_name is read only by a CRC with `extra: mavlink`" \
        in errors[0], errors
