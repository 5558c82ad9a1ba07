"""The CRC methods of the generated C, side by side, for scripts/size-report: flash on AVR
and Cortex-M0, cycles on an ATmega32 under simavr, and the host's in-place scan against
MAVLink's parser, each method as `-DMTV4_CRC_<METHOD>` selects it.

Flash: size-report's program that encodes and decodes one mtv4 SetWheelsVelocities frame,
above the same program with the codec calls replaced (its harness). Cycles: bench/avr.py's
`mtv4_scan` over 26-byte frames, and the CRC alone over one frame's 23 bytes (simavr is
cycle-accurate, so these figures repeat exactly). Host: bench/c_host.py's `mtv4_scan` over
a capture, as MB/s of CPU time and as a ratio to `mavlink_parse_char` measured in the same
run, rounds interleaved; the MB/s vary from run to run on a shared machine, the ratios less.
"""

import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))  # bench/ is a package at the root

from bench import avr, c_host, peers_c  # noqa: E402
from protocol_sizes import flash_of  # noqa: E402 - scripts/ is on the path as the script's own folder
from codeword.targets.c.crc import DEFAULT, METHODS  # noqa: E402

TARGETS = [
    ("AVR", ["avr-gcc", "-std=c99", "-Os", "-mmcu=atmega32", "-ffunction-sections", "-fdata-sections",
             "-Wl,--gc-sections"], "avr-size"),
    ("Cortex-M0", ["arm-none-eabi-gcc", "-std=c99", "-Os", "-mcpu=cortex-m0", "-mthumb", "--specs=nosys.specs",
                   "-ffunction-sections", "-fdata-sections", "-Wl,--gc-sections"], "arm-none-eabi-size"),
]
HOST_ROUNDS = 7
HOST_BYTES = 4_000_000


class ToolError(Exception):
    pass


def run(cmd, cwd=None):
    proc = subprocess.run(cmd, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if proc.returncode != 0:
        raise ToolError(f"command failed ({proc.returncode}): {' '.join(map(str, cmd))}\n{proc.stdout}{proc.stderr}")
    return proc.stdout


def flash(target, work: Path, source: Path, defines: list[str]) -> int:
    """.text + .rodata + .data of the program, above its harness."""
    label, cmd, size_tool = target
    figures = []
    for extra in ([], ["-DSR_HARNESS_ONLY"]):
        elf = work / f"{source.stem}_{label}_{len(extra)}.elf"
        run([*cmd, *defines, *extra, "-I", str(ROOT / "generated" / "c"), str(source), "-o", str(elf)])
        figures.append(flash_of(size_tool, elf))  # size-report reports either script's ToolError
    return figures[0] - figures[1]


def measure(program: str) -> dict:
    """{"methods": {method: {"AVR": B, "Cortex-M0": B, "scan": cycles, "crc": cycles, "MB/s": x,
    "ratio": x}}, "mavlink MB/s": x}; `program` is size-report's mtv4 source."""
    with tempfile.TemporaryDirectory(prefix="codeword-crc-methods-") as tmp:
        work = Path(tmp)
        source = work / "mtv4_codec.c"
        source.write_text(program, encoding="utf-8")
        out = {m.guard: {t[0]: flash(t, work, source, [f"-DMTV4_CRC_{m.guard}"]) for t in TARGETS} for m in METHODS}
        cycles = avr.crc_choice(work / "avr")
        host = c_host.run(work, peers_c.generate_mavlink(work / "mavlink"), HOST_ROUNDS, HOST_BYTES)
    mav = host["parser mavlink_parse_char MB/s"]
    for m in METHODS:
        _flash, scan, crc = cycles[m.guard.lower()]
        speed = host[f"parser mtv4_scan, CRC {m.guard.lower()} MB/s"]
        out[m.guard].update({"scan": scan, "crc": crc, "MB/s": speed, "ratio": speed / mav})
    return {"methods": out, "mavlink MB/s": mav}


def report_lines(result: dict) -> list[str]:
    figures = result["methods"]
    lines = [
        "## CRC methods",
        "",
        "A header computes its CRCs by the method one macro selects when it is compiled "
        "(`-D<PROTOCOL>_CRC_<METHOD>`; at most one, the header refuses two), every method's tables `const` "
        "and in flash on AVR. Flash: encode and decode of one mtv4 SetWheelsVelocities frame (CRC-16) "
        f"as in the first table, on the ATmega32 (`{' '.join(TARGETS[0][1][1:])}`) and on Cortex-M0 "
        f"(`{' '.join(TARGETS[1][1][1:])}`), `.text` + `.rodata` + `.data` above the harness. AVR cycles: "
        f"`mtv4_scan` over {avr.CRC_FRAMES} frames of 26 bytes, per frame, and the CRC alone over one frame's "
        "23 bytes, on an ATmega32 at 16 MHz under simavr (`bench/avr.py`; cycle-accurate, the same in every run). "
        f"Host: `mtv4_scan` over a {HOST_BYTES / 1e6:.0f} MB capture (`bench/c_host.py`, gcc -O2, median of "
        f"{HOST_ROUNDS} interleaved rounds, CPU time) and the same run's `mavlink_parse_char` over a MAVLink 2 "
        f"capture ({result['mavlink MB/s']:.1f} MB/s); the MB/s move with the machine's load, the ratios little.",
        "",
        "| method | table entries | AVR flash (B) | Cortex-M0 flash (B) | AVR cycles per frame, scan | "
        "AVR cycles, CRC alone | host `mtv4_scan` MB/s | × `mavlink_parse_char` |",
        "|---|---:|---:|---:|---:|---:|---:|---:|",
    ]
    for m in METHODS:
        f = figures[m.guard]
        name = f"`{m.guard}`" + (" (default)" if m.guard == DEFAULT else "")
        lines.append(f"| {name}: {m.what} | {m.entries} | {f['AVR']} | {f['Cortex-M0']} | {f['scan']:,.0f} | "
                     f"{f['crc']:,} | {f['MB/s']:,.1f} | {f['ratio']:.2f} |")
    bit, default = figures["BITWISE"], figures[DEFAULT]
    best = max(METHODS, key=lambda m: figures[m.guard]["ratio"])
    uart = {k: figures[k]["scan"] / 26 * 11520 / 16e6 for k in ("BITWISE", DEFAULT)}  # 115200 baud, 8N1
    lines += [
        "",
        f"`{DEFAULT}` is the default: the smallest method that scans at least twice as fast as "
        f"`mavlink_parse_char` on the host ({default['ratio']:.2f}×, against {bit['ratio']:.2f}× bitwise), "
        f"for {default['AVR'] - bit['AVR']} B more flash than bitwise on AVR and "
        f"{default['Cortex-M0'] - bit['Cortex-M0']} B on Cortex-M0; on the ATmega32 it scans a frame "
        f"{bit['scan'] / default['scan']:.1f}× as fast as bitwise (a saturated 115200-baud UART takes "
        f"{uart[DEFAULT]:.1%} of the 16 MHz CPU, {uart['BITWISE']:.1%} bitwise). `NIBBLE` costs about as much "
        "flash and is slower: two lookups a byte that wait on each other, where `SPLIT`'s two do not. "
        "Define `<PROTOCOL>_CRC_BITWISE` where every byte of flash counts; on a host, `"
        f"{best.guard}` scans fastest ({figures[best.guard]['ratio']:.2f}× `mavlink_parse_char`). "
        "Slicing gains nothing on AVR, whose 8-bit loads see no parallelism, and `SLICE8` gains over "
        "`SLICE4` on long frames only (a frame of 23 covered bytes is mostly a `SLICE4` turn of four).",
        "",
    ]
    return lines
