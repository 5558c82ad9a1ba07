"""`codeword accelerate`: compile each protocol's accelerator, the optional C module
that decodes frames for its generated Python module, with the system's C compiler.

The accelerator is made from the generated C header and `_<name>_accel.c` (both
rendered from the schema here, whatever targets the project writes) and put beside
the Python module as `_<name>_accel<EXT_SUFFIX>`. Without a C compiler or Python's
headers nothing is built and the module decodes in pure Python, as it does wherever
no accelerator is found; a module also leaves an accelerator made from another
version of its schema. An accelerator already built from the same sources is kept.
"""
from __future__ import annotations

import hashlib
import os
import shlex
import shutil
import subprocess
import sys
import sysconfig
import tempfile
from dataclasses import dataclass, field
from pathlib import Path
from typing import Optional

from .loader import load_file
from .resolver import resolve
from .targets import accelerator as accelerator_target
from .targets import c as c_target

BUILD_MARK = b"codeword-accelerator-build:"
FLAGS = ("-O2", "-shared", "-fPIC", "-ffp-contract=off")  # no fused multiply-add: C rounds as Python does
# macOS links an extension against the interpreter that loads it, not against libpython
PLATFORM_FLAGS = ("-undefined", "dynamic_lookup") if sys.platform == "darwin" else ()


@dataclass
class Outcome:
    built: list[Path] = field(default_factory=list)
    unchanged: list[Path] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)  # what was not built, and why


def extension_suffix() -> str:
    return sysconfig.get_config_var("EXT_SUFFIX") or ".so"


def is_accelerator(path: Path) -> bool:
    """A compiled accelerator (built, never generated: `build --check` leaves it alone)."""
    return path.name.startswith("_") and "_accel." in path.name and path.suffix in (".so", ".pyd")


def compiler() -> Optional[list[str]]:
    """The C compiler command: $CC, Python's own, or cc; None when there is none."""
    command = shlex.split(os.environ.get("CC") or sysconfig.get_config_var("CC") or "cc")
    if command and shutil.which(command[0]):
        return command
    return shutil.which("cc") and ["cc"]


def python_headers() -> Optional[Path]:
    include = Path(sysconfig.get_paths()["include"])
    return include if (include / "Python.h").is_file() else None


def accelerate(schemas: list[Path], folder: Path, extra_flags: tuple[str, ...] = ()) -> Outcome:
    """Build the accelerator of each schema whose Python module has one, into `folder`."""
    outcome = Outcome()
    if sys.platform == "win32":  # MSVC takes other flags: not supported yet
        outcome.notes.append("no accelerators built: Windows is not supported yet; the Python modules "
                             "decode in pure Python")
        return outcome
    cc, include = compiler(), python_headers()
    if cc is None or include is None:
        missing = "a C compiler (cc, or $CC)" if cc is None else f"Python's headers ({sysconfig.get_paths()['include']})"
        outcome.notes.append(f"no accelerators built: {missing} not found; the Python modules decode in pure Python")
        return outcome
    for schema in schemas:
        p = resolve(load_file(schema))
        sources = {**c_target.render(p), **accelerator_target.render(p)}
        main = f"python/_{p.name}_accel.c"
        if main not in sources:
            outcome.notes.append(f"{p.name}: no message the accelerator serves; decoded in pure Python")
            continue
        command = [*cc, *FLAGS, *PLATFORM_FLAGS, *extra_flags, f"-I{include}"]
        digest = hashlib.sha256(repr((command, sorted(sources.items()))).encode()).hexdigest()[:32]
        target = folder / f"_{p.name}_accel{extension_suffix()}"
        if target.is_file() and BUILD_MARK + digest.encode() in target.read_bytes():
            outcome.unchanged.append(target)
            continue
        folder.mkdir(parents=True, exist_ok=True)
        _compile(command, sources, main, digest, target)
        outcome.built.append(target)
    return outcome


class CompileError(Exception):
    """The C compiler refused an accelerator: a codeword bug, or a compiler it does not suit."""


def _compile(command: list[str], sources: dict[str, str], main: str, digest: str, target: Path) -> None:
    with tempfile.TemporaryDirectory(prefix="codeword-accel-") as tmp:
        for rel, text in sources.items():
            (Path(tmp) / Path(rel).name).write_text(text, encoding="utf-8")
        partial = Path(tmp) / target.name
        run = subprocess.run([*command, f"-I{tmp}", f'-DCW_ACCEL_BUILD="{digest}"', "-o", str(partial),
                              str(Path(tmp) / Path(main).name)], capture_output=True, text=True)
        if run.returncode != 0:
            raise CompileError(f"{' '.join(command)} failed on {Path(main).name}:\n{run.stderr.strip()}")
        shutil.copyfile(partial, target.with_suffix(".partial"))
        os.replace(target.with_suffix(".partial"), target)  # an importer never sees half a file
