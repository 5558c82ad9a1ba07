"""The end of a byte stream: whole frames that a false start hid are decoded. A frame
header near the end that promises more bytes than ever come keeps the frames after it
waiting; at the end (StreamDecoder.finish, <px>_parser_finish, <px>_scan_end) the
false start is refused, its first byte skipped and the rest read again. The frames are
examples/mavlink2.yaml's, packed by pymavlink: HEARTBEAT, then ATTITUDE's header (28
payload bytes: a 40-byte frame) with only two COMMAND_ACKs (28 bytes) after it."""
from __future__ import annotations

from pathlib import Path

import schema_in_a_test as scratch
from conftest import ROOT

HEARTBEAT = bytes.fromhex("fd 09 00 00 00 01 01 00 00 00 03 00 00 00 02 03 51 04 03 8e 6a")
ACK = bytes.fromhex("fd 02 00 00 07 ff be 4d 00 00 90 01 77 8b")
FALSE_START = bytes.fromhex("fd 1c")
STREAM = HEARTBEAT + FALSE_START + ACK + ACK

DRIVER = """#include <stdio.h>
#include "mavlink2.h"
static const uint8_t stream[] = {%s};
static void show(int rc, const mavlink2_message_t *m) {
    if (rc != 1) printf("error %%s\\n", cw_error_name(rc));
    else printf("message %%s\\n", m->kind == MAVLINK2_MSG_HEARTBEAT ? "heartbeat" :
                                 m->kind == MAVLINK2_MSG_COMMAND_ACK ? "command_ack" : "other");
}
int main(void) {
    static mavlink2_parser_t parser;
    mavlink2_scan_state_t scan;
    mavlink2_message_t m;
    size_t i, at = 0, used;
    int rc;
    mavlink2_parser_init(&parser, MAVLINK2_DIR_ANY);
    for (i = 0; i < sizeof stream; i++) {
        mavlink2_parser_feed(&parser, stream[i]);
        while ((rc = mavlink2_parser_next(&parser, &m)) != 0) show(rc, &m);
    }
    printf("end\\n");
    while ((rc = mavlink2_parser_finish(&parser, &m)) != 0) show(rc, &m);
    printf("scan\\n");
    mavlink2_scan_start(&scan, MAVLINK2_DIR_ANY);
    while ((rc = mavlink2_scan(&scan, stream + at, sizeof stream - at, &used, &m)) != 0) {
        at += used;
        show(rc, &m);
    }
    at += used;
    printf("end\\n");
    while ((rc = mavlink2_scan_end(&scan, stream + at, sizeof stream - at, &used, &m)) != 0) {
        at += used;
        show(rc, &m);
    }
    printf("%%u skipped\\n", (unsigned)scan.skipped);
    return 0;
}
"""


def events(mod, items) -> list[str]:
    return [f"error {x.rule}" if isinstance(x, mod.DecodeError) else f"message {type(x).NAME}" for x in items]


def test_python_decodes_the_frames_a_false_start_hid_at_the_end(tmp_path: Path):
    where = scratch.render(tmp_path, "mavlink2", (ROOT / "examples" / "mavlink2.yaml").read_text(encoding="utf-8"))
    mod = scratch.load(where / "mavlink2.py")
    for piece in (1, 7, len(STREAM)):
        decoder = mod.StreamDecoder()
        fed = [item for at in range(0, len(STREAM), piece) for item in decoder.feed(STREAM[at:at + piece])]
        assert events(mod, fed) == ["message heartbeat"]
        assert events(mod, decoder.finish()) == ["error length", "message command_ack", "message command_ack"]
        assert decoder.spans[1:] == [(len(HEARTBEAT) + 2, len(ACK)), (len(HEARTBEAT) + 2 + len(ACK), len(ACK))]
        assert decoder.skipped == 2 and decoder.offset == len(STREAM) and decoder.finish() == []


def test_c_decodes_them_too(tmp_path: Path):
    where = scratch.render(tmp_path, "mavlink2", (ROOT / "examples" / "mavlink2.yaml").read_text(encoding="utf-8"))
    lines = scratch.run_c(where, DRIVER % ", ".join(f"0x{b:02x}" for b in STREAM))
    found = ["message heartbeat", "end", "error length", "message command_ack", "message command_ack"]
    assert lines == found + ["scan"] + found + ["2 skipped"]
