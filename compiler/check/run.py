"""`codeword check`: build the schema's Python codec in memory, pick the reader
that fits the protocol and the input, and report every finding."""
from __future__ import annotations

import os
import re
import sys
from contextlib import contextmanager
from dataclasses import dataclass, field
from functools import partial
from pathlib import Path
from typing import BinaryIO, Callable, Iterator, Optional

from ..build import compile_schema, verify
from ..fingerprint import fingerprint
from ..model import Protocol
from ..usage import UsageError
from ..targets import python as python_target
from ..frames.can_bus import is_can_log
from . import sources
from .sources import Tally

PROGRESS_MIN_BYTES = 4 * 1024 * 1024  # smaller inputs finish before a bar would help
INPUT_FORMATS = ("auto", "raw", "hex", "text", "can-log")
_HEX_TEXT = re.compile(rb"(?:[0-9a-fA-F\s:,xX]|#[^\n]*)*\Z")


@dataclass
class Options:
    input_format: str = "auto"
    direction: Optional[str] = None
    sequence: Optional[str] = None
    progress: Optional[bool] = None  # None: only on a terminal, for large inputs
    key: Optional[bytes] = field(default=None, repr=False)  # verify signatures with it; never shown


def load_codec(schema: Path, display: str | None = None):
    """The protocol model and its generated Python codec, built in memory."""
    protocol = compile_schema(schema, display)
    return protocol, verify(protocol, python_target.render(protocol))


@dataclass
class Plan:
    reader: Callable  # (fh, file, tally, progress) -> Iterator[Finding]
    input_format: str
    unit: str


def plan(p: Protocol, codec, options: Options, sample: bytes, path: Optional[str] = None) -> Plan:
    """Which reader fits this protocol and this input."""
    fmt = options.input_format
    if options.direction and options.direction not in {d.name for d in p.directions}:
        raise UsageError(f"{p.name} has no direction {options.direction!r} "
                         f"(directions: {', '.join(d.name for d in p.directions) or 'none'})")
    looks_hex = bool(sample) and _HEX_TEXT.match(sample) is not None
    kind = p.framing.kind
    if fmt == "can-log" or fmt == "auto" and path is not None and is_can_log(p, path):
        if p.framing.can is None:
            raise UsageError(f"{p.name} is not a CAN protocol: a CAN log holds CAN frames")
        return Plan(partial(sources.can_log, codec), "can-log", "frame")
    if kind == "text":
        if fmt == "hex":
            raise UsageError(f"{p.name} is a text protocol: give its text, not hex")
        return Plan(partial(sources.text_stream, codec, direction=options.direction), "text", "message")
    if kind == "bytes":
        if fmt == "text":
            raise UsageError(f"{p.name} is a byte protocol: give a raw capture or a hex dump")
        if fmt == "hex" or fmt == "auto" and looks_hex:
            return Plan(partial(sources.hex_frames, codec, direction=options.direction, key=options.key),
                        "hex", "frame")
        return Plan(partial(sources.binary_stream, codec, direction=options.direction, key=options.key),
                    "raw", "frame")
    sequence = _sequence(p, options.sequence)
    if options.direction:
        raise UsageError(f"{p.name}: --direction applies to framed streams, not to a {sequence}")
    if p.framing.text_form:
        if fmt not in ("auto", "text"):
            raise UsageError(f"{p.name}: a {sequence} is checked in its text form (the exchange file)")
        return Plan(partial(sources.text_sequence, codec, sequence), "text", "item")
    word_bits = p.framing.word_bits
    if not word_bits or word_bits % 8:
        raise UsageError(f"{p.name}: no input form to check (neither text form nor whole-byte words)")
    if fmt == "text":
        raise UsageError(f"{p.name} has no text form: give raw bytes or hex words")
    hex_words = fmt == "hex" or fmt == "auto" and looks_hex
    return Plan(partial(sources.word_sequence, codec, sequence, hex_words=hex_words, word_bytes=word_bits // 8),
                "hex" if hex_words else "raw", "word")


def _sequence(p: Protocol, name: Optional[str]) -> str:
    names = [s.name for s in p.sequences]
    if name:
        if name not in names:
            raise UsageError(f"{p.name} has no sequence {name!r} (sequences: {', '.join(names) or 'none'})")
        return name
    if not names:
        raise UsageError(f"{p.name}: bit-packed messages are checked as a sequence, and the schema declares none")
    return names[0]


@contextmanager
def _open(path: str) -> Iterator[tuple[BinaryIO, Optional[int]]]:
    if path == "-":
        yield sys.stdin.buffer, None
        return
    try:
        fh = open(path, "rb")
    except OSError as exc:
        raise UsageError(f"{path}: cannot read: {exc.strerror}") from None
    with fh:
        yield fh, os.fstat(fh.fileno()).st_size


def _progress_bar(size: Optional[int], file: str, wanted: Optional[bool]):
    show = wanted if wanted is not None else sys.stderr.isatty()
    if not show or size is None or size < PROGRESS_MIN_BYTES:
        return None
    from tqdm import tqdm
    return tqdm(total=size, unit="B", unit_scale=True, unit_divisor=1024, desc=file, file=sys.stderr,
                leave=False, dynamic_ncols=True)


def check(p: Protocol, codec, inputs: list[str], report, options: Options) -> int:
    """Check every input, writing to `report`; returns the number of findings."""
    plan(p, codec, options, b"")  # options that cannot work fail before any output
    for path in inputs:  # devices and pipes are read like files
        if path != "-" and os.path.isdir(path):
            raise UsageError(f"{path}: is a folder; give the capture files in it")
        if path != "-" and not os.path.exists(path):
            raise UsageError(f"{path}: no such file")
    report.start(p.file, p.name, fingerprint(p))
    total, findings = Tally(), 0
    for path in inputs:
        with _open(path) as (fh, size):
            sample = fh.peek(4096)[:4096] if hasattr(fh, "peek") else b""
            how = plan(p, codec, options, sample, path)
            tally, count = Tally(), 0
            bar = _progress_bar(size, path, options.progress)
            step = bar.update if bar else (lambda n: None)
            try:
                for finding in how.reader(fh, path, tally, step):
                    count += 1
                    if bar:
                        bar.clear()
                    report.finding(finding, how.unit)
            finally:
                if bar:
                    bar.close()
        report.input_done(path, how.input_format, how.unit, tally, count)
        total.add(tally)
        findings += count
    report.finish(total, findings, len(inputs))
    return findings
