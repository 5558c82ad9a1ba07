"""`codeword check` reads a capture in one pass with constant memory.

The peak RSS of a check of a large generated mtv4 capture must stay within a
small margin of the peak for a tiny one. The default run uses a 24 MB capture
(2 MB of frames, the rest line noise without sync bytes); the benchmark,
`CODEWORD_CHECK_BENCH=1 python3 -m pytest -s tests/test_check_memory.py`, uses
200 MB of frames (several minutes) and prints the measurements. Time is
reported, never asserted.
"""
from __future__ import annotations

import os
import subprocess
import sys
import time

from conftest import ROOT

MB = 1024 * 1024
GROWTH_LIMIT_KB = 16 * 1024  # reading 24 MB (or 200 MB) whole would exceed this many times over
SET_WHEELS = bytes.fromhex("aa 08 03 01 20 00 24 03 60 ff 40 00")  # schemas/mtv4.yaml, first example
BAD_CRC = SET_WHEELS[:-1] + b"\xff"

_PEAK = ("import resource, subprocess, sys; subprocess.run(sys.argv[1:], stdout=subprocess.DEVNULL);"
         "print(resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss)")


def make_capture(path, frame_bytes: int, noise_bytes: int) -> None:
    """Valid frames with one bad CRC in every 1000, then noise (no 0xAA byte), in 1 MB writes."""
    block = (SET_WHEELS * 999 + BAD_CRC)
    with open(path, "wb") as fh:
        written = 0
        while written < frame_bytes:
            fh.write(block * 80)
            written += len(block) * 80
        noise = bytes(range(0x10, 0x90)) * (MB // 0x80)
        for _ in range(noise_bytes // MB):
            fh.write(noise)


def peak_rss_kb(capture) -> tuple[int, float]:
    """Peak RSS (KiB) of `codeword check mtv4 CAPTURE` in a child process, and its run time."""
    start = time.monotonic()
    out = subprocess.run([sys.executable, "-c", _PEAK, sys.executable, "-m", "codeword", "check",
                          "--format", "json", "--no-progress", "mtv4", str(capture)],
                         cwd=ROOT, capture_output=True, text=True, check=True)
    return int(out.stdout.strip()), time.monotonic() - start


def test_check_memory_is_constant(tmp_path):
    bench = os.environ.get("CODEWORD_CHECK_BENCH") == "1"
    small, large = tmp_path / "small.bin", tmp_path / "large.bin"
    make_capture(small, 12_000, 0)
    make_capture(large, 200 * MB if bench else 2 * MB, 0 if bench else 22 * MB)
    base, base_time = peak_rss_kb(small)
    peak, peak_time = peak_rss_kb(large)
    size = large.stat().st_size
    print(f"\ncheck of {size / MB:.0f} MB: peak RSS {peak / 1024:.1f} MiB in {peak_time:.1f} s "
          f"({size / MB / peak_time:.2f} MB/s); {small.stat().st_size} bytes: {base / 1024:.1f} MiB")
    assert peak - base < GROWTH_LIMIT_KB, (base, peak)
