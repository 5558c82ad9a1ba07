"""Text streams through every text stream reader: the Python StreamDecoder (fed
whole, one character at a time, and split in two at every point) and the C scan
(its characters arriving one, three or all at a time) and byte parser, each told
where the stream ends. Expected events are worked out by hand from the framing
rules (where each line starts, how long it is), and for NMEA which lines are
sentences comes from pynmea2."""
from __future__ import annotations

import json

import pynmea2  # the test extra (scripts/setup installs it)
import pytest

from conftest import ROOT
from schema_in_a_test import conformance_on_host_and_avr, load, render
from stream_events import c_text_events, python_text_events

TANK = (ROOT / "schemas" / "tank.yaml").read_text(encoding="utf-8")
NMEA = (ROOT / "examples" / "nmea0183.yaml").read_text(encoding="utf-8")
SENTENCES = [  # gpsd's "NMEA 0183 revealed"
    "$GPGGA,123519,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,*47",
    "$GPRMC,123519,A,4807.038,N,01131.000,E,022.4,084.4,230394,003.1,W*6A",
    "$GPVTG,054.7,T,034.4,M,005.5,N,010.2,K*48",
]


@pytest.fixture(scope="module")
def tank(tmp_path_factory):
    where = tmp_path_factory.mktemp("tankstream")
    render(where, "tank", TANK)
    return where, load(where / "tank.py")


@pytest.fixture(scope="module")
def nmea(tmp_path_factory):
    where = tmp_path_factory.mktemp("nmeastream")
    render(where, "nmea0183", NMEA)
    return where, load(where / "nmea0183.py")


def every_reader(where, name: str, mod, data: bytes) -> list[list[tuple]]:
    """The events of each reader and each way of feeding it."""
    messages = [m.NAME for m in mod.MESSAGES.values()]
    got = [python_text_events(mod, data), python_text_events(mod, data, 1), python_text_events(mod, data, 3)]
    for chunk in (0, 1, 3):
        got.extend(c_text_events(where, name, messages, data, chunk))
    return got


def python_split_in_two(mod, data: bytes) -> list[tuple]:
    """Differences from the whole-stream events, the stream fed in two pieces cut at each point."""
    whole = python_text_events(mod, data)
    wrong = []
    for cut in range(1, len(data)):
        d = mod.StreamDecoder()
        events = []
        for part in (data[:cut], data[cut:]):
            for item, (start, length) in zip(d.feed(part), d.spans):
                events.append(("error", item.rule, start, length) if isinstance(item, mod.DecodeError)
                              else ("message", type(item).NAME, start, length))
        for item, (start, length) in zip(d.finish(), d.spans):
            events.append(("error", item.rule, start, length))
        if events != whole:
            wrong.append((cut, events))
    return wrong


def test_tank_lines_with_line_breaks_and_garbage_between(tank):
    where, mod = tank
    command = "%:f,100,s,10,1,0,0,0,1;"  # 23 characters
    data = ("\r\n" + command + "\r\n\r\n" + "zz;" + "*:ping;" + "\n" + "%:f,1").encode()
    expected = [("message", "command", 2, 23),  # after the skipped CR LF
                ("error", "prefix", 29, 3),  # `zz;` has no `:` after a prefix
                ("message", "payload_command", 32, 7),
                ("error", "syntax", 40, 5)]  # unterminated at the end
    for events in every_reader(where, "tank", mod, data):
        assert events == expected
    assert python_split_in_two(mod, data) == []


def test_a_line_too_long_is_one_error_and_the_next_line_reads(tank):
    where, mod = tank
    bound = mod.StreamDecoder.MAX_MESSAGE
    assert bound == 496  # telemetry's line: 20 values of at most 24 characters, 19 commas, `$:` and `;`
    data = ("%:" + "9" * 600 + ";" + "*:ping;" + "1" * (bound + 3)).encode()
    expected = [("error", "length", 0, bound),  # when the line outgrows the bound
                ("message", "payload_command", 603, 7),
                ("error", "length", 610, bound)]  # and no second error at the end: its rest is dropped
    for events in every_reader(where, "tank", mod, data):
        assert events == expected


def test_the_longest_line_is_read(tank):
    where, mod = tank
    bound = mod.StreamDecoder.MAX_MESSAGE
    data = ("z" * (bound - 1) + ";").encode()  # exactly the bound: a line, decoded (it has no prefix)
    for events in every_reader(where, "tank", mod, data):
        assert events == [("error", "prefix", 0, bound)]


def test_nmea_sentences_among_garbage_as_pynmea2_reads_them(nmea):
    where, mod = nmea
    pieces = ["garbage\r\n", SENTENCES[0] + "\r\n", SENTENCES[1] + "\r\n", "$GPXYZ,1*00\r\n",
              SENTENCES[2] + "\r\n", SENTENCES[0][:20]]
    expected, at = [], 0
    for piece in pieces:
        if piece.startswith("$GP") and piece.endswith("\r\n") and piece != "$GPXYZ,1*00\r\n":
            expected.append(("message", pynmea2.parse(piece.strip()).sentence_type.lower(), at, len(piece)))
        at += len(piece)
    expected.insert(0, ("error", "prefix", 0, 9))  # no `$`
    expected.insert(3, ("error", "checksum", sum(map(len, pieces[:3])), 13))  # XOR of GPXYZ,1 is not 00
    expected.append(("error", "syntax", at - 20, 20))
    data = "".join(pieces).encode()
    for events in every_reader(where, "nmea0183", mod, data):
        assert events == expected
    assert python_split_in_two(mod, data) == []


def test_a_terminator_across_the_bound_ends_the_line_too_long(nmea):
    where, mod = nmea
    bound = mod.StreamDecoder.MAX_MESSAGE
    assert bound == 269  # GGA: 14 values, each number kept in at most 24 characters
    # CR is the bound's last character, LF the next: the line is one too long
    data = ("$" + "A" * (bound - 2) + "\r\n" + SENTENCES[2] + "\r\n").encode()
    expected = [("error", "length", 0, bound), ("message", "vtg", bound + 1, len(SENTENCES[2]) + 2)]
    for events in every_reader(where, "nmea0183", mod, data):
        assert events == expected


TWO_CHARACTER_TERMINATOR = """codeword: 1
protocol: marks
title: lines ended by two characters
source: written for this test
framing:
  kind: text
  prefix_separator: "="
  separator: ","
  terminator: "#!"
  ignore_between: "\\r\\n"
messages:
  set:
    id: "S"
    fields:
      - {name: a, type: u8}
      - {name: b, type: i16}
streams:
  - name: lines with line breaks and a garbage line between
    text: "\\r\\nS=1,-2#!\\r\\nQQ#!S=3,4#!"
    events:
      - {message: set, end: 10}   # S=1,-2#! from 2
      - {error: prefix}           # QQ#! from 12: no `=`
      - {message: set, end: 23}   # S=3,4#! from 16
"""


def test_the_schemas_streams_and_the_vectors_streams_run_in_c_on_the_host_and_on_avr(tmp_path):
    """The hand-worked stream (checked by the build in Python) and the random ones of the
    vectors, through the conformance driver's byte parser and scan, finish included."""
    host, avr = conformance_on_host_and_avr(tmp_path, "marks", TWO_CHARACTER_TERMINATOR)
    assert host > 0 and avr == host
    vectors = json.loads((tmp_path / "out" / "vectors" / "marks.json").read_text(encoding="utf-8"))
    worked = vectors["streams"][0]
    assert [(e.get("message") or e["error"], e["at"], e["length"]) for e in worked["events"]] == \
        [("set", 2, 8), ("prefix", 12, 4), ("set", 16, 7)]
    assert any(e.get("error") == "length" for s in vectors["streams"] for e in s["events"])
    assert any(e.get("error") == "syntax" for s in vectors["streams"] for e in s["events"])


@pytest.mark.parametrize("schema", ["schemas/tank.yaml", "examples/nmea0183.yaml"])
def test_the_bound_holds_every_line_an_encoder_writes(schema):
    """The readers' bound is at least the C encoder's longest line (its MAX_TEXT less the NUL),
    and Python's StreamDecoder and the C header state the same number."""
    from codeword.build import compile_schema, render_protocol
    from codeword.targets.c.view import CView
    p = compile_schema(ROOT / schema)
    files = render_protocol(p)
    assert max(CView(p).max_text(m) for m in p.messages) <= p.framing.line_max
    assert f"MAX_MESSAGE = {p.framing.line_max}  #" in files[f"python/{p.name}.py"]
    assert f"#define {p.name.upper()}_STREAM_MAX {p.framing.line_max}u" in files[f"c/{p.name}.h"]


def test_a_line_whose_value_is_too_long_is_a_line_read_whole(nmea):
    """A `length` error of the decoder (a latitude spelt in 30 characters, at most 24 kept)
    is no line too long for the stream: the line is consumed whole, through its CR LF."""
    where, mod = nmea
    body = "GPGGA,123519,4807.0380000000000000000000000,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,"
    checksum = 0
    for ch in body:
        checksum ^= ord(ch)
    line = f"${body}*{checksum:02X}\r\n"
    data = (line + SENTENCES[2] + "\r\n").encode()
    expected = [("error", "length", 0, len(line)), ("message", "vtg", len(line), len(SENTENCES[2]) + 2)]
    for events in every_reader(where, "nmea0183", mod, data):
        assert events == expected
