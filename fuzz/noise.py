"""Bit errors and bursts injected into long mtv4 and tr24 captures.

A capture is a random sequence of the protocol's conformance frames
(generated/vectors/<p>.json), fed to the generated Python StreamDecoder in
small chunks. For every message the decoder accepts, its stream offset tells
which sent frame it claims to be:

- recovered: the same bytes as the frame sent at that offset;
- falsely accepted: anything else (a corrupted frame that passed every check,
  or a window across two frames);
- resync latency: bytes from the end of a corrupted frame to the start of the
  next frame the decoder recovers.

mtv4 has a CRC-16 (polynomial 0x8005 = (x+1)(x^15+x+1): every 1-3 bit error and
every burst up to 16 bits in a frame of fewer than 32767 bits is detected), so
its false accepts must be 0 for such corruption and about 2^-16 of the frames
with heavier damage. tr24 has no checksum (the radio module checks its own
CRC, TR24-D1): only the start byte, stop byte and reserved service bits are
checked, so corruption elsewhere is accepted; what must hold there is that a
false accept differs from the sent frame only in unchecked bits.

    python3 fuzz/noise.py [--frames N] [--seed S]   # prints a Markdown table
"""
from __future__ import annotations

import argparse
import importlib.util
import os
import json
import random
import sys
from dataclasses import dataclass, field
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
RATES = (1e-4, 1e-3, 1e-2)
BURST_BITS = 16
# Bits a tr24 decoder checks: start byte, the six reserved service bits, stop byte (TR24-D1).
TR24_CHECKED = {0: 0xFF, 1: 0xFC, -1: 0xFF}


def load(name: str):
    key = f"noise_{name}"
    if key not in sys.modules:
        spec = importlib.util.spec_from_file_location(key, ROOT / "generated" / "python" / f"{name}.py")
        mod = importlib.util.module_from_spec(spec)
        sys.modules[key] = mod
        # pure Python: the harness watches each frame the stream decoder decodes through `decode`
        saved = os.environ.get("CODEWORD_PURE_PYTHON")
        os.environ["CODEWORD_PURE_PYTHON"] = "1"
        try:
            spec.loader.exec_module(mod)
        finally:
            if saved is None:
                del os.environ["CODEWORD_PURE_PYTHON"]
    return sys.modules[key]


def frames_of(name: str) -> list[bytes]:
    vectors = json.loads((ROOT / "generated" / "vectors" / f"{name}.json").read_text())
    return [bytes.fromhex(v["hex"]) for v in vectors["valid"]]


@dataclass
class Capture:
    stream: bytearray
    starts: list[int]          # offset of each sent frame
    frames: list[bytes]
    damaged: set[int] = field(default_factory=set)  # indexes of frames with a flipped bit


def capture(name: str, count: int, rng: random.Random) -> Capture:
    pool = frames_of(name)
    frames = [rng.choice(pool) for _ in range(count)]
    starts, stream = [], bytearray()
    for f in frames:
        starts.append(len(stream))
        stream += f
    return Capture(stream, starts, frames)


def flip(cap: Capture, bit: int) -> None:
    cap.stream[bit // 8] ^= 0x80 >> (bit % 8)


def mark_damage(cap: Capture) -> None:
    cap.damaged = {i for i, (s, f) in enumerate(zip(cap.starts, cap.frames))
                   if bytes(cap.stream[s:s + len(f)]) != f}


def random_errors(cap: Capture, rate: float, rng: random.Random) -> None:
    total = len(cap.stream) * 8
    bit = 0
    while True:
        bit += int(rng.expovariate(rate)) + 1  # gaps between independent errors
        if bit >= total:
            break
        flip(cap, bit)
    mark_damage(cap)


def bursts(cap: Capture, every: int, rng: random.Random) -> None:
    """A burst of up to BURST_BITS bits (first and last flipped) in one frame of every `every`."""
    for i in range(0, len(cap.frames), every):
        nbits = len(cap.frames[i]) * 8
        length = rng.randint(2, min(BURST_BITS, nbits))
        first = cap.starts[i] * 8 + rng.randrange(nbits - length + 1)
        flip(cap, first)
        flip(cap, first + length - 1)
        for b in range(first + 1, first + length - 1):
            if rng.random() < 0.5:
                flip(cap, b)
    mark_damage(cap)


def detectable_errors(cap: Capture, rng: random.Random, every: int = 3) -> None:
    """1-3 flipped bits in one frame of every `every` (within CRC-16's Hamming distance 4)."""
    for i in range(0, len(cap.frames), every):
        nbits = len(cap.frames[i]) * 8
        for b in rng.sample(range(nbits), rng.randint(1, 3)):
            flip(cap, cap.starts[i] * 8 + b)
    mark_damage(cap)


@dataclass
class Result:
    sent: int
    damaged: int
    recovered: int
    recovered_intact: int
    false_accepts: list[tuple[int, bytes]]  # (offset, accepted bytes)
    latencies: list[int]

    @property
    def intact(self) -> int:
        return self.sent - self.damaged


def run(name: str, cap: Capture, chunk: int = 7) -> Result:
    mod = load(name)
    decoder = mod.StreamDecoder()
    real_decode, starts = mod.decode, []

    def decode(frame, direction=None):
        # The stream decoder calls this with its offset at the frame's first byte.
        value = real_decode(frame, direction)
        starts.append(decoder.offset)
        return value

    mod.decode = decode
    try:
        data = bytes(cap.stream)
        accepted = [e for pos in range(0, len(data), chunk)
                    for e in decoder.feed(data[pos:pos + chunk]) if not isinstance(e, mod.CodecError)]
    finally:
        mod.decode = real_decode
    assert len(starts) == len(accepted)
    by_start = {s: i for i, s in enumerate(cap.starts)}
    good, false = set(), []
    for start, message in zip(starts, accepted):
        wire = mod.encode(message)
        i = by_start.get(start)
        if i is not None and wire == cap.frames[i]:
            good.add(i)
        else:
            false.append((start, wire))
    latencies = []
    for i in sorted(cap.damaged):
        later = next((j for j in range(i + 1, len(cap.frames)) if j in good), None)
        if later is not None and i + 1 not in cap.damaged:
            latencies.append(cap.starts[later] - (cap.starts[i] + len(cap.frames[i])))
    return Result(len(cap.frames), len(cap.damaged), len(good), len(good - cap.damaged), false, latencies)


def only_unchecked_bits_differ(cap: Capture, start: int, wire: bytes) -> bool:
    """tr24: a false accept at a sent frame's offset differs from it only where nothing is checked."""
    i = cap.starts.index(start) if start in cap.starts else None
    if i is None or len(cap.frames[i]) != len(wire):
        return False
    sent = cap.frames[i]
    for pos, mask in TR24_CHECKED.items():
        if (sent[pos] ^ wire[pos]) & mask:
            return False
    return True


def scenarios(name: str, frames: int, seed: int):
    for rate in RATES:
        rng = random.Random(f"{seed}-{name}-{rate}")
        cap = capture(name, frames, rng)
        random_errors(cap, rate, rng)
        yield f"BER {rate:g}", cap
    rng = random.Random(f"{seed}-{name}-burst")
    cap = capture(name, frames, rng)
    bursts(cap, 10, rng)
    yield f"bursts <= {BURST_BITS} bits, 1 frame in 10", cap


def report(frames: int, seed: int) -> str:
    rows = ["| protocol | corruption | frames | damaged | recovered (intact) | falsely accepted "
            "| expected false (2^-16 x damaged) | resync latency mean / max [bytes] |",
            "|---|---|---|---|---|---|---|---|"]
    for name in ("mtv4", "tr24"):
        for label, cap in scenarios(name, frames, seed):
            r = run(name, cap)
            expected = f"{r.damaged / 65536:.3f}" if name == "mtv4" else "n/a (no CRC)"
            lat = (f"{sum(r.latencies) / len(r.latencies):.1f} / {max(r.latencies)}" if r.latencies else "-")
            rows.append(f"| {name} | {label} | {r.sent} | {r.damaged} | {r.recovered} ({r.recovered_intact} "
                        f"of {r.intact}) | {len(r.false_accepts)} | {expected} | {lat} |")
    return "\n".join(rows)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--frames", type=int, default=20000)
    parser.add_argument("--seed", type=int, default=1)
    args = parser.parse_args(argv)
    print(report(args.frames, args.seed))
    return 0


if __name__ == "__main__":
    sys.exit(main())
