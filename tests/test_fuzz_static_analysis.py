"""Static analysis of every generated C header: cppcheck and gcc -fanalyzer, clean.

All headers are included into one translation unit; -fkeep-inline-functions makes
gcc emit (and so analyse) every static inline function, not only the used ones.
A missing tool is a failure: CI installs both (.ci/run).
"""
from __future__ import annotations

import re
import shutil
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
INCLUDE = ROOT / "generated" / "c"


def unit(tmp_path: Path) -> Path:
    headers = sorted(p.name for p in INCLUDE.glob("*.h") if p.name != "codeword.h")
    assert headers
    src = tmp_path / "all_headers.c"
    src.write_text("".join(f'#include "{h}"\n' for h in headers) + "int main(void) { return 0; }\n")
    return src


def tool(name: str) -> str:
    path = shutil.which(name)
    assert path, f"{name} is not installed (CI installs it in .ci/run)"
    return path


def configurations() -> dict[str, list[str]]:
    """The builds a firmware makes of the headers, each as its -D flags: the default, each
    CRC method, no message selected and every one selected (one -D makes cppcheck check that
    configuration alone; left to itself it tries a dozen of the thousands the macros make)."""
    prefixes = sorted(p.stem.upper() for p in INCLUDE.glob("*.h") if p.name != "codeword.h")
    text = "".join(p.read_text(encoding="utf-8") for p in INCLUDE.glob("*.h"))
    methods = sorted({m for m in re.findall(r"defined\([A-Z0-9]+_CRC_([A-Z0-9]+)\)", text)} - {"SPLIT"})
    out = {"default": ["-DCW_DEFAULT_BUILD"]}
    for method in methods:
        out[f"CRC {method}"] = [f"-D{px}_CRC_{method}" for px in prefixes if f"{px}_CRC_{method}" in text]
    out["no message selected"] = [f"-D{px}_SELECTED_MESSAGES" for px in prefixes]
    out["every message selected"] = out["no message selected"] + sorted(
        f"-D{name}" for name in set(re.findall(r"defined\(([A-Z0-9_]+_SELECT_[A-Z0-9_]+)\)", text)))
    return out


@pytest.mark.parametrize("configuration", sorted(configurations()))
def test_cppcheck_finds_nothing(tmp_path: Path, configuration: str):
    proc = subprocess.run([tool("cppcheck"), "--enable=warning,portability,performance", "--inconclusive",
                           "--std=c99", "--error-exitcode=1", "--quiet", "--suppress=missingIncludeSystem",
                           *configurations()[configuration], f"-I{INCLUDE}", str(unit(tmp_path))],
                          capture_output=True, text=True, timeout=600)
    assert proc.returncode == 0 and not proc.stderr.strip(), proc.stderr


def test_gcc_analyzer_finds_nothing(tmp_path: Path):
    proc = subprocess.run([tool("gcc"), "-std=c99", "-fanalyzer", "-fkeep-inline-functions", "-O0", "-Wall",
                           "-Wextra", "-Werror", f"-I{INCLUDE}", "-c", str(unit(tmp_path)), "-o",
                           str(tmp_path / "all.o")], capture_output=True, text=True, timeout=600)
    assert proc.returncode == 0 and "warning" not in proc.stderr, proc.stderr
