"""examples/mavlink1.yaml against pymavlink, the reference MAVLink implementation:
frames pymavlink packs decode to the values it packed, and codeword's encoders
write pymavlink's bytes back, in Python and in C; both stream decoders find the
frames in a stream with garbage between them. Expected bytes come from pymavlink."""
from __future__ import annotations

import random
import struct

import pytest
from pymavlink.dialects.v10 import common as mavlink  # a test extra: pip install -e ".[peers]"

from schema_in_a_test import build_example, c_bytes, load, run_c



def f32(x: float) -> float:
    return struct.unpack("<f", struct.pack("<f", x))[0]


MESSAGES = ("heartbeat", "sys_status", "param_value", "gps_raw_int", "attitude", "command_long")


def field_value(rng: random.Random, ctype: str):
    """A value of a MAVLink field type spread over its range."""
    if ctype == "char":
        return b"PARAM_%d" % rng.getrandbits(16)
    if ctype == "float":
        return f32(rng.uniform(-1e6, 1e6))
    bits = int(ctype.strip("uint_t"))
    if ctype.startswith("uint"):
        return rng.getrandbits(bits)
    return rng.randint(-(1 << (bits - 1)), (1 << (bits - 1)) - 1)


def sample_messages(seed: int = 7) -> list:
    """pymavlink messages of every type the example has, with random values."""
    rng = random.Random(seed)
    out = []
    for _ in range(8):
        for name in MESSAGES:
            cls = getattr(mavlink, f"MAVLink_{name}_message")
            out.append(cls(**{field: field_value(rng, ctype) for field, ctype in zip(cls.fieldnames, cls.fieldtypes)}))
    return out


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    return build_example("mavlink1", tmp_path_factory.mktemp("mavlink1"))


def packed(messages) -> list[bytes]:
    mav = mavlink.MAVLink(None, srcSystem=42, srcComponent=190)
    return [bytes(m.pack(mav)) for m in messages]


def test_python_decodes_pymavlink_frames_and_encodes_them_back(built):
    mod = load(built / "mavlink1.py")
    messages = sample_messages()
    for message, frame in zip(messages, packed(messages)):
        ours = mod.decode(frame)
        assert type(ours).__name__.lower() == message.get_type().lower().replace("_", "")
        assert (ours.sysid, ours.compid) == (42, 190)
        for name in message.get_fieldnames():
            theirs = getattr(message, name)
            mine = getattr(ours, name)
            if isinstance(mine, bytes):  # pymavlink gives char arrays as text without the NULs
                mine = mine.rstrip(b"\0").decode()
                theirs = theirs.decode() if isinstance(theirs, bytes) else theirs
            assert mine == theirs, (message.get_type(), name)
        assert mod.encode(ours) == frame


def test_pymavlink_accepts_what_codeword_encodes(built):
    mod = load(built / "mavlink1.py")
    parser = mavlink.MAVLink(None)
    for frame in packed(sample_messages(seed=11)):
        again = mod.encode(mod.decode(frame))
        assert parser.decode(bytearray(again)).get_msgbuf() == frame


def test_a_wrong_crc_extra_is_a_checksum_error(built):
    mod = load(built / "mavlink1.py")
    frame = bytearray(packed([mavlink.MAVLink_heartbeat_message(1, 2, 3, 4, 5, 3)])[0])
    frame[5] = 1  # a heartbeat's payload under SYS_STATUS's id: the size check refuses it first
    with pytest.raises(mod.DecodeError):
        mod.decode(bytes(frame))
    frame = bytearray(packed([mavlink.MAVLink_heartbeat_message(1, 2, 3, 4, 5, 3)])[0])
    frame[-1] ^= 0x01
    with pytest.raises(mod.DecodeError) as err:
        mod.decode(bytes(frame))
    assert err.value.rule == "checksum" and err.value.field == "checksum"


def garbage_stream(frames: list[bytes], seed: int = 3) -> bytes:
    rng = random.Random(seed)
    out = b""
    for frame in frames:
        out += bytes(rng.choice([0x00, 0xFE, 0x55, rng.getrandbits(8)]) for _ in range(rng.randint(0, 6)))
        out += frame
    return out


def test_python_stream_finds_every_frame_among_garbage(built):
    mod = load(built / "mavlink1.py")
    messages = sample_messages(seed=5)
    frames = packed(messages)
    stream = garbage_stream(frames)
    dec = mod.StreamDecoder()
    found = [x for i in range(0, len(stream), 17) for x in dec.feed(stream[i:i + 17])]
    decoded = [mod.encode(x) for x in found if not isinstance(x, Exception)]
    assert decoded == frames


def test_c_decodes_and_encodes_pymavlink_frames(built):
    frames = packed(sample_messages(seed=9))
    stream = garbage_stream(frames, seed=4)

    table = "\n".join(f"    {{{len(f)}u, {{{c_bytes(f)}}}}}," for f in frames)
    driver = r"""
#include <stdio.h>
#include "mavlink1.h"
struct frame { size_t len; uint8_t bytes[MAVLINK1_MAX_FRAME]; };
static const struct frame frames[] = {
TABLE
};
static const uint8_t stream[] = {STREAM};
static void show(const uint8_t *buf, int n) {
    int i;
    for (i = 0; i < n; i++) printf("%02x", buf[i]);
    printf("\n");
}
int main(void) {
    mavlink1_message_t m;
    mavlink1_parser_t p;
    uint8_t out[MAVLINK1_MAX_FRAME];
    size_t i;
    int rc, n;
    for (i = 0; i < sizeof frames / sizeof frames[0]; i++) {
        rc = mavlink1_decode(frames[i].bytes, frames[i].len, MAVLINK1_DIR_ANY, &m);
        n = rc == 0 ? mavlink1_encode(&m, out, sizeof out) : rc;
        if (n < 0) { printf("error %d\n", n); continue; }
        show(out, n);
    }
    mavlink1_parser_init(&p, MAVLINK1_DIR_ANY);
    for (i = 0; i < sizeof stream; i++) {
        mavlink1_parser_feed(&p, stream[i]);
        while ((rc = mavlink1_parser_next(&p, &m)) != 0) {
            if (rc == 1) {
                n = mavlink1_encode(&m, out, sizeof out);
                printf("stream ");
                show(out, n);
            }
        }
    }
    return 0;
}
""".replace("TABLE", table).replace("STREAM", c_bytes(stream))
    lines = run_c(built, driver)
    assert lines[:len(frames)] == [f.hex() for f in frames]
    assert lines[len(frames):] == ["stream " + f.hex() for f in frames]
