"""Multiplexed fields against cantools, the reference CAN database library: random
messages of 1 to 8 bytes are built with cantools' Python API, each with a multiplexor
whose values select groups of signals that share bits, signals carried for several
values, multiplexed multiplexors (extended multiplexing) and a second multiplexor
side by side, signals of both byte orders; the same layout is written as a codeword
schema. For random values of the signals a frame carries, the bytes cantools encodes
are what codeword's Python and C encoders write, and both decoders read cantools'
frames (noise in every bit no carried signal takes) back to the values cantools
decodes, the fields not carried None in Python. Expected bytes and values come from
cantools."""
from __future__ import annotations

import random

import pytest
from cantools.database.can import Message, Signal  # a test extra: pip install -e ".[peers]"

from can_frames import C_DRIVER, c_case, noise, random_layout, raw_values
from cdriver import Driver
from codeword.build import compile_schema
from codeword.targets.c.view import CView
from schema_in_a_test import load, render, run_c


def cantools_message(frame_id: int, size: int, signals: list[dict]) -> Message:
    return Message(frame_id=frame_id, name=f"m{frame_id}", length=size, strict=True, signals=[
        Signal(s["name"], s["start"], s["length"], s["order"], s["signed"], is_multiplexer=s["is_mux"],
               multiplexer_ids=s["ids"], multiplexer_signal=s["mux"]) for s in signals])


def schema_of(name: str, messages: list[tuple[int, list[dict]]]) -> str:
    lines = [f"codeword: 1\nprotocol: {name}\ntitle: random multiplexed CAN messages\nsource: cantools\n",
             "framing:\n  kind: bytes\n  layout:\n    - {name: can_id, type: u16, dispatch: true}\n",
             "    - {payload: true}\nmessages:\n"]
    for frame_id, (size, signals) in enumerate(messages):
        lines.append(f"  m{frame_id}:\n    id: {frame_id}\n    payload_bytes: {size}\n    fields:\n")
        for s in signals:
            kind = f"{'i' if s['signed'] else 'u'}{s['length']}"
            order = "big" if s["order"] == "big_endian" else "little"
            mux = f", multiplexed_by: {{field: {s['mux']}, values: {s['ids']}}}" if s["mux"] else ""
            lines.append(f"      - {{name: {s['name']}, type: {kind}, start_bit: {s['start']}, "
                         f"byte_order: {order}{mux}}}\n")
    return "".join(lines)


@pytest.mark.parametrize("seed", range(3))
def test_random_multiplexed_messages_match_cantools(tmp_path, seed):
    rng = random.Random(f"cantools multiplex {seed}")
    layouts = [(size, random_layout(rng, size)) for size in [rng.randint(1, 8) for _ in range(8)]]
    refs = [cantools_message(i, size, signals) for i, (size, signals) in enumerate(layouts)]
    assert sum(any(s["mux"] and by[s["mux"]]["mux"] for s in signals)
               for _, signals in layouts for by in [{x["name"]: x for x in signals}]) >= 1  # some nested
    name = f"canmux{seed}"
    render(tmp_path, name, schema_of(name, layouts))
    module = load(tmp_path / f"{name}.py")
    protocol = compile_schema(tmp_path / f"{name}.yaml")
    v, driver = CView(protocol), Driver(protocol)
    checks = []
    for i, (ref, (size, signals)) in enumerate(zip(refs, layouts)):
        cls = module.MESSAGES[f"m{i}"]
        message = protocol.message(f"m{i}")
        for k in range(25):
            values = raw_values(rng, ref)
            data = ref.encode(values, scaling=True, strict=True)
            frame = i.to_bytes(2, "big") + data
            assert cls(**values).encode() == frame, (ref.name, values)
            sent = i.to_bytes(2, "big") + noise(rng, data, [s for s in signals if s["name"] in values])
            expected = ref.decode(sent[2:], decode_choices=False)
            got = module.decode(sent)
            assert {s["name"]: getattr(got, s["name"]) for s in signals} == \
                {s["name"]: expected.get(s["name"]) for s in signals}, (ref.name, sent.hex())
            again = {s["name"]: getattr(got, s["name"]) for s in signals if getattr(got, s["name"]) is not None}
            assert ref.encode(again, strict=True) == data  # cantools writes back what codeword read
            checks.append(c_case(v, driver, message, values, frame, sent, f"{ref.name} #{k}"))
    lines = run_c(tmp_path, C_DRIVER.format(header=name, cases="\n".join(checks), n=len(checks)))
    assert lines == [f"OK {len(checks)}"], lines[:20]


def test_a_field_its_multiplexor_does_not_select_is_refused_by_name(tmp_path):
    """Python's encoder refuses a value for a field the multiplexor leaves out, and None
    for one it selects: EncodeError naming the field, rule `present`."""
    signals = [{"name": "mux", "start": 0, "length": 2, "order": "little_endian", "signed": False, "mux": None,
                "ids": None, "is_mux": True},
               {"name": "a", "start": 8, "length": 8, "order": "little_endian", "signed": False, "mux": "mux",
                "ids": [0], "is_mux": False},
               {"name": "b", "start": 8, "length": 4, "order": "little_endian", "signed": True, "mux": "mux",
                "ids": [1, 2], "is_mux": False}]
    render(tmp_path, "canmuxerr", schema_of("canmuxerr", [(2, signals)]))
    module = load(tmp_path / "canmuxerr.py")
    ref = cantools_message(0, 2, signals)
    assert module.MESSAGES["m0"](mux=2, b=-1).encode() == b"\0\0" + ref.encode({"mux": 2, "b": -1})
    for given, field in (({"mux": 0, "a": 1, "b": 1}, "b"), ({"mux": 1}, "b"), ({"mux": 3, "a": 1}, "a")):
        with pytest.raises(module.EncodeError) as err:
            module.MESSAGES["m0"](**given).encode()
        assert (err.value.field, err.value.rule) == (field, "present")
