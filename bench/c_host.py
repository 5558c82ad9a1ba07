"""C on the host (gcc -O2): builds bench/c/host_bench.c against the generated
headers, hand-written C and MAVLink's generated C, with bench/c/mtv4_stream.c
once per CRC method, and runs it."""

import subprocess
from pathlib import Path

from bench import streams
from bench.protocols import ROOT
from codeword.targets.c.crc import DEFAULT as DEFAULT_METHOD, METHODS

CFLAGS = ["-O2", "-std=gnu99", "-DMTV4_CRC_TABLE"]
SOURCE = ROOT / "bench" / "c" / "host_bench.c"
STREAMS = ROOT / "bench" / "c" / "mtv4_stream.c"  # built once with each CRC method
CRC_METHODS = [m.guard.lower() for m in METHODS]
DEFAULT = DEFAULT_METHOD.lower()
PARSERS = tuple(f"{api}, CRC {m}" for api in ("mtv4_parser_feed/next", "mtv4_scan") for m in CRC_METHODS)


def compiler_version():
    return subprocess.run(["gcc", "--version"], capture_output=True, text=True, check=True).stdout.splitlines()[0]


def run(tmp: Path, mavlink_dir: Path, rounds: int, capture_bytes: int):
    """{key: figure} from host_bench; checks the parser found every good mtv4 frame."""
    exe = tmp / "host_bench"
    include = ["-I", str(ROOT / "generated" / "c")]
    objects = []
    plain = [f for f in CFLAGS if f != "-DMTV4_CRC_TABLE"]
    for method in CRC_METHODS:
        obj = tmp / f"mtv4_stream_{method}.o"
        subprocess.run(["gcc", *plain, f"-DMTV4_CRC_{method.upper()}", f"-DMETHOD={method}", "-Wall", "-Wextra",
                        "-Werror", *include, "-c", str(STREAMS), "-o", str(obj)], check=True)
        objects.append(str(obj))
    listed = " ".join(f"X({m})" for m in CRC_METHODS)
    # -w: MAVLink's headers warn about packed-member addresses; not ours to fix
    subprocess.run(["gcc", *CFLAGS, "-w", f"-DCRC_METHODS={listed}", *include, "-I", str(mavlink_dir),
                    "-I", str(SOURCE.parent), str(SOURCE), *objects, "-o", str(exe), "-lm"], check=True)
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
    for key in PARSERS:
        if figures[f"parser {key} frames"] != good:
            raise AssertionError(f"C parser {key} found {figures[f'parser {key} frames']} frames, {good} were sent")
    return figures


CAN_SOURCE = ROOT / "bench" / "c" / "can_bench.c"
CAN_MESSAGES = ("steering", "extended")


def run_can(tmp: Path, cantools_dir: Path, rounds: int):
    """{key: ns per call} of bench/c/can_bench.c: can_mixed's messages, codeword's C against
    cantools'; checks that both wrote the same data."""
    exe = tmp / "can_bench"
    subprocess.run(["gcc", *[f for f in CFLAGS if f != "-DMTV4_CRC_TABLE"], "-Wall", "-Wextra",
                    "-I", str(ROOT / "generated" / "examples" / "c"), "-I", str(cantools_dir), str(CAN_SOURCE),
                    str(cantools_dir / "cantools_can_mixed.c"), "-o", str(exe)], check=True)
    out = subprocess.run([str(exe), str(min(max(rounds, 1), 64))], capture_output=True, text=True, check=True).stdout
    figures = {}
    for line in out.splitlines():
        key, value = line.split("\t")
        figures[key] = float(value)
    for message in CAN_MESSAGES:
        if figures[f"{message} agree"] != 1:
            raise AssertionError(f"can_mixed {message}: codeword's and cantools' C wrote different data")
    return figures
