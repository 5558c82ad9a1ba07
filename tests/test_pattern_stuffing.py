"""Pattern stuffing (`framing.stuffing`) in general, apart from DYNAMIXEL: which
patterns the resolver accepts, proven against two receivers written here (one
that looks for the pattern in the bytes received, as the Dynamixel SDK does, one
in the bytes meant); and a frame with a header checksum over its length, a
one-byte pattern stuffed in the payload alone and an end marker after the
checksum, whose frames are worked out by hand, in Python and in C."""
from __future__ import annotations

import itertools
import random

import pytest

from codeword.fingerprint import fingerprint
from codeword.resolver.stuffing import pattern_problem
from codeword.build import compile_schema

from schema_in_a_test import c_bytes, load, render, run_c


def send(data: bytes, pattern: bytes, insert: int) -> bytes:
    """The sender: after each place where the bytes meant so far end with the pattern, the byte."""
    out = bytearray()
    for i, byte in enumerate(data):
        out.append(byte)
        if data[:i + 1].endswith(pattern):
            out.append(insert)
    return bytes(out)


def receive_sent(wire: bytes, pattern: bytes, insert: int) -> bytes | None:
    """A receiver that looks for the pattern in the bytes received, and drops the byte after it."""
    out, i = bytearray(), 0
    while i < len(wire):
        out.append(wire[i])
        if wire[:i + 1].endswith(pattern):
            if i + 1 >= len(wire) or wire[i + 1] != insert:
                return None
            i += 1
        i += 1
    return bytes(out)


def receive_meant(wire: bytes, pattern: bytes, insert: int) -> bytes | None:
    """A receiver that looks for the pattern in the bytes it has kept."""
    out, i = bytearray(), 0
    while i < len(wire):
        out.append(wire[i])
        if out.endswith(pattern):
            if i + 1 >= len(wire) or wire[i + 1] != insert:
                return None
            i += 1
        i += 1
    return bytes(out)


def test_accepted_patterns_read_back_one_way_and_refused_ones_do_not():
    rng = random.Random(2)
    alphabet = [0, 1, 2]
    refused_disagree = 0
    for size in (1, 2, 3):
        for pattern in map(bytes, itertools.product(alphabet, repeat=size)):
            for insert in alphabet:
                disagree = False
                for _ in range(300):
                    data = bytes(rng.choice(alphabet) for _ in range(rng.randrange(12)))
                    wire = send(data, pattern, insert)
                    sent, meant = receive_sent(wire, pattern, insert), receive_meant(wire, pattern, insert)
                    if pattern_problem(pattern, insert) is None:
                        assert sent == meant == data, (pattern, insert, data)
                    disagree |= sent != data
                refused_disagree += pattern_problem(pattern, insert) is not None and disagree
    assert refused_disagree > 20  # the refused patterns are misread by one receiver or the other
    assert pattern_problem(bytes.fromhex("FF FF FD"), 0xFD) is None  # DYNAMIXEL's


SCHEMA = """codeword: 1
protocol: stuffed_tail
title: t
source: hand-written
framing:
  kind: bytes
  byte_order: big
  stuffing: {after: "7E", insert: 0x00, covers: {from: payload, to: payload}}
  layout:
    - {name: sync, type: u8, const: 0xAA}
    - {name: len, type: u8, length_of: {from: payload, to: payload}}
    - {name: hsum, type: u8, checksum: {algorithm: xor, covers: {from: sync, to: len}}}
    - {name: kind, type: u8, dispatch: true}
    - {payload: true}
    - {name: sum, type: u8, checksum: {algorithm: sum, covers: {from: len, to: payload}}}
    - {name: end, type: u8, const: 0x0D}
messages:
  data:
    id: 1
    fields:
      - {name: a, type: u16}
      - {name: b, type: u8}
"""

# By hand. a=0x7E7E b=1: the payload 7E 7E 01 is sent as 7E 00 7E 00 01, so len = 5;
# hsum = AA ^ 05 = AF; sum = 05+AF+01+7E+00+7E+00+01 = 0x1B2 -> B2.
STUFFED = ("AA 05 AF 01 7E 00 7E 00 01 B2 0D", {"a": 0x7E7E, "b": 1})
# a=0x0102 b=3: nothing to stuff; len 3, hsum AA^03 = A9, sum 03+A9+01+01+02+03 = B3.
PLAIN = ("AA 03 A9 01 01 02 03 B3 0D", {"a": 0x0102, "b": 3})
# b=0x7E last: payload 00 05 7E sent as 00 05 7E 00; len 4, hsum AE, sum 04+AE+01+05+7E = 0x136 -> 36.
AT_THE_END = ("AA 04 AE 01 00 05 7E 00 36 0D", {"a": 5, "b": 0x7E})
# 7E followed by 01 instead of 00 (lengths and sums agreeing): 7E 01 02 03, len 4, hsum AE,
# sum 04+AE+01+7E+01+02+03 = 0x137 -> 37
NO_INSERTED_BYTE = "AA 04 AE 01 7E 01 02 03 37 0D"
FRAMES = [STUFFED, PLAIN, AT_THE_END]


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    where = tmp_path_factory.mktemp("stuffed_tail")
    render(where, "stuffed_tail", SCHEMA)
    return where, load(where / "stuffed_tail.py")


def test_python_writes_and_reads_the_hand_worked_frames(built):
    _, mod = built
    for frame, values in FRAMES:
        data = bytes.fromhex(frame)
        assert mod.encode(mod.Data(**values)) == data
        assert mod.decode(data) == mod.Data(**values)
    # before stuffing, the length and sum count the payload meant: 03, and 03+A9+01+7E+7E+01 = 0x1AA
    assert mod.unstuff(bytes.fromhex(STUFFED[0])) == bytes.fromhex("AA 03 A9 01 7E 7E 01 AA 0D")


def test_python_refuses_a_pattern_without_its_byte_and_a_stale_checksum(built):
    _, mod = built
    with pytest.raises(mod.DecodeError) as caught:
        mod.decode(bytes.fromhex(NO_INSERTED_BYTE))
    assert (caught.value.rule, caught.value.offset) == ("escape", 5 * 8)
    damaged = bytearray(bytes.fromhex(STUFFED[0]))
    damaged[5] = 0x01  # the inserted byte changed: the sum over the bytes sent no longer holds
    with pytest.raises(mod.DecodeError) as caught:
        mod.decode(bytes(damaged))
    assert (caught.value.rule, caught.value.field) == ("checksum", "sum")


def test_python_stream_finds_stuffed_frames_among_noise(built):
    _, mod = built
    frames = [bytes.fromhex(f) for f, _ in FRAMES]
    stream = b"".join(b"\xaa\x7e" + f for f in frames)
    got = mod.StreamDecoder().feed(stream)
    assert [mod.encode(x) for x in got if not isinstance(x, mod.DecodeError)] == frames


DRIVER = r"""
#include <stdio.h>
#include "stuffed_tail.h"
static const uint8_t stream_bytes[] = {STREAM};
static void show(const uint8_t *b, size_t n) {
    stuffed_tail_message_t m;
    uint8_t out[STUFFED_TAIL_WIRE_MAX];
    int k = 0;
    size_t i;
    int rc = stuffed_tail_decode(b, n, STUFFED_TAIL_DIR_ANY, &m);
    if (rc == 0) {
        k = stuffed_tail_encode(&m, out, sizeof out);
    }
    printf("%d", rc);
    for (i = 0; k > 0 && i < (size_t)k; i++) {
        printf(" %02X", out[i]);
    }
    printf("\n");
}
int main(void) {
    stuffed_tail_parser_t p;
    stuffed_tail_message_t m;
    size_t i;
    int rc;
    CALLS
    stuffed_tail_parser_init(&p, STUFFED_TAIL_DIR_ANY);
    for (i = 0; i < sizeof stream_bytes; i++) {
        stuffed_tail_parser_feed(&p, stream_bytes[i]);
        while ((rc = stuffed_tail_parser_next(&p, &m)) != 0) {
            if (rc == 1) {
                printf("frame %u %u\n", (unsigned)m.as.data.a, (unsigned)m.as.data.b);
            }
        }
    }
    return 0;
}
"""


def test_c_writes_and_reads_the_hand_worked_frames_and_finds_them_in_a_stream(built):
    where, _ = built
    frames = [bytes.fromhex(f) for f, _ in FRAMES]
    bad = bytes.fromhex(NO_INSERTED_BYTE)
    calls = [f"{{ static const uint8_t f[] = {{{c_bytes(x)}}}; show(f, sizeof f); }}" for x in frames + [bad]]
    stream = b"".join(b"\xaa\x7e" + f for f in frames)
    lines = run_c(where, DRIVER.replace("STREAM}", c_bytes(stream) + "}").replace("CALLS", "\n    ".join(calls)))
    assert lines == (["0 " + f for f, _ in FRAMES] + ["-27"]
                     + [f"frame {v['a']} {v['b']}" for _, v in FRAMES])


def test_the_stuffing_is_in_the_fingerprint(tmp_path):
    before = tmp_path / "a.yaml"
    after = tmp_path / "b.yaml"
    before.write_text(SCHEMA.replace("stuffed_tail", "fp"), encoding="utf-8")
    after.write_text(SCHEMA.replace("stuffed_tail", "fp").replace("insert: 0x00", "insert: 0x01"), encoding="utf-8")
    moved = tmp_path / "c.yaml"
    moved.write_text("# a comment moves every line\n" + SCHEMA.replace("stuffed_tail", "fp"), encoding="utf-8")
    assert fingerprint(compile_schema(before)) != fingerprint(compile_schema(after))
    assert fingerprint(compile_schema(before)) == fingerprint(compile_schema(moved))
