"""examples/mavlink2.yaml against pymavlink, the reference MAVLink implementation:
frames pymavlink packs (truncated: trailing zero bytes of the payload dropped, the
extension fields among them) decode to the values it packed, and codeword's encoders
write pymavlink's bytes back, in Python and in C; both stream decoders find the
frames in a stream with garbage between them; frames pymavlink signs decode and verify
with the key, codeword's signed frames pass pymavlink's signature check, and a tampered
frame is a signature error. Expected bytes come from pymavlink."""
from __future__ import annotations

import hashlib
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


def test_every_bytes_like_form_of_a_frame_decodes_alike(built):
    """A frame in a bytearray or a memoryview reads as it does in bytes, by module decode
    and by its class's decode."""
    mod = load(built / "mavlink2.py")
    for frame in packed(sample_messages(seed=5)):
        want = mod.decode(frame)
        for form in (bytearray(frame), memoryview(frame), memoryview(bytearray(frame))):
            assert mod.decode(form) == want
            assert type(want).decode(form) == want


def test_pymavlink_accepts_what_codeword_encodes(built):
    mod = load(built / "mavlink2.py")
    parser = mavlink.MAVLink(None)
    for frame in packed(sample_messages(seed=11)):
        again = mod.encode(mod.decode(frame))
        assert bytes(parser.decode(bytearray(again)).get_msgbuf()) == frame


def test_a_wrong_crc_is_refused(built):
    mod = load(built / "mavlink2.py")
    frame = bytearray(packed([mavlink.MAVLink_heartbeat_message(1, 2, 3, 4, 5, 3)])[0])
    frame[-1] ^= 0x01
    with pytest.raises(mod.DecodeError) as err:
        mod.decode(bytes(frame))
    assert err.value.rule == "checksum" and err.value.field == "checksum"


# Signing (https://mavlink.io/en/guide/message_signing.html): a test key, as pymavlink takes it
KEY = bytes(range(100, 132))
START = 0x0123456789  # 10 us units since 2015: the first timestamp pymavlink signs with


def signed_packed(messages, link_id: int = 7, start: int = START) -> list[bytes]:
    """The messages as pymavlink signs them (each frame's timestamp one more than the last's)."""
    mav = mavlink.MAVLink(None, srcSystem=42, srcComponent=190)
    mav.signing.secret_key = KEY
    mav.signing.link_id = link_id
    mav.signing.timestamp = start
    mav.signing.sign_outgoing = True
    return [bytes(m.pack(mav)) for m in messages]


def pymavlink_accepts(frames: list[bytes]) -> list[bool]:
    """Whether pymavlink's signature check passes each frame (unsigned frames refused:
    no allow_unsigned_callback)."""
    parser = mavlink.MAVLink(None)
    parser.signing.secret_key = KEY
    out = []
    for frame in frames:
        good = parser.signing.goodsig_count
        try:
            message = parser.parse_char(bytearray(frame))
        except mavlink.MAVError:  # its word for a signature it refuses
            message = None
        out.append(message is not None and message.get_type() != "BAD_DATA" and parser.signing.goodsig_count == good + 1)
    return out


def forged(frame: bytes, at: int) -> bytes:
    """The frame with a payload byte changed and its CRC made right again (pymavlink's CRC):
    only the signature can tell."""
    f = bytearray(frame)
    f[at] ^= 0x40
    end = 10 + f[1]
    crc = mavlink.x25crc(bytes(f[1:end]))
    msgid = int.from_bytes(f[7:10], "little")
    crc.accumulate(bytes([mavlink.mavlink_map[msgid].crc_extra]))
    f[end:end + 2] = struct.pack("<H", crc.crc)
    return bytes(f)


def test_the_signed_samples_are_signed():
    frames = signed_packed(sample_messages(seed=21))
    assert all(f[2] & 0x01 and len(f) == 12 + f[1] + 13 for f in frames)
    assert all(pymavlink_accepts(frames))


def test_python_decodes_and_verifies_what_pymavlink_signs(built):
    mod = load(built / "mavlink2.py")
    messages = sample_messages(seed=21)
    for n, (message, frame) in enumerate(zip(messages, signed_packed(messages))):
        ours = mod.decode(frame, key=KEY)
        assert (ours.link_id, ours.timestamp, ours.signature) == (7, START + n, frame[-6:])
        assert ours.incompat_flags == mod.IncompatFlags.signing
        assert ours.sysid == 42 and getattr(ours, message.get_fieldnames()[0]) is not None
        assert mod.encode(ours) == frame and mod.encode(ours, key=KEY) == frame
        assert type(ours).decode(frame, key=KEY) == ours and ours.encode(KEY) == frame


def test_pymavlink_verifies_what_python_signs(built):
    mod = load(built / "mavlink2.py")
    mine = []
    for n, frame in enumerate(packed(sample_messages(seed=23))):
        ours = mod.decode(frame)
        assert ours.link_id is None and ours.timestamp is None and ours.signature is None
        ours.incompat_flags = mod.IncompatFlags.signing
        ours.link_id, ours.timestamp, ours.signature = 2, START + 10 * n, None
        mine.append(mod.encode(ours, key=KEY))
    assert all(pymavlink_accepts(mine))
    wrong = mod.decode(mine[0])
    wrong.timestamp += 1  # the signature of another timestamp
    assert pymavlink_accepts([mod.encode(wrong)]) == [False]


def test_python_refuses_a_tampered_or_unsigned_frame(built):
    mod = load(built / "mavlink2.py")
    frame = signed_packed([mavlink.MAVLink_command_ack_message(400, 5, 100, 0, 255, 190)])[0]
    body = len(frame) - 13
    for damaged, field in ((forged(frame, 11), "signature"), (frame[:body] + bytes([frame[body] ^ 1]) + frame[body + 1:], "signature"),
                           (frame[:body + 3] + bytes([frame[body + 3] ^ 0x80]) + frame[body + 4:], "signature"),
                           (frame[:-1] + bytes([frame[-1] ^ 1]), "signature")):
        assert mod.decode(damaged).sysid == 42  # read without a key
        with pytest.raises(mod.DecodeError) as err:
            mod.decode(damaged, key=KEY)
        assert (err.value.rule, err.value.field, err.value.offset) == ("signature", field, 8 * (body + 7))
        # the signature that would make the damaged frame good (MAVLink's definition: the first
        # 6 bytes of SHA-256 over the key and the frame through the timestamp) is never shown
        right = hashlib.sha256(KEY + damaged[:body + 7]).digest()[:6]
        told = str(err.value) + repr(vars(err.value))
        assert right.hex() not in told.lower() and repr(right) not in told
    with pytest.raises(mod.DecodeError) as err:
        mod.decode(frame, key=bytes(32))
    assert err.value.rule == "signature"
    unsigned = packed([mavlink.MAVLink_command_ack_message(400, 5, 100, 0, 255, 190)])[0]
    with pytest.raises(mod.DecodeError) as err:
        mod.decode(unsigned, key=KEY)
    assert (err.value.rule, err.value.field) == ("unsigned", "incompat_flags")
    ours = mod.decode(unsigned)
    with pytest.raises(mod.EncodeError) as enc:
        mod.encode(ours, key=KEY)  # the flag is the one truth: a key signs only a flagged frame
    assert enc.value.rule == "unsigned"
    ours.incompat_flags = mod.IncompatFlags.signing
    with pytest.raises(mod.EncodeError) as enc:
        mod.encode(ours, key=KEY)  # flagged, but no link id or timestamp
    assert (enc.value.rule, enc.value.field) == ("present", "link_id")


def test_streams_find_signed_and_unsigned_frames_among_garbage(built):
    mod = load(built / "mavlink2.py")
    frames = [f for pair in zip(signed_packed(sample_messages(seed=25)), packed(sample_messages(seed=26))) for f in pair]
    stream = garbage_stream(frames, seed=8)
    dec = mod.StreamDecoder()
    found = [x for i in range(0, len(stream), 13) for x in dec.feed(stream[i:i + 13])]
    assert [mod.encode(x) for x in found if not isinstance(x, Exception)] == frames


def test_c_decodes_verifies_and_signs_as_pymavlink_does(built):
    """Each pymavlink-signed frame: decoded and verified with the key, signed again with it
    (pymavlink's bytes back); its forged, re-linked and re-timed copies, a wrong key and an
    unsigned frame: the distinct errors; the byte-at-a-time parser finds signed frames."""
    frames = signed_packed(sample_messages(seed=27))
    unsigned = packed(sample_messages(seed=27))[:3]
    damaged = []
    for f in frames[:6]:
        body = len(f) - 13
        damaged += [forged(f, 10), f[:body] + bytes([f[body] ^ 1]) + f[body + 1:], f[:-2] + bytes([f[-2] ^ 4]) + f[-1:]]
    table = lambda fs: "\n".join(f"    {{{len(f)}u, {{{c_bytes(f)}}}}}," for f in fs)  # noqa: E731
    stream = garbage_stream(frames, seed=9)
    driver = r"""
#include <stdio.h>
#include "mavlink2.h"
struct frame { size_t len; uint8_t bytes[MAVLINK2_MAX_FRAME]; };
static const struct frame frames[] = {
FRAMES
};
static const struct frame damaged[] = {
DAMAGED
};
static const struct frame unsigned_frames[] = {
UNSIGNED
};
static const uint8_t key[MAVLINK2_KEY_SIZE] = {@KEY@};
static const uint8_t other[MAVLINK2_KEY_SIZE] = {0};
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
        rc = mavlink2_decode_signed(frames[i].bytes, frames[i].len, MAVLINK2_DIR_ANY, key, &m);
        if (rc < 0) { printf("error %s\n", cw_error_name(rc)); continue; }
        printf("link %u time %llu ", m.trailer.link_id, (unsigned long long)m.trailer.timestamp);
        memset(m.trailer.signature, 0, sizeof m.trailer.signature);  /* the key makes it again */
        n = mavlink2_encode_signed(&m, key, out, sizeof out);
        show(out, n);
    }
    for (i = 0; i < sizeof damaged / sizeof damaged[0]; i++) {
        rc = mavlink2_decode_signed(damaged[i].bytes, damaged[i].len, MAVLINK2_DIR_ANY, key, &m);
        printf("damaged %s %d\n", cw_error_name(rc), mavlink2_decode(damaged[i].bytes, damaged[i].len, MAVLINK2_DIR_ANY, &m));
    }
    printf("other key %s\n", cw_error_name(mavlink2_decode_signed(frames[0].bytes, frames[0].len, MAVLINK2_DIR_ANY, other, &m)));
    for (i = 0; i < sizeof unsigned_frames / sizeof unsigned_frames[0]; i++) {
        rc = mavlink2_decode_signed(unsigned_frames[i].bytes, unsigned_frames[i].len, MAVLINK2_DIR_ANY, key, &m);
        printf("unsigned %s ", cw_error_name(rc));
        rc = mavlink2_decode(unsigned_frames[i].bytes, unsigned_frames[i].len, MAVLINK2_DIR_ANY, &m);
        printf("%d %s\n", rc, cw_error_name(mavlink2_encode_signed(&m, key, out, sizeof out)));
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
""".replace("FRAMES", table(frames)).replace("DAMAGED", table(damaged)).replace("UNSIGNED", table(unsigned)) \
        .replace("@KEY@", c_bytes(KEY)).replace("STREAM", c_bytes(stream))
    lines = run_c(built, driver)
    assert lines[:len(frames)] == [f"link 7 time {START + n} {f.hex()}" for n, f in enumerate(frames)]
    rest = lines[len(frames):]
    assert rest[:len(damaged)] == ["damaged signature 0"] * len(damaged)
    rest = rest[len(damaged):]
    assert rest[0] == "other key signature"
    assert rest[1:1 + len(unsigned)] == ["unsigned unsigned 0 unsigned"] * len(unsigned)
    assert rest[1 + len(unsigned):] == ["stream " + f.hex() for f in frames]


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


AVR_PARTS = 24  # the vectors (signed frames among them) and the codec: in parts that fit 32 KB


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
