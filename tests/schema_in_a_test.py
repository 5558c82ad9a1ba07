"""Schemas written by a test: build one into a temporary folder, import its
Python codec, compile and run a C driver against its header."""
from __future__ import annotations

import importlib.util
import json
import re
import shutil
import subprocess
import sys
from pathlib import Path

from codeword.build import build, compile_schema, render_protocol, verify

from cdriver import Driver, firmware_source

C_FLAGS = ["-std=c99", "-g", "-O1", "-fsanitize=address,undefined", "-fno-sanitize-recover=all",
           "-Wall", "-Wextra", "-Werror"]


def render(where: Path, name: str, schema: str) -> Path:
    """Write the schema and its Python module and C headers into `where`; the schema's
    own examples must hold."""
    path = where / f"{name}.yaml"
    path.write_text(schema, encoding="utf-8")
    protocol = compile_schema(path)
    files = render_protocol(protocol)
    verify(protocol, files)
    for rel in (f"python/{name}.py", f"c/{name}.h", "c/codeword.h"):
        (where / Path(rel).name).write_text(files[rel], encoding="utf-8")
    return where


def load(path: Path):
    """Import a generated module from its file, under a name unique to its folder."""
    key = f"{path.stem}_{path.parent.name}"
    spec = importlib.util.spec_from_file_location(key, path)
    module = importlib.util.module_from_spec(spec)
    sys.modules[key] = module  # dataclasses look their module up while the class is made
    spec.loader.exec_module(module)
    return module


def run_c(where: Path, driver: str, extra_flags: tuple[str, ...] = ()) -> list[str]:
    """Compile `driver` against the headers in `where` with the sanitizers; its output lines."""
    gcc = shutil.which("gcc")
    assert gcc, "gcc is not installed (.ci/run installs it)"
    src, exe = where / "driver.c", where / "driver"
    src.write_text(driver, encoding="utf-8")
    build = subprocess.run([gcc, *C_FLAGS, *extra_flags, "-I", str(where), str(src), "-o", str(exe)],
                           capture_output=True, text=True, timeout=300)
    assert build.returncode == 0, build.stderr
    run = subprocess.run([str(exe)], capture_output=True, text=True, timeout=60)
    assert run.returncode == 0, run.stdout + run.stderr
    return run.stdout.splitlines()


def show_calls(frames: list[str]) -> str:
    """C statements that pass each frame (spaced hex) to the driver's show(hex, bytes, length)."""
    return "\n".join(
        f"    {{ static const uint8_t f[] = {{{', '.join(f'0x{b:02x}' for b in bytes.fromhex(h))}}};"
        f" show(\"{h}\", f, sizeof f); }}"
        for h in frames)


def build_example(name: str, out: Path) -> Path:
    """`codeword build examples/<name>.yaml --out OUT`, as a user runs it; the codec
    and the headers are also copied into OUT itself, for `load` and `run_c`."""
    root = Path(__file__).resolve().parent.parent
    run = subprocess.run([sys.executable, "-m", "codeword", "build", str(root / "examples" / f"{name}.yaml"),
                          "--out", str(out)], capture_output=True, text=True, timeout=300, cwd=root)
    assert run.returncode == 0, run.stdout + run.stderr
    for rel in (f"python/{name}.py", f"c/{name}.h", "c/codeword.h"):
        (out / Path(rel).name).write_text((out / rel).read_text(encoding="utf-8"), encoding="utf-8")
    return out


def c_bytes(data: bytes) -> str:
    """The bytes as the items of a C array initialiser."""
    return ", ".join(f"0x{b:02x}" for b in data)



def conformance_on_host_and_avr(where: Path, name: str, schema: str, parts: int = 4) -> tuple[int, int]:
    """Python's vectors of the schema (valid frames, damaged ones, streams) through the
    C conformance driver, on the host with the sanitizers and on an ATmega32 (whose
    `int` is 16 bits) under simavr, the vectors in `parts` programs that each fit its
    32 KiB of flash: the checks passed on each."""
    (where / f"{name}.yaml").write_text(schema, encoding="utf-8")
    out = where / "out"
    assert not build([where / f"{name}.yaml"], out, root=where).errors
    protocol = compile_schema(where / f"{name}.yaml")
    vectors = json.loads((out / "vectors" / f"{name}.json").read_text(encoding="utf-8"))
    for rel in (f"{name}.h", "codeword.h"):
        shutil.copy(out / "c" / rel, where / rel)
    host = passed("\n".join(run_c(where, Driver(protocol).source(vectors))), name)
    avr_gcc, simavr = shutil.which("avr-gcc"), shutil.which("simavr")
    assert avr_gcc and simavr, "avr-gcc and simavr are not installed (.ci/run installs them)"
    avr = 0
    for part in range(parts):
        src, elf = where / f"avr_{part}.c", where / f"avr_{part}.elf"
        src.write_text(Driver(protocol).source(vectors, part, parts), encoding="utf-8")
        made = subprocess.run([avr_gcc, "-std=gnu99", "-Os", "-mmcu=atmega32", "-Wall", "-Wextra", "-Werror",
                               "-ffunction-sections", "-fdata-sections", "-Wl,--gc-sections",
                               "-I", str(where), str(src), "-o", str(elf)], capture_output=True, text=True)
        assert made.returncode == 0, made.stderr[-3000:]
        ran = subprocess.run([simavr, "-m", "atmega32", "-f", "16000000", str(elf)], capture_output=True,
                             text=True, timeout=600, errors="replace")
        avr += passed(ran.stdout + ran.stderr, name)
    return host, avr


def passed(output: str, name: str) -> int:
    """The checks of a conformance driver that passed them all."""
    found = re.search(rf"CONFORMANCE {name} PASS (\d+) checks 0 failures", re.sub(r"\x1b\[[0-9;]*m", "", output))
    assert found, output[-3000:]
    return int(found.group(1))


STRICT_WARNINGS = ["-std=c99", "-Wall", "-Wextra", "-Wpedantic", "-Wconversion", "-Wsign-conversion", "-Wshadow",
                   "-Werror"]


def firmware_warnings(where: Path, name: str, compiler: str, level: str) -> str:
    """Compile (-c) the codec of the header in `where` as firmware uses it
    (cdriver.firmware_source) with the strict warnings at `level`: the compiler's
    complaints, empty when there are none."""
    path = shutil.which(compiler)
    assert path, f"{compiler} is not installed (.ci/run installs it)"
    src = where / f"firmware_{compiler}{level}.c"
    src.write_text(firmware_source(compile_schema(where / f"{name}.yaml")), encoding="utf-8")
    built = subprocess.run([path, *STRICT_WARNINGS, level, "-I", str(where), "-c", str(src), "-o",
                            str(src.with_suffix(".o"))], capture_output=True, text=True, timeout=300)
    return built.stderr if built.returncode != 0 else ""
