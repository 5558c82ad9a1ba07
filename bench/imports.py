"""Importing a generated module of MAVLink's size next to pymavlink's common dialect, each
in a new process: with its bytecode cached (an installed package, a module imported
before) and from source (a module just generated, or a read-only install)."""

import importlib.util
import json
import os
import py_compile
import shutil
import statistics
import subprocess
import sys
from pathlib import Path

from bench.scaling import mavlink_shaped_schema

MESSAGES = 220  # MAVLink's common.xml with the messages it includes, about

# One process: import a module, print the CPU and wall seconds the import took. Nothing
# is written: whether bytecode is found is the caller's choice.
CHILD = """\
import json, sys, time
sys.dont_write_bytecode = True
cpu, wall = time.process_time(), time.perf_counter()
__import__(sys.argv[1])
print(json.dumps({"cpu": time.process_time() - cpu, "wall": time.perf_counter() - wall}))
"""


def prepare(tmp: Path, messages: int = MESSAGES) -> dict:
    """{contender: (folder for sys.path, module to import, its source file)}: codeword's
    module for a MAVLink-shaped protocol of `messages` messages (bench/scaling.py), and a copy
    of the installed pymavlink whose bytecode this benchmark controls."""
    tmp.mkdir(parents=True, exist_ok=True)
    schema = tmp / f"mav{messages}.yaml"
    schema.write_text(mavlink_shaped_schema(messages))
    out = tmp / "built"  # not a folder named codeword: it would shadow the package
    subprocess.run([sys.executable, "-m", "codeword", "build", str(schema), "--out", str(out)],
                   check=True, capture_output=True, cwd=tmp)
    installed = Path(importlib.util.find_spec("pymavlink").origin).parent
    peer = tmp / "peer"
    shutil.rmtree(peer, ignore_errors=True)
    shutil.copytree(installed, peer / "pymavlink", ignore=shutil.ignore_patterns("__pycache__"))
    for source in (peer / "pymavlink").rglob("*.py"):  # every module it imports, compiled as pip would
        py_compile.compile(str(source), doraise=False, quiet=2)
    return {"codeword": (out / "python", f"mav{messages}", out / "python" / f"mav{messages}.py"),
            "pymavlink common": (peer, "pymavlink.dialects.v20.common",
                                 peer / "pymavlink" / "dialects" / "v20" / "common.py")}


def _import_once(folder: Path, module: str, source: Path, cached: bool) -> dict:
    pyc = Path(importlib.util.cache_from_source(str(source)))
    if cached and not pyc.exists():
        py_compile.compile(str(source), doraise=True)
    elif not cached and pyc.exists():
        pyc.unlink()
    env = dict(os.environ, PYTHONPATH=str(folder))
    out = subprocess.run([sys.executable, "-c", CHILD, module], capture_output=True, text=True, env=env,
                         cwd=folder, check=True)
    return json.loads(out.stdout.strip().splitlines()[-1])


def measure(tmp: Path, repeats: int, messages: int = MESSAGES) -> dict:
    """{"messages": n, (contender, cached): (median CPU s, median wall s)}, the contenders
    interleaved round by round."""
    contenders = prepare(tmp, messages)
    samples: dict = {(name, cached): [] for name in contenders for cached in (True, False)}
    for _ in range(repeats):
        for (name, cached), got in samples.items():
            got.append(_import_once(*contenders[name], cached))
    figures = {key: (statistics.median(s["cpu"] for s in got), statistics.median(s["wall"] for s in got))
               for key, got in samples.items()}
    return dict(figures, messages=messages, repeats=repeats)


def section(r: dict, verdicts: list, met) -> list[str]:
    """Section 9 of bench/RESULTS.md; appends its verdicts (codeword no slower, both ways)."""
    lines = ["## 9. Importing a protocol of MAVLink's size", "",
             f"`bench/imports.py`: `import` of codeword's Python module for a MAVLink-shaped protocol of "
             f"{r['messages']} messages of eight fields (`bench/scaling.py`, as section 5) and of pymavlink's "
             "common dialect (`pymavlink.dialects.v20.common`, a copy of the installed package), each in a new "
             "process, the modules they import included; medians of "
             f"{r['repeats']} interleaved rounds. Cached: the module's bytecode is there, as for an installed "
             "package. From source: it is not (a module just generated), and is not written.", "",
             "| module | cached, CPU ms | from source, CPU ms |", "|---|---:|---:|"]
    for name in ("codeword", "pymavlink common"):
        lines.append(f"| {name} | {r[(name, True)][0] * 1e3:.1f} | {r[(name, False)][0] * 1e3:.1f} |")
    lines.append("")
    for cached, how in ((True, "cached"), (False, "from source")):
        ratio = r[("codeword", cached)][0] / r[("pymavlink common", cached)][0]
        ok = ratio <= 1.0
        verdicts.append(ok)
        lines.append(f"- {how}: codeword / pymavlink = {ratio:.2f} (target ≤ 1.0): {met(ok)}")
        if not ok and not cached:
            lines.append("  - from source, the import is mostly Python compiling the module: codeword writes a "
                         "straight-line encoder and decoder for each message (its speed), where pymavlink "
                         "decodes every message with one table-driven function")
    return lines
