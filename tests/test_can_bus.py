"""CAN buses and logs through python-can: `codeword decode` and `check` read the logs
python-can writes (candump -L, ASC, BLF), and `codeword monitor --can` decodes a live
bus (python-can's virtual interface). The frames are encoded by cantools from the
hand-written DBC the schema is imported from; the expected values are cantools'."""
from __future__ import annotations

import json
import threading
import time

import can  # a test extra: pip install -e ".[peers]"
import cantools
import pytest
from cantools.database.namedsignalvalue import NamedSignalValue

from codeword.cli import main
from codeword.importers.dbc import import_database
from test_import_dbc import POWERTRAIN

EXTENDED_FLAG = 0x80000000
VALUES = {  # cantools' names and physical values
    "EngineStatus": {"EngineSpeed": 1000, "CoolantTemp": 90, "ThrottlePos": 12.5, "Running": -1, "Gear": 2},
    "Diagnostics": {"Mode": 2, "Torque": -100.5, "Counter": 3},
    "FdSensors": {"Pressure": 101.25, "Position": -0.5, "Samples": 513},
}
FIELDS = {"EngineSpeed": "engine_speed", "CoolantTemp": "coolant_temp", "ThrottlePos": "throttle_pos",
          "Running": "running", "Gear": "gear", "Mode": "mode", "Torque": "torque", "Counter": "counter",
          "Pressure": "pressure", "Position": "position", "Samples": "samples"}


@pytest.fixture(scope="module")
def schema(tmp_path_factory):
    where = tmp_path_factory.mktemp("can_bus")
    path = where / "powertrain.yaml"
    path.write_text(import_database(POWERTRAIN).text, encoding="utf-8")
    return path


def frames() -> list[can.Message]:
    db = cantools.database.load_file(POWERTRAIN, strict=False)
    out = []
    for k, (name, values) in enumerate(VALUES.items()):
        ref = db.get_message_by_name(name)
        data = ref.encode({**{s.name: 0 for s in ref.signals if s.name == "LegacySpeed"}, **values}, strict=False)
        out.append(can.Message(timestamp=1.0 + k, arbitration_id=ref.frame_id, data=data,
                               is_extended_id=ref.is_extended_frame, is_fd=ref.is_fd))
    return out


def expected(message: can.Message) -> dict:
    """cantools' values, a value table's (an open enum's member) by its name in lower case."""
    db = cantools.database.load_file(POWERTRAIN, strict=False)
    decoded = db.decode_message(message.arbitration_id, message.data, force_extended_id=message.is_extended_id)
    return {FIELDS[k]: str(v).lower() if isinstance(v, NamedSignalValue) else v
            for k, v in decoded.items() if k in FIELDS}


@pytest.mark.parametrize("suffix", [".log", ".asc", ".blf"])
def test_decode_reads_the_logs_python_can_writes(tmp_path, schema, capsys, suffix):
    log = tmp_path / f"bus{suffix}"
    sent = frames() + [can.Message(timestamp=9.0, arbitration_id=0x7FF, data=b"\x01\x02", is_extended_id=False)]
    with can.Logger(str(log)) as writer:
        for message in sent:
            writer.on_message_received(message)
    assert main(["decode", str(schema), str(log), "--format", "json"]) == 1  # the last frame: an unknown id
    rows = [json.loads(line) for line in capsys.readouterr().out.splitlines()]
    assert len(rows) == 4
    for row, message in zip(rows, sent):
        flag = EXTENDED_FLAG if message.is_extended_id else 0
        head = (message.arbitration_id | flag).to_bytes(4, "big") + bytes([len(message.data)])
        assert row["frame"] == (head + bytes(message.data)).hex(" ")
    for row, message in zip(rows[:3], sent):
        assert {k: v for k, v in row["values"].items() if v is not None} == expected(message)
    assert "dispatch" in rows[3]["error"] and "2 bytes of data" in rows[3]["error"]


def test_check_counts_frames_of_a_candump_log_and_names_what_is_not_a_message(tmp_path, schema, capsys):
    log = tmp_path / "bus.log"
    with can.Logger(str(log)) as writer:
        for message in frames():
            writer.on_message_received(message)
        writer.on_message_received(can.Message(timestamp=8.0, arbitration_id=0x64, is_remote_frame=True,
                                               is_extended_id=False))
        db = cantools.database.load_file(POWERTRAIN, strict=False)
        short = db.get_message_by_name("EngineStatus").encode(VALUES["EngineStatus"] | {"LegacySpeed": 0},
                                                                 strict=False)[:6]
        writer.on_message_received(can.Message(timestamp=9.0, arbitration_id=0x64, data=short, is_extended_id=False))
    assert main(["check", str(schema), str(log), "--format", "json"]) == 1
    report = json.loads(capsys.readouterr().out)
    findings = report["findings"]
    assert [f["unit"] for f in findings] == [4, 5]
    assert "remote request" in findings[0]["text"]
    assert findings[1]["rule"] == "dispatch" and "6 bytes of data" in findings[1]["text"]
    assert report["inputs"][0]["input_format"] == "can-log"
    assert (report["summary"]["read"], report["summary"]["valid"]) == (5, 3)


def test_check_refuses_a_log_python_can_cannot_read(tmp_path, schema, capsys):
    log = tmp_path / "bus.log"
    log.write_text("this is not a candump log\n", encoding="utf-8")
    assert main(["check", str(schema), str(log)]) == 2
    assert "not a CAN log python-can reads" in capsys.readouterr().err


def test_monitor_decodes_a_virtual_bus(schema, capsys):
    sent = frames()
    result: list[int] = []
    monitor = threading.Thread(target=lambda: result.append(main(
        ["monitor", str(schema), "--can", "codeword-test", "--interface", "virtual", "--count", "6", "--json",
         "--duration", "20"])))
    monitor.start()
    with can.Bus(interface="virtual", channel="codeword-test") as bus:
        k = 0
        while monitor.is_alive():  # the monitor sees what is sent once its bus is open: send the frames round
            bus.send(sent[k % len(sent)])
            k += 1
            time.sleep(0.02)
    monitor.join()
    assert result == [0]
    rows = [json.loads(line) for line in capsys.readouterr().out.splitlines()]
    assert len(rows) == 6
    first = next(i for i, m in enumerate(sent) if expected(m) == {k: v for k, v in rows[0]["values"].items()
                                                                 if v is not None})
    for i, row in enumerate(rows):  # in the order sent, round and round
        assert {k: v for k, v in row["values"].items() if v is not None} == expected(sent[(first + i) % len(sent)])


def test_monitor_refuses_a_schema_that_is_not_can(capsys):
    assert main(["monitor", "mtv4", "--can", "codeword-test", "--interface", "virtual", "--count", "1"]) == 2
    assert "not a CAN protocol" in capsys.readouterr().err
