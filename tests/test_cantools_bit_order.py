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
from schema_in_a_test import c_bytes, load, render, run_c

SCALES = ((1, 0), (0.5, 0), (0.25, -10), (2, 3), (0.125, 2.5))  # exact in binary: no rounding to disagree on


def msb_position(start: int) -> int:
    """A DBC Motorola start bit as its place counted most significant bit first (its own inverse)."""
    return 8 * (start // 8) + 7 - start % 8


def covered(start: int, length: int, order: str) -> list[int]:
    """The DBC bit numbers a signal takes (bit k is bit k % 8 of byte k // 8)."""
    if order == "little_endian":
        return list(range(start, start + length))
    first = msb_position(start)
    return [msb_position(q) for q in range(first, first + length)]


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


def noise(rng: random.Random, data: bytes, signals: list[dict]) -> bytes:
    """The frame with random values in the bits no signal takes, which decoders ignore."""
    used = {b for s in signals for b in covered(s["start"], s["length"], s["order"])}
    free = sum(1 << b for b in range(8 * len(data)) if b not in used)
    return (int.from_bytes(data, "little") | rng.getrandbits(8 * len(data)) & free).to_bytes(len(data), "little")


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


def c_case(v: CView, driver: Driver, message, values: dict, frame: bytes, sent: bytes, label: str) -> str:
    """C statements: encoding the values writes `frame` (cantools' bytes); decoding `sent`
    (those bytes with noise in the unused bits) gives the values."""
    t, init = v.tname(message), driver.init(message.fields, values)
    compare = " || ".join(f"got.{f.name} != want.{f.name}" for f in message.fields) or "0"
    return (f"    {{ static const {t} want = {init};\n"
            f"      static const uint8_t frame[] = {{{c_bytes(frame)}}};\n"
            f"      static const uint8_t sent[] = {{{c_bytes(sent)}}};\n"
            f"      {t} got;\n"
            f"      int n = {v.fn(message, 'encode')}(&want, buf, sizeof buf);\n"
            f"      if (n != (int)sizeof frame || memcmp(buf, frame, sizeof frame) != 0) {{ fail(\"encode {label}\"); }}\n"
            f"      memset(&got, 0, sizeof got);\n"
            f"      if ({v.fn(message, 'decode')}(sent, sizeof sent, &got) != CW_OK || {compare}) "
            f"{{ fail(\"decode {label}\"); }}\n    }}")


C_DRIVER = """#include <stdio.h>
#include <string.h>
#include "{header}.h"

static int failures;

static void fail(const char *what)
{{
    printf("FAIL %s\\n", what);
    failures++;
}}

int main(void)
{{
    uint8_t buf[16];
{cases}
    if (!failures) {{
        printf("OK %d\\n", {n});
    }}
    return 0;
}}
"""
