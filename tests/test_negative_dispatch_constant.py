"""A signed dispatch field in bits framing may hold a negative constant: both
decoders compare the header's raw bits with the constant's two's complement.
Frames below are written out by hand."""
from __future__ import annotations

from pathlib import Path

import schema_in_a_test as scratch

SCHEMA = """\
codeword: 1
protocol: negd
title: a signed header
source: hand-written
framing: {kind: bits, word_bits: 8, byte_order: big}
messages:
  down:
    fields:
      - {name: tag, type: i4, const: -2, dispatch: true}
      - {name: v, type: u4}
  up:
    fields:
      - {name: tag, type: i4, const: 3, dispatch: true}
      - {name: v, type: u4}
"""

# tag -2 in 4 bits is 1110: down v=5 -> 1110 0101 = e5; up v=9 -> 0011 1001 = 39
DOWN, UP = bytes.fromhex("e5"), bytes.fromhex("39")

DRIVER = """\
#include <stdio.h>
#include "negd.h"

static void show(const uint8_t *frame)
{
    negd_message_t m;
    int rc = negd_decode(frame, 1u, &m);
    if (rc != CW_OK) {
        printf("error %s\\n", cw_error_name(rc));
    } else if (m.kind == NEGD_MSG_DOWN) {
        printf("down %u\\n", (unsigned)m.as.down.v);
    } else {
        printf("up %u\\n", (unsigned)m.as.up.v);
    }
}

int main(void)
{
    static const uint8_t down[] = {0xe5}, up[] = {0x39}, neither[] = {0x75};
    show(down);
    show(up);
    show(neither);
    return 0;
}
"""


def test_python_dispatches_on_a_negative_constant(tmp_path: Path):
    negd = scratch.load(scratch.render(tmp_path, "negd", SCHEMA) / "negd.py")
    assert negd.encode(negd.Down(v=5)) == DOWN
    assert negd.decode(DOWN) == negd.Down(v=5)
    assert negd.decode(UP) == negd.Up(v=9)


def test_c_dispatches_on_a_negative_constant(tmp_path: Path):
    where = scratch.render(tmp_path, "negd", SCHEMA)
    assert scratch.run_c(where, DRIVER) == ["down 5", "up 9", "error dispatch"]
