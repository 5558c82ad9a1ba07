"""The `codeword diff` command line: load two schema versions (files or
`git:REV:path`), compare, print, exit 1 when anything breaks the wire."""
from __future__ import annotations

import argparse
import subprocess
import sys
import tempfile
from pathlib import Path

from ..build import compile_schema
from ..diagnostics import SchemaError
from ..model import Protocol
from .compare import compare
from .render import as_markdown, as_text


class SourceError(Exception):
    pass


def add_arguments(parser: argparse.ArgumentParser, func) -> None:
    parser.description = ("Classify the changes between two versions of a schema as wire-breaking, "
                          "compatible or docs-only. Exit 1 if anything breaks the wire, 2 on errors.")
    parser.add_argument("old", help="old schema: a file or git:REV:path")
    parser.add_argument("new", help="new schema: a file or git:REV:path")
    parser.add_argument("--format", choices=("text", "markdown"), default="text",
                        help="text, or a Markdown changelog section")
    parser.set_defaults(func=func)


def load(spec: str) -> Protocol:
    """A schema from a file, or from git as `git:REV:path`."""
    if not spec.startswith("git:"):
        if not Path(spec).is_file():
            raise SourceError(f"{spec}: no such file")
        return compile_schema(Path(spec), spec)
    rev, sep, path = spec[len("git:"):].partition(":")
    if not sep or not rev or not path:
        raise SourceError(f"{spec}: expected git:REV:path")
    if rev.startswith("-"):  # git would read it as an option (--output=FILE writes a file)
        raise SourceError(f"{spec}: a revision cannot start with '-'")
    try:
        shown = subprocess.run(["git", "show", "--end-of-options", f"{rev}:{path}"],
                               capture_output=True, check=False)
    except OSError as exc:
        raise SourceError(f"{spec}: cannot run git: {exc.strerror}") from None
    if shown.returncode != 0:
        raise SourceError(f"{spec}: {shown.stderr.decode(errors='replace').strip()}")
    with tempfile.TemporaryDirectory() as tmp:
        copy = Path(tmp) / Path(path).name
        copy.write_bytes(shown.stdout)
        return compile_schema(copy, spec)


def run_diff(args: argparse.Namespace) -> int:
    try:
        old, new = load(args.old), load(args.new)
    except SourceError as exc:
        print(f"codeword diff: {exc}", file=sys.stderr)
        return 2
    except SchemaError as exc:
        for diagnostic in exc.diagnostics:
            print(diagnostic, file=sys.stderr)
        return 2
    if old.name != new.name:
        print(f"codeword diff: these are different protocols ({old.name}, {new.name})", file=sys.stderr)
        return 2
    d = compare(old, new)
    render = as_markdown if args.format == "markdown" else as_text
    sys.stdout.write(render(d, args.old, args.new))
    return 1 if d.breaking else 0
