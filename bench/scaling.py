"""Compiler scaling: time and peak memory of `codeword build` on synthetic
schemas of growing size, each in a fresh process, and the cold build of the
five seed protocols."""

import json
import math
import resource
import statistics
import subprocess
import sys
import time
from pathlib import Path

from bench.protocols import ROOT

SIZES = (10, 100, 1000, 5000)

# One process: import the compiler, build, report wall seconds and peak RSS.
CHILD = """\
import json, resource, sys, time
start = time.perf_counter()
from codeword.cli import main


def peak_kib():
    # VmHWM belongs to this process image; ru_maxrss would carry the parent's peak over exec
    for line in open("/proc/self/status"):
        if line.startswith("VmHWM:"):
            return int(line.split()[1])
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss


rc = main(sys.argv[1:])
usage = resource.getrusage(resource.RUSAGE_SELF)
print(json.dumps({"rc": rc, "seconds": time.perf_counter() - start,
                  "cpu": usage.ru_utime + usage.ru_stime,
                  "peak_kib": peak_kib()}))
"""


def synthetic_schema(n: int) -> str:
    """A byte-framed protocol with n messages of four fields each, a 16-bit id
    and no checksum; one hand-checkable example on the first message."""
    lines = [
        "codeword: 1",
        f"protocol: synth{n}",
        f"title: synthetic protocol with {n} messages",
        "source: bench/scaling.py",
        "framing:",
        "  kind: bytes",
        "  byte_order: big",
        "  layout:",
        "    - {name: sync, type: u8, const: 0x55}",
        "    - {name: kind, type: u16, dispatch: true}",
        "    - {payload: true}",
        "messages:",
    ]
    for i in range(n):
        lines += [
            f"  m{i}:",
            f"    id: {i + 1}",
            "    fields:",
            "      - {name: a, type: u8, range: [0, 200]}",
            "      - {name: b, type: i16, scale: 0.5, range: [-1000, 1000]}",
            "      - {name: c, type: u32}",
            "      - {name: d, type: u8, range: [0, 9]}",
        ]
        if i == 0:
            # 55 | kind 00 01 | a=2 | b=1.5/0.5=3 -> 00 03 | c=1 -> 00 00 00 01 | d=1 -> 01;
            lines += [
                "    examples:",
                '      - values: {a: 2, b: 1.5, c: 1, d: 1}',
                '        hex: "55 00 01 02 00 03 00 00 00 01 01"',
                "        source: hand calculation",
            ]
    return "\n".join(lines) + "\n"


def _child(args, cwd):
    out = subprocess.run([sys.executable, "-c", CHILD, *args], capture_output=True, text=True,
                         cwd=cwd, check=True)
    result = json.loads(out.stdout.strip().splitlines()[-1])
    if result["rc"] != 0:
        raise RuntimeError(f"codeword {' '.join(args)} exited {result['rc']}: {out.stderr[-2000:]}")
    return result


def scaling(tmp: Path, repeats: int, sizes=SIZES):
    """{n: (median CPU seconds, median wall seconds, median peak MiB)}, the
    fitted exponent of CPU time in n, and {n: error} for builds that failed. CPU time is the primary figure: on a
    shared machine wall time also counts the waits for a core."""
    tmp.mkdir(parents=True, exist_ok=True)
    paths = {}
    for n in sizes:
        path = tmp / f"synth{n}.yaml"
        path.write_text(synthetic_schema(n))
        paths[n] = path
    samples = {n: [] for n in sizes}
    failures = {}
    for _ in range(repeats):
        for n in sizes:
            if n in failures:
                continue
            try:
                samples[n].append(_child(["build", str(paths[n]), "--out", str(tmp / f"out{n}")], ROOT))
            except (RuntimeError, subprocess.CalledProcessError) as exc:
                failures[n] = str(exc).strip().splitlines()[-1][:300]
    figures = {n: (statistics.median(s["cpu"] for s in samples[n]),
                   statistics.median(s["seconds"] for s in samples[n]),
                   statistics.median(s["peak_kib"] for s in samples[n]) / 1024)
               for n in sizes if n not in failures}
    return figures, exponent({n: f[0] for n, f in figures.items()}), failures


def exponent(times: dict) -> float:
    """Least-squares slope of log(time) against log(n) over the sizes from 100
    up (start-up time dominates the smallest build)."""
    pts = [(math.log(n), math.log(t)) for n, t in sorted(times.items()) if n >= 100] or \
        [(math.log(n), math.log(t)) for n, t in sorted(times.items())]
    if len(pts) < 2:
        return float("nan")
    mx = sum(x for x, _ in pts) / len(pts)
    my = sum(y for _, y in pts) / len(pts)
    return sum((x - mx) * (y - my) for x, y in pts) / sum((x - mx) ** 2 for x, _ in pts)


def seed_build(tmp: Path, repeats: int):
    """Median (CPU seconds, wall seconds) of a cold `codeword build` of the five
    seed schemas: a new process each time, interpreter start and imports included."""
    cpu, wall = [], []
    for _ in range(repeats):
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        start = time.perf_counter()
        subprocess.run([sys.executable, "-m", "codeword", "build", "--out", str(tmp / "seeds")],
                       cwd=ROOT, check=True, capture_output=True)
        wall.append(time.perf_counter() - start)
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpu.append(after.ru_utime + after.ru_stime - before.ru_utime - before.ru_stime)
    return statistics.median(cpu), statistics.median(wall)
