"""A checksum over fields covers every other field of the message, in bytes
framing too, where it needs no `covers` (a `covers: {from, to}` range is the
byte range of a checksum over bytes; on a checksum over fields it is refused,
see tests/broken/field_checksum_covers_range.yaml). The generated Python and C
codecs write and check the sums worked out by hand below."""
from __future__ import annotations

from pathlib import Path

import pytest

import schema_in_a_test as scratch


SCHEMA = """\
codeword: 1
protocol: fsum
title: a sum of field values in a byte frame
source: hand-written
framing:
  kind: bytes
  byte_order: big
  layout:
    - {name: sync, type: u8, const: 0x55}
    - {name: kind, type: u8, dispatch: true}
    - {payload: true}
    - {name: sum, type: u8, checksum: {algorithm: sum, over: fields}}
messages:
  reading:
    id: 1
    fields:
      - {name: a, type: u8}
      - {name: b, type: u16}
"""

# sum = (sync + kind + a + b) mod 256, b taken as one 16-bit value:
#   a=2, b=0x0304:      0x55 + 1 + 2 + 0x304 = 0x35c            -> 5c
#   a=0xff, b=0xffff:   85 + 1 + 255 + 65535 = 65876 = 257*256 + 84 -> 54
GOOD = {"55 01 02 03 04 5c": (2, 0x0304), "55 01 ff ff ff 54": (0xFF, 0xFFFF)}
BAD = "55 01 02 03 04 5d"

DRIVER = """\
#include <stdio.h>
#include "fsum.h"

static void show(const char *hex, const uint8_t *frame, size_t len)
{
    fsum_message_t m;
    uint8_t buf[FSUM_MAX_FRAME];
    int rc = fsum_decode(frame, len, 0, &m);
    int i;
    if (rc != CW_OK) {
        printf("%s error %s\\n", hex, cw_error_name(rc));
        return;
    }
    rc = fsum_encode(&m, buf, sizeof buf);
    printf("%s %u %u encoded", hex, (unsigned)m.as.reading.a, (unsigned)m.as.reading.b);
    for (i = 0; i < rc; i++) {
        printf(" %02x", (unsigned)buf[i]);
    }
    printf("\\n");
}

int main(void)
{
FRAMES
    return 0;
}
"""


@pytest.fixture(scope="module")
def built(tmp_path_factory) -> Path:
    return scratch.render(tmp_path_factory.mktemp("fsum"), "fsum", SCHEMA)


def test_python_sums_every_other_field(built):
    fsum = scratch.load(built / "fsum.py")
    for hex_, (a, b) in GOOD.items():
        frame = bytes.fromhex(hex_)
        assert fsum.encode(fsum.Reading(a=a, b=b)) == frame
        assert fsum.decode(frame) == fsum.Reading(a=a, b=b)
    with pytest.raises(fsum.DecodeError) as err:
        fsum.decode(bytes.fromhex(BAD))
    assert err.value.rule == "checksum"


def test_c_sums_every_other_field(built):
    frames = scratch.show_calls([*GOOD, BAD])
    assert scratch.run_c(built, DRIVER.replace("FRAMES", frames)) == [
        f"{h} {a} {b} encoded {h}" for h, (a, b) in GOOD.items()] + [f"{BAD} error checksum"]
