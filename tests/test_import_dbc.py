"""`codeword import dbc` against cantools, the reference CAN database library.

Random databases are built with cantools' API (messages at standard and extended
identifiers, classic and CAN FD lengths, signals of both byte orders at any start bit
and width, signed, float, scaled and offset, multiplexed groups and multiplexed
multiplexors), written as DBC text by cantools and imported by codeword. For random
values of every message, the bytes cantools encodes are what codeword's Python and C
encoders write, and both decoders read cantools' frames (noise in every bit no carried
signal takes) back to the values cantools decodes. A hand-written DBC
(tests/data/dbc/powertrain.dbc) holds the sections real files have: value tables,
attribute definitions, comments over several lines, SG_MUL_VAL_, SIG_VALTYPE_,
BO_TX_BU_, odd spacing, CRLF line ends, a message of no data and overlapping signals
that cantools reads only leniently. Expected bytes and values come from cantools."""
from __future__ import annotations

import random
from pathlib import Path

import cantools  # a test extra: pip install -e ".[peers]"
import pytest
import yaml
from cantools.database.can import Database, Message, Node, Signal
from cantools.database.conversion import BaseConversion

from can_frames import C_DRIVER, c_case, covered, msb_position, noise, random_layout, raw_values
from cdriver import Driver
from codeword.build import compile_schema
from codeword.cli import main
from codeword.importers.dbc import import_database
from codeword.targets.c.view import CView
from schema_in_a_test import load, render, run_c

POWERTRAIN = Path(__file__).resolve().parent / "data" / "dbc" / "powertrain.dbc"
EXTENDED_FLAG = 0x80000000
FD_LENGTHS = (12, 16, 20, 24, 32, 48, 64)
SCALES = ((1, 0), (0.5, 0), (0.25, -10), (2, 3), (0.125, 2.5), (0.1, 0), (0.01, -40))
WORDS = ("Engine", "Speed", "ABS", "Wheel", "Temp", "Brake", "Yaw", "Rate", "HV", "Cell", "Volt", "Mode")


def camel(rng: random.Random, k: int) -> str:
    return "".join(rng.sample(WORDS, 2)) + str(k)


def plain_signals(rng: random.Random, size: int) -> list[dict]:
    """Non-overlapping signals of both orders in `size` bytes, some floats, with gaps."""
    taken: set[int] = set()
    out: list[dict] = []
    for _ in range(12):
        real = size >= 4 and rng.random() < 0.15
        length = (64 if size >= 8 and rng.random() < 0.4 else 32) if real else \
            min(64, rng.choice((rng.randint(1, 8 * size), rng.randint(1, min(16, 8 * size)))))
        order = rng.choice(("big_endian", "little_endian"))
        place = rng.randint(0, 8 * size - length)
        start = place if order == "little_endian" else msb_position(place)
        bits = set(covered(start, length, order))
        if taken & bits:
            continue
        taken |= bits
        scale, offset = (1, 0) if real or length > 53 else rng.choice(SCALES)
        out.append({"name": f"s{len(out)}", "start": start, "length": length, "order": order,
                    "signed": real or rng.random() < 0.5, "float": real, "scale": scale, "offset": offset,
                    "mux": None, "ids": None, "is_mux": False})
    return out


def cantools_signal(rng: random.Random, s: dict, k: int, nodes: list[str]) -> Signal:
    choices = None
    if (s.get("scale", 1), s.get("offset", 0)) == (1, 0) and not s.get("float") and not s["is_mux"] \
            and s["length"] <= 8 and rng.random() < 0.4:  # a value table, values of the width only
        lo = -(1 << (s["length"] - 1)) if s["signed"] else 0
        values = rng.sample(range(lo, lo + (1 << s["length"])), min(3, 1 << s["length"]))
        choices = {v: rng.choice(("Off", "On", "Not Available", "Error", "Init")) + str(v) for v in values}
    conversion = BaseConversion.factory(scale=s.get("scale", 1), offset=s.get("offset", 0),
                                        is_float=s.get("float", False), choices=choices)
    return Signal(s["name"] if s["is_mux"] or s["mux"] else camel(rng, k), s["start"], s["length"], s["order"],
                  s["signed"] and not s["is_mux"], conversion=conversion, is_multiplexer=s["is_mux"],
                  multiplexer_ids=s["ids"], multiplexer_signal=s["mux"], unit=rng.choice((None, "km/h", "degC")),
                  receivers=rng.sample(nodes, rng.randint(0, len(nodes))))


def random_database(rng: random.Random) -> Database:
    nodes = ["ECU", "Gateway", "Dash"]
    messages: list[Message] = []
    used: set[int] = set()  # cantools finds a message by its identifier alone
    while len(messages) < 8:
        extended = not messages or rng.random() < 0.4  # the first extended, the second CAN FD: each has both
        frame_id = rng.choice((0, 0x1FFFFFFF if extended else 0x7FF, rng.randint(0, 0x1FFFFFFF if extended else 0x7FF)))
        if frame_id in used:
            continue
        used.add(frame_id)
        fd = len(messages) == 1 or rng.random() < 0.3
        size = rng.choice(FD_LENGTHS) if fd else rng.randint(1, 8)
        layout = random_layout(rng, min(size, 8)) if rng.random() < 0.35 else plain_signals(rng, size)
        for s in layout:
            s.setdefault("scale", 1)
            s.setdefault("offset", 0)
        signals = [cantools_signal(rng, s, k, nodes) for k, s in enumerate(layout)]
        messages.append(Message(frame_id=frame_id, name=camel(rng, len(messages)), length=size, signals=signals,
                                is_extended_frame=extended, is_fd=fd, senders=[rng.choice(nodes)],
                                comment=rng.choice((None, "A message; its comment."))))
    return Database(messages=messages, nodes=[Node(n) for n in nodes], version="1.0")


FRAME_FORMATS = ",".join(['"StandardCAN"', '"ExtendedCAN"'] + ['"reserved"'] * 12 + ['"StandardCAN_FD"', '"ExtendedCAN_FD"'])


def dbc_text(db: Database) -> str:
    """The database as cantools writes it, with the VFrameFormat attribute that marks its
    CAN FD frames (cantools writes it only for a database read from a file that has it)."""
    lines = [f'BA_DEF_ BO_ "VFrameFormat" ENUM {FRAME_FORMATS};', 'BA_DEF_DEF_ "VFrameFormat" "StandardCAN";']
    for m in db.messages:
        if m.is_fd:
            ident = m.frame_id | (EXTENDED_FLAG if m.is_extended_frame else 0)
            lines.append(f'BA_ "VFrameFormat" BO_ {ident} {15 if m.is_extended_frame else 14};')
    return db.as_dbc_string() + "\n".join(lines) + "\n"


def imported(tmp_path: Path, dbc: Path):
    """The schema codeword imports from `dbc`, rendered in tmp_path: its module, model and C view."""
    text = import_database(dbc).text
    name = yaml.safe_load(text)["protocol"]
    render(tmp_path, name, text)
    protocol = compile_schema(tmp_path / f"{name}.yaml")
    return name, load(tmp_path / f"{name}.py"), protocol


def frame_checks(rng, db, name, module, protocol, rounds: int) -> list[str]:
    """Python against cantools for `rounds` random values of every message; the C
    statements that check the same frames."""
    v, driver = CView(protocol), Driver(protocol)
    by_title = {str(m.title) if m.title else m.name: m for m in protocol.messages}
    checks = []
    for ref in db.messages:
        ours = by_title[ref.name]
        # a field's doc starts with the signal's DBC name where codeword's differs
        names = {str(f.doc).split(".")[0].removeprefix("DBC "): f.name for f in ours.fields if f.doc} | \
            {f.name: f.name for f in ours.fields}
        cls = module.MESSAGES[ours.name]
        frame_id = ref.frame_id | (EXTENDED_FLAG if ref.is_extended_frame else 0)
        head = frame_id.to_bytes(4, "big") + bytes([ref.length])
        signals = [{"start": s.start, "length": s.length, "order": s.byte_order} for s in ref.signals]
        for k in range(rounds):
            values = raw_values(rng, ref)
            data = ref.encode(values, scaling=True, strict=False)
            mine = {names[n]: x for n, x in values.items()}
            assert cls(**mine).encode_can() == (frame_id, data), (ref.name, values)
            carried = [s for s, x in zip(signals, ref.signals) if x.name in values]
            sent = noise(rng, data, carried)
            expected = {names[n]: x for n, x in ref.decode(sent, decode_choices=False).items()}
            got = module.decode_can(frame_id, sent)
            assert {f.name: getattr(got, f.name) for f in ours.members} == \
                {f.name: expected.get(f.name) for f in ours.members}, (ref.name, sent.hex())
            assert ref.decode(got.encode_can()[1], decode_choices=False) == \
                ref.decode(sent, decode_choices=False), (ref.name, sent.hex())
            checks.append(c_case(v, driver, ours, mine, head + data, head + sent, f"{ref.name} #{k}"))
    return checks


@pytest.mark.parametrize("seed", range(3))
def test_random_databases_match_cantools(tmp_path, seed):
    rng = random.Random(f"dbc import {seed}")
    db = random_database(rng)
    dbc = tmp_path / f"random{seed}.dbc"
    dbc.write_text(dbc_text(db), encoding="utf-8")
    db = cantools.database.load_file(dbc)  # as cantools reads the file codeword imports
    assert any(m.is_extended_frame for m in db.messages) and any(m.is_fd for m in db.messages)
    name, module, protocol = imported(tmp_path, dbc)
    assert len(protocol.messages) == len(db.messages)
    checks = frame_checks(rng, db, name, module, protocol, rounds=20)
    lines = run_c(tmp_path, C_DRIVER.format(header=name, cases="\n".join(checks), n=len(checks)).replace(
        "uint8_t buf[16];", "uint8_t buf[80];"))
    assert lines == [f"OK {len(checks)}"], lines[:20]


def test_the_hand_written_database_imports_whole(tmp_path):
    db = cantools.database.load_file(POWERTRAIN, strict=False)
    text = import_database(POWERTRAIN).text
    doc = yaml.safe_load(text)
    assert doc["framing"] == {"kind": "can", "fd": True}  # FdSensors is a CAN FD frame
    assert doc["doc"] == "Powertrain bus of a test vehicle"  # the network's CM_, which cantools does not keep
    messages = doc["messages"]
    assert list(messages) == ["engine_status", "diagnostics", "fd_sensors", "heartbeat"]
    assert messages["diagnostics"]["id"] == 0x18FF0000 and messages["diagnostics"]["extended"] is True
    assert "extended" not in messages["engine_status"]
    assert messages["heartbeat"]["fields"] == []  # no data: the frame is its identifier
    fields = {m: {f["name"]: f for f in body["fields"]} for m, body in messages.items()}
    speed = fields["engine_status"]["engine_speed"]
    assert speed == {"name": "engine_speed", "type": "u16", "start_bit": 0, "byte_order": "little",
                     "scale": 0.25, "unit": "rpm", "doc": speed["doc"]}
    assert "Crankshaft speed; measured at the flywheel." in speed["doc"]  # a comment over two lines
    assert "Range 0 to 16383.75" in speed["doc"]
    assert fields["engine_status"]["throttle_pos"]["byte_order"] == "big"
    assert fields["engine_status"]["running"]["type"] == "i1"  # a one-bit signed signal: -1 or 0
    gear = fields["engine_status"]["gear"]
    assert gear["enum"] == "gear" and doc["enums"]["gear"] == {  # VAL_: an open enum
        "type": "u4", "open": True, "values": [{"name": "neutral", "value": 0, "doc": "Neutral"},
                                               {"name": "first", "value": 1, "doc": "First"},
                                               {"name": "second", "value": 2, "doc": "Second"},
                                               {"name": "reverse", "value": 8, "doc": "Reverse"}]}
    assert fields["diagnostics"]["torque"]["multiplexed_by"] == {"field": "mode", "values": [2, 3, 4]}  # 2-4
    assert [f["type"] for f in fields["fd_sensors"].values()] == ["f32", "f64", "u16"]  # SIG_VALTYPE_ 1 and 2
    assert messages["engine_status"]["role"] == "engine"
    assert "Sent by Engine, Gateway. Cycle time 10 ms." in messages["engine_status"]["doc"]
    # what has no key is said where it was
    assert "# value table OnOff (VAL_TABLE_): 1 = On, 0 = Off" in text
    assert "# network attribute BusType = CAN FD" in text
    assert "# signal LegacySpeed (7|8@0) takes bits of EngineSpeed in frames that carry both: not carried" in text
    assert fields["engine_status"]["coolant_temp"]["default"] == 0  # GenSigStartValue 40, offset -40
    assert len(db.messages) == 4


@pytest.mark.parametrize("file", ["powertrain.dbc", "j1939_truck.dbc", "odd_syntax.dbc"])
def test_hand_written_databases_match_cantools(tmp_path, file):
    dbc = POWERTRAIN.parent / file
    db = cantools.database.load_file(dbc, strict=False)
    name, module, protocol = imported(tmp_path, dbc)
    carried = {str(f.doc).split(".")[0].removeprefix("DBC ") for m in protocol.messages for f in m.fields if f.doc} \
        | {f.name for m in protocol.messages for f in m.fields}
    for message in db.messages:  # a signal codeword does not carry, as its comment says (LegacySpeed)
        message.signals[:] = [s for s in message.signals if s.name in carried]
        message.refresh(strict=False)
    checks = frame_checks(random.Random(file), db, name, module, protocol, rounds=30)
    lines = run_c(tmp_path, C_DRIVER.format(header=name, cases="\n".join(checks), n=len(checks)).replace(
        "uint8_t buf[16];", "uint8_t buf[80];"))
    assert lines == [f"OK {len(checks)}"], lines[:20]


def test_what_cantools_reads_past_is_named_and_odd_spellings_come_through():
    truck = import_database(POWERTRAIN.parent / "j1939_truck.dbc")
    assert "# not carried: 1 EV_ line (environment variables)" in truck.text  # not the NS_ list's EV_DATA_
    assert truck.skipped == ["EV_ (environment variables)"]
    doc = yaml.safe_load(truck.text)
    assert doc["messages"]["eec1"]["id"] == 0xCF004FE and doc["messages"]["eec1"]["extended"] is True
    assert "Signal group Torques: DriversDemandTorque, ActualEngTorque, EngDemandTorque." in \
        doc["messages"]["eec1"]["doc"]
    odd = yaml.safe_load(import_database(POWERTRAIN.parent / "odd_syntax.dbc").text)
    status = {f["name"]: f for f in odd["messages"]["status"]["fields"]}
    assert status["switch_"]["enum"] == "switch_"  # the VAL_TABLE_'s name; `switch` is a C keyword
    assert odd["messages"]["status"]["doc"].startswith('Status with "quotes" and a comment over three lines.')
    assert status["level"]["scale"] == 0.5 and status["level"]["offset"] == -10
    assert status["code"]["multiplexed_by"] == {"field": "mode", "values": [2]}
    assert odd["messages"]["ext"]["id"] == 1 and odd["messages"]["ext"]["extended"] is True


def test_an_import_is_the_same_every_time():
    assert import_database(POWERTRAIN).text == import_database(POWERTRAIN).text


def test_the_command_writes_the_schema_and_refuses_what_is_not_a_dbc(tmp_path, capsys):
    assert main(["import", "dbc", str(POWERTRAIN), "--out", str(tmp_path)]) == 0
    assert (tmp_path / "powertrain.yaml").read_text(encoding="utf-8") == import_database(POWERTRAIN).text
    out = capsys.readouterr().out
    assert "4 messages" in out and "LegacySpeed" in out
    bad = tmp_path / "bad.dbc"
    bad.write_text("BO_ 12 Broken: x\n", encoding="utf-8")
    assert main(["import", "dbc", str(bad), "--out", str(tmp_path)]) == 2
    assert "not a DBC database cantools can read" in capsys.readouterr().err
    assert main(["import", "dbc", str(tmp_path / "missing.dbc"), "--out", str(tmp_path)]) == 2
    assert "cannot read" in capsys.readouterr().err


def test_initial_values_are_defaults_that_encode_the_initial_raw_values(tmp_path):
    signals = [Signal("Alpha", 0, 8, "little_endian", False, raw_initial=3,
                      conversion=BaseConversion.factory(scale=0.1, offset=0)),
               Signal("Beta", 8, 12, "big_endian", True, raw_initial=-7,
                      conversion=BaseConversion.factory(scale=0.05, offset=-3.3)),
               Signal("Gamma", 40, 8, "little_endian", False, raw_initial=200),
               Signal("Delta", 48, 8, "little_endian", False)]  # no initial value: a value to give
    db = Database(messages=[Message(frame_id=0x10, name="Start", length=8, signals=signals)])
    dbc = tmp_path / "initial.dbc"
    dbc.write_text(db.as_dbc_string(), encoding="utf-8")
    fields = {f["name"]: f for f in yaml.safe_load(import_database(dbc).text)["messages"]["start"]["fields"]}
    assert (fields["alpha"]["default"], fields["beta"]["default"], fields["gamma"]["default"]) == (0.3, -3.65, 200)
    assert "default" not in fields["delta"]
    name, module, _ = imported(tmp_path, dbc)
    frame_id, data = module.MESSAGES["start"](delta=9).encode_can()
    raw = cantools.database.load_file(dbc).get_message_by_name("Start").decode(data, scaling=False)
    assert (frame_id, raw) == (0x10, {"Alpha": 3, "Beta": -7, "Gamma": 200, "Delta": 9})
