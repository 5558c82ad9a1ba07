"""examples/can_mixed.yaml against cantools loading the equivalent DBC (written here):
for random values of every message, the data bytes cantools encodes are what
codeword's Python and C encoders write (`encode_can` gives them with the identifier
cantools has), and both decoders read cantools' data, with noise in the unused bits,
back to the values cantools decodes (`decode_can` from the identifier and the data).
Expected bytes and values come from cantools."""
from __future__ import annotations

import random
from pathlib import Path

import cantools  # a test extra: pip install -e ".[peers]"
import pytest

from can_frames import C_DRIVER, c_case, noise, raw_values
from cdriver import Driver
from codeword.build import compile_schema
from codeword.targets.c.view import CView
from schema_in_a_test import build_example, conformance_on_host_and_avr, firmware_warnings, load, render, run_c

SCHEMA = Path(__file__).resolve().parent.parent / "examples" / "can_mixed.yaml"

# The same messages as a DBC (examples/can_mixed.dbc): `start|length@order sign (scale,offset)`, @0 Motorola, @1 Intel;
# `M` a multiplexor, `m<n>` a signal it multiplexes, `m<n>M` both, and SG_MUL_VAL_ the values
# of a multiplexor that carry each signal (Message1 as in cantools' tests/files/dbc/multiplex.dbc,
# Extended and Shared as in multiplex_2.dbc, with their multiplexors unsigned and short ids;
# the float YawRate by SIG_VALTYPE_, 1 for a 32-bit float).
DBC = (Path(__file__).resolve().parent.parent / "examples" / "can_mixed.dbc").read_text(encoding="utf-8")

# codeword's message for each DBC message, and its field for each signal
NAMES = {"ExampleMessage": "example_message", "WheelSpeeds": "wheel_speeds", "Steering": "steering", "Gear": "gear",
         "Message1": "multiplexed", "Extended": "extended", "Shared": "shared", "ImuRates": "imu_rates"}
EXTENDED_FLAG = 0x80000000  # in a frame id, as SocketCAN's CAN_EFF_FLAG


def snake(name: str) -> str:
    if name.isupper():  # BIT_J, S0
        return name.lower()
    return "".join("_" + c.lower() if c.isupper() and i else c.lower() for i, c in enumerate(name))


def as_signals(message, names) -> list[dict]:
    return [{"start": s.start, "length": s.length, "order": s.byte_order} for s in message.signals if s.name in names]


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    return build_example("can_mixed", tmp_path_factory.mktemp("can_mixed"))


def test_frames_match_cantools_in_python_and_c(built):
    db = cantools.database.load_string(DBC, "dbc")
    module = load(built / "can_mixed.py")
    protocol = compile_schema(SCHEMA)
    v, driver = CView(protocol), Driver(protocol)
    rng = random.Random("can_mixed")
    checks = []
    for ref in db.messages:
        ours = protocol.message(NAMES[ref.name])
        cls = module.MESSAGES[ours.name]
        frame_id = ref.frame_id | (EXTENDED_FLAG if ref.is_extended_frame else 0)
        head = frame_id.to_bytes(4, "big") + bytes([ref.length])
        for k in range(60):
            values = raw_values(rng, ref)
            data = ref.encode(values, scaling=True, strict=True)
            mine = {snake(n): x for n, x in values.items()}
            assert cls(**mine).encode() == head + data, (ref.name, values)
            assert cls(**mine).encode_can() == (frame_id, data), (ref.name, values)
            sent = head + noise(rng, data, as_signals(ref, values))  # noise in the bits of signals not carried too
            expected = {snake(n): x for n, x in ref.decode(sent[5:], decode_choices=False).items()}
            for got in (module.decode(sent), module.decode_can(frame_id, sent[5:])):
                assert {f.name: getattr(got, f.name) for f in ours.members} == \
                    {f.name: expected.get(f.name) for f in ours.members}, (ref.name, sent.hex())
            checks.append(c_case(v, driver, ours, mine, head + data, sent, f"{ref.name} #{k}"))
    lines = run_c(built, C_DRIVER.format(header="can_mixed", cases="\n".join(checks), n=len(checks)))
    assert lines == [f"OK {len(checks)}"], lines[:20]


def test_conformance_vectors_on_the_host_and_on_atmega32_under_simavr(tmp_path):
    """Edge values, random values and damaged frames (noise in the unused bits among
    them): C agrees with Python on the host and on an 8-bit AVR."""
    host, avr = conformance_on_host_and_avr(tmp_path, "can_mixed", SCHEMA.read_text(encoding="utf-8"), parts=8)
    assert host > 100 and avr > 100


@pytest.mark.parametrize("compiler", ["gcc", "clang"])
@pytest.mark.parametrize("level", ["-O0", "-O2", "-Os"])
def test_codec_compiles_without_warnings(tmp_path, compiler, level):
    render(tmp_path, "can_mixed", SCHEMA.read_text(encoding="utf-8"))
    assert firmware_warnings(tmp_path, "can_mixed", compiler, level) == ""
