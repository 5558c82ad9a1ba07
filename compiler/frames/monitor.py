"""`codeword monitor`: live decode of a serial port, or of a capture replayed."""
from __future__ import annotations

import argparse
import json
import sys
import time
from datetime import datetime
from typing import BinaryIO, Optional

from .. import signing_key
from ..usage import UsageError
from .can_bus import CanDecoder, open_bus
from .rows import Row
from .stream import Stream, open_codec

READ_SIZE = 4096


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("schema", help="schema file, or a protocol name of the project")
    source = parser.add_mutually_exclusive_group(required=True)
    source.add_argument("--port", metavar="DEV", help="serial port (or a pySerial URL such as socket://host:port)")
    source.add_argument("--replay", metavar="FILE", help="read a raw capture instead of a port")
    source.add_argument("--can", metavar="CHANNEL", help="a CAN bus through python-can (can0, vcan0, ...), "
                                                         "for a schema of CAN framing")
    parser.add_argument("--interface", metavar="NAME", help="--can: python-can's interface (socketcan, "
                                                           "pcan, kvaser, virtual, ...; default: its configuration)")
    parser.add_argument("--bitrate", type=int, help="--can: the bus's bit rate, for interfaces that set it")
    parser.add_argument("--baud", type=int, default=115200, help="baud rate of the port (default: 115200)")
    parser.add_argument("--direction", help="decode frames as sent in this direction of the schema")
    parser.add_argument("--log", metavar="FILE", help="append the raw bytes read to FILE (for check or decode)")
    parser.add_argument("--json", action="store_true", help="print JSON lines instead of text")
    parser.add_argument("--count", type=int, metavar="N", help="stop after N lines (messages, bad frames, skipped stretches)")
    parser.add_argument("--duration", type=float, metavar="S", help="stop after S seconds")
    signing_key.add_arguments(parser, "verify each frame's signature")


class Counts:
    """Running counts: rows shown, frames among them, errors, bytes skipped."""

    def __init__(self) -> None:
        self.rows = self.frames = self.errors = self.skipped = 0

    def add(self, row: Row) -> None:
        self.rows += 1
        if row.skipped:
            self.skipped += row.skipped
        else:
            self.frames += 1
            self.errors += row.error is not None

    def line(self, read: int) -> str:
        return f"{self.frames} frames, {self.errors} errors, {self.skipped} bytes skipped, {read} bytes read"


def run(args: argparse.Namespace) -> int:
    protocol, codec = open_codec(args.schema)
    if args.can:
        return _run_can(args, protocol, codec)
    stream = Stream(protocol, codec, args.direction, key=signing_key.signing_key(args, protocol))
    counts = Counts()
    log = _open_log(args.log)
    port = _open_source(args)
    if args.port:  # bytes that arrive from now on are read: a script may start sending
        print(f"monitoring {args.port} at {args.baud} baud (Ctrl-C to stop)", file=sys.stderr, flush=True)
    deadline = time.monotonic() + args.duration if args.duration is not None else None
    try:
        while not _done(args, counts, deadline):
            data = port.read(READ_SIZE)
            if log is not None and data:
                log.write(data)
                log.flush()
            if not data and args.replay:
                _show(stream.finish(), counts, args)
                break
            _show(stream.feed(data), counts, args)
    except KeyboardInterrupt:
        pass
    finally:
        port.close()
        if log is not None:
            log.close()
    print(counts.line(stream.read), file=sys.stderr)
    return 1 if counts.errors or counts.skipped else 0


def _run_can(args: argparse.Namespace, protocol, codec) -> int:
    """Frames of a CAN bus, each decoded from its identifier and data."""
    if protocol.framing.can is None:
        raise UsageError(f"{protocol.name} is not a CAN protocol: --can reads a CAN bus")
    decoder = CanDecoder(protocol, codec)
    counts = Counts()
    bus = open_bus(args.can, args.interface, args.bitrate)
    print(f"monitoring CAN {args.can} (Ctrl-C to stop)", file=sys.stderr, flush=True)
    deadline = time.monotonic() + args.duration if args.duration is not None else None
    try:
        while not _done(args, counts, deadline):
            message = bus.recv(timeout=0.1)
            if message is not None:
                _show([decoder.row(message)], counts, args, stamped=True)
    except KeyboardInterrupt:
        pass
    finally:
        bus.shutdown()
    print(f"{counts.frames} frames, {counts.errors} errors", file=sys.stderr)
    return 1 if counts.errors else 0


def _show(rows: list[Row], counts: Counts, args: argparse.Namespace, stamped: bool = False) -> None:
    for row in rows:
        if args.count is not None and counts.rows >= args.count:
            return
        counts.add(row)
        if not stamped:  # a CAN frame keeps the time the bus gave it
            row.time = datetime.now().isoformat(timespec="milliseconds")
        if args.json:
            print(json.dumps(row.as_json(), ensure_ascii=False), flush=True)
        else:
            print(f"{row.time}  [{counts.frames} frames, {counts.errors} errors, {counts.skipped} skipped]  "
                  f"{row.summary()}", flush=True)


def _done(args: argparse.Namespace, counts: Counts, deadline: Optional[float]) -> bool:
    if args.count is not None and counts.rows >= args.count:
        return True
    return deadline is not None and time.monotonic() >= deadline


def _open_log(path: Optional[str]) -> Optional[BinaryIO]:
    if path is None:
        return None
    try:
        return open(path, "ab")
    except OSError as exc:
        raise UsageError(f"{path}: cannot write: {exc.strerror}") from None


def _open_source(args: argparse.Namespace):
    if args.replay:
        try:
            return open(args.replay, "rb")
        except OSError as exc:
            raise UsageError(f"{args.replay}: cannot read: {exc.strerror}") from None
    import serial  # pySerial: ports on Linux, macOS and Windows, and URLs (socket://, rfc2217://)
    try:
        return serial.serial_for_url(args.port, baudrate=args.baud, timeout=0.1)
    except (serial.SerialException, ValueError) as exc:
        raise UsageError(f"{args.port}: cannot open: {exc}") from None
