"""Build: schemas → model → rendered files → (check examples) → write or compare.

Rendering is pure (returns {path: text}; the vectors, much the largest output,
go to a temporary file); writing is separate so that `--check` can compare
instead of writing.
"""
from __future__ import annotations

import types
from dataclasses import dataclass, field
from pathlib import Path

from .accelerate import is_accelerator
from .diagnostics import Diagnostic, Loc, SchemaError
from .examples import check_examples
from .loader import load_file
from .ownership import written_by_codeword
from .model import Protocol
from .project import Project
from .pyload import load_module
from .resolver import resolve
from .spool import InPlace, Spool, file_sha256
from . import cache
from .targets import accelerator as accelerator_target
from .targets import python as python_target
from .targets import c as c_target
from .targets.c.view import CTargetError
from .targets.machines.packets import MachineTargetError
from .targets import markdown as markdown_target
from .targets import promela as promela_target
from .targets.markdown.site import is_generated, render_site
from .vectors import write_vectors


def schema_files(directory: Path) -> list[Path]:
    return sorted(p for p in directory.glob("*.yaml") if p.is_file())


def compile_schema(path: Path, display: str | None = None) -> Protocol:
    return resolve(load_file(path, display))


def render_protocol(p: Protocol) -> dict[str, str]:
    return render_with_codec(p)[0]


def render_with_codec(p: Protocol) -> tuple[dict[str, str], types.ModuleType]:
    """Every target's files and the generated Python codec, loaded once and the
    schema's examples checked with it: the docs run it for their examples and the
    build for its vectors. The Promela target writes a model only for schemas that
    declare machines."""
    files: dict[str, str] = {}
    try:
        files.update(python_target.render(p))
        files.update(c_target.render(p))
        files.update(accelerator_target.render(p))
    except (CTargetError, MachineTargetError) as exc:  # a shape a target cannot serve: say so against the schema
        target = "C target" if isinstance(exc, CTargetError) else "machines"
        fallback = p.machines[0].loc if isinstance(exc, MachineTargetError) and p.machines else Loc(p.file, 1, 1)
        raise SchemaError([Diagnostic(exc.loc or fallback, f"{target}: {exc}",
                                      "change the schema as the message says; every schema must "
                                      "build for every target")]) from None
    codec = checked(p, load_codec(p, files))  # the docs show only examples that hold
    files.update(markdown_target.render(p, codec))
    files.update(promela_target.render(p))
    return files, codec


def load_codec(p: Protocol, files: dict[str, str]) -> types.ModuleType:
    path = f"python/{p.name}.py"
    try:
        return load_module(f"_codeword_check_{p.name}", files[path], path)
    except Exception as exc:  # a generator bug, but report it against the schema
        raise SchemaError([Diagnostic(Loc(p.file, 1, 1),
                                      f"generated Python does not load: {type(exc).__name__}: {exc}",
                                      "this is a codeword bug; please report it with the schema")]) from exc


def checked(p: Protocol, module: types.ModuleType) -> types.ModuleType:
    problems = check_examples(p, module)
    if problems:
        raise SchemaError(problems)
    return module


def verify(p: Protocol, files: dict[str, str]):
    """Load the generated Python codec, run every example through it, return it."""
    return checked(p, load_codec(p, files))


def vector_spool(p: Protocol, codec: types.ModuleType) -> Spool:
    """The conformance vectors, written to a temporary file as they are made: for a
    large protocol they are far larger than every other output together."""
    spool = Spool()
    write_vectors(p, codec, spool.file)
    return spool


def vectors_for(p: Protocol, codec: types.ModuleType, target: Path | None) -> Spool | InPlace:
    """The vectors, or InPlace when `target` already holds those the same schema, codec
    and compiler made before (their hash is kept in the build cache)."""
    place = cache.slot("vectors", p.name)
    wanted = cache.key("vectors", p.sha256, getattr(codec, "__source_sha256__", None), cache.compiler_hash())
    made = cache.load(place, wanted)
    if made is not None and target is not None and file_sha256(target) == made.decode("ascii", "replace"):
        return InPlace(target)
    spool = vector_spool(p, codec)
    cache.store(place, wanted, spool.sha256().encode("ascii"))
    return spool


@dataclass
class BuildResult:
    # where each file goes, as the command line names it
    written: list[Path] = field(default_factory=list)
    unchanged: list[Path] = field(default_factory=list)
    stale: list[Path] = field(default_factory=list)  # check mode: differ or missing
    extra: list[Path] = field(default_factory=list)  # check mode: generated files with no schema
    foreign: list[Path] = field(default_factory=list)  # files in the way that codeword did not write: nothing written
    notes: list[str] = field(default_factory=list)  # what the build left alone, and why
    errors: list[Diagnostic] = field(default_factory=list)


def build(schemas: list[Path], out: Path | Project, check: bool = False, root: Path | None = None,
          all_schemas: list[Path] | None = None) -> BuildResult:
    """Build `schemas` into the project's output folders (or into `out/<target>/`).

    `all_schemas` are every schema of the project: the docs index lists them all
    and, in check mode, files that none of them generates are reported, so that
    building some schemas leaves the others' outputs and the index correct."""
    project = out if isinstance(out, Project) else Project(root=root or Path.cwd(), config=None, out=out)
    building_all = all_schemas is None or {p.resolve() for p in all_schemas} <= {p.resolve() for p in schemas}
    result = BuildResult()
    expected: dict[str, str | Spool | InPlace] = {}
    protocols: list[Protocol] = []
    for path in schemas:
        display = _display(path, root)
        try:
            protocol = compile_schema(path, display)
            files, codec = render_with_codec(protocol)
            if "vectors" in project.targets:
                rel = f"vectors/{protocol.name}.json"
                files[rel] = vectors_for(protocol, codec, _place(project, rel))
        except SchemaError as exc:
            result.errors.extend(exc.diagnostics)
            continue
        expected.update(files)
        protocols.append(protocol)
    if result.errors:
        _close(expected)
        return result
    listed = protocols + ([] if building_all else _others(all_schemas or [], protocols, root))
    if listed:
        expected.update(markdown_target.render_index(listed))
    placed = {place: text for rel, text in expected.items() if (place := _place(project, rel)) is not None}
    if project.python_package and "python" in project.targets and protocols:
        package = project.folder("python") / project.python_package
        placed[package / "__init__.py"] = package_init(listed)
        placed[package / "py.typed"] = ""  # PEP 561: type checkers read the modules' annotations
    placed.update(_site(project, listed, result))
    changed = []
    for target, text in sorted(placed.items()):
        if isinstance(text, InPlace):
            same = text.path == target
        elif isinstance(text, Spool):
            same = text.same_as(target)
        else:
            same = (_read(target) if target.is_file() else None) == text
        if same:
            result.unchanged.append(target)
        elif check:
            result.stale.append(target)
        elif not written_by_codeword(target, text if isinstance(text, str) else ""):
            result.foreign.append(target)
        else:
            changed.append((target, text))
    if result.foreign:  # a file of someone else's in the way: write none, rather than some
        changed = []
    for target, text in changed:
        target.parent.mkdir(parents=True, exist_ok=True)
        if isinstance(text, Spool):
            text.write_to(target)
        else:
            target.write_text(text, encoding="utf-8")
        result.written.append(target)
    _close(expected)
    if check and building_all:
        known = set(placed)
        folders = {project.folder(t) for t in project.targets}
        # only the folders this build writes to: a subfolder may hold another project's
        # output (examples/ puts its pages in generated/docs/examples for the site)
        ours = folders | {path.parent for path in placed}
        for folder in sorted(folders):
            if not folder.is_dir():
                continue
            for existing in sorted(folder.rglob("*")):
                if existing.is_file() and existing not in known and existing.parent in ours \
                        and "__pycache__" not in existing.parts and not is_accelerator(existing):
                    result.extra.append(existing)
    return result


def _read(path: Path) -> str | None:
    """A file's text; None if it is not UTF-8 text (then it is not the same as any output)."""
    try:
        return path.read_text(encoding="utf-8")
    except UnicodeDecodeError:
        return None


def _site(project: Project, listed: list[Protocol], result: BuildResult) -> dict[Path, str]:
    """The project's MkDocs configuration, unless it has none or keeps its own."""
    if project.site is None or "docs" not in project.targets or not listed:
        return {}
    if not is_generated(project.site):
        result.notes.append(f"{project.site}: not written by codeword, left as it is (name another file with "
                            "`[docs] site = \"...\"` in codeword.toml, or none with `site = false`)")
        return {}
    return render_site(listed, project.site, project.folder("docs"))


def _display(path: Path, root: Path | None) -> str:
    """How generated files name their schema: relative to the project's root, so
    that they are the same whichever folder the build ran from."""
    if root is None:
        return str(path)
    try:
        return path.resolve().relative_to(root.resolve()).as_posix()
    except ValueError:
        return str(path)


def _place(project: Project, rel: str) -> Path | None:
    """Where a rendered file goes: `python/x.py` into the python folder, and so on;
    None for a target the project does not build."""
    target, _, rest = rel.partition("/")
    if target not in project.targets:
        return None
    folder = project.folder(target)
    if target == "python" and project.python_package:
        folder = folder / project.python_package
    return folder / rest


def _others(all_schemas: list[Path], built: list[Protocol], root: Path | None) -> list[Protocol]:
    """The project's other protocols, for the index; one that does not resolve is
    left out of it (its own build reports why)."""
    names = {p.name for p in built}
    others = []
    for path in all_schemas:
        try:
            protocol = compile_schema(path, _display(path, root))
        except SchemaError:
            continue
        if protocol.name not in names:
            others.append(protocol)
    return others


def package_init(protocols: list[Protocol]) -> str:
    names = ", ".join(sorted(p.name for p in protocols))
    return (f'"""Protocol codecs generated by codeword: {names}.\n\n'
            'Each module is stand-alone; import the one you need."""\n')


def _close(expected: dict[str, str | Spool | InPlace]) -> None:
    for text in expected.values():
        if isinstance(text, Spool):
            text.close()
