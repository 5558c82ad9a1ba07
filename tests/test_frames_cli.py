"""decode, encode and monitor on the seed protocols, against the frames worked
out by hand in their schemas (the hex and values below are copied from those
examples, not produced by the encoder under test)."""
from __future__ import annotations

import json
import os
import subprocess
import sys
import time
import tty
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent

# mtv4.yaml, "robot 5 in group 3": 100.5 mm/s = 804 -> 24 03, -20 mm/s -> 60 ff, CRC 0x4000
ROBOT5 = "aa 08 03 01 20 00 24 03 60 ff 40 00"
# mtv4.yaml, "robot 12 in group 15, velocity limits"
ROBOT12 = "aa 08 0f 01 00 10 00 80 ff 7f 9c b3"
# tank.yaml, "the seed's test line"
TANK_LINE = "%:f,100,s,10,1,0,0,0,1;"


def codeword(*args: str, stdin: bytes | None = None, cwd: Path = ROOT) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "codeword", *args], cwd=cwd, input=stdin,
                          capture_output=True, timeout=120)


def lines(proc: subprocess.CompletedProcess) -> list[dict]:
    return [json.loads(line) for line in proc.stdout.decode().splitlines()]


def test_decode_hex_frames_as_a_table_with_names_and_units():
    proc = codeword("decode", "mtv4", ROBOT5, ROBOT12)
    assert proc.returncode == 0, proc.stderr
    out = proc.stdout.decode().splitlines()
    assert out[0].split() == ["offset", "frame", "message"]
    assert "set_wheels_velocities  group=3 robots=robot5 vl=100.5 mm/s vr=-20.0 mm/s" in out[1]
    assert "group=15 robots=robot12 vl=-4096.0 mm/s vr=4095.875 mm/s" in out[2]
    assert out[1].index("set_wheels") == out[2].index("set_wheels")  # aligned


def test_decode_a_capture_reports_garbage_and_bad_frames_inline_with_offsets(tmp_path):
    bad = bytearray.fromhex(ROBOT12)
    bad[-1] ^= 0xFF  # the CRC's second byte
    capture = tmp_path / "capture.bin"
    capture.write_bytes(b"zz" + bytes.fromhex(ROBOT5) + bytes(bad))
    proc = codeword("decode", "mtv4", str(capture), "--format", "json")
    assert proc.returncode == 1  # invalid data is a finding
    rows = lines(proc)
    assert [r["offset"] for r in rows] == [0, 2, 14]
    assert "2 byte(s) skipped" in rows[0]["error"] and rows[0]["frame"] == "7a 7a"
    assert rows[1]["message"] == "set_wheels_velocities"
    assert rows[1]["values"] == {"group": 3, "robots": ["robot5"], "vl": 100.5, "vr": -20.0, "radio_crc_flag": 0}
    assert "set_wheels_velocities.crc" in rows[2]["error"] and "byte 24" in rows[2]["error"]
    assert rows[2]["frame"] == bytes(bad).hex(" ")


def test_decode_reads_a_hex_dump_from_standard_input_and_writes_csv():
    proc = codeword("decode", "mtv4", "--format", "csv", stdin=f"# two frames\n{ROBOT5}\n{ROBOT12}\n".encode())
    assert proc.returncode == 0, proc.stderr
    out = proc.stdout.decode().splitlines()
    assert out[0] == "offset,frame,message,field,value,error"
    assert f"0,{ROBOT5},set_wheels_velocities,vl,100.5," in out
    assert f'12,{ROBOT12},set_wheels_velocities,robots,"[""robot12""]",' in out


def test_decode_a_text_line_and_a_bad_one():
    proc = codeword("decode", "tank", TANK_LINE, "junk;", "--format", "json")
    assert proc.returncode == 1
    good, bad = lines(proc)
    assert good["message"] == "command" and good["frame"] == TANK_LINE
    assert good["values"]["move"] == "forward" and good["values"]["speed"] == 100
    assert good["values"]["systemstatus"] == "work" and good["values"]["gpio1"] == 1.0
    assert "prefix" in bad["error"]


def test_decode_a_bit_packed_sequence():
    # car.yaml, "two master states and one slave word": header 02010400 | master 67000001 40781000 | slave b2848001
    proc = codeword("decode", "car", "02010400 67000001 40781000 b2848001", "--format", "json")
    assert proc.returncode == 0, proc.stderr
    (program,) = lines(proc)
    values = program["values"]
    assert program["message"] == "program"
    assert values["header.h1"] == 2 and values["header.h2_count"] == 1 and values["header.h2_time"] == 2
    assert values["master[0].motor.speed"] == 3 and values["master[1].led.led"] == 3
    assert values["slaves[0].motor.direction"] == "right" and values["slaves[0].ultrasonic.duration"] == 2
    cut = codeword("decode", "car", "02010400 67000001", "--format", "json")
    assert cut.returncode == 1 and "count" in lines(cut)[0]["error"]


def test_decode_refuses_what_is_not_an_input():
    proc = codeword("decode", "mtv4", "not-hex")
    assert proc.returncode == 2 and b"neither a file nor frames in hex" in proc.stderr
    proc = codeword("decode", "nosuchprotocol", ROBOT5)
    assert proc.returncode == 2 and b"no schema 'nosuchprotocol'" in proc.stderr


def test_encode_reproduces_the_worked_examples():
    proc = codeword("encode", "mtv4", "set_wheels_velocities", "group=3", "robots=robot5", "vl=100.5", "vr=-20")
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout.decode().strip() == ROBOT5
    proc = codeword("encode", "tank", "command", "move=forward", "speed=100", "value=s", "azimutloc=10",
                    "gpio1=1", "gpio2=0", "gpio3=0", "gpio4=0", "systemstatus=work")
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout.decode().strip() == TANK_LINE


def test_encode_takes_json_and_writes_raw_bytes(tmp_path):
    values = tmp_path / "values.json"
    values.write_text(json.dumps({"group": 15, "robots": ["robot12"], "vl": -4096, "vr": 4095.875}))
    proc = codeword("encode", "mtv4", "set_wheels_velocities", "--json", str(values), "--raw")
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout == bytes.fromhex(ROBOT12)


def test_encode_checks_every_value_as_the_codec_does():
    proc = codeword("encode", "mtv4", "set_wheels_velocities", "group=3", "robots=robot5", "vl=100.5", "vr=-5000")
    assert proc.returncode == 1 and not proc.stdout
    assert b"set_wheels_velocities.vr: -5000 breaks rule range (expected -4096..4095.875)" in proc.stderr
    proc = codeword("encode", "mtv4", "set_wheels_velocities", "speed=1")
    assert proc.returncode == 2 and b"has no field speed (fields: group, radio_crc_flag, robots, vl, vr)" in proc.stderr
    proc = codeword("encode", "mtv4", "fly")
    assert proc.returncode == 2 and b"has no message 'fly'" in proc.stderr
    proc = codeword("encode", "mtv4", "set_wheels_velocities", "vl")
    assert proc.returncode == 2 and b"FIELD=VALUE" in proc.stderr
    assert b"Traceback" not in proc.stderr


@pytest.fixture
def pty_pair():
    master, slave = os.openpty()
    tty.setraw(slave)
    yield master, os.ttyname(slave)
    os.close(master)
    os.close(slave)


def test_monitor_decodes_a_serial_port_live_and_logs_the_bytes(pty_pair, tmp_path):
    master, port = pty_pair
    log = tmp_path / "link.bin"
    monitor = subprocess.Popen([sys.executable, "-m", "codeword", "monitor", "mtv4", "--port", port,
                                "--baud", "115200", "--log", str(log), "--count", "3", "--duration", "60"],
                               cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    sent = bytes.fromhex(ROBOT5) + b"\x00\x01" + bytes.fromhex(ROBOT12)
    try:
        assert monitor.stderr.readline().startswith(f"monitoring {port} at 115200 baud")  # the port is open
        os.write(master, sent[:7])
        time.sleep(0.2)
        os.write(master, sent[7:])  # a frame split across reads
        out, err = monitor.communicate(timeout=60)
    finally:
        monitor.kill()
    assert monitor.returncode == 1, err  # two bytes of garbage were skipped
    rows = out.splitlines()
    assert len(rows) == 3
    assert "[1 frames, 0 errors, 0 skipped]  set_wheels_velocities group=3 robots=robot5" in rows[0]
    assert "[1 frames, 0 errors, 2 skipped]  error: 2 byte(s) skipped" in rows[1]
    assert "[2 frames, 0 errors, 2 skipped]  set_wheels_velocities group=15 robots=robot12" in rows[2]
    assert rows[0][:4].isdigit() and rows[0][10] == "T"  # an ISO timestamp
    assert "2 frames, 0 errors, 2 bytes skipped, 26 bytes read" in err
    assert log.read_bytes() == sent


def test_monitor_replays_a_capture_as_json(tmp_path):
    capture = tmp_path / "capture.bin"
    capture.write_bytes(bytes.fromhex(ROBOT12) + bytes.fromhex(ROBOT5)[:5])
    proc = codeword("monitor", "mtv4", "--replay", str(capture), "--json")
    assert proc.returncode == 1
    whole, cut = lines(proc)
    assert whole["values"]["robots"] == ["robot12"] and "time" in whole
    assert cut["offset"] == 12 and "whole frame" in cut["error"]


def test_monitor_names_a_port_it_cannot_open(tmp_path):
    proc = codeword("monitor", "mtv4", "--port", str(tmp_path / "ttyNONE"))
    assert proc.returncode == 2 and b"cannot open" in proc.stderr and b"Traceback" not in proc.stderr


def test_decode_csv_writes_no_control_character_from_the_wire(tmp_path):
    """Control characters in a line (an ANSI escape, a bell, CR LF between lines) reach
    the CSV escaped as the table shows them, and every row stays one line of valid CSV."""
    import csv
    import io
    log = tmp_path / "tank.log"
    log.write_bytes(TANK_LINE.encode() + b"\r\n%:f\x1b[2J\x07,1;" + b"%:f,100,\x1b]0;x\x07,10,1,0,0,0,1;")
    proc = codeword("decode", "tank", str(log), "--format", "csv")
    out = proc.stdout.decode()
    assert not [c for c in out if (ord(c) < 0x20 and c != "\n") or ord(c) == 0x7f], repr(out)
    rows = list(csv.reader(io.StringIO(out)))
    assert len(rows) == len(out.splitlines()) and all(len(row) == 6 for row in rows), rows
    frames = [row[1] for row in rows]
    assert "\\r\\n" in frames and "%:f\\x1b[2J\\x07,1;" in frames, frames
