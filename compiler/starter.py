"""`codeword init`: a starter project that builds as it is.

It writes a schema with a worked example, the project configuration (a
`codeword.toml`, or a `[tool.codeword]` table appended to an existing
`pyproject.toml`), the language's JSON Schema for editors and the editor
setting that points YAML files at it. It never overwrites a file.
"""
from __future__ import annotations

import json
import os
from dataclasses import dataclass, field
from pathlib import Path

from .names import protocol_name_problem
from .project import CONFIG_FILE, find_config
from .targets.render import environment
from .validate import SCHEMA_FILE

EDITOR_SCHEMA = Path(".codeword") / "codeword.schema.json"
VSCODE_SETTINGS = Path(".vscode") / "settings.json"


class InitError(Exception):
    """The starter cannot be written as asked (a usage error, exit status 2)."""


@dataclass
class Written:
    created: list[Path] = field(default_factory=list)
    changed: list[Path] = field(default_factory=list)
    kept: list[Path] = field(default_factory=list)


def init(folder: Path, name: str, schemas: str = "schemas", out: str = "generated") -> Written:
    problem = protocol_name_problem(name)
    if problem:
        raise InitError(f"protocol name {problem}")
    existing = find_config(folder)
    if existing is not None and existing[0].parent == folder:
        raise InitError(f"{existing[0]} already configures codeword here")
    schema = folder / schemas / f"{name}.yaml"
    if schema.exists():
        raise InitError(f"{schema} exists; choose another protocol name")
    env = environment()
    done = Written()
    _create(done, folder / EDITOR_SCHEMA, SCHEMA_FILE.read_text(encoding="utf-8"))
    reference = Path(os.path.relpath(folder / EDITOR_SCHEMA, schema.parent)).as_posix()
    _create(done, schema, env.get_template("starter/schema.yaml.j2").render(name=name, schema_ref=reference))
    settings = dict(name=name, schemas=schemas, out=out)
    pyproject = folder / "pyproject.toml"
    if pyproject.is_file():
        table = env.get_template("starter/pyproject-table.toml.j2").render(**settings)
        text = pyproject.read_text(encoding="utf-8")
        pyproject.write_text(text + ("" if text.endswith("\n") else "\n") + table, encoding="utf-8")
        done.changed.append(pyproject)
    else:
        _create(done, folder / CONFIG_FILE, env.get_template("starter/codeword.toml.j2").render(**settings))
    _editor_settings(done, folder, schemas)
    return done


def _create(done: Written, path: Path, text: str) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text, encoding="utf-8")
    done.created.append(path)


def _editor_settings(done: Written, folder: Path, schemas: str) -> None:
    """Point VS Code's YAML extension at the JSON Schema for the schema folder; a
    settings file that exists is changed only where it says nothing yet."""
    path = folder / VSCODE_SETTINGS
    pattern = f"{schemas.strip('/')}/*.yaml"
    if not path.exists():
        _create(done, path, json.dumps({"yaml.schemas": {EDITOR_SCHEMA.as_posix(): pattern}}, indent=2) + "\n")
        return
    try:
        settings = json.loads(path.read_text(encoding="utf-8"))
    except (ValueError, OSError):  # comments (JSONC) or unreadable: leave it to the user
        done.kept.append(path)
        return
    mapping = settings.get("yaml.schemas") if isinstance(settings, dict) else None
    if not isinstance(settings, dict) or (mapping is not None and not isinstance(mapping, dict)):
        done.kept.append(path)
        return
    settings.setdefault("yaml.schemas", {}).setdefault(EDITOR_SCHEMA.as_posix(), pattern)
    path.write_text(json.dumps(settings, indent=2) + "\n", encoding="utf-8")
    done.changed.append(path)


def editor_schema() -> str:
    """The language's JSON Schema (`codeword schema`)."""
    return SCHEMA_FILE.read_text(encoding="utf-8")
