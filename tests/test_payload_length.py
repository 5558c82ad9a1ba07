"""A length field that counts the payload alone (`{from: payload, to: payload}`),
including an empty one: UBX-CFG-RATE and its poll, which shares its class and id
and has no payload. Frames from the u-blox protocol specification, checksum left
out (this schema declares none): B5 62 | class | id | length (u16 LE) | payload."""
from __future__ import annotations

from schema_in_a_test import load, render, run_c

SCHEMA = """codeword: 1
protocol: ubxlen
title: t
source: s
framing:
  kind: bytes
  byte_order: little
  layout:
    - {name: sync1, type: u8, const: 0xB5}
    - {name: sync2, type: u8, const: 0x62}
    - {name: msg_class, type: u8, dispatch: true}
    - {name: msg_id, type: u8, dispatch: true}
    - {name: length, type: u16, length_of: {from: payload, to: payload}}
    - {payload: true}
messages:
  cfg_rate_poll:
    id: {msg_class: 0x06, msg_id: 0x08}
    fields: []
    examples:
      - {hex: "b5 62 06 08 00 00", values: {}}
  cfg_rate:
    id: {msg_class: 0x06, msg_id: 0x08}
    fields:
      - {name: meas_rate, type: u16}
      - {name: nav_rate, type: u16}
      - {name: time_ref, type: u16}
    examples:
      - {hex: "b5 62 06 08 06 00 e8 03 01 00 01 00", values: {meas_rate: 1000, nav_rate: 1, time_ref: 1}}
"""

POLL = "b5 62 06 08 00 00"
RATE = "b5 62 06 08 06 00 e8 03 01 00 01 00"


def test_python_counts_the_payload_alone(tmp_path):
    render(tmp_path, "ubxlen", SCHEMA)  # the examples above are checked both ways by the build
    mod = load(tmp_path / "ubxlen.py")
    assert mod.encode(mod.CfgRatePoll()) == bytes.fromhex(POLL)
    dec = mod.StreamDecoder()
    out = dec.feed(bytes.fromhex("00" + POLL + RATE + POLL))
    assert [type(x).__name__ for x in out] == ["CfgRatePoll", "CfgRate", "CfgRatePoll"]
    assert dec.skipped == 1
    try:
        mod.decode(bytes.fromhex("b5 62 06 08 01 00 00"))  # claims one byte: no such message
    except mod.DecodeError as err:
        assert err.rule in ("dispatch", "length")
    else:
        raise AssertionError("a frame of an unknown size decoded")


def test_c_counts_the_payload_alone(tmp_path):
    render(tmp_path, "ubxlen", SCHEMA)
    driver = r"""
#include <stdio.h>
#include "ubxlen.h"
static const uint8_t stream[] = {0x00, 0xb5, 0x62, 0x06, 0x08, 0x00, 0x00,
    0xb5, 0x62, 0x06, 0x08, 0x06, 0x00, 0xe8, 0x03, 0x01, 0x00, 0x01, 0x00};
int main(void) {
    ubxlen_message_t m;
    ubxlen_parser_t p;
    ubxlen_cfg_rate_poll_t poll;
    uint8_t out[8];
    size_t i;
    int rc = ubxlen_cfg_rate_poll_encode(&poll, out, sizeof out);
    printf("%d %02x %02x %02x %02x %02x %02x\n", rc, out[0], out[1], out[2], out[3], out[4], out[5]);
    ubxlen_parser_init(&p, UBXLEN_DIR_ANY);
    for (i = 0; i < sizeof stream; i++) {
        ubxlen_parser_feed(&p, stream[i]);
        while ((rc = ubxlen_parser_next(&p, &m)) != 0) {
            printf("%d %d\n", rc, rc == 1 && m.kind == UBXLEN_MSG_CFG_RATE ? (int)m.as.cfg_rate.meas_rate : -1);
        }
    }
    printf("skipped %lu\n", (unsigned long)p.scan.skipped);
    return 0;
}
"""
    assert run_c(tmp_path, driver) == ["6 b5 62 06 08 00 00", "1 -1", "1 1000", "skipped 1"]
