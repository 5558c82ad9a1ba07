"""`--mypy`: the Python module of each generated schema through `mypy --strict`, all in
one run (a schema that builds must give a module that type-checks)."""
from __future__ import annotations

import subprocess
import sys
import tempfile
from pathlib import Path

from codeword.build import compile_schema
from codeword.diagnostics import SchemaError
from codeword.targets.python import render

from .generate import generate


def mypy_problems(seeds: range, features: frozenset[str]) -> list[str]:
    """One line per mypy error in the modules of `seeds`; schemas that do not build are skipped."""
    with tempfile.TemporaryDirectory(prefix="fz-mypy-") as tmp:
        folder = Path(tmp)
        modules = []
        for seed in seeds:
            path = folder / f"fz{seed}.yaml"
            path.write_text(generate(seed, features), encoding="utf-8")
            try:
                files = render(compile_schema(path))
            except SchemaError:
                continue  # the main run reports it
            for text in files.values():
                modules.append(folder / f"fz{seed}.py")
                modules[-1].write_text(text, encoding="utf-8")
        if not modules:
            return []
        proc = subprocess.run([sys.executable, "-m", "mypy", "--strict", "--cache-dir", str(folder / ".mypy"),
                               *map(str, modules)], cwd=folder, capture_output=True, text=True)
        if proc.returncode == 0:
            return []
        return [line for line in (proc.stdout + proc.stderr).splitlines() if ": error:" in line] or [proc.stdout]
