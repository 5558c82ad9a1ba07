"""C on the host (gcc -O2): builds bench/c/host_bench.c against the generated
headers, hand-written C and MAVLink's generated C, and runs it."""

import subprocess
from pathlib import Path

from bench import streams
from bench.protocols import ROOT

CFLAGS = ["-O2", "-std=gnu99", "-DMTV4_CRC_TABLE"]
SOURCE = ROOT / "bench" / "c" / "host_bench.c"


def compiler_version():
    return subprocess.run(["gcc", "--version"], capture_output=True, text=True, check=True).stdout.splitlines()[0]


def run(tmp: Path, mavlink_dir: Path, rounds: int, capture_bytes: int):
    """{key: figure} from host_bench; checks the parser found every good mtv4 frame."""
    exe = tmp / "host_bench"
    # -w: MAVLink's headers warn about packed-member addresses; not ours to fix
    subprocess.run(["gcc", *CFLAGS, "-w", "-I", str(ROOT / "generated" / "c"), "-I", str(mavlink_dir),
                    "-I", str(SOURCE.parent), str(SOURCE), "-o", str(exe), "-lm"], check=True)
    cap, good = streams.mtv4_capture(capture_bytes)
    mcap, _ = streams.mavlink_capture(capture_bytes)
    (tmp / "mtv4.bin").write_bytes(cap)
    (tmp / "mavlink.bin").write_bytes(mcap)
    out = subprocess.run([str(exe), str(rounds), str(tmp / "mtv4.bin"), str(tmp / "mavlink.bin")],
                         capture_output=True, text=True, check=True).stdout
    figures = {}
    for line in out.splitlines():
        key, value = line.split("\t")
        figures[key] = float(value)
    if figures["parser mtv4 codeword frames"] != good:
        raise AssertionError(f"C parser found {figures['parser mtv4 codeword frames']} frames, {good} were sent")
    return figures
