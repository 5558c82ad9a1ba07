"""Compiler scaling: time and peak memory of `codeword build` on synthetic
schemas of growing size, each in a fresh process; the cold build of the five
seed protocols; and codeword against mavgen on the same message count."""

import json
import math
import os
import resource
import statistics
import subprocess
import sys
import time
import xml.etree.ElementTree as ET
from pathlib import Path

from bench.protocols import ROOT

SIZES = (10, 100, 1000, 5000)
COLD = dict(os.environ, CODEWORD_CACHE="off")  # builds that find nothing kept by an earlier one

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


# One process: mavgen's C and Python for a MAVLink XML, as two `mavgen --lang` runs would.
MAVGEN_CHILD = """\
import json, resource, sys, time
start = time.perf_counter()
from pymavlink.generator import mavgen
for lang in ("C", "Python"):
    mavgen.mavgen(mavgen.Opts(f"{sys.argv[2]}/{lang}", wire_protocol="2.0", language=lang), [sys.argv[1]])
usage = resource.getrusage(resource.RUSAGE_SELF)
print(json.dumps({"rc": 0, "seconds": time.perf_counter() - start, "cpu": usage.ru_utime + usage.ru_stime}))
"""


# One process: mavgen's C and Python for a MAVLink XML, with its peak memory.
MAVGEN_PEAK_CHILD = MAVGEN_CHILD.replace(
    'print(json.dumps({"rc": 0,',
    'peak = next((int(x.split()[1]) for x in open("/proc/self/status") if x.startswith("VmHWM:")), usage.ru_maxrss)\n'
    'print(json.dumps({"rc": 0, "peak_kib": peak,')

# One process: `codeword import mavlink` of a dialect and the build of its C and Python, as a
# user who had the XML runs them; the CPU time and peak memory of both.
IMPORT_BUILD_CHILD = """\
import json, resource, sys, time
start = time.perf_counter()
from codeword.cli import main

xml, out = sys.argv[1], sys.argv[2]
rc = main(["import", "mavlink", xml, "--out", out])
if rc == 0:
    name = xml.rsplit("/", 1)[-1].rsplit(".", 1)[0]
    rc = main(["build", f"{out}/{name}.yaml", "--out", out, "--targets", "c,python"])
usage = resource.getrusage(resource.RUSAGE_SELF)
peak = next((int(x.split()[1]) for x in open("/proc/self/status") if x.startswith("VmHWM:")), usage.ru_maxrss)
print(json.dumps({"rc": rc, "seconds": time.perf_counter() - start,
                  "cpu": usage.ru_utime + usage.ru_stime, "peak_kib": peak}))
"""


def versus_mavgen_dialects(tmp: Path, repeats: int, dialects: list[Path]) -> dict:
    """{dialect: {"mavgen" | "codeword": (CPU s, wall s, peak MiB)}}, medians of interleaved
    rounds of new processes: mavgen's C and Python for each MAVLink XML, and codeword's
    import of the same XML with the build of its C and Python (no build cache)."""
    tmp.mkdir(parents=True, exist_ok=True)
    out = {}
    for xml in dialects:
        samples: dict[str, list] = {"mavgen": [], "codeword": []}
        for i in range(repeats):
            samples["mavgen"].append(_child([str(xml), str(tmp / f"mavgen-{xml.stem}-{i}")], tmp, MAVGEN_PEAK_CHILD))
            samples["codeword"].append(_child([str(xml), str(tmp / f"codeword-{xml.stem}-{i}")], tmp,
                                              IMPORT_BUILD_CHILD, env=COLD))
        out[xml.name] = {k: (statistics.median(r["cpu"] for r in v), statistics.median(r["seconds"] for r in v),
                             statistics.median(r["peak_kib"] for r in v) / 1024) for k, v in samples.items()}
    return out


# One process: a codeword build with the CPU time of each stage (wrapping the stages' functions).
PHASES_CHILD = """\
import functools, json, resource, sys, time


def cpu():
    usage = resource.getrusage(resource.RUSAGE_SELF)
    return usage.ru_utime + usage.ru_stime


start = cpu()
from codeword import build, cli
from codeword.targets import c, markdown, python
spent = {"interpreter start and imports": start}
spent["interpreter start and imports"] += cpu() - start


def timed(owner, name, stage):
    inner = getattr(owner, name)

    @functools.wraps(inner)
    def wrapper(*args, **kwargs):
        began = cpu()
        try:
            return inner(*args, **kwargs)
        finally:
            spent[stage] = spent.get(stage, 0.0) + cpu() - began
    setattr(owner, name, wrapper)


for owner, name, stage in ((build, "load_file", "YAML"), (build, "resolve", "validation and resolution"),
                           (python, "render", "Python"), (c, "render", "C"),
                           (build, "load_module", "compiling the generated Python"),
                           (build, "check_examples", "checking the examples"), (markdown, "render", "docs"),
                           (build, "write_vectors", "vectors")):
    timed(owner, name, stage)
rc = cli.main(sys.argv[1:])
spent["writing and the rest"] = cpu() - sum(spent.values())
print(json.dumps({"rc": rc, "phases": spent}))
"""


def phases(tmp: Path, schema: Path) -> dict:
    """{stage: CPU seconds} of one cold codeword build of `schema`."""
    out = subprocess.run([sys.executable, "-c", PHASES_CHILD, "build", str(schema), "--out", str(tmp / "phases")],
                         capture_output=True, text=True, cwd=tmp, check=True, env=COLD)
    return json.loads(out.stdout.strip().splitlines()[-1])["phases"]


def mavlink_shaped_schema(n: int) -> str:
    """A protocol framed as MAVLink 2 (length, sequence, system and component ids, a
    24-bit id, CRC-16/MCRF4XX with a CRC extra per message) with n messages of eight
    fields each: integers of every width, a float, a scaled and two ranged fields."""
    lines = [
        "codeword: 1",
        f"protocol: mav{n}",
        f"title: synthetic MAVLink-shaped protocol with {n} messages",
        "source: bench/scaling.py",
        "framing:",
        "  kind: bytes",
        "  byte_order: little",
        "  layout:",
        "    - {name: stx, type: u8, const: 0xFD}",
        "    - {name: len, type: u8, length_of: {from: payload, to: payload}}",
        "    - {name: seq, type: u8}",
        "    - {name: sysid, type: u8}",
        "    - {name: compid, type: u8}",
        "    - {name: msgid, type: u24, dispatch: true}",
        "    - {payload: true}",
        "    - name: checksum",
        "      type: u16",
        "      checksum: {algorithm: CRC-16/MCRF4XX, covers: {from: len, to: payload}, extra: message}",
        "messages:",
    ]
    for i in range(n):
        lines += [
            f"  m{i}:",
            f"    id: {i}",
            f"    crc_extra: {i * 37 % 256}",
            f"    doc: synthetic message {i}",
            "    fields:",
            "      - {name: time_ms, type: u32, unit: ms}",
            "      - {name: x, type: f32}",
            "      - {name: y, type: i16, scale: 0.01, range: [-300, 300]}",
            "      - {name: speed, type: u16, range: [0, 5000]}",
            "      - {name: mode, type: u8}",
            "      - {name: trim, type: i8}",
            "      - {name: level, type: u8, range: [0, 100]}",
            "      - {name: count, type: u16}",
        ]
    return "\n".join(lines) + "\n"


def mavlink_messages(xml: Path) -> int:
    """Messages in a MAVLink XML file and the files it includes."""
    root = ET.parse(xml).getroot()
    included = sum(mavlink_messages(xml.parent / inc.text.strip()) for inc in root.iter("include"))
    return included + len(root.findall("./messages/message"))


def versus_mavgen(tmp: Path, repeats: int, xml: Path):
    """{"mavgen" | "codeword" | "codeword again": (CPU s, wall s)}, medians of interleaved
    rounds, each a new process: mavgen's C and Python for `xml`; codeword's full build
    (Python, C, docs, vectors) of a MAVLink-shaped synthetic protocol with as many messages,
    with no build cache and again with the cache an earlier build left; and that count."""
    n = mavlink_messages(xml)
    tmp.mkdir(parents=True, exist_ok=True)
    schema = tmp / f"mav{n}.yaml"
    schema.write_text(mavlink_shaped_schema(n))
    # not a folder named codeword: `python -c` in tmp would import it as the package
    build = ["build", str(schema), "--out", str(tmp / "out")]
    warm = dict(os.environ, CODEWORD_CACHE=str(tmp / "cache"))
    _child(build, tmp, env=warm)  # fills the cache the rebuilds find
    jobs = {"mavgen": lambda: _child([str(xml), str(tmp / "mavgen")], tmp, MAVGEN_CHILD),
            "codeword": lambda: _child(build, tmp, env=COLD),
            "codeword again": lambda: _child(build, tmp, env=warm)}
    samples = {k: [] for k in jobs}
    for _ in range(repeats):
        for k, job in jobs.items():
            samples[k].append(job())
    figures = {k: (statistics.median(r["cpu"] for r in v), statistics.median(r["seconds"] for r in v))
               for k, v in samples.items()}
    return figures, n, phases(tmp, schema)


def _child(args, cwd, code=CHILD, env=None):
    out = subprocess.run([sys.executable, "-c", code, *args], capture_output=True, text=True, cwd=cwd, env=env)
    if out.returncode != 0:
        raise RuntimeError(f"{' '.join(args)} failed ({out.returncode}): {out.stderr[-2000:]}")
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
                samples[n].append(_child(["build", str(paths[n]), "--out", str(tmp / f"out{n}")], tmp, env=COLD))
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
    seed schemas, a new process each time, interpreter start and imports included:
    {"first": with an empty build cache, "again": with the cache the first build left}."""
    figures = {}
    for label, cache in (("first", None), ("again", tmp / "seed-cache")):
        cpu, wall = [], []
        for _ in range(repeats):
            env = dict(os.environ, CODEWORD_CACHE=str(cache) if cache else "off")
            if cache is not None and not cache.exists():  # fill it, untimed
                subprocess.run([sys.executable, "-m", "codeword", "build", "--out", str(tmp / "seeds")],
                               cwd=ROOT, check=True, capture_output=True, env=env)
            before = resource.getrusage(resource.RUSAGE_CHILDREN)
            start = time.perf_counter()
            subprocess.run([sys.executable, "-m", "codeword", "build", "--out", str(tmp / "seeds")],
                           cwd=ROOT, check=True, capture_output=True, env=env)
            wall.append(time.perf_counter() - start)
            after = resource.getrusage(resource.RUSAGE_CHILDREN)
            cpu.append(after.ru_utime + after.ru_stime - before.ru_utime - before.ru_stime)
        figures[label] = (statistics.median(cpu), statistics.median(wall))
    return figures
