"""Noise on long mtv4 and tr24 captures (fuzz/noise.py does the injecting and counting).

mtv4 carries a CRC-16 with Hamming distance 4 at these lengths and detects every
burst up to 16 bits, so for 1-3 flipped bits or a <=16-bit burst per frame no
damaged frame may be accepted. tr24 has no checksum (TR24-D1: the radio checks
its own CRC), so damage to its data, addresses and sequence bit is accepted by
design; what must hold is that every false accept differs from the frame sent
at that offset only in those unchecked bits, never in the start byte, stop
byte or reserved service bits, and that damage there is never accepted.
In both, every undamaged frame must come out of the stream decoder.

CODEWORD_FUZZ_LONG=1 runs 100 times more frames.
"""
from __future__ import annotations

import os
import random
import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "fuzz"))
import noise  # noqa: E402

FRAMES = 200_000 if os.environ.get("CODEWORD_FUZZ_LONG") == "1" else 2000


def check_intact_recovered(r: noise.Result):
    assert r.recovered_intact == r.intact, f"{r.intact - r.recovered_intact} undamaged frames lost"


@pytest.mark.parametrize("inject", ["bits", "bursts"])
def test_mtv4_accepts_no_frame_with_crc_detectable_damage(inject):
    rng = random.Random(f"mtv4-{inject}")
    cap = noise.capture("mtv4", FRAMES, rng)
    if inject == "bits":
        noise.detectable_errors(cap, rng)
    else:
        noise.bursts(cap, 3, rng)
    assert len(cap.damaged) >= FRAMES // 4  # the damage really happened
    r = noise.run("mtv4", cap)
    assert r.false_accepts == [], f"accepted damaged frames: {r.false_accepts[:5]}"
    check_intact_recovered(r)


@pytest.mark.parametrize("rate", noise.RATES)
def test_mtv4_random_bit_errors(rate):
    rng = random.Random(f"mtv4-ber-{rate}")
    cap = noise.capture("mtv4", FRAMES, rng)
    noise.random_errors(cap, rate, rng)
    r = noise.run("mtv4", cap)
    # Heavier damage slips through CRC-16 about once in 65536 damaged frames: far below 1 here.
    assert len(r.false_accepts) <= r.damaged / 65536 * 10 + 1
    check_intact_recovered(r)


@pytest.mark.parametrize("rate", noise.RATES)
def test_tr24_false_accepts_touch_only_unchecked_bits(rate):
    rng = random.Random(f"tr24-ber-{rate}")
    cap = noise.capture("tr24", FRAMES, rng)
    noise.random_errors(cap, rate, rng)
    r = noise.run("tr24", cap)
    at_frames, shifted = split_false_accepts(cap, r)
    for start, wire in at_frames:
        assert noise.only_unchecked_bits_differ(cap, start, wire), (
            f"accepted {wire.hex()} at {start}: differs from the sent frame in a checked bit")
    check_shifted_accepts_are_rare(cap, shifted)
    check_intact_recovered_beside(cap, r, shifted)


def test_tr24_damage_to_checked_bits_is_never_accepted():
    rng = random.Random("tr24-checked")
    cap = noise.capture("tr24", FRAMES, rng)
    for i in range(0, FRAMES, 2):
        pos, mask = rng.choice(list(noise.TR24_CHECKED.items()))
        byte = cap.starts[i] + (pos if pos >= 0 else len(cap.frames[i]) + pos)
        bit = rng.choice([b for b in range(8) if mask & (0x80 >> b)])
        cap.stream[byte] ^= 0x80 >> bit
    noise.mark_damage(cap)
    assert len(cap.damaged) == (FRAMES + 1) // 2
    r = noise.run("tr24", cap)
    at_frames, shifted = split_false_accepts(cap, r)
    assert at_frames == []  # a damaged frame is never accepted where it was sent
    check_shifted_accepts_are_rare(cap, shifted)
    check_intact_recovered_beside(cap, r, shifted)


def split_false_accepts(cap: noise.Capture, r: noise.Result):
    """False accepts where a frame was sent, and those at other offsets: without a
    checksum, resynchronising inside damaged data can find bytes shaped like a frame
    (a start byte, zero service bits and a stop byte where the size puts it)."""
    starts = set(cap.starts)
    return ([(s, w) for s, w in r.false_accepts if s in starts],
            [(s, w) for s, w in r.false_accepts if s not in starts])


def check_shifted_accepts_are_rare(cap: noise.Capture, shifted: list) -> None:
    assert len(shifted) <= max(1, len(cap.damaged) // 100), (
        f"{len(shifted)} frames accepted at offsets where none was sent, "
        f"for {len(cap.damaged)} damaged frames: {[(s, w.hex()) for s, w in shifted[:5]]}")


def check_intact_recovered_beside(cap: noise.Capture, r: noise.Result, shifted: list) -> None:
    """Every undamaged frame comes out, but one whose first bytes a frame found inside
    damaged data took (tr24 has no checksum to refuse that one)."""
    lost = r.intact - r.recovered_intact
    overlapped = sum(1 for s, w in shifted for start in cap.starts if s < start < s + len(w))
    assert lost <= overlapped, f"{lost} undamaged frames lost, {overlapped} overlapped by a shifted accept"
