"""`codeword check`: every input kind with good and bad data, the exact ROUTE-D3
result, the JSON shape, exit codes and the progress bar.

Expected findings come from the seeds, PROTOCOLS.md and hand calculation; the
frames used are the hand-computed examples of the schemas (cited per case).
"""
from __future__ import annotations

import json

import pytest

from codeword.cli import main
from conftest import DATA, ROOT

CHECK = DATA / "check"


def run(capsys, *argv):
    """(exit status, stdout, stderr) of `codeword check …`."""
    status = main(["check", *map(str, argv)])
    out, err = capsys.readouterr()
    return status, out, err


def run_json(capsys, *argv):
    status, out, err = run(capsys, "--format", "json", *argv)
    return status, json.loads(out)


def brief(doc):
    """(line or offset, field, rule, actual) per finding."""
    return [(f["line"] if f["line"] is not None else f["offset"], f["field"], f["rule"], f["actual"])
            for f in doc["findings"]]


def write(tmp_path, name, data):
    path = tmp_path / name
    (path.write_bytes if isinstance(data, bytes) else path.write_text)(data)
    return path


# ---------------------------------------------------------------- route

def test_route_seed_file_gives_exactly_the_four_rc_errors(capsys):
    # ROUTE-D3: object lines 2, 4, 6, 8 of the seed's example carry rc = 5, 4, 5, 5 (2 bits: 0..3)
    status, doc = run_json(capsys, "route", DATA / "route_seed_example.txt")
    assert status == 1
    assert brief(doc) == [(2, "rc", "range", 5), (4, "rc", "range", 4),
                          (6, "rc", "range", 5), (8, "rc", "range", 5)]
    # rc is the 7th value: "1 0 0 0 2 2 " is 12 characters, so it starts in column 13
    assert {f["column"] for f in doc["findings"]} == {13}
    assert {(f["allowed"], f["decision"]) for f in doc["findings"]} == {("0..3", "ROUTE-D3")}
    assert doc["summary"] == {"read": 11, "valid": 7, "invalid": 4, "skipped_bytes": 0, "findings": 4}


def test_route_seed_file_is_the_seed_verbatim():
    seed = (DATA / "seeds" / "000_2b5d4a2b27f09abb.txt").read_text(encoding="utf-8").splitlines()[3:14]
    assert (DATA / "route_seed_example.txt").read_text().splitlines() == seed


def test_route_valid_file(capsys):
    status, out, err = run(capsys, "route", DATA / "route_example.txt")
    assert status == 0, out
    assert "11 item(s) read (text), 11 valid, 0 invalid" in out and "all valid" in out


def test_route_grammar_rule_across_lines(tmp_path, capsys):
    # route_example.txt with the object on line 4 moved to scene 2 (ns 1 -> 2, CS
    # (1+2+0+0+3+4+2+5+4) mod 8 = 5): its group is closed by scene 1 (ROUTE-D5 equal),
    # and its key (2, 0, 0) is the key of the object on line 6 (ROUTE-D5 unique)
    lines = (DATA / "route_example.txt").read_text().splitlines()
    assert lines[3] == "1 1 0 0 3 4 2 5 4 4"
    lines[3] = "1 2 0 0 3 4 2 5 4 5"
    status, doc = run_json(capsys, "route", write(tmp_path, "moved.txt", "\n".join(lines) + "\n"))
    assert status == 1
    assert [(f["line"], f["field"], f["rule"], f["actual"], f["decision"]) for f in doc["findings"]] == \
        [(4, "ns", "equal", 2, "ROUTE-D5"), (6, "ns,nl,no", "unique", [2, 0, 0], "ROUTE-D5")]


def test_route_missing_end_is_a_grammar_finding(tmp_path, capsys):
    lines = (DATA / "route_example.txt").read_text().splitlines()[:-1]  # drop "3 2 5"
    status, doc = run_json(capsys, "route", write(tmp_path, "no_end.txt", "\n".join(lines) + "\n"))
    assert status == 1
    assert [(f["field"], f["rule"]) for f in doc["findings"]] == [("end", "grammar")]


# ---------------------------------------------------------------- mtv4

def test_mtv4_hex_dump_one_frame_per_line(capsys):
    status, doc = run_json(capsys, "mtv4", CHECK / "mtv4_frames.hex")
    assert status == 1
    # line 4: last CRC byte inverted; line 6: length byte 9 for 12 bytes (MTV4-D6); line 7: group 16
    assert [(f["line"], f["unit"], f["field"], f["rule"]) for f in doc["findings"]] == [
        (4, 3, "crc", "checksum"), (6, 5, "length", "length"), (7, 6, "group", "range")]
    assert doc["findings"][2]["allowed"] == "0..15"
    assert doc["inputs"][0]["input_format"] == "hex"
    assert doc["summary"]["read"] == 6 and doc["summary"]["valid"] == 3


SET_WHEELS = bytes.fromhex("aa 08 03 01 20 00 24 03 60 ff 40 00")  # schemas/mtv4.yaml, first example
ACK = bytes.fromhex("aa 04 03 01 20 00 59 f7")  # its acknowledgement, CRC 0x59F7 by hand
BAD_CRC = SET_WHEELS[:-1] + b"\xff"  # last CRC byte inverted


def test_mtv4_raw_capture_offsets_and_resynchronisation(tmp_path, capsys):
    # 2 garbage bytes @0, frame @2, ack @14, bad frame @22, frame @34, 3 bytes of a frame @46
    data = b"\x00\x11" + SET_WHEELS + ACK + BAD_CRC + SET_WHEELS + b"\xaa\x08\x03"
    status, doc = run_json(capsys, "mtv4", write(tmp_path, "capture.bin", data))
    assert status == 1
    # the CRC is bytes 10-11 of the bad frame: 22 + 10 = 32
    assert brief(doc) == [(32, "crc", "checksum", 0x40FF), (46, None, "length", 3),
                          (None, None, "sync", 17)]
    # skipped: 2 garbage + the bad frame's 12 (no 0xAA in its other bytes) + the 3 left over
    assert doc["summary"] == {"read": 5, "valid": 3, "invalid": 2, "skipped_bytes": 17, "findings": 3}
    assert doc["inputs"][0]["input_format"] == "raw"


def test_mtv4_clean_raw_capture_is_valid(tmp_path, capsys):
    status, out, _ = run(capsys, "mtv4", write(tmp_path, "clean.bin", (SET_WHEELS + ACK) * 50))
    assert status == 0, out
    assert "100 frame(s) read (raw), 100 valid, 0 invalid" in out


def test_mtv4_direction_is_applied(tmp_path, capsys):
    # an acknowledgement is robot_to_host: read as host_to_robot it is not a known frame
    path = write(tmp_path, "ack.hex", ACK.hex(" ") + "\n")
    assert run(capsys, "mtv4", "--direction", "robot_to_host", path)[0] == 0
    status, doc = run_json(capsys, "mtv4", "--direction", "host_to_robot", path)
    assert status == 1 and [f["rule"] for f in doc["findings"]] == ["dispatch"]


# ---------------------------------------------------------------- tr24

TR24_COMMAND = "02 00 01 03 2c 00 00 00 00 00 00 03"  # schemas/tr24.yaml: the seed's command
TR24_REPLY = "02 02 03 01 00 00 00 00 00 00 00 03"  # its reply, service byte 0b10


def test_tr24_hex_and_raw(tmp_path, capsys):
    bad_stop = TR24_COMMAND[:-2] + "04"  # stop byte 0x04 (TR24-D1: 0x03)
    path = write(tmp_path, "link.hex", f"{TR24_COMMAND}\n{TR24_REPLY}\n{bad_stop}\n")
    status, doc = run_json(capsys, "tr24", path)
    assert status == 1
    assert brief(doc) == [(3, "stop", "const", 4)]
    raw = bytes.fromhex(TR24_COMMAND + TR24_REPLY)
    assert run(capsys, "tr24", write(tmp_path, "good.bin", raw))[0] == 0
    status, doc = run_json(capsys, "tr24", write(tmp_path, "bad.bin", raw + bytes.fromhex(bad_stop)))
    # the stop byte is byte 11 of the third frame: 24 + 11 = 35
    assert status == 1 and brief(doc)[0] == (35, "stop", "const", 4)


def test_text_passed_as_raw_capture_is_not_valid(tmp_path, capsys):
    path = write(tmp_path, "link.hex", f"{TR24_COMMAND}\n")
    status, doc = run_json(capsys, "tr24", "--input-format", "raw", path)
    assert status == 1  # no 0x02 start byte in ASCII hex digits: everything is skipped
    assert doc["summary"]["read"] == 0 and [f["rule"] for f in doc["findings"]] == ["sync"]


# ---------------------------------------------------------------- tank

def test_tank_log_one_message_per_line(capsys):
    status, doc = run_json(capsys, "tank", CHECK / "tank.log")
    assert status == 1
    # line 3: systemstatus 5 in a command (TANK-D2); line 5: speed 101 (TANK-D3: 0..100)
    assert [(f["line"], f["field"], f["rule"], f["actual"], f["decision"]) for f in doc["findings"]] == [
        (3, "systemstatus", "values", 5, "TANK-D2"), (5, "speed", "range", 101, "TANK-D3")]
    # "%:f,100,s,10,1,0,0,0," is 21 characters: systemstatus starts in column 22
    assert doc["findings"][0]["column"] == 22
    assert doc["findings"][0]["user_message"]  # the schema's own wording is carried
    assert doc["summary"]["read"] == 6 and doc["summary"]["valid"] == 4


def test_tank_raw_stream_and_unterminated_message(tmp_path, capsys):
    # the seed's test line, then the same with speed 101, no newline; then an unterminated message
    text = "%:f,100,s,10,1,0,0,0,1;%:f,101,s,10,1,0,0,0,1;\n%:f,1"
    status, doc = run_json(capsys, "tank", write(tmp_path, "stream.log", text))
    assert status == 1
    # message 2 starts at offset 23, its speed at 23 + 4 = 27: column 28 of line 1
    assert [(f["line"], f["column"], f["unit"], f["rule"]) for f in doc["findings"]] == [
        (1, 28, 2, "range"), (2, 1, 3, "syntax")]


def test_tank_non_ascii_is_reported(tmp_path, capsys):
    status, doc = run_json(capsys, "tank", write(tmp_path, "utf8.log", "*:привет;\n".encode()))
    assert status == 1 and doc["findings"][0]["rule"] == "text" and doc["findings"][0]["line"] == 1


def test_tank_seed_line_is_valid(tmp_path, capsys):
    assert run(capsys, "tank", write(tmp_path, "seed.log", "%:f,100,s,10,1,0,0,0,1;\r\n"))[0] == 0


# ---------------------------------------------------------------- car

def test_car_program_hex_words(capsys):
    assert run(capsys, "car", CHECK / "car_program.hex")[0] == 0
    status, doc = run_json(capsys, "car", CHECK / "car_program_bad.hex")
    assert status == 1
    found = [(f["line"], f["unit"], f["field"], f["rule"]) for f in doc["findings"]]
    # word 2: parity cleared (CAR-D2); word 3: a master that accepts IR (CAR-R1);
    # the header asks for one slave word and none follows
    assert found == [(4, 2, "parity", "checksum"), (6, 3, "accept_ir", "rule"), (None, 4, "slaves", "count")]
    assert doc["findings"][1]["decision"] == "CAR-R1"
    assert "无法设置主机接受红外信息" in doc["findings"][1]["user_message"]
    assert doc["summary"]["read"] == 3 and doc["summary"]["invalid"] == 2


def test_car_program_raw_bytes(tmp_path, capsys):
    good = bytes.fromhex("020104006700000140781000b2848001")  # schemas/car.yaml program example
    assert run(capsys, "car", write(tmp_path, "good.bin", good))[0] == 0
    bad = good[:7] + b"\x00" + good[8:]  # master word 1 with c9 cleared
    status, doc = run_json(capsys, "car", write(tmp_path, "bad.bin", bad))
    # c9 is the last bit of word 2, which starts at byte 4: byte 7
    assert status == 1 and brief(doc) == [(7, "parity", "checksum", 0)]


def test_car_bad_hex_word_is_a_syntax_finding(tmp_path, capsys):
    status, doc = run_json(capsys, "car", "--input-format", "hex", write(tmp_path, "p.hex", "0201040\n"))
    assert status == 1 and doc["findings"][0]["rule"] == "syntax" and doc["findings"][0]["line"] == 1


# ---------------------------------------------------------------- output and exit status

def test_json_shape(capsys):
    status, doc = run_json(capsys, "route", DATA / "route_seed_example.txt", DATA / "route_example.txt")
    assert list(doc) == ["format", "schema", "protocol", "fingerprint", "findings", "inputs", "summary", "valid"]
    assert doc["format"] == 1 and doc["protocol"] == "route" and doc["valid"] is False
    assert len(doc["fingerprint"]) == 16
    assert set(doc["findings"][0]) == {"file", "line", "column", "offset", "unit", "message", "field", "rule",
                                       "decision", "actual", "allowed", "user_message", "text"}
    assert [i["file"] for i in doc["inputs"]] == [str(DATA / "route_seed_example.txt"),
                                                 str(DATA / "route_example.txt")]
    assert set(doc["inputs"][0]) == {"file", "input_format", "unit", "read", "valid", "invalid",
                                     "skipped_bytes", "findings"}
    assert doc["summary"] == {"read": 22, "valid": 18, "invalid": 4, "skipped_bytes": 0, "findings": 4}


@pytest.mark.parametrize("argv", [
    ["route", "no/such/file.txt"],
    ["no_such_schema", "x"],
    ["mtv4", "--direction", "sideways", str(CHECK / "mtv4_frames.hex")],
    ["tank", "--input-format", "hex", str(CHECK / "tank.log")],
    ["car", "--input-format", "text", str(CHECK / "car_program.hex")],
    [str(ROOT / "tests" / "broken" / "car_33_bits.yaml"), str(CHECK / "car_program.hex")],
])
def test_usage_and_schema_errors_exit_2(capsys, argv):
    status, out, err = run(capsys, *argv)
    assert status == 2 and err and not out


def test_missing_inputs_is_a_usage_error(capsys):
    with pytest.raises(SystemExit) as exc:
        main(["check", "route"])
    assert exc.value.code == 2


def test_progress_bar_only_when_asked_or_on_a_terminal(tmp_path, capsys):
    big = write(tmp_path, "big.bin", SET_WHEELS * 10 + bytes(5 * 1024 * 1024))  # > 4 MiB threshold
    status, out, err = run(capsys, "mtv4", big)  # stderr is captured, not a terminal
    assert status == 1 and err == ""
    status, out, err = run(capsys, "mtv4", "--progress", big)
    assert "B/s" in err or "%" in err
    small = write(tmp_path, "small.bin", SET_WHEELS)
    assert run(capsys, "mtv4", "--progress", small)[2] == ""


def test_hex_words_take_the_schemas_word_width(tmp_path, capsys):
    # a protocol of 16-bit words: a sequence of a head word and item words
    schema = write(tmp_path, "w16.yaml", """\
codeword: 1
protocol: w16
title: 16-bit words
source: hand-written
framing: {kind: bits, word_bits: 16, byte_order: big}
messages:
  head:
    fields:
      - {name: tag, type: u2, const: 1, dispatch: true}
      - {name: n, type: u14}
  item:
    fields:
      - {name: tag, type: u2, const: 2, dispatch: true}
      - {name: v, type: u14}
sequences:
  list:
    items:
      - {name: head, message: head}
      - {name: items, message: item, repeat: true}
""".encode())
    # head n=1: 01 000000 00000001 = 4001; item v=2: 10 ... 10 = 8002
    assert run(capsys, schema, write(tmp_path, "good.hex", b"4001 8002\n"))[0] == 0
    status, doc = run_json(capsys, schema, write(tmp_path, "bad.hex", b"4001 80020000\n"))
    assert status == 1 and doc["findings"][0]["rule"] == "syntax"
    assert doc["findings"][0]["allowed"] == "4 hex digits"


def test_nmea_sentences_of_each_version_and_one_field_short(tmp_path, capsys):
    """RMC of NMEA 0183 2.0 (gpsd's published sentence, 11 fields) and 2.3 (u-blox M8's, 12)
    are valid; the 2.0 one without its last field (checksum by hand: XOR 0x11) is a count
    finding naming how many fields a line may have."""
    lines = ["$GPRMC,123519,A,4807.038,N,01131.000,E,022.4,084.4,230394,003.1,W*6A",
             "$GPRMC,083559.00,A,4717.11437,N,00833.91522,E,0.004,77.52,091202,,,A*57",
             "$GPRMC,123519,A,4807.038,N,01131.000,E,022.4,084.4,230394,003.1*11"]
    log = write(tmp_path, "nmea.log", "".join(line + "\r\n" for line in lines))
    status, doc = run_json(capsys, ROOT / "examples" / "nmea0183.yaml", log)
    assert status == 1 and doc["summary"]["valid"] == 2
    assert [(f["line"], f["rule"], f["actual"]) for f in doc["findings"]] == [(3, "count", 10)]
    assert "11..13 fields" in run(capsys, ROOT / "examples" / "nmea0183.yaml", log)[1]
