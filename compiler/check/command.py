"""The `codeword check` command line: arguments, output format, exit status."""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

from .. import signing_key
from ..diagnostics import SchemaError
from .report import JsonReport, TextReport
from .run import INPUT_FORMATS, Options, UsageError, check, load_codec


def add_arguments(parser: argparse.ArgumentParser, func) -> None:
    parser.description = ("Check data against a schema with its generated codec and report every "
                          "violation. Exit 0 when all is valid, 1 when anything is invalid, 2 on usage "
                          "or schema errors.")
    parser.add_argument("schema", help="schema file, or a protocol name of the project (a schema file's stem)")
    parser.add_argument("inputs", nargs="+", metavar="INPUT", help="files to check ('-' for standard input)")
    parser.add_argument("--format", choices=("text", "json"), default="text", help="output format")
    parser.add_argument("--input-format", choices=INPUT_FORMATS, default="auto",
                        help="raw bytes, hex (one frame per line, or hex words), text, or a CAN log python-can reads "
                             "(candump -L, ASC, BLF, TRC, CSV); default: guess (a CAN log by its suffix)")
    parser.add_argument("--direction", help="decode frames as sent in this direction of the schema")
    parser.add_argument("--sequence", help="the sequence a bit-packed input holds (default: the schema's first)")
    signing_key.add_arguments(parser, "verify each frame's signature")
    bar = parser.add_mutually_exclusive_group()
    bar.add_argument("--progress", dest="progress", action="store_true", default=None,
                     help="show a progress bar for large inputs even when stderr is not a terminal")
    bar.add_argument("--no-progress", dest="progress", action="store_false", help="never show a progress bar")
    parser.set_defaults(func=func)


def _schema_path(name: str) -> Path | None:
    """A schema file, or a protocol of the project named by its name (its file's stem)."""
    from ..project import load_project
    return load_project().find_schema(name)


def run_check(args: argparse.Namespace) -> int:
    path = _schema_path(args.schema)
    if path is None:
        print(f"codeword check: no schema {args.schema!r} (not a file, nor a protocol of this project)",
              file=sys.stderr)
        return 2
    try:
        protocol, codec = load_codec(path, args.schema if path == Path(args.schema) else str(path))
    except SchemaError as exc:
        for diagnostic in exc.diagnostics:
            print(diagnostic, file=sys.stderr)
        print(f"codeword check: {path}: the schema has errors; nothing checked", file=sys.stderr)
        return 2
    report = JsonReport(sys.stdout) if args.format == "json" else TextReport(sys.stdout)
    try:
        options = Options(args.input_format, args.direction, args.sequence, args.progress,
                          key=signing_key.signing_key(args, protocol))
        findings = check(protocol, codec, args.inputs, report, options)
    except UsageError as exc:
        sys.stdout.flush()
        print(f"codeword check: {exc}", file=sys.stderr)
        return 2
    except BrokenPipeError:
        return 1
    return 1 if findings else 0
