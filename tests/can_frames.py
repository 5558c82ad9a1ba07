"""CAN frames for the tests against cantools: which bits a DBC signal takes, noise in
the bits none takes, and C statements that check a message's encoder and decoder
against bytes and values cantools gave."""
from __future__ import annotations

import math
import random
import struct
import sys

from cdriver import Driver
from codeword.targets.c.view import CView
from schema_in_a_test import c_bytes


def msb_position(start: int) -> int:
    """A DBC Motorola start bit as its place counted most significant bit first (its own inverse)."""
    return 8 * (start // 8) + 7 - start % 8


def covered(start: int, length: int, order: str) -> list[int]:
    """The DBC bit numbers a signal takes (bit k is bit k % 8 of byte k // 8)."""
    if order == "little_endian":
        return list(range(start, start + length))
    first = msb_position(start)
    return [msb_position(q) for q in range(first, first + length)]


def noise(rng: random.Random, data: bytes, signals: list[dict]) -> bytes:
    """The frame with random values in the bits no signal takes, which decoders ignore."""
    used = {b for s in signals for b in covered(s["start"], s["length"], s["order"])}
    free = sum(1 << b for b in range(8 * len(data)) if b not in used)
    return (int.from_bytes(data, "little") | rng.getrandbits(8 * len(data)) & free).to_bytes(len(data), "little")


def raw_values(rng: random.Random, message) -> dict:
    """Raw values over each signal's whole range, its ends often, scaled as cantools scales
    them: of the signals a frame carries, each multiplexor holding a value some signal it
    multiplexes is carried for (cantools encodes no other)."""
    signals = {s.name: s for s in message.signals}
    out: dict = {}

    def carried(s) -> bool:
        mux = signals.get(s.multiplexer_signal)
        return mux is None or carried(mux) and value(mux) in s.multiplexer_ids

    def value(s):
        if s.name not in out:
            selects = sorted({v for x in message.signals if x.multiplexer_signal == s.name for v in x.multiplexer_ids})
            if selects:
                raw = rng.choice(selects)
            elif s.is_float:  # SIG_VALTYPE_: a float the signal's width holds exactly
                out[s.name] = random_float(rng, s.length)
                return out[s.name]
            else:
                lo, hi = (-(1 << (s.length - 1)), (1 << (s.length - 1)) - 1) if s.is_signed else (0, (1 << s.length) - 1)
                raw = rng.choice((lo, hi, 0, rng.randint(lo, hi), rng.randint(lo, hi)))
            out[s.name] = s.conversion.raw_to_scaled(raw, decode_choices=False)
        return out[s.name]

    return {s.name: value(s) for s in message.signals if carried(s)}


def random_float(rng: random.Random, bits: int) -> float:
    """A finite float of `bits` (32 or 64) bits: ends, zero, tiny and random ones."""
    fmt = "<f" if bits == 32 else "<d"
    while True:
        raw = rng.getrandbits(bits)
        value = struct.unpack(fmt, raw.to_bytes(bits // 8, "little"))[0]
        if math.isfinite(value):
            break
    largest = 3.4028234663852886e38 if bits == 32 else sys.float_info.max
    return rng.choice((value, value, 0.0, -1.5, largest, -largest, 2.0 ** -149 if bits == 32 else 5e-324))


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


class Layout:
    """Random signals placed in a payload of `size` bytes: a signal multiplexed for some
    values avoids every bit a signal that may be carried with it takes."""

    def __init__(self, rng: random.Random, size: int):
        self.rng, self.size, self.signals = rng, size, []

    def place(self, taken: set[int], most: int = 16, mux: bool = False) -> tuple[dict, set[int]] | None:
        rng = self.rng
        for _ in range(30):
            length = rng.randint(1, 3) if mux else rng.randint(1, min(most, 8 * self.size))
            order = rng.choice(("big_endian", "little_endian"))
            first = rng.randint(0, 8 * self.size - length)
            start = first if order == "little_endian" else msb_position(first)
            bits = set(covered(start, length, order))
            if not bits & taken:
                signed = not mux and length > 1 and rng.random() < 0.5
                return {"name": f"s{len(self.signals)}", "start": start, "length": length, "order": order,
                        "signed": signed, "mux": None, "ids": None, "is_mux": mux}, bits
        return None

    def add(self, taken: set[int], mux: dict | None = None, ids: list[int] | None = None,
            is_mux: bool = False) -> tuple[dict, set[int]] | None:
        placed = self.place(taken, mux=is_mux)
        if placed is None:
            return None
        sig, bits = placed
        sig.update(mux=mux and mux["name"], ids=ids)
        self.signals.append(sig)
        return sig, bits

    def fill(self, taken: set[int], mux: dict, depth: int) -> set[int]:
        """Groups of signals for some values of `mux`, each group placed apart from what
        may be carried with it; the bits every group takes."""
        rng = self.rng
        values = rng.sample(range(1 << mux["length"]), min(1 << mux["length"], rng.randint(1, 3)))
        per = {v: set(taken) for v in values}
        for v in values:
            for _ in range(rng.randint(1, 3)):
                nested = depth < 1 and rng.random() < 0.3
                got = self.add(per[v], mux, [v], nested)
                if got is None:
                    break
                per[v] |= got[1]
                if nested:
                    per[v] = self.fill(per[v], got[0], depth + 1)
        if len(values) > 1 and rng.random() < 0.6:  # one signal carried for two of the values
            both = rng.sample(values, 2)
            got = self.add(per[both[0]] | per[both[1]], mux, sorted(both))
            if got is not None:
                for v in both:
                    per[v] |= got[1]
        return set().union(*per.values())


def random_layout(rng: random.Random, size: int) -> list[dict]:
    layout = Layout(rng, size)
    taken: set[int] = set()
    for _ in range(rng.randint(1, 2)):  # multiplexors side by side, each with plain signals
        got = layout.add(taken, is_mux=True)
        if got is None:
            break
        taken |= got[1]
        if rng.random() < 0.5:
            plain = layout.add(taken)
            if plain is not None:
                taken |= plain[1]
        taken = layout.fill(taken, got[0], 0)
    return layout.signals
