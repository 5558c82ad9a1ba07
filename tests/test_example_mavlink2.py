"""examples/mavlink2.yaml against pymavlink, the reference MAVLink implementation:
frames pymavlink packs (truncated: trailing zero bytes of the payload dropped, the
extension fields among them) decode to the values it packed, and codeword's encoders
write pymavlink's bytes back, in Python and in C; both stream decoders find the
frames in a stream with garbage between them; a signed frame is refused. Expected
bytes come from pymavlink."""
from __future__ import annotations

import json
import os
import random
import re
import shutil
import struct
import subprocess
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import pytest

os.environ["MAVLINK20"] = "1"  # before pymavlink is imported: its v2 framing
from pymavlink.dialects.v20 import common as mavlink  # noqa: E402  (a test extra: pip install -e ".[peers]")

from cdriver import Driver  # noqa: E402
from codeword.build import compile_schema  # noqa: E402
from schema_in_a_test import C_FLAGS, build_example, c_bytes, load, run_c  # noqa: E402

SCHEMA = Path(__file__).resolve().parent.parent / "examples" / "mavlink2.yaml"


def f32(x: float) -> float:
    return struct.unpack("<f", struct.pack("<f", x))[0]


MESSAGES = ("heartbeat", "sys_status", "param_value", "gps_raw_int", "attitude", "command_ack")
# common.xml's <extensions/>: the fields a sender of an older version leaves off
EXTENSIONS = {
    "sys_status": ("onboard_control_sensors_present_extended", "onboard_control_sensors_enabled_extended",
                   "onboard_control_sensors_health_extended"),
    "gps_raw_int": ("alt_ellipsoid", "h_acc", "v_acc", "vel_acc", "hdg_acc", "yaw"),
    "command_ack": ("progress", "result_param2", "target_system", "target_component"),
}


def field_value(rng: random.Random, ctype: str):
    """A value of a MAVLink field type spread over its range; zero often, so that
    pymavlink truncates payloads by various lengths."""
    if rng.random() < 0.4:
        return b"" if ctype == "char" else 0
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
    for round_ in range(8):
        for name in MESSAGES:
            cls = getattr(mavlink, f"MAVLink_{name}_message")
            values = {field: field_value(rng, ctype) for field, ctype in zip(cls.fieldnames, cls.fieldtypes)}
            if round_ % 3 == 0:  # as an older sender, without the extension fields
                values.update(dict.fromkeys(EXTENSIONS.get(name, ()), 0))
            out.append(cls(**values))
    return out


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    return build_example("mavlink2", tmp_path_factory.mktemp("mavlink2"))


def packed(messages) -> list[bytes]:
    mav = mavlink.MAVLink(None, srcSystem=42, srcComponent=190)
    return [bytes(m.pack(mav)) for m in messages]


def full_size(message) -> int:
    return 12 + struct.calcsize("<" + message.unpacker.format[1:])


def test_the_samples_hold_truncated_frames_and_frames_without_extensions():
    messages = sample_messages()
    frames = packed(messages)
    assert all(f[0] == 0xFD and f[1] == len(f) - 12 for f in frames)
    assert sum(len(f) < full_size(m) for m, f in zip(messages, frames)) > 10
    short_of_extensions = [f for m, f in zip(messages, frames) if m.get_type() == "COMMAND_ACK" and len(f) <= 15]
    assert short_of_extensions  # command and result only: no extension field was sent
    assert any(len(f) == full_size(m) for m, f in zip(messages, frames))


def test_python_decodes_pymavlink_frames_and_encodes_them_back(built):
    mod = load(built / "mavlink2.py")
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


def test_a_frame_not_truncated_decodes_too(built):
    """A sender may send the whole payload, trailing zeros and all: the CRC covers what it sent."""
    mod = load(built / "mavlink2.py")
    heartbeat = mavlink.MAVLink_heartbeat_message(0, 0, 0, 0, 0, 0)
    mav = mavlink.MAVLink(None, srcSystem=1, srcComponent=1)
    truncated = bytes(heartbeat.pack(mav))
    assert len(truncated) == 13  # one payload byte kept
    mav = mavlink.MAVLink(None, srcSystem=1, srcComponent=1)
    heartbeat.pack(mav)
    payload = bytes(9)
    header = bytes([9, 0, 0, 0, 1, 1, 0, 0, 0])
    crc = mavlink.x25crc(header + payload)
    crc.accumulate(bytes([50]))
    whole = b"\xfd" + header + payload + struct.pack("<H", crc.crc)
    assert mod.decode(whole) == mod.decode(truncated)
    assert mod.encode(mod.decode(whole)) == truncated


def test_pymavlink_accepts_what_codeword_encodes(built):
    mod = load(built / "mavlink2.py")
    parser = mavlink.MAVLink(None)
    for frame in packed(sample_messages(seed=11)):
        again = mod.encode(mod.decode(frame))
        assert bytes(parser.decode(bytearray(again)).get_msgbuf()) == frame


def test_a_wrong_crc_and_a_signed_frame_are_refused(built):
    mod = load(built / "mavlink2.py")
    frame = bytearray(packed([mavlink.MAVLink_heartbeat_message(1, 2, 3, 4, 5, 3)])[0])
    frame[-1] ^= 0x01
    with pytest.raises(mod.DecodeError) as err:
        mod.decode(bytes(frame))
    assert err.value.rule == "checksum" and err.value.field == "checksum"
    mav = mavlink.MAVLink(None, srcSystem=1, srcComponent=1)
    mav.signing.secret_key = bytes(range(32))
    mav.signing.sign_outgoing = True
    signed = bytes(mavlink.MAVLink_heartbeat_message(1, 2, 3, 4, 5, 3).pack(mav))
    assert signed[2] & 0x01 and len(signed) == 12 + signed[1] + 13
    with pytest.raises(mod.DecodeError) as err:
        mod.decode(signed[:-13])  # the frame without its signature: the flag refuses it
    assert err.value.rule == "const" and err.value.field == "incompat_flags"
    assert "signed packet" in str(err.value.user_message)  # recognised, and said so


def garbage_stream(frames: list[bytes], seed: int = 3) -> bytes:
    rng = random.Random(seed)
    out = b""
    for frame in frames:
        out += bytes(rng.choice([0x00, 0xFD, 0x55, rng.getrandbits(8)]) for _ in range(rng.randint(0, 6)))
        out += frame
    return out


def test_python_stream_finds_every_frame_among_garbage(built):
    mod = load(built / "mavlink2.py")
    frames = packed(sample_messages(seed=5))
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
#include "mavlink2.h"
struct frame { size_t len; uint8_t bytes[MAVLINK2_MAX_FRAME]; };
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
    mavlink2_message_t m;
    mavlink2_parser_t p;
    uint8_t out[MAVLINK2_MAX_FRAME];
    size_t i;
    int rc, n;
    for (i = 0; i < sizeof frames / sizeof frames[0]; i++) {
        rc = mavlink2_decode(frames[i].bytes, frames[i].len, MAVLINK2_DIR_ANY, &m);
        n = rc == 0 ? mavlink2_encode(&m, out, sizeof out) : rc;
        if (n < 0) { printf("error %d\n", n); continue; }
        show(out, n);
    }
    mavlink2_parser_init(&p, MAVLINK2_DIR_ANY);
    for (i = 0; i < sizeof stream; i++) {
        mavlink2_parser_feed(&p, stream[i]);
        while ((rc = mavlink2_parser_next(&p, &m)) != 0) {
            if (rc == 1) {
                n = mavlink2_encode(&m, out, sizeof out);
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


def conformance_driver(built, part: int = 0, parts: int = 1) -> str:
    vectors = json.loads((built / "vectors" / "mavlink2.json").read_text())
    return Driver(compile_schema(SCHEMA)).source(vectors, part, parts)


def test_c_conformance_on_the_host(built, tmp_path):
    """The vectors (truncated frames, frames without extensions, damaged frames) in C."""
    src, exe = tmp_path / "conf.c", tmp_path / "conf"
    src.write_text(conformance_driver(built))
    build = subprocess.run(["gcc", *C_FLAGS, "-Wconversion", "-Wsign-conversion", "-Wshadow", "-Wpedantic",
                            "-I", str(built / "c"), str(src), "-o", str(exe)],
                           capture_output=True, text=True, timeout=300)
    assert build.returncode == 0, build.stderr
    run = subprocess.run([str(exe)], capture_output=True, text=True, timeout=120)
    assert run.returncode == 0 and re.search(r"CONFORMANCE mavlink2 PASS \d+ checks 0 failures", run.stdout), \
        run.stdout[-3000:] + run.stderr


AVR_PARTS = 16  # the vectors and the codec take about 350 KB of flash: in parts that fit 32 KB


def test_c_conformance_on_atmega32_under_simavr(built, tmp_path):
    if not (shutil.which("avr-gcc") and shutil.which("simavr")):
        pytest.fail("avr-gcc and simavr are needed (.ci/run installs them)")

    def build_and_run(part: int) -> str:
        src, elf = tmp_path / f"conf{part}.c", tmp_path / f"conf{part}.elf"
        src.write_text(conformance_driver(built, part, AVR_PARTS))
        build = subprocess.run(["avr-gcc", "-std=gnu99", "-Os", "-mmcu=atmega32", "-Wall", "-Wextra", "-Werror",
                                "-ffunction-sections", "-fdata-sections", "-Wl,--gc-sections",
                                "-I", str(built / "c"), str(src), "-o", str(elf)],
                               capture_output=True, text=True, timeout=300)
        if build.returncode != 0:
            return f"part {part}: build failed\n{build.stderr[-3000:]}"
        run = subprocess.run(["simavr", "-m", "atmega32", "-f", "16000000", str(elf)],
                             capture_output=True, text=True, timeout=600, errors="replace")
        return f"part {part}: " + run.stdout + run.stderr

    with ThreadPoolExecutor(max_workers=os.cpu_count() or 1) as pool:
        for output in pool.map(build_and_run, range(AVR_PARTS)):
            assert re.search(r"CONFORMANCE mavlink2 PASS \d+ checks 0 failures",
                             re.sub(r"\x1b\[[0-9;]*m", "", output)), output[-3000:]
