"""`codeword decode`: every frame or line of the inputs, decoded."""
from __future__ import annotations

import argparse
import os
import sys

from .. import signing_key
from ..usage import UsageError
from . import output
from .can_bus import CanDecoder, is_can_log, log_messages
from .stream import Stream, hex_bytes, open_codec


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("schema", help="schema file, or a protocol name of the project")
    parser.add_argument("inputs", nargs="*", metavar="INPUT",
                        help="frames in hex, a file (a raw capture, a hex dump or a text log; for a CAN "
                             "schema also a candump -L, ASC, BLF, TRC or CSV log) or '-' for standard input "
                             "(the default); a text protocol takes lines too")
    parser.add_argument("--format", choices=output.FORMATS, default="table",
                        help="an aligned table (default), JSON lines or CSV")
    parser.add_argument("--direction", help="decode frames as sent in this direction of the schema")
    parser.add_argument("--sequence", help="the sequence a bit-packed input holds, when its words do not "
                                           "identify themselves (default: the schema's first)")
    signing_key.add_arguments(parser, "verify each frame's signature")


def run(args: argparse.Namespace) -> int:
    protocol, codec = open_codec(args.schema)
    key = signing_key.signing_key(args, protocol)
    rows, text = [], protocol.framing.kind == "text"
    for source in args.inputs or ["-"]:
        if is_can_log(protocol, source):  # candump, ASC, BLF...: frames with their identifiers
            decoder = CanDecoder(protocol, codec)
            rows += [decoder.row(message) for message in log_messages(source)]
            continue
        stream = Stream(protocol, codec, args.direction, args.sequence, key)
        data = _input(source, text, protocol.framing.terminator if text else None)
        rows += stream.feed(data) + stream.finish()
    output.write(rows, args.format, sys.stdout)
    return 1 if any(r.error is not None for r in rows) else 0


def _input(source: str, text: bool, terminator) -> bytes:
    """The bytes of one input: a file (hex dumps read as hex), stdin, or the argument itself."""
    if source == "-":
        data = sys.stdin.buffer.read()
    elif os.path.isfile(source):
        try:
            with open(source, "rb") as fh:
                data = fh.read()
        except OSError as exc:
            raise UsageError(f"{source}: cannot read: {exc.strerror}") from None
    elif text:
        line = source.encode("utf-8")
        end = terminator.encode("utf-8")
        return line if line.endswith(end) else line + end
    else:
        data = hex_bytes(source)
        if data is None:
            raise UsageError(f"{source!r} is neither a file nor frames in hex")
        return data
    if not text:
        as_hex = hex_bytes(data.decode("latin-1")) if data.strip() else None
        if as_hex is not None:
            return as_hex
    return data
