"""Several dispatch fields (u-blox UBX's class and id) and a sync of several bytes
(UBX's B5 62). Frames are UBX-CFG-RATE and UBX-ACK-ACK as the u-blox protocol
specification lays them out (checksum left out: this schema declares none):
B5 62 | class | id | length (u16 LE) | payload."""
from __future__ import annotations

from schema_in_a_test import load, render, run_c

SCHEMA = """codeword: 1
protocol: ubxlite
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
    - {name: length, type: u16}
    - {payload: true}
messages:
  ack_ack:
    id: {msg_class: 0x05, msg_id: 0x01}
    fields:
      - {name: acked_class, type: u8}
      - {name: acked_id, type: u8}
  ack_nak:
    id: {msg_class: 0x05, msg_id: 0x00}
    fields:
      - {name: acked_class, type: u8}
      - {name: acked_id, type: u8}
  cfg_rate:
    id: {msg_class: 0x06, msg_id: 0x08}
    fields:
      - {name: meas_rate, type: u16}
      - {name: nav_rate, type: u16}
      - {name: time_ref, type: u16}
  nav_x:
    id: {msg_class: 0x01, msg_id: 0x06}
    fields:
      - {name: acked_class, type: u8}
      - {name: acked_id, type: u8}
"""

ACK_ACK = "b5 62 05 01 02 00 06 08"         # acknowledges CFG-RATE (06 08)
ACK_NAK = "b5 62 05 00 02 00 06 08"
CFG_RATE = "b5 62 06 08 06 00 e8 03 01 00 01 00"  # 1000 ms, every cycle, GPS time
NAV_X = "b5 62 01 06 02 00 06 08"          # class and id swapped against CFG-RATE: another message


def test_python_tells_messages_apart_by_class_and_id(tmp_path):
    render(tmp_path, "ubxlite", SCHEMA)
    mod = load(tmp_path / "ubxlite.py")
    assert mod.decode(bytes.fromhex(ACK_ACK)) == mod.AckAck(length=2, acked_class=6, acked_id=8)
    assert isinstance(mod.decode(bytes.fromhex(ACK_NAK)), mod.AckNak)
    assert isinstance(mod.decode(bytes.fromhex(NAV_X)), mod.NavX)
    rate = mod.decode(bytes.fromhex(CFG_RATE))
    assert (rate.meas_rate, rate.nav_rate, rate.time_ref) == (1000, 1, 1)
    assert mod.encode(rate) == bytes.fromhex(CFG_RATE)
    assert mod.encode(mod.AckAck(length=2, acked_class=6, acked_id=8)) == bytes.fromhex(ACK_ACK)
    try:
        mod.decode(bytes.fromhex("b5 62 05 02 02 00 06 08"))  # class 05 with an unknown id
    except mod.DecodeError as err:
        assert err.rule == "dispatch" and err.offset == 16
    else:
        raise AssertionError("an unknown class and id decoded")


def test_python_stream_resynchronises_on_the_whole_sync(tmp_path):
    render(tmp_path, "ubxlite", SCHEMA)
    mod = load(tmp_path / "ubxlite.py")
    # B5 not followed by 62 is garbage, not a frame: no error, the bytes are skipped;
    # a frame split after its first sync byte is completed by the next feed.
    stream = bytes.fromhex("b5 00 b5 b5" + CFG_RATE + "00 b5" + ACK_ACK)
    dec = mod.StreamDecoder()
    split = stream.index(bytes.fromhex("b5 62 05 01")) + 1
    out = dec.feed(stream[:split]) + dec.feed(stream[split:])
    assert [type(x).__name__ for x in out] == ["CfgRate", "AckAck"]
    assert dec.skipped == 6  # b5 00 b5 b5, then 00 b5


def test_c_decodes_and_streams_the_same_frames(tmp_path):
    render(tmp_path, "ubxlite", SCHEMA)
    driver = r"""
#include <stdio.h>
#include "ubxlite.h"
static const uint8_t ack[] = {0xb5, 0x62, 0x05, 0x01, 0x02, 0x00, 0x06, 0x08};
static const uint8_t navx[] = {0xb5, 0x62, 0x01, 0x06, 0x02, 0x00, 0x06, 0x08};
static const uint8_t stream[] = {0xb5, 0x00, 0xb5, 0xb5,
    0xb5, 0x62, 0x06, 0x08, 0x06, 0x00, 0xe8, 0x03, 0x01, 0x00, 0x01, 0x00,
    0x00, 0xb5, 0xb5, 0x62, 0x05, 0x01, 0x02, 0x00, 0x06, 0x08};
int main(void) {
    ubxlite_message_t m;
    ubxlite_parser_t p;
    size_t i;
    int rc = ubxlite_decode(ack, sizeof ack, UBXLITE_DIR_ANY, &m);
    printf("%d %d %d %d\n", rc, m.kind == UBXLITE_MSG_ACK_ACK, m.as.ack_ack.acked_class, m.as.ack_ack.acked_id);
    rc = ubxlite_decode(navx, sizeof navx, UBXLITE_DIR_ANY, &m);
    printf("%d %d\n", rc, m.kind == UBXLITE_MSG_NAV_X);
    ubxlite_parser_init(&p, UBXLITE_DIR_ANY);
    for (i = 0; i < sizeof stream; i++) {
        ubxlite_parser_feed(&p, stream[i]);
        while ((rc = ubxlite_parser_next(&p, &m)) != 0) {
            if (rc == 1 && m.kind == UBXLITE_MSG_CFG_RATE) {
                printf("rate %u\n", (unsigned)m.as.cfg_rate.meas_rate);
            } else if (rc == 1 && m.kind == UBXLITE_MSG_ACK_ACK) {
                printf("ack\n");
            } else {
                printf("error %d\n", rc);
            }
        }
    }
    printf("skipped %lu\n", (unsigned long)p.scan.skipped);
    return 0;
}
"""
    assert run_c(tmp_path, driver) == ["0 1 6 8", "0 1", "rate 1000", "ack", "skipped 6"]
