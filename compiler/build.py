"""Build: schemas → model → rendered files → (check examples) → write or compare.

Rendering is pure (returns {path: text}); writing is separate so that
`--check` can compare instead of writing.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

from .diagnostics import Diagnostic, Loc, SchemaError
from .examples import check_examples
from .loader import load_file
from .model import Protocol
from .pyload import load_module
from .resolve import resolve
from .targets import python as python_target
from .targets import c as c_target
from .targets import markdown as markdown_target
from .targets import promela as promela_target
from .vectors import vector_file

# The Markdown target runs the generated Python codec to write its examples.
# The Promela target writes a model only for schemas that declare machines.
TARGETS = (python_target, c_target, markdown_target, promela_target)


def schema_files(directory: Path) -> list[Path]:
    return sorted(p for p in directory.glob("*.yaml") if p.is_file())


def compile_schema(path: Path, display: str | None = None) -> Protocol:
    return resolve(load_file(path, display))


def render_protocol(p: Protocol) -> dict[str, str]:
    files: dict[str, str] = {}
    for target in TARGETS:
        files.update(target.render(p))
    return files


def verify(p: Protocol, files: dict[str, str]):
    """Load the generated Python codec, run every example through it, return it."""
    path = f"python/{p.name}.py"
    try:
        module = load_module(f"_codeword_check_{p.name}", files[path], path)
    except Exception as exc:  # a generator bug, but report it against the schema
        raise SchemaError([Diagnostic(Loc(p.file, 1, 1),
                                      f"generated Python does not load: {type(exc).__name__}: {exc}",
                                      "this is a codeword bug; please report it with the schema")]) from exc
    problems = check_examples(p, module)
    if problems:
        raise SchemaError(problems)
    return module


@dataclass
class BuildResult:
    written: list[str] = field(default_factory=list)
    unchanged: list[str] = field(default_factory=list)
    stale: list[str] = field(default_factory=list)  # check mode: differ or missing
    extra: list[str] = field(default_factory=list)  # check mode: generated files with no schema
    errors: list[Diagnostic] = field(default_factory=list)


def build(schemas: list[Path], out: Path, check: bool = False, root: Path | None = None) -> BuildResult:
    result = BuildResult()
    expected: dict[str, str] = {}
    protocols: list[Protocol] = []
    for path in schemas:
        display = str(path.relative_to(root)) if root and path.is_relative_to(root) else str(path)
        try:
            protocol = compile_schema(path, display)
            files = render_protocol(protocol)
            module = verify(protocol, files)
            files[f"vectors/{protocol.name}.json"] = vector_file(protocol, module)
        except SchemaError as exc:
            result.errors.extend(exc.diagnostics)
            continue
        expected.update(files)
        protocols.append(protocol)
    if result.errors:
        return result
    if protocols:
        expected.update(markdown_target.render_index(protocols))
    for rel, text in sorted(expected.items()):
        target = out / rel
        current = target.read_text(encoding="utf-8") if target.exists() else None
        if current == text:
            result.unchanged.append(rel)
        elif check:
            result.stale.append(rel)
        else:
            target.parent.mkdir(parents=True, exist_ok=True)
            target.write_text(text, encoding="utf-8")
            result.written.append(rel)
    if check and out.exists():
        known = set(expected)
        for existing in sorted(out.rglob("*")):
            rel = existing.relative_to(out).as_posix()
            if existing.is_file() and rel not in known and "__pycache__" not in rel:
                result.extra.append(rel)
    return result
