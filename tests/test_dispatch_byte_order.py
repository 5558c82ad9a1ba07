"""A multi-byte dispatch field in a byte-framed protocol follows the byte
order the schema declares: the generated Python and C encoders write the
frames written out by hand below, and the Python and C decoders, which find the
message by that field, read each back as the message it holds."""
from __future__ import annotations

from pathlib import Path

import pytest

import schema_in_a_test as scratch


SCHEMA = """\
codeword: 1
protocol: ledis
title: a two-byte message id
source: hand-written
framing:
  kind: bytes
  byte_order: {order}
  layout:
    - {{name: sync, type: u8, const: 0x55}}
    - {{name: kind, type: u16, dispatch: true}}
    - {{payload: true}}
messages:
  ping:
    id: 0x0102
    fields:
      - {{name: v, type: u16}}
  pong:
    id: 0x0201
    fields:
      - {{name: w, type: u16}}
"""

# The ids are each other's byte swap, so a frame read in the wrong order
# names the other message. ping v=0x1234, pong w=0xabcd:
#   little: 55 | 02 01 | 34 12    and    55 | 01 02 | cd ab
#   big:    55 | 01 02 | 12 34    and    55 | 02 01 | ab cd
FRAMES = {
    "little": ("55 02 01 34 12", "55 01 02 cd ab"),
    "big": ("55 01 02 12 34", "55 02 01 ab cd"),
}

DRIVER = """\
#include <stdio.h>
#include "ledis.h"

static const uint8_t ping_frame[] = {PING};
static const uint8_t pong_frame[] = {PONG};

static void show_decode(const char *label, const uint8_t *frame, size_t len)
{
    ledis_message_t m;
    int rc = ledis_decode(frame, len, 0, &m);
    if (rc != CW_OK) {
        printf("%s error %s\\n", label, cw_error_name(rc));
    } else if (m.kind == LEDIS_MSG_PING) {
        printf("%s ping %04x\\n", label, (unsigned)m.as.ping.v);
    } else {
        printf("%s pong %04x\\n", label, (unsigned)m.as.pong.w);
    }
}

int main(void)
{
    ledis_message_t m;
    uint8_t buf[LEDIS_MAX_FRAME];
    int n;
    int i;
    show_decode("ping_frame", ping_frame, sizeof ping_frame);
    show_decode("pong_frame", pong_frame, sizeof pong_frame);
    m.kind = LEDIS_MSG_PING;
    m.as.ping.v = 0x1234u;
    n = ledis_encode(&m, buf, sizeof buf);
    printf("encoded");
    for (i = 0; i < n; i++) {
        printf(" %02x", (unsigned)buf[i]);
    }
    printf("\\n");
    return 0;
}
"""


def c_array(spaced_hex: str) -> str:
    return "{" + ", ".join(f"0x{b:02x}" for b in bytes.fromhex(spaced_hex)) + "}"


@pytest.fixture(params=sorted(FRAMES))
def built(request, tmp_path: Path):
    return request.param, scratch.render(tmp_path, "ledis", SCHEMA.format(order=request.param))


def test_python_writes_the_id_in_the_declared_order(built):
    order, where = built
    ledis = scratch.load(where / "ledis.py")
    ping, pong = (bytes.fromhex(h) for h in FRAMES[order])
    assert ledis.encode(ledis.Ping(v=0x1234)) == ping
    assert ledis.encode(ledis.Pong(w=0xABCD)) == pong
    assert ledis.Ping.decode(ping).v == 0x1234
    assert ledis.Pong.decode(pong).w == 0xABCD


def test_python_dispatch_reads_the_id_in_the_declared_order(built):
    order, where = built
    ledis = scratch.load(where / "ledis.py")
    ping, pong = (bytes.fromhex(h) for h in FRAMES[order])
    assert ledis.decode(ping) == ledis.Ping(v=0x1234)
    assert ledis.decode(pong) == ledis.Pong(w=0xABCD)
    stream = ledis.StreamDecoder()
    assert stream.feed(ping + pong) == [ledis.Ping(v=0x1234), ledis.Pong(w=0xABCD)]


def test_c_dispatch_reads_the_id_in_the_declared_order(built):
    order, where = built
    ping, pong = FRAMES[order]
    assert scratch.run_c(where, DRIVER.replace("{PING}", c_array(ping)).replace("{PONG}", c_array(pong))) == [
        "ping_frame ping 1234",
        "pong_frame pong abcd",
        f"encoded {ping}",
    ]
