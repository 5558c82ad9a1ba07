"""A user's project: where its schemas are, which targets it builds, and where
each target's files go.

Read from `codeword.toml`, or from `[tool.codeword]` in `pyproject.toml`, in the
current folder or the nearest folder above it; without either, the defaults
(every `schemas/*.yaml`, every target, into `generated/<target>/`, the MkDocs
configuration of the docs as `mkdocs.yml`). Paths in the configuration are
relative to the file that holds it.

A configuration may come from someone else (a cloned repository): the folders and
files it has written to (`out`, `[outputs]`, `[docs] site`) must lie inside the
project, the repository holding the configuration (or, outside one, the
configuration's own folder). A folder elsewhere is written only when the command
line names it (`--out`).
"""
from __future__ import annotations

import sys
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any, Optional

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover - Python 3.10
    import tomli as tomllib

from .names import protocol_name_problem

CONFIG_FILE = "codeword.toml"
TARGETS = ("python", "c", "docs", "vectors", "promela")
KEYS = {"schemas", "targets", "out", "outputs", "python", "docs"}
SITE_FILE = "mkdocs.yml"


class ProjectError(Exception):
    """The configuration cannot be used as written (a usage error, exit status 2)."""


@dataclass(frozen=True)
class Project:
    root: Path  # the folder the configuration's paths are relative to
    config: Optional[Path]  # the file it came from; None for the defaults
    schema_paths: tuple[Path, ...] = (Path("schemas"),)
    targets: tuple[str, ...] = TARGETS
    out: Path = Path("generated")
    outputs: tuple[tuple[str, Path], ...] = ()  # per-target folders that differ from out/<target>
    python_package: Optional[str] = None
    # the MkDocs configuration written for the docs; None: none (a build into
    # another folder, or a project that configures `[docs] site = false`)
    site: Optional[Path] = None
    # what the configuration names to write outside the project: (key, why refused)
    outside: tuple[tuple[str, str], ...] = ()

    def writable(self) -> "Project":
        """The project, if every place it writes to lies inside it (or was named on the
        command line); else a ProjectError at the configuration's line."""
        if self.outside:
            raise ProjectError(self.outside[0][1])
        return self

    def folder(self, target: str) -> Path:
        """Where a target's files go, relative to the working folder."""
        return dict(self.outputs).get(target, self.out / target)

    def schema_files(self) -> list[Path]:
        files: list[Path] = []
        for path in self.schema_paths:
            if path.is_dir():
                files.extend(sorted(p for p in path.glob("*.yaml") if p.is_file()))
            elif path.is_file():
                files.append(path)
        return files

    def find_schema(self, name: str) -> Optional[Path]:
        """A schema named by its protocol name (its file's stem) or by its file."""
        path = Path(name)
        if path.is_file():
            return path
        if "/" in name or name.endswith((".yaml", ".yml")):
            return None
        for file in self.schema_files():
            if file.stem == name:
                return file
        return None

    def describe_schemas(self) -> str:
        return ", ".join(f"{p}/" if p.is_dir() or not p.suffix else str(p) for p in self.schema_paths)

    def with_options(self, schema_dir: Optional[str] = None, out: Optional[str] = None,
                     targets: Optional[str] = None) -> "Project":
        """The project as the command line overrides it."""
        changes: dict[str, Any] = {}
        if schema_dir is not None:
            changes["schema_paths"] = (Path(schema_dir),)
        if out is not None:  # a build elsewhere leaves the project's site configuration alone
            changes["out"] = Path(out)
            changes["outputs"] = ()
            changes["site"] = None
            changes["outside"] = ()  # every place the build writes to is now the command line's
        if targets is not None:
            changes["targets"] = parse_targets([t.strip() for t in targets.split(",") if t.strip()], "--targets")
        if not changes:
            return self
        return replace(self, **changes)


def parse_targets(names: list, where: str) -> tuple[str, ...]:
    if not names:
        raise ProjectError(f"{where}: name at least one target ({', '.join(TARGETS)})")
    unknown = [n for n in names if n not in TARGETS]
    if unknown:
        raise ProjectError(f"{where}: unknown target {unknown[0]!r} (targets: {', '.join(TARGETS)})")
    return tuple(t for t in TARGETS if t in names)


def find_config(start: Path) -> Optional[tuple[Path, dict]]:
    """The nearest codeword.toml, or pyproject.toml with a [tool.codeword] table."""
    for folder in (start, *start.parents):
        candidate = folder / CONFIG_FILE
        if candidate.is_file():
            return candidate, _read(candidate)
        pyproject = folder / "pyproject.toml"
        if pyproject.is_file():
            table = _read(pyproject).get("tool", {}).get("codeword")
            if table is not None:
                return pyproject, table
    return None


def _read(path: Path) -> dict:
    try:
        return tomllib.loads(path.read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError) as exc:
        raise ProjectError(f"{path}: cannot read: {exc}") from None
    except tomllib.TOMLDecodeError as exc:
        raise ProjectError(f"{path}: {exc}") from None


def project_bounds(config: Path) -> Path:
    """The folder a configuration may write into: the repository holding it, found by
    its `.git`, or else the configuration's own folder."""
    folder = config.resolve().parent
    for candidate in (folder, *folder.parents):
        if (candidate / ".git").exists():
            return candidate
    return folder


def _line_of(path: Path, value: str) -> Optional[int]:
    """The line of the configuration that spells `value` (a path), for the error."""
    try:
        lines = path.read_text(encoding="utf-8").splitlines()
    except (OSError, UnicodeDecodeError):
        return None
    quoted = (f'"{value}"', f"'{value}'", f'"{value.replace(chr(92), chr(92) * 2)}"')
    return next((n for n, line in enumerate(lines, 1) if any(q in line for q in quoted)), None)


def load_project(cwd: Optional[Path] = None) -> Project:
    cwd = cwd or Path.cwd()
    found = find_config(cwd)
    if found is None:
        return Project(root=cwd, config=None, site=Path(SITE_FILE))
    path, table = found
    return from_table(table, path, cwd)


def _site(docs: Any, where: str, place) -> Optional[Path]:
    """`[docs] site = "mkdocs.yml"` (the default) or `site = false`."""
    if not isinstance(docs, dict) or set(docs) - {"site"}:
        raise ProjectError(f"{where}: [docs] takes one key, site = \"{SITE_FILE}\" (or false for none)")
    site = docs.get("site", SITE_FILE)
    if site is False:
        return None
    return place(site, "docs.site")


def from_table(table: dict, path: Path, cwd: Path) -> Project:
    where = str(path)
    if not isinstance(table, dict):
        raise ProjectError(f"{where}: the codeword configuration must be a table")
    unknown = sorted(set(table) - KEYS)
    if unknown:
        raise ProjectError(f"{where}: unknown key {unknown[0]!r} (keys: {', '.join(sorted(KEYS))})")
    base = path.parent
    bounds = project_bounds(path)
    outside: list[tuple[str, str]] = []

    def place(value: Any, key: str, written: bool = True) -> Path:
        if not isinstance(value, str) or not value:
            raise ProjectError(f"{where}: {key} must be a path (a non-empty string)")
        full = (base / value)
        if written and not full.resolve().is_relative_to(bounds):  # resolve(): `..` and links too
            line = _line_of(path, value)
            outside.append((key, f"{where}{f':{line}' if line else ''}: {key} = {value!r} is outside the project "
                                 f"({bounds}): a configuration writes only inside it; name a folder elsewhere "
                                 "on the command line (--out) to write there"))
        try:
            return full.relative_to(cwd)
        except ValueError:
            return full

    schemas = table.get("schemas", ["schemas"])
    if isinstance(schemas, str):
        schemas = [schemas]
    if not isinstance(schemas, list) or not schemas:
        raise ProjectError(f"{where}: schemas must be a list of folders or files")
    targets = table.get("targets", list(TARGETS))
    if not isinstance(targets, list):
        raise ProjectError(f"{where}: targets must be a list such as [\"python\", \"c\"]")
    outputs = table.get("outputs", {})
    if not isinstance(outputs, dict):
        raise ProjectError(f"{where}: [outputs] must be a table of target = \"folder\"")
    for target in outputs:
        if target not in TARGETS:
            raise ProjectError(f"{where}: outputs: unknown target {target!r} (targets: {', '.join(TARGETS)})")
    python = table.get("python", {})
    if not isinstance(python, dict) or set(python) - {"package"}:
        raise ProjectError(f"{where}: [python] takes one key, package = \"name\"")
    package = python.get("package")
    if package is not None:
        problem = protocol_name_problem(package) if isinstance(package, str) else "must be a string"
        if problem:
            raise ProjectError(f"{where}: python.package {problem}")
    return Project(
        root=base, config=path, site=_site(table.get("docs", {}), where, place),
        schema_paths=tuple(place(s, "schemas", written=False) for s in schemas),
        targets=parse_targets(targets, f"{where}: targets"),
        out=place(table.get("out", "generated"), "out"),
        outputs=tuple(sorted((t, place(f, f"outputs.{t}")) for t, f in outputs.items())),
        python_package=package, outside=tuple(outside),
    )
