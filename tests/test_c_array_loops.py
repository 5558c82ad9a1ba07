"""Arrays the generated C reads and writes in a loop (model.Repeat): a counted array of
groups, a fixed array of numbers and an array sent whole or not at all. Frames worked
out by hand: A5, the id, the payload's length, the payload, then the sum of the bytes from
the id to the payload's end, modulo 256. A track is its speed (i16, little-endian), then a
byte holding its lane (3 bits), whether it is lit (1 bit) and 4 reserved bits, most
significant first: lane 5, lit is 101 1 0000 = B0."""
from __future__ import annotations

import pytest

from codeword.build import compile_schema
from schema_in_a_test import conformance_on_host_and_avr, load, render, run_c

SCHEMA = """codeword: 1
protocol: rally
title: arrays looped over
source: hand-written
flags:
  parts:
    type: u8
    bits:
      - {name: points, bit: 0}
framing:
  kind: bytes
  byte_order: little
  layout:
    - {name: sync, type: u8, const: 0xA5}
    - {name: id, type: u8, dispatch: true}
    - {name: len, type: u8, length_of: {from: payload, to: payload}}
    - {payload: true}
    - {name: sum, type: u8, checksum: {algorithm: sum, covers: {from: id, to: payload}}}
messages:
  tracks:
    id: 1
    fields:
      - {name: n, type: u8}
      - name: track
        type: group
        count: {from: n}
        max_count: MOST
        fields:
          - {name: speed, type: i16}
          - {name: lane, type: u3, range: [0, 5]}
          - {name: lit, type: bool}
          - {name: spare, type: u4, reserved: true}
  table:
    id: 2
    fields:
      - {name: mode, type: u8}
      - {name: reg, type: u16, count: COUNT}
      - {name: tail, type: u8}
  maybe:
    id: 3
    fields:
      - {name: flags, type: u8, flags: parts}
      - {name: points, type: i8, count: 8, present_if: {field: flags, has: points}}
      - {name: end, type: u8}
"""


def schema(most: int = 12, count: int = 10) -> str:
    return SCHEMA.replace("MOST", str(most)).replace("COUNT", str(count))


TRACKS = "a5 01 07 02 fe ff b0 2c 01 00 e4"  # n 2: (-2, lane 5, lit), (300, lane 0, unlit)
TRACK_LANE_6 = "a5 01 07 02 fe ff b0 2c 01 c0 a4"  # the second track's lane 6, past its range
TRACK_SPARE = "a5 01 07 02 fe ff b1 2c 01 00 e5"  # the first track's reserved bits not 0
TABLE = "a5 02 16 07" + "".join(f" {k:02x} {k:02x}" for k in range(10)) + " 42 bb"  # reg[k] = 0x0101 * k
POINTS = "a5 03 0a 01 ff fe fd fc fb fa f9 f8 33 1d"  # points -1 .. -8
NO_POINTS = "a5 03 02 00 33 38"


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    where = tmp_path_factory.mktemp("rally")
    render(where, "rally", schema())
    return where, load(where / "rally.py")


def test_the_arrays_are_looped_over(built):
    protocol = compile_schema(built[0] / "rally.yaml")
    assert {m.name: [r.field.name for r in m.wire.repeats] for m in protocol.messages} == \
        {"tracks": ["track"], "table": ["reg"], "maybe": ["points"]}


def test_python_reads_the_hand_worked_frames(built):
    mod = built[1]
    tracks = mod.decode(bytes.fromhex(TRACKS))
    assert [(t.speed, t.lane, t.lit) for t in tracks.track] == [(-2, 5, True), (300, 0, False)]
    assert mod.decode(bytes.fromhex(TABLE)).reg == [0x0101 * k for k in range(10)]
    assert mod.decode(bytes.fromhex(POINTS)).points == [-1, -2, -3, -4, -5, -6, -7, -8]
    assert mod.decode(bytes.fromhex(NO_POINTS)).points is None
    for frame in (TRACKS, TABLE, POINTS, NO_POINTS):
        assert mod.encode(mod.decode(bytes.fromhex(frame))) == bytes.fromhex(frame)


DRIVER = r"""
#include <stdio.h>
#include <string.h>
#include "rally.h"

static void show(const char *name, const uint8_t *frame, size_t n)
{
    rally_message_t m;
    uint8_t out[64];
    int rc = rally_decode(frame, n, RALLY_DIR_ANY, &m), i, k;
    printf("%s decode %s", name, cw_error_name(rc < 0 ? rc : 0));
    if (rc < 0) {
        printf("\n");
        return;
    }
    if (m.kind == RALLY_MSG_TRACKS) {
        for (k = 0; k < m.as.tracks.track_count; k++) {
            printf(" (%d %u %d)", m.as.tracks.track[k].speed, (unsigned)m.as.tracks.track[k].lane,
                   (int)m.as.tracks.track[k].lit);
        }
        printf(" rest %d", m.as.tracks.track[2].speed | m.as.tracks.track[11].lane);
    } else if (m.kind == RALLY_MSG_TABLE) {
        for (k = 0; k < 10; k++) printf(" %u", (unsigned)m.as.table.reg[k]);
    } else {
        for (k = 0; k < 8; k++) printf(" %d", m.as.maybe.points[k]);
    }
    n = (size_t)rally_encode(&m, out, sizeof out);
    printf(" | encode");
    for (i = 0; i < (int)n; i++) printf(" %02x", out[i]);
    printf("\n");
}

#define SHOW(name, ...) do { static const uint8_t f[] = {__VA_ARGS__}; show(name, f, sizeof f); } while (0)

int main(void)
{
    rally_tracks_t t;
    uint8_t out[64];
    SHOW("tracks", FRAMES_TRACKS);
    SHOW("lane", FRAMES_LANE);
    SHOW("spare", FRAMES_SPARE);
    SHOW("table", FRAMES_TABLE);
    SHOW("points", FRAMES_POINTS);
    SHOW("none", FRAMES_NONE);
    memset(&t, 0, sizeof t);
    t.track_count = 3;
    t.track[2].lane = 6;
    printf("encode lane 6: %s\n", cw_error_name(rally_tracks_encode(&t, out, sizeof out)));
    t.track[2].lane = 5;
    t.track[5].lane = 7;  /* past the count: not sent, not checked */
    printf("encode past the count: %d\n", rally_tracks_encode(&t, out, sizeof out));
    t.track_count = 13;
    printf("encode 13 tracks: %s\n", cw_error_name(rally_tracks_encode(&t, out, sizeof out)));
    return 0;
}
"""


def c_list(frame: str) -> str:
    return ", ".join(f"0x{b}" for b in frame.split())


def test_c_reads_and_writes_the_hand_worked_frames(built):
    where = built[0]
    driver = DRIVER
    for name, frame in (("TRACKS", TRACKS), ("LANE", TRACK_LANE_6), ("SPARE", TRACK_SPARE), ("TABLE", TABLE),
                        ("POINTS", POINTS), ("NONE", NO_POINTS)):
        driver = driver.replace(f"FRAMES_{name}", c_list(frame))
    table = " ".join(str(0x0101 * k) for k in range(10))
    assert run_c(where, driver) == [
        f"tracks decode ok (-2 5 1) (300 0 0) rest 0 | encode {TRACKS}",
        "lane decode range",
        "spare decode reserved",
        f"table decode ok {table} | encode {TABLE}",
        f"points decode ok -1 -2 -3 -4 -5 -6 -7 -8 | encode {POINTS}",
        f"none decode ok 0 0 0 0 0 0 0 0 | encode {NO_POINTS}",
        "encode lane 6: range",
        "encode past the count: 14",  # sync, id, len, n, 3 tracks of 3 bytes, sum
        "encode 13 tracks: range",
    ]


def test_c_agrees_with_python_on_host_and_avr(tmp_path):
    host, avr = conformance_on_host_and_avr(tmp_path, "rally", schema())
    assert host > 0 and avr == host


def test_the_header_grows_with_the_schema_not_the_count(tmp_path):
    """Seven times the elements cost no code: only the counts in the header change."""
    sizes = []
    for most, count in ((12, 10), (80, 80)):
        where = tmp_path / str(most)
        where.mkdir()
        render(where, "rally", schema(most, count))
        sizes.append(len((where / "rally.h").read_text(encoding="utf-8")))
    assert abs(sizes[1] - sizes[0]) < 200, sizes
