"""Edges of the generated C text codec (tests/c/text_edges.c) in each of its
builds: -O2 (decimals read by the 32-bit fast path, the body split eight bytes
at a time), -Os (every decimal by the general reader) and with no byte order
known (the body split byte by byte, as on 8- and 32-bit targets); each under
ASan and UBSan."""
from __future__ import annotations

import re
import shutil
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
INCLUDE = ROOT / "generated" / "c"
SOURCE = Path(__file__).resolve().parent / "c" / "text_edges.c"
BUILDS = {"fast": ["-O2"], "size": ["-Os"], "bytewise": ["-O2", "-U__BYTE_ORDER__"]}


@pytest.mark.parametrize("build", BUILDS)
def test_text_edges(tmp_path: Path, build: str):
    gcc = shutil.which("gcc")
    assert gcc, "gcc is not installed"
    exe = tmp_path / "text_edges"
    flags = [*BUILDS[build], "-std=c99", "-g", "-fsanitize=address,undefined", "-fno-sanitize-recover=all",
             "-Wall", "-Wextra", "-Werror"]
    proc = subprocess.run([gcc, *flags, "-I", str(INCLUDE), str(SOURCE), "-o", str(exe)],
                          capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stderr
    run = subprocess.run([str(exe)], capture_output=True, text=True, timeout=60)
    assert run.returncode == 0 and re.search(r"TEXT EDGES PASS \d+ checks 0 failures", run.stdout), \
        run.stdout + run.stderr
