"""Byte streams of the seed protocols with the events worked out by hand from the
schemas' framing rules (not from a decoder): mtv4 frames start at 0xAA and are the
length byte + 4 bytes long (sizes 8, 12, 22 and 26 exist), with a CRC; tr24 frames
start at 0x02, are 12 bytes and end in the stop byte 0x03. After a bad frame a
decoder resumes one byte after the frame's first byte, never a whole claimed frame
later: a false sync with a plausible length must not hide the real frame after it.

Each case runs through the pure-Python StreamDecoder (whole and byte by byte), the
accelerated one, the C scan and the C byte parser. An event is (message, end offset)
or (error, rule); a rule of None is any rule (where the schema does not say which of
several faults a decoder reports first). Frames are the schemas' examples."""
from __future__ import annotations

import shutil

import pytest

from conftest import ROOT
from schema_in_a_test import load
from stream_events import accelerated, c_events, python_events, without_ends

ROBOT5 = "aa 08 03 01 20 00 24 03 60 ff 40 00"     # mtv4 set_wheels_velocities, 12 bytes
ROBOT12 = "aa 08 0f 01 00 10 00 80 ff 7f 9c b3"    # mtv4 set_wheels_velocities, 12 bytes
ACK = "aa 04 03 01 20 00 59 f7"                      # mtv4 ack, 8 bytes
BAD_CRC = "aa 08 03 01 20 00 24 03 60 ff 40 ff"    # ROBOT5 with its last CRC byte inverted
BAD_LENGTH = "aa 09 03 01 20 00 24 03 60 ff c6 63"  # length 9: a 13-byte frame, a size no message has
COMMAND = "02 00 01 03 2c 00 00 00 00 00 00 03"    # tr24 command
REPLY = "02 03 03 01 2d 00 00 00 00 00 01 03"      # tr24 reply
BAD_STOP = "02 00 01 03 2c 00 00 00 00 00 00 04"   # COMMAND with stop byte 04

SWV = "set_wheels_velocities"
CASES = {
    "mtv4": [
        ("two frames", ROBOT5 + ROBOT12, [("message", SWV, 12), ("message", SWV, 24)]),
        ("frames of two sizes", ROBOT5 + ACK, [("message", SWV, 12), ("message", "ack", 20)]),
        ("noise before a frame: no sync in it, skipped without an error", "00 ff 01" + ROBOT5,
         [("message", SWV, 15)]),
        # AA 08 claims 12 bytes (aa 08 aa 08 03 .. ff) that are no frame; the real frame is at 2
        ("a false sync with a plausible length, then a frame", "aa 08" + ROBOT5,
         [("error", None), ("message", SWV, 14)]),
        # the cut frame's AA 08 claims 12 bytes, 7 of them ROBOT12's; ROBOT12 is at 5
        ("a frame cut short, then a frame", ROBOT5[:14] + ROBOT12, [("error", None), ("message", SWV, 17)]),
        # no AA in the damaged frame after its first byte: the next frame is the next sync
        ("a damaged CRC, then a frame", BAD_CRC + ROBOT12, [("error", "checksum"), ("message", SWV, 24)]),
        ("a length no message has, then a frame", BAD_LENGTH + ROBOT5, [("error", "length"), ("message", SWV, 24)]),
        # one stretch: the false sync and the damaged frame give one error together
        ("two bad frames in a row give one error", "aa 08" + BAD_CRC + ROBOT5,
         [("error", None), ("message", SWV, 26)]),
    ],
    "tr24": [
        ("command and reply", COMMAND + REPLY, [("message", "command", 12), ("message", "reply", 24)]),
        # 02 02 02 00 01 03 2c 00 00 00 00 00: its 12th byte is no stop byte; nor is the next
        # candidate's; the command starts at 2
        ("false starts, then a frame", "02 02" + COMMAND, [("error", "const"), ("message", "command", 14)]),
        ("a bad stop byte, then a frame", BAD_STOP + REPLY, [("error", "const"), ("message", "reply", 24)]),
    ],
}
MESSAGES = {"mtv4": ["set_wheels_velocities", "set_led", "set_wheels_velocities_with_odometry", "ack",
                     "odometry_reply"], "tr24": ["command", "reply"]}


def matches(got: list[tuple], expected: list[tuple]) -> bool:
    return len(got) == len(expected) and all(
        g == e or (e[0] == "error" and e[1] is None and g[0] == "error") for g, e in zip(got, expected))


def cases(name: str) -> list[tuple[str, bytes, list[tuple]]]:
    return [(label, bytes.fromhex(data), events) for label, data, events in CASES[name]]


@pytest.fixture
def seed(tmp_path, request):
    """The seed protocol's schema, generated module and headers, copied into tmp_path."""
    name = request.param
    shutil.copy(ROOT / "schemas" / f"{name}.yaml", tmp_path)
    shutil.copy(ROOT / "generated" / "python" / f"{name}.py", tmp_path)
    for header in (f"{name}.h", "codeword.h"):
        shutil.copy(ROOT / "generated" / "c" / header, tmp_path)
    return tmp_path, name


@pytest.mark.parametrize("seed", sorted(CASES), indirect=True)
def test_python(seed):
    where, name = seed
    mod = load(where / f"{name}.py")
    for label, data, expected in cases(name):
        for piece in (0, 1):
            got = python_events(mod, data, piece)
            assert matches(got, expected), f"{name}, {label} (pieces of {piece or 'all'}): {got}"


@pytest.mark.parametrize("seed", sorted(CASES), indirect=True)
def test_accelerator(seed):
    where, name = seed
    fast = accelerated(where, name)
    for label, data, expected in cases(name):
        for piece in (0, 5):
            got = python_events(fast, data, piece)
            assert matches(got, expected), f"{name}, {label} (pieces of {piece or 'all'}): {got}"


@pytest.mark.parametrize("seed", sorted(CASES), indirect=True)
def test_c(seed):
    where, name = seed
    for label, data, expected in cases(name):
        scan, parser = c_events(where, name, MESSAGES[name], data)
        assert matches(scan, expected), f"{name}, {label}: scan {scan}"
        assert matches(parser, without_ends(expected)), f"{name}, {label}: parser {parser}"
