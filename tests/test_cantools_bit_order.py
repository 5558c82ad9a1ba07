"""Fields placed by start_bit against cantools, the reference CAN database library:
random messages of 1 to 8 bytes whose signals mix Motorola (big-endian) and Intel
(little-endian) byte order at random start bits and widths of 1 to 64 bits, signed
and unsigned, some scaled, are built with cantools' Python API and written as a
codeword schema with the same start bits. The bytes cantools encodes are what
codeword's Python and C encoders write, and both decoders read cantools' frames,
with noise in the unused bits, back to the values cantools decodes. Expected bytes
and values come from cantools."""
from __future__ import annotations

import random

import pytest
from cantools.database.can import Message, Signal  # a test extra: pip install -e ".[peers]"
from cantools.database.conversion import BaseConversion

from cdriver import Driver
from codeword.build import compile_schema
from codeword.targets.c.view import CView
from can_frames import C_DRIVER, c_case, covered, msb_position, noise
from schema_in_a_test import load, render, run_c

SCALES = ((1, 0), (0.5, 0), (0.25, -10), (2, 3), (0.125, 2.5))  # exact in binary: no rounding to disagree on


def random_signals(rng: random.Random, size: int) -> list[dict]:
    """Non-overlapping signals of both orders in a payload of `size` bytes, with gaps."""
    taken: set[int] = set()
    out: list[dict] = []
    for attempt in range(12):
        length = rng.choice((rng.randint(1, 8 * size), rng.randint(1, min(16, 8 * size))))
        length = min(length, 64)
        order = rng.choice(("big_endian", "little_endian"))
        place = rng.randint(0, 8 * size - length)  # the first bit in the order's own numbering
        start = place if order == "little_endian" else msb_position(place)
        bits = covered(start, length, order)
        if taken & set(bits):
            continue
        taken |= set(bits)
        signed = length > 1 and rng.random() < 0.5
        scale, offset = rng.choice(SCALES) if length <= 53 else (1, 0)
        out.append({"name": f"s{len(out)}", "start": start, "length": length, "order": order,
                    "signed": signed, "scale": scale, "offset": offset})
    return out


def cantools_message(frame_id: int, size: int, signals: list[dict]) -> Message:
    return Message(frame_id=frame_id, name=f"m{frame_id}", length=size, strict=True, signals=[
        Signal(s["name"], s["start"], s["length"], s["order"], s["signed"],
               conversion=BaseConversion.factory(scale=s["scale"], offset=s["offset"])) for s in signals])


def schema_of(name: str, messages: list[tuple[int, list[dict]]]) -> str:
    """The same layouts in codeword's language: a CAN id before each payload."""
    lines = [f"codeword: 1\nprotocol: {name}\ntitle: random CAN messages\nsource: cantools\n",
             "framing:\n  kind: bytes\n  layout:\n    - {name: can_id, type: u16, dispatch: true}\n",
             "    - {payload: true}\nmessages:\n"]
    for frame_id, (size, signals) in enumerate(messages):
        lines.append(f"  m{frame_id}:\n    id: {frame_id}\n    payload_bytes: {size}\n    fields:\n")
        for s in signals:
            kind = f"{'i' if s['signed'] else 'u'}{s['length']}"
            order = "big" if s["order"] == "big_endian" else "little"
            scaled = f", scale: {s['scale']}, offset: {s['offset']}" if (s["scale"], s["offset"]) != (1, 0) else ""
            lines.append(f"      - {{name: {s['name']}, type: {kind}, start_bit: {s['start']}, "
                         f"byte_order: {order}{scaled}}}\n")
    return "".join(lines)


def random_values(rng: random.Random, signals: list[dict]) -> dict:
    """Values over each signal's whole raw range, its ends often."""
    out = {}
    for s in signals:
        n = s["length"]
        lo, hi = (-(1 << (n - 1)), (1 << (n - 1)) - 1) if s["signed"] else (0, (1 << n) - 1)
        raw = rng.choice((lo, hi, 0, rng.randint(lo, hi), rng.randint(lo, hi)))
        out[s["name"]] = raw if (s["scale"], s["offset"]) == (1, 0) else raw * s["scale"] + s["offset"]
    return out


@pytest.mark.parametrize("seed", range(4))
def test_random_can_messages_match_cantools(tmp_path, seed):
    rng = random.Random(f"cantools {seed}")
    layouts = [(size, random_signals(rng, size)) for size in [rng.randint(1, 8) for _ in range(8)]]
    refs = [cantools_message(i, size, signals) for i, (size, signals) in enumerate(layouts)]
    name = f"canrand{seed}"
    render(tmp_path, name, schema_of(name, layouts))
    module = load(tmp_path / f"{name}.py")
    protocol = compile_schema(tmp_path / f"{name}.yaml")
    v, driver = CView(protocol), Driver(protocol)
    checks = []
    for i, (ref, (size, signals)) in enumerate(zip(refs, layouts)):
        cls = module.MESSAGES[f"m{i}"]
        message = protocol.message(f"m{i}")
        for k in range(25):
            values = random_values(rng, signals)
            data = ref.encode(values, scaling=True, strict=True)
            frame = i.to_bytes(2, "big") + data
            assert cls(**values).encode() == frame, (ref.name, values)
            sent = i.to_bytes(2, "big") + noise(rng, data, signals)
            expected = ref.decode(sent[2:], decode_choices=False, scaling=True)
            got = module.decode(sent)
            assert {s["name"]: getattr(got, s["name"]) for s in signals} == expected, (ref.name, sent.hex())
            assert ref.decode(cls(**expected).encode()[2:], decode_choices=False) == expected
            checks.append(c_case(v, driver, message, values, frame, sent, f"{ref.name} #{k}"))
    lines = run_c(tmp_path, C_DRIVER.format(header=name, cases="\n".join(checks), n=len(checks)))
    assert lines == [f"OK {len(checks)}"], lines[:20]
