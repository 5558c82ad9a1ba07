"""A schema's codec, and a byte stream cut into rows with it, for any framing."""
from __future__ import annotations

import re
from pathlib import Path
from typing import Optional

from ..check.run import load_codec
from ..verified_frames import VerifyingDecoder
from ..diagnostics import SchemaError
from ..model import Protocol
from ..project import load_project
from ..usage import UsageError
from .rows import Row, error_row, message_row, units_of

_HEX = re.compile(r"(?:[0-9a-fA-F\s:,]|0[xX]|#[^\n]*)*\Z")
_SEPARATORS = re.compile(r"#[^\n]*|0[xX]|[\s:,]")
GAP_HELD = 1 << 16  # bytes skipped between rows held to be shown; a longer stretch is shown at once


def open_codec(name: str):
    """The protocol model and its generated Python codec, for a schema file or a
    protocol of the project named by its name."""
    path = load_project().find_schema(name)
    if path is None:
        raise UsageError(f"no schema {name!r} (not a file, nor a protocol of this project)")
    try:
        return load_codec(path, name if path == Path(name) else str(path))
    except SchemaError as exc:
        raise UsageError("the schema has errors:\n" + "\n".join(map(str, exc.diagnostics))) from None


def hex_bytes(text: str) -> Optional[bytes]:
    """Bytes written in hex (spaces, colons, commas, 0x and # comments allowed), or None."""
    if not _HEX.match(text):
        return None
    digits = _SEPARATORS.sub("", text)
    try:
        return bytes.fromhex(digits)
    except ValueError:
        return None


class Stream:
    """Bytes in, rows out: frames of a byte protocol, lines of a text protocol or
    words of a bit-packed one, each with its offset in the stream."""

    def __init__(self, protocol: Protocol, codec, direction: Optional[str] = None,
                 sequence: Optional[str] = None, key: Optional[bytes] = None):
        if direction is not None and direction not in {d.name for d in protocol.directions}:
            raise UsageError(f"{protocol.name} has no direction {direction!r} "
                             f"(directions: {', '.join(d.name for d in protocol.directions) or 'none'})")
        self.codec = codec
        self.direction = direction
        self.fields = units_of(protocol)
        self.kind = protocol.framing.kind
        self.read = 0  # bytes fed so far
        self._held = b""  # bytes kept to show each row's frame
        self._held_at = 0  # stream offset of _held[0]
        self._shown = 0  # stream offset up to which rows cover the stream
        if self.kind == "bits":
            bits = protocol.framing.word_bits or 0
            if bits % 8:
                raise UsageError(f"{protocol.name}: words of {bits} bits are not whole bytes; "
                                 "give them to `codeword check` in the text form")
            self.word = bits // 8
            self.decoder = None
            self.sequence = _sequence(protocol, sequence)
        elif key is not None:  # a schema with a signature: frames verified with the key
            self.decoder = VerifyingDecoder(codec, direction, key)
        else:
            self.decoder = codec.StreamDecoder(direction)

    @property
    def skipped(self) -> int:
        return getattr(self.decoder, "skipped", 0)

    def feed(self, data: bytes) -> list[Row]:
        self._held += data
        self.read += len(data)
        if self.decoder is None:
            return self._words(final=False)
        items = self.decoder.feed(data.decode("latin-1") if self.kind == "text" else data)
        return self._rows(items)

    def finish(self) -> list[Row]:
        if self.decoder is None:
            return self._words(final=True)
        rows = self._rows(self.decoder.finish())
        if self.decoder.offset > self._shown:  # skipped bytes at the end, after the last row
            rows.append(self._gap(self.decoder.offset))
            self._forget(self._shown)
        return rows

    def _rows(self, items) -> list[Row]:
        rows = []
        for item, (start, length) in zip(items, self.decoder.spans):
            if start > self._shown:  # bytes between frames: skipped while resynchronising
                rows.append(self._gap(start))
            raw = self._held[start - self._held_at:start - self._held_at + length]
            rows.append(self._row(item, start, self._raw(raw)))
            self._shown = max(self._shown, start + length)
        # Skipped bytes are kept until the row after them shows them, however many reads
        # they came in; a stretch of GAP_HELD is shown at once, so memory stays bounded.
        if self.decoder.offset - self._shown > GAP_HELD:
            rows.append(self._gap(self.decoder.offset))
        self._forget(min(self.decoder.offset, self._shown))
        return rows

    def _gap(self, upto: int) -> Row:
        """The row of the bytes skipped from the last row shown up to stream offset `upto`."""
        gap = self._held[self._shown - self._held_at:upto - self._held_at]
        row = Row(self._shown, self._raw(gap), error=f"{len(gap)} byte(s) skipped: not a frame", skipped=len(gap))
        self._shown = upto
        return row

    def _raw(self, data: bytes):
        return data.decode("latin-1") if self.kind == "text" else data

    def _words(self, final: bool) -> list[Row]:
        if self.sequence is not None:  # messages that do not identify themselves: one document
            return self._document() if final else []
        rows, n = [], self.word
        whole = len(self._held) - len(self._held) % n
        for i in range(0, whole, n):
            word = self._held[i:i + n]
            try:
                item = self.codec.decode(word)
            except self.codec.CodecError as exc:
                item = exc
            rows.append(self._row(item, self._held_at + i, word))
        self._forget(self._held_at + whole)
        if final and self._held:
            rows.append(Row(self._held_at, self._held, error=f"{len(self._held)} byte(s) left over, "
                                                             f"not a whole {n}-byte word"))
            self._forget(self._held_at + len(self._held))
        return rows

    def _document(self) -> list[Row]:
        data, at = self._held, self._held_at
        self._forget(at + len(data))
        if not data:
            return []
        try:
            item = getattr(self.codec, f"decode_{self.sequence}")(data)
        except self.codec.CodecError as exc:
            return [error_row(exc, at, data)]
        return [message_row(item, {}, at, data, name=self.sequence)]

    def _row(self, item, offset: int, raw: bytes) -> Row:
        if isinstance(item, self.codec.CodecError):
            return error_row(item, offset, raw)
        return message_row(item, self.fields.get(item.NAME, {}), offset, raw)

    def _forget(self, upto: int) -> None:
        """Drop held bytes before stream offset `upto`: rows past it are not out yet."""
        drop = max(0, upto - self._held_at)
        self._held = self._held[drop:]
        self._held_at += drop


def _sequence(protocol: Protocol, name: Optional[str]) -> Optional[str]:
    """The sequence a bit-packed input holds, when its words do not identify themselves."""
    names = [s.name for s in protocol.sequences]
    if name is not None and name not in names:
        raise UsageError(f"{protocol.name} has no sequence {name!r} (sequences: {', '.join(names) or 'none'})")
    if name is not None or protocol.self_identifying:
        return name
    return names[0] if names else None
