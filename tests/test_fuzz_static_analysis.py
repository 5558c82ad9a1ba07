"""Static analysis of every generated C header: cppcheck and gcc -fanalyzer, clean.

All headers are included into one translation unit; -fkeep-inline-functions makes
gcc emit (and so analyse) every static inline function, not only the used ones.
A missing tool is a failure: CI installs both (.ci/run).
"""
from __future__ import annotations

import shutil
import subprocess
from pathlib import Path

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


def test_cppcheck_finds_nothing(tmp_path: Path):
    proc = subprocess.run([tool("cppcheck"), "--enable=warning,portability,performance", "--inconclusive",
                           "--std=c99", "--error-exitcode=1", "--quiet", "--suppress=missingIncludeSystem",
                           f"-I{INCLUDE}", str(unit(tmp_path))], capture_output=True, text=True, timeout=600)
    assert proc.returncode == 0 and not proc.stderr.strip(), proc.stderr


def test_gcc_analyzer_finds_nothing(tmp_path: Path):
    proc = subprocess.run([tool("gcc"), "-std=c99", "-fanalyzer", "-fkeep-inline-functions", "-O0", "-Wall",
                           "-Wextra", "-Werror", f"-I{INCLUDE}", "-c", str(unit(tmp_path)), "-o",
                           str(tmp_path / "all.o")], capture_output=True, text=True, timeout=600)
    assert proc.returncode == 0 and "warning" not in proc.stderr, proc.stderr
