"""The command line with MAVLink 2 signing keys (examples/mavlink2.yaml), against
pymavlink: frames pymavlink signs are verified by `check`, `decode` and `monitor`
given the key; a frame `encode` signs passes pymavlink's signature check; a
tampered frame, a wrong key and an unsigned frame are findings of the codec's
error kinds; bad key files are usage errors; the key is never printed.

Signed frames, signatures and timestamps come from pymavlink, offsets from the
frame lengths it gives, never from the encoder under test."""
from __future__ import annotations

import hashlib
import json
import os
import struct
import subprocess
import sys
from pathlib import Path

import pytest

os.environ["MAVLINK20"] = "1"  # before pymavlink is imported: its v2 framing
from pymavlink.dialects.v20 import common as mavlink  # noqa: E402  (a test extra: pip install -e ".[peers]")

from codeword.cli import main  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
SCHEMA = str(ROOT / "examples" / "mavlink2.yaml")
KEY = bytes(range(100, 132))  # a test key, as pymavlink takes it
OTHER_KEY = bytes(range(1, 33))
LINK, START = 7, 0x0123456789  # pymavlink signs with this link and timestamp, one more per frame
COMMANDS = ("check", "decode", "monitor")


def messages() -> list:
    return [mavlink.MAVLink_heartbeat_message(6, 8, 81, 4, 3, 3),
            mavlink.MAVLink_command_ack_message(400, 5, 100, 0, 255, 190),
            mavlink.MAVLink_attitude_message(1000, 0.5, -0.25, 1.0, 0.0, 0.0, 2.0),
            mavlink.MAVLink_param_value_message(b"SYSID_THISMAV", 42.0, 9, 300, 12)]


def signed(key: bytes = KEY) -> list[bytes]:
    """The messages as pymavlink signs them."""
    mav = mavlink.MAVLink(None, srcSystem=42, srcComponent=190)
    mav.signing.secret_key = key
    mav.signing.link_id = LINK
    mav.signing.timestamp = START
    mav.signing.sign_outgoing = True
    return [bytes(m.pack(mav)) for m in messages()]


def unsigned() -> list[bytes]:
    mav = mavlink.MAVLink(None, srcSystem=42, srcComponent=190)
    return [bytes(m.pack(mav)) for m in messages()]


def forged(frame: bytes, at: int) -> bytes:
    """The frame with a payload byte changed and its CRC made right again (pymavlink's
    CRC): only the signature can tell."""
    f = bytearray(frame)
    f[at] ^= 0x40
    end = 10 + f[1]
    crc = mavlink.x25crc(bytes(f[1:end]))
    crc.accumulate(bytes([mavlink.mavlink_map[int.from_bytes(f[7:10], "little")].crc_extra]))
    f[end:end + 2] = struct.pack("<H", crc.crc)
    return bytes(f)


def run(capsys, *argv) -> tuple[int, str, str]:
    status = main([*map(str, argv)])
    out, err = capsys.readouterr()
    return status, out, err


def write(tmp_path: Path, name: str, data) -> Path:
    path = tmp_path / name
    (path.write_bytes if isinstance(data, bytes) else path.write_text)(data)
    return path


@pytest.fixture
def key_files(tmp_path):
    """The key as raw bytes, as hex on one line, and as spaced hex over several lines."""
    spread = "\n".join(" ".join(KEY[i:i + 4].hex() for i in range(j, j + 16, 4)) for j in (0, 16)) + "\n"
    return {"raw": write(tmp_path, "key.bin", KEY), "hex": write(tmp_path, "key.hex", KEY.hex() + "\n"),
            "spread": write(tmp_path, "key.txt", spread)}


def rows(out: str) -> list[dict]:
    return [json.loads(line) for line in out.splitlines()]


# ---------------------------------------------------------------- verifying what pymavlink signs

@pytest.mark.parametrize("form", ["raw", "hex", "spread"])
def test_check_verifies_a_capture_pymavlink_signed(tmp_path, capsys, key_files, form):
    capture = write(tmp_path, "signed.bin", b"".join(signed()))
    status, out, err = run(capsys, "check", "--format", "json", SCHEMA, capture, "--key-file", key_files[form])
    doc = json.loads(out)
    assert status == 0, (out, err)
    assert doc["findings"] == [] and doc["summary"]["read"] == doc["summary"]["valid"] == len(messages())


def test_check_verifies_a_hex_dump_and_takes_the_key_in_hex(tmp_path, capsys):
    dump = write(tmp_path, "signed.hex", "".join(f.hex(" ") + "\n" for f in signed()))
    status, out, _ = run(capsys, "check", SCHEMA, dump, "--key", KEY.hex().upper())
    assert status == 0 and "4 frame(s) read (hex), 4 valid, 0 invalid" in out


def test_decode_verifies_and_shows_the_trailer_pymavlink_wrote(capsys, key_files):
    frames = signed()
    status, out, err = run(capsys, "decode", SCHEMA, *(f.hex() for f in frames), "--format", "json",
                           "--key-file", key_files["hex"])
    assert status == 0, err
    got = rows(out)
    assert [r["message"] for r in got] == ["heartbeat", "command_ack", "attitude", "param_value"]
    for n, (row, frame) in enumerate(zip(got, frames)):
        assert row["frame"] == frame.hex(" ")
        assert row["values"]["incompat_flags"] == ["signing"]
        assert (row["values"]["link_id"], row["values"]["timestamp"]) == (LINK, START + n)
        assert row["values"]["signature"] == frame[-6:].hex()
    assert got[1]["values"]["command"] == 400 and got[1]["values"]["target_component"] == 190


def test_monitor_replays_a_signed_capture_with_the_key(tmp_path, capsys, key_files):
    capture = write(tmp_path, "signed.bin", b"".join(signed()))
    status, out, err = run(capsys, "monitor", SCHEMA, "--replay", capture, "--json", "--key-file", key_files["raw"])
    assert status == 0, err
    assert [r["message"] for r in rows(out)] == ["heartbeat", "command_ack", "attitude", "param_value"]
    assert "4 frames, 0 errors, 0 bytes skipped" in err


# ---------------------------------------------------------------- frames the key refuses

def test_a_tampered_frame_is_a_signature_finding_and_the_stream_goes_on(tmp_path, capsys, key_files):
    frames = signed()
    bad_payload = forged(frames[1], 12)  # CRC right, signature of other bytes
    bad_signature = frames[2][:-1] + bytes([frames[2][-1] ^ 1])
    capture = write(tmp_path, "tampered.bin", frames[0] + bad_payload + bad_signature + frames[3])
    status, out, _ = run(capsys, "check", "--format", "json", SCHEMA, capture, "--key-file", key_files["hex"])
    doc = json.loads(out)
    assert status == 1
    at1 = len(frames[0]) + len(frames[1]) - 6  # each signature: the frame's last 6 bytes
    at2 = at1 + len(frames[2])
    assert [(f["offset"], f["message"], f["field"], f["rule"]) for f in doc["findings"]] == [
        (at1, "command_ack", "signature", "signature"), (at2, "attitude", "signature", "signature")]
    assert doc["findings"][0]["actual"] == frames[1][-6:].hex()
    assert doc["summary"] == {"read": 4, "valid": 2, "invalid": 2, "skipped_bytes": 0, "findings": 2}
    # without the key the same capture is well-formed: only the signature tells
    status, out, _ = run(capsys, "check", "--format", "json", SCHEMA, capture)
    assert status == 0 and json.loads(out)["findings"] == []


def test_a_wrong_key_refuses_every_frame_in_every_command(tmp_path, capsys):
    frames = signed()
    capture = write(tmp_path, "signed.bin", b"".join(frames))
    wrong = write(tmp_path, "wrong.key", OTHER_KEY.hex())
    status, out, _ = run(capsys, "check", "--format", "json", SCHEMA, capture, "--key-file", wrong)
    doc = json.loads(out)
    assert status == 1 and {(f["field"], f["rule"]) for f in doc["findings"]} == {("signature", "signature")}
    assert doc["summary"]["invalid"] == 4 and doc["summary"]["skipped_bytes"] == 0
    status, out, _ = run(capsys, "decode", SCHEMA, capture, "--format", "json", "--key-file", wrong)
    got = rows(out)
    assert status == 1 and len(got) == 4 and all("breaks rule signature" in r["error"] for r in got)
    assert [r["frame"] for r in got] == [f.hex(" ") for f in frames]
    status, out, err = run(capsys, "monitor", SCHEMA, "--replay", capture, "--key-file", wrong)
    assert status == 1 and out.count("breaks rule signature") == 4
    assert "4 frames, 4 errors, 0 bytes skipped" in err


def test_frames_pymavlink_signed_with_another_key_are_refused(tmp_path, capsys, key_files):
    capture = write(tmp_path, "other.bin", b"".join(signed(OTHER_KEY)))
    status, out, _ = run(capsys, "check", "--format", "json", SCHEMA, capture, "--key-file", key_files["raw"])
    assert status == 1 and [f["rule"] for f in json.loads(out)["findings"]] == ["signature"] * 4


def test_an_unsigned_frame_is_refused_when_a_key_is_given(tmp_path, capsys, key_files):
    frames = signed()
    plain = unsigned()[1]
    capture = write(tmp_path, "mixed.bin", frames[0] + plain + frames[2])
    status, out, _ = run(capsys, "check", "--format", "json", SCHEMA, capture, "--key-file", key_files["hex"])
    doc = json.loads(out)
    assert status == 1
    assert [(f["offset"], f["field"], f["rule"]) for f in doc["findings"]] == [
        (len(frames[0]) + 2, "incompat_flags", "unsigned")]  # the flags byte, third of the frame
    status, out, _ = run(capsys, "decode", SCHEMA, capture, "--format", "json", "--key-file", key_files["hex"])
    got = rows(out)
    assert status == 1 and [r.get("message") for r in got] == ["heartbeat", None, "attitude"]
    assert "breaks rule unsigned" in got[1]["error"]


def test_a_signature_error_does_not_show_the_signature_the_key_makes(tmp_path, capsys, key_files):
    frame = forged(signed()[1], 12)
    # the signature the key makes for the forged bytes, by MAVLink's definition (pymavlink's
    # check_signature): SHA-256 over the key and the frame through the timestamp, its first 6 bytes
    expected = hashlib.sha256(KEY + frame[:-6]).digest()[:6]
    assert expected != frame[-6:]
    dump = write(tmp_path, "forged.hex", frame.hex() + "\n")
    for argv in (("check", SCHEMA, dump), ("check", "--format", "json", SCHEMA, dump),
                 ("decode", SCHEMA, frame.hex()), ("decode", SCHEMA, frame.hex(), "--format", "json"),
                 ("decode", SCHEMA, frame.hex(), "--format", "csv")):
        status, out, err = run(capsys, *argv, "--key-file", key_files["raw"])
        assert status == 1 and "signature" in out
        for shown in (expected.hex(), expected.hex(" "), repr(expected)):
            assert shown not in out + err, argv


# ---------------------------------------------------------------- signing what encode writes

def test_pymavlink_verifies_what_encode_signs(tmp_path, capsys, key_files):
    values = ["incompat_flags=signing", "compat_flags=0", "seq=9", "sysid=42", "compid=190", "command=400",
              "result=5", "progress=100", "result_param2=0", "target_system=255", "target_component=190",
              f"link_id={LINK + 1}", f"timestamp={START + 5}"]
    status, out, err = run(capsys, "encode", SCHEMA, "command_ack", *values, "--key-file", key_files["hex"])
    assert status == 0, err
    frame = bytes.fromhex(out)
    parser = mavlink.MAVLink(None)
    parser.signing.secret_key = KEY
    message = parser.parse_char(bytearray(frame))
    assert parser.signing.goodsig_count == 1 and message._signed and message._link_id == LINK + 1
    assert parser.signing.stream_timestamps[(LINK + 1, 42, 190)] == START + 5
    assert (message.command, message.result, message.target_system) == (400, 5, 255)
    # the same frame pymavlink signs with the same link and timestamp
    mav = mavlink.MAVLink(None, srcSystem=42, srcComponent=190)
    mav.seq = 9
    mav.signing.secret_key, mav.signing.link_id, mav.signing.timestamp = KEY, LINK + 1, START + 5
    mav.signing.sign_outgoing = True
    assert frame == bytes(mavlink.MAVLink_command_ack_message(400, 5, 100, 0, 255, 190).pack(mav))
    # another key's signature is refused by pymavlink
    other = write(tmp_path, "other.key", OTHER_KEY)
    status, out, _ = run(capsys, "encode", SCHEMA, "command_ack", *values, "--key-file", other)
    parser = mavlink.MAVLink(None)
    parser.signing.secret_key = KEY
    try:
        parser.parse_char(bytearray(bytes.fromhex(out)))
    except mavlink.MAVError:
        pass
    assert status == 0 and parser.signing.goodsig_count == 0 and parser.signing.badsig_count == 1


def test_encode_with_a_key_leaves_the_trailer_rules_to_the_codec(capsys, key_files):
    base = ["compat_flags=0", "seq=0", "sysid=1", "compid=1", "command=1", "result=0", "progress=0",
            "result_param2=0", "target_system=0", "target_component=0"]
    key = ("--key-file", key_files["hex"])
    status, _, err = run(capsys, "encode", SCHEMA, "command_ack", "incompat_flags=signing", *base, *key)
    assert status == 1 and "command_ack.link_id: None breaks rule present" in err
    status, _, err = run(capsys, "encode", SCHEMA, "command_ack", "incompat_flags=0", *base, "link_id=1",
                         "timestamp=2", *key)
    assert status == 1 and "breaks rule unsigned" in err
    status, _, err = run(capsys, "encode", SCHEMA, "command_ack", "incompat_flags=signing", *base, "link_id=1",
                         "timestamp=2", "signature=000000000000", *key)
    assert status == 2 and "signature: the key computes it" in err


# ---------------------------------------------------------------- bad keys

BAD_KEY_FILES = {
    "31 raw bytes": (KEY[:31], "holds 31 byte(s)"),
    "33 raw bytes": (KEY + b"\n", "holds 33 byte(s)"),
    "65 hex digits": ((KEY.hex() + "a\n").encode(), "holds 65 hex digit(s)"),
    "62 hex digits": ((KEY.hex()[:62] + "\n").encode(), "holds 62 hex digit(s)"),
    "non-hex": (("g" + KEY.hex()[1:] + "\n").encode(), "holds 65 byte(s), neither the raw key nor hex digits"),
    "empty": (b"", "holds no key (empty)"),
}


@pytest.mark.parametrize("case", BAD_KEY_FILES)
@pytest.mark.parametrize("command", COMMANDS + ("encode",))
def test_a_bad_key_file_is_a_usage_error_naming_the_file(tmp_path, capsys, case, command):
    data, holds = BAD_KEY_FILES[case]
    path = write(tmp_path, "bad.key", data)
    argv = {"check": ("check", SCHEMA, path), "decode": ("decode", SCHEMA, signed()[0].hex()),
            "monitor": ("monitor", SCHEMA, "--replay", path),
            "encode": ("encode", SCHEMA, "heartbeat")}[command]
    status, out, err = run(capsys, *argv, "--key-file", path)
    assert status == 2 and out == ""
    assert f"--key-file {path}: {holds}" in err
    assert "a key of 32 bytes (32 raw bytes, or 64 hex digits)" in err
    assert "Traceback" not in err


def test_bad_keys_on_the_command_line_and_missing_files(tmp_path, capsys):
    for text, holds in ((KEY.hex()[:-2], "holds 62 hex digit(s)"), ("zz" * 32, "not hex digits"), ("", "empty")):
        status, out, err = run(capsys, "decode", SCHEMA, signed()[0].hex(), "--key", text)
        assert status == 2 and "codeword decode: --key: " in err and holds in err and "64 hex digits" in err
    status, _, err = run(capsys, "check", SCHEMA, "-", "--key-file", tmp_path / "none.key")
    assert status == 2 and f"--key-file {tmp_path / 'none.key'}: cannot read" in err
    status, _, err = run(capsys, "check", SCHEMA, "-", "--key-file", tmp_path)
    assert status == 2 and "cannot read" in err


def test_key_and_key_file_are_one_or_the_other(capsys, key_files):
    with pytest.raises(SystemExit) as exc:
        main(["decode", SCHEMA, "--key-file", str(key_files["hex"]), "--key", KEY.hex()])
    assert exc.value.code == 2 and "not allowed with argument" in capsys.readouterr().err


@pytest.mark.parametrize("command", COMMANDS + ("encode",))
def test_a_key_for_a_schema_without_a_signature_is_a_usage_error_naming_it(tmp_path, capsys, key_files, command):
    mtv4 = ROOT / "schemas" / "mtv4.yaml"
    frame = write(tmp_path, "f.hex", "aa 08 03 01 20 00 24 03 60 ff 40 00\n")  # mtv4.yaml's robot 5 example
    argv = {"check": ("check", mtv4, frame), "decode": ("decode", mtv4, frame), "monitor": ("monitor", mtv4, "--replay", frame),
            "encode": ("encode", mtv4, "set_wheels_velocities")}[command]
    status, out, err = run(capsys, *argv, "--key-file", key_files["hex"])
    assert status == 2 and out == ""
    assert f"--key-file: mtv4 ({mtv4}) declares no signature" in err


# ---------------------------------------------------------------- the key is never shown

def _shown_forms(key: bytes) -> list[str]:
    text = key.hex()
    return [text, text.upper(), key.hex(" "), repr(key)[2:-1], text[:16], text[-16:]]


def test_the_key_never_appears_in_any_output(tmp_path, capsys):
    """Every command, with good and bad keys, good and bad frames, in every format, with
    --debug: neither the key nor a run of it is in what it writes (two runs as processes)."""
    frames = signed()
    capture = write(tmp_path, "c.bin", frames[0] + forged(frames[1], 12) + unsigned()[2] + frames[3])
    key_file = write(tmp_path, "k.hex", KEY.hex())
    near = write(tmp_path, "near.hex", KEY.hex() + "0")  # 65 digits: refused, and not echoed
    short = write(tmp_path, "short.bin", KEY[:31])
    runs = []
    for key in (("--key-file", key_file), ("--key", KEY.hex()), ("--key-file", near), ("--key-file", short),
                ("--key", KEY.hex() + "0")):
        runs += [("check", SCHEMA, capture, *key), ("check", "--format", "json", SCHEMA, capture, *key),
                 ("decode", SCHEMA, capture, "--format", "csv", *key),
                 ("--debug", "monitor", SCHEMA, "--replay", capture, "--json", *key),
                 ("encode", SCHEMA, "heartbeat", "incompat_flags=signing", "compat_flags=0", "seq=0", "sysid=1",
                  "compid=1", "custom_mode=0", "type=1", "autopilot=2", "base_mode=0", "system_status=4",
                  "mavlink_version=3", "link_id=0", "timestamp=1", *key)]
    outputs = [run(capsys, *argv) for argv in runs]
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(filter(None, [str(ROOT), os.environ.get("PYTHONPATH")])))
    for argv in (runs[1], runs[8]):
        proc = subprocess.run([sys.executable, "-m", "codeword", *map(str, argv)], capture_output=True, text=True,
                              timeout=120, env=env, cwd=tmp_path)
        outputs.append((proc.returncode, proc.stdout, proc.stderr))
    assert {status for status, _, _ in outputs} == {0, 1, 2}
    for argv, (status, out, err) in zip(runs + [runs[1], runs[8]], outputs):
        assert out or err, argv
        assert "Traceback" not in err
        for shown in _shown_forms(KEY):
            assert shown not in out and shown not in err, (argv, shown)


def test_encode_without_a_key_writes_the_trailer_it_is_given(capsys):
    """A frame pymavlink signed, its values given back: the same bytes, signature and all."""
    frame = signed()[1]  # pymavlink's pack leaves seq at 0 (send counts it)
    values = ["incompat_flags=signing", "compat_flags=0", "seq=0", "sysid=42", "compid=190", "command=400",
              "result=5", "progress=100", "result_param2=0", "target_system=255", "target_component=190",
              f"link_id={LINK}", f"timestamp={START + 1}", f"signature={frame[-6:].hex()}"]
    status, out, err = run(capsys, "encode", SCHEMA, "command_ack", *values)
    assert status == 0, err
    assert bytes.fromhex(out) == frame
