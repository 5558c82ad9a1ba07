"""CAN frames from buses and logs through python-can (an optional extra): a live bus
for `monitor`, candump (`-L`), ASC, BLF and the other logs python-can reads for
`decode` and `check`. Each frame is decoded from its identifier and data with the
codec's `decode_can`; a row shows it as its frame bytes (the identifier in four bytes,
bit 31 set for an extended one, the data length, the data)."""
from __future__ import annotations

from pathlib import Path
from typing import Any, Iterator, Optional

from ..can import EXTENDED_FLAG
from ..model import Protocol
from ..usage import UsageError
from .rows import Row, error_row, message_row, units_of

# The logs python-can's LogReader reads, by file suffix.
LOG_SUFFIXES = (".log", ".asc", ".blf", ".trc", ".csv")


def python_can() -> Any:
    try:
        import can
    except ImportError:
        raise UsageError("CAN buses and logs need python-can: pip install 'codeword[can]'") from None
    return can


def is_can_log(protocol: Protocol, source: str) -> bool:
    """Whether `source` is a CAN log to read with python-can (a CAN schema's log file)."""
    return protocol.framing.can is not None and Path(source).suffix.lower() in LOG_SUFFIXES \
        and Path(source).is_file()


def frame_of(message: Any) -> tuple[int, bytes]:
    """A python-can message's identifier, as SocketCAN's can_id, and its data."""
    flag = EXTENDED_FLAG if message.is_extended_id else 0
    return message.arbitration_id | flag, bytes(message.data)


def frame_bytes(frame_id: int, data: bytes) -> bytes:
    return frame_id.to_bytes(4, "big") + bytes((len(data) & 0xFF,)) + data


def log_messages(path: str) -> Iterator[Any]:
    """The messages of a log file, in order; a file python-can cannot read is a usage error."""
    can = python_can()
    try:
        reader = can.LogReader(path)
    except (ValueError, OSError) as exc:
        raise UsageError(f"{path}: not a CAN log python-can reads: {exc}") from None
    try:
        yield from reader
    except (ValueError, IndexError, OSError) as exc:  # python-can's readers raise these on a malformed line
        raise UsageError(f"{path}: not a CAN log python-can reads: {' '.join(str(exc).split())}") from None
    finally:
        reader.stop()


class CanDecoder:
    """python-can messages in, rows out."""

    def __init__(self, protocol: Protocol, codec):
        self.codec = codec
        self.fields = units_of(protocol)

    def row(self, message: Any) -> Row:
        frame_id, data = frame_of(message)
        raw = frame_bytes(frame_id, data)
        if message.is_error_frame:
            row = Row(None, raw, error="a CAN error frame")
        elif message.is_remote_frame:
            row = Row(None, raw, error=f"a remote request for 0x{message.arbitration_id:X}: no data to decode")
        else:
            try:
                obj = self.codec.decode_can(frame_id, data)
            except self.codec.DecodeError as exc:  # its offset counts bits of the data
                row = error_row(exc, None, raw)
            else:
                row = message_row(obj, self.fields[obj.NAME], None, raw)
        row.time = f"{message.timestamp:.6f}"
        return row


def open_bus(channel: str, interface: Optional[str], bitrate: Optional[int]) -> Any:
    """A python-can bus, or a usage error naming why not."""
    can = python_can()
    options: dict[str, Any] = {"channel": channel}
    if interface:
        options["interface"] = interface
    if bitrate:
        options["bitrate"] = bitrate
    try:
        return can.Bus(**options)
    except (can.CanError, ValueError, OSError, ImportError) as exc:
        raise UsageError(f"CAN channel {channel!r}{f' ({interface})' if interface else ''}: cannot open: {exc}") \
            from None
