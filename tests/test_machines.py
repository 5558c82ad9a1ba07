"""The generated Python tr24 machines, step by step, against packets built by
hand from TR24-D1 (02 | service byte = type << 1 | seq | sender | receiver | data | 03)."""
from __future__ import annotations

import pytest

from conftest import load_generated


@pytest.fixture(scope="module")
def tr24():
    return load_generated("tr24")


def packet(type_, seq, sender, receiver, data):
    return bytes([0x02, type_ << 1 | seq, sender, receiver]) + bytes(data) + b"\x03"


def test_master_sends_resends_and_accepts_only_its_reply(tr24):
    m = tr24.MasterMachine(own_id=1, data_length=3, timeout=100)
    out = m.send(0, 3, b"\x2c\x00\x01")
    assert out.sent == [packet(0, 0, 1, 3, b"\x2c\x00\x01")] and m.state == "waiting"
    assert m.tick(99).sent == []  # not yet
    assert m.tick(100).sent == [packet(0, 0, 1, 3, b"\x2c\x00\x01")]  # same command, same seq (TR24-D4)
    # TR24-D3: wrong sender, wrong receiver, wrong seq, a command instead of a reply
    for wrong in (packet(1, 0, 4, 1, b"abc"), packet(1, 0, 3, 2, b"abc"), packet(1, 1, 3, 1, b"abc")):
        assert m.receive(150, wrong).delivered == [] and m.state == "waiting"
    assert m.receive(150, packet(0, 0, 3, 1, b"abc")).dropped
    out = m.receive(160, packet(1, 0, 3, 1, b"xyz"))
    assert out.delivered == [b"xyz"] and m.state == "idle" and m.seq == 1
    assert m.tick(1000).sent == []  # the timer was stopped
    assert m.send(1000, 3, b"\x00\x00\x00").sent == [packet(0, 1, 1, 3, b"\x00\x00\x00")]


def test_master_refuses_a_second_command_and_bad_arguments(tr24):
    m = tr24.MasterMachine(own_id=1)
    m.send(0, 3, bytes(7))
    with pytest.raises(tr24.MachineError):
        m.send(1, 3, bytes(7))
    m = tr24.MasterMachine(own_id=1)
    for receiver, data in ((3, bytes(6)), (256, bytes(7)), (3, "text")):
        with pytest.raises(tr24.MachineError):
            m.send(0, receiver, data)
    assert m.state == "idle"
    for bad in (dict(own_id=300), dict(own_id=1, data_length=60), dict(own_id=1, data_length=0),
                dict(own_id=1, retry_limit=-1)):
        with pytest.raises(tr24.MachineError):
            tr24.MasterMachine(**bad)
    with pytest.raises(tr24.MachineError):
        tr24.MasterMachine(own_id=1).receive(0, "not bytes")


def test_master_fails_after_the_retry_limit(tr24):
    m = tr24.MasterMachine(own_id=1, timeout=10, retry_limit=2)
    m.send(0, 3, bytes(7))
    sent = [len(m.tick(t).sent) for t in (10, 20)]  # two resends
    out = m.tick(30)
    assert sent == [1, 1] and out.sent == [] and out.failed and m.state == "idle"
    assert m.seq == 0  # kept after a failure (see the master's doc)


def test_slave_executes_once_and_repeats_its_reply(tr24):
    runs = []
    s = tr24.SlaveMachine(own_id=3, data_length=2, execute=lambda d: runs.append(d) or d[::-1])
    dup_first = s.receive(0, packet(0, 1, 1, 3, b"ab"))  # a duplicate before any command: blank reply
    assert dup_first.sent == [packet(1, 1, 3, 1, b"\x00\x00")] and runs == []
    out = s.receive(1, packet(0, 0, 1, 3, b"ab"))
    assert out.sent == [packet(1, 0, 3, 1, b"ba")] and out.executed == [b"ab"] and runs == [b"ab"]
    again = s.receive(2, packet(0, 0, 1, 3, b"ab"))  # TR24-D2: same reply, not executed
    assert again.sent == out.sent and again.executed == [] and runs == [b"ab"]
    assert s.receive(3, packet(0, 1, 1, 4, b"cd")).sent == []  # for another ID (TR24-D3)
    assert s.receive(4, packet(0, 1, 1, 3, b"cd")).sent == [packet(1, 1, 3, 1, b"dc")]
    assert runs == [b"ab", b"cd"]


def test_slave_refuses_a_wrong_sized_result(tr24):
    s = tr24.SlaveMachine(own_id=3, data_length=2, execute=lambda d: b"x")
    with pytest.raises(tr24.MachineError):
        s.receive(0, packet(0, 0, 1, 3, b"ab"))


def test_machines_are_in_the_model():
    from conftest import load_model
    p = load_model("tr24")
    master, slave = p.machines
    assert [s.name for s in master.states] == ["idle", "waiting"]
    assert master.event("timer").timer and master.event("send").args == ("receiver", "data")
    assert {a.kind for a in slave.actions} >= {"execute", "keep", "transmit", "flip"}


def test_a_shape_the_machine_targets_cannot_generate_is_a_schema_error(tmp_path):
    # two transmits in one step: the generated machines send at most one packet per call
    from pathlib import Path

    from codeword.build import compile_schema, render_protocol
    from codeword.diagnostics import SchemaError
    seed = (Path(__file__).resolve().parent.parent / "schemas" / "tr24.yaml").read_text(encoding="utf-8")
    schema = tmp_path / "tr24.yaml"
    schema.write_text(seed.replace("actions: [send_kept, start_timer]",
                                   "actions: [send_kept, send_kept, start_timer]", 1), encoding="utf-8")
    with pytest.raises(SchemaError) as err:
        render_protocol(compile_schema(schema))
    (diagnostic,) = err.value.diagnostics
    assert "more than one transmit in a step" in diagnostic.message
    assert diagnostic.loc.file == str(schema) and diagnostic.loc.line > 1
