"""Readers that run one input through the generated codec and yield findings.

Each reader takes the codec module, an open binary file and a Tally, reads the
file once in bounded pieces (streams) or whole (sequence documents, which are
small by definition and capped), and yields a Finding for every problem the
codec reports. Decoding itself is always the codec's: readers only cut the
input into the units the codec expects and map its offsets back to the file.
"""
from __future__ import annotations

import re
from bisect import bisect_right
from dataclasses import dataclass
from typing import BinaryIO, Callable, Iterator

from .. import verified_frames
from .finding import Finding, from_error

CHUNK = 64 * 1024
TEXT_CHUNK = 8 * 1024  # the text stream decoder re-slices its buffer per message
MAX_LINE = 64 * 1024  # a hex-dump line longer than this is not a frame
MAX_DOCUMENT = 16 * 1024 * 1024  # sequence documents (text files, word programs) are read whole

_NON_ASCII = re.compile(rb"[\x80-\xff]+")
_HEX_SEPARATORS = re.compile(r"[\s:,]+")


@dataclass
class Tally:
    read: int = 0  # frames, messages, sentences or words
    valid: int = 0
    invalid: int = 0
    skipped: int = 0  # bytes dropped while resynchronising

    def add(self, other: "Tally") -> None:
        self.read += other.read
        self.valid += other.valid
        self.invalid += other.invalid
        self.skipped += other.skipped


Progress = Callable[[int], None]


def _chunks(fh: BinaryIO, size: int, progress: Progress) -> Iterator[bytes]:
    while True:
        chunk = fh.read(size)
        if not chunk:
            return
        progress(len(chunk))
        yield chunk


def _bounded_lines(fh: BinaryIO, progress: Progress) -> Iterator[tuple[int, bytes, bool]]:
    """(line number, line without its end, too long) for every line, in bounded memory."""
    number = 0
    while True:
        line = fh.readline(MAX_LINE + 1)
        if not line:
            return
        progress(len(line))
        number += 1
        too_long = len(line) > MAX_LINE and not line.endswith(b"\n")
        while too_long:  # drop the rest of an overlong line
            rest = fh.readline(CHUNK)
            progress(len(rest))
            if not rest or rest.endswith(b"\n"):
                break
        yield number, line.rstrip(b"\r\n"), too_long


def _problem(file: str, rule: str, text: str, **where) -> Finding:
    return Finding(file=file, unit=where.pop("unit", None), rule=rule, text=text, **where)


def _is_blank_or_comment(text: str) -> bool:
    return not text or text.startswith("#")


# ---------------------------------------------------------------- byte frames

def binary_stream(codec, fh: BinaryIO, file: str, tally: Tally, progress: Progress,
                  direction: str | None = None, key: bytes | None = None) -> Iterator[Finding]:
    """A raw capture of a byte-framed protocol, through the codec's StreamDecoder
    (each frame verified with `key` when one is given)."""
    decoder = verified_frames.VerifyingDecoder(codec, direction, key) if key is not None \
        else codec.StreamDecoder(direction)
    for chunk in _chunks(fh, CHUNK, progress):
        yield from _frames(decoder.feed(chunk), codec, file, tally)
    yield from _frames(decoder.finish(), codec, file, tally)
    tally.skipped = decoder.skipped
    if decoder.skipped:  # garbage between frames is a violation too, even with no bad frame
        yield _problem(file, "sync", f"{decoder.skipped} byte(s) outside valid frames were skipped while "
                       "resynchronising", actual=decoder.skipped, allowed="frames back to back")


def _frames(items, codec, file: str, tally: Tally) -> Iterator[Finding]:
    for item in items:
        tally.read += 1
        if isinstance(item, codec.DecodeError):
            tally.invalid += 1
            offset = item.offset // 8 if isinstance(item.offset, int) else None
            yield from_error(item, file, tally.read, offset=offset)
        else:
            tally.valid += 1


def hex_frames(codec, fh: BinaryIO, file: str, tally: Tally, progress: Progress,
               direction: str | None = None, key: bytes | None = None) -> Iterator[Finding]:
    """A hex dump with one frame per line ('#' comments and blank lines skipped), each
    frame verified with `key` when one is given."""
    for number, raw, too_long in _bounded_lines(fh, progress):
        text = raw.decode("latin-1").split("#", 1)[0].strip()
        if not text and not too_long:
            continue
        tally.read += 1
        frame = None if too_long else _hex_bytes(text)
        if frame is None:
            tally.invalid += 1
            yield _problem(file, "syntax", "not a frame in hex (pairs of hex digits, optionally separated)",
                           unit=tally.read, line=number, actual=text[:40], allowed="hex bytes")
            continue
        try:
            if key is not None:
                verified_frames.decode(codec, frame, direction, key)
            else:
                codec.decode(frame, direction)
        except codec.DecodeError as exc:
            tally.invalid += 1
            yield from_error(exc, file, tally.read, line=number)
        else:
            tally.valid += 1


def can_log(codec, fh: BinaryIO, file: str, tally: Tally, progress: Progress) -> Iterator[Finding]:
    """A CAN log python-can reads (candump -L, ASC, BLF...): each frame decoded from its
    identifier and data; error frames and remote requests are findings too."""
    from ..frames.can_bus import frame_of, log_messages
    for message in log_messages(file):
        tally.read += 1
        frame_id, data = frame_of(message)
        if message.is_error_frame or message.is_remote_frame:
            tally.invalid += 1
            what = "an error frame" if message.is_error_frame else "a remote request, no data"
            yield _problem(file, "frame", f"{what} (identifier 0x{message.arbitration_id:X})",
                           unit=tally.read, actual=f"0x{frame_id:08X}", allowed="a data frame")
            continue
        try:
            codec.decode_can(frame_id, data)
        except codec.DecodeError as exc:
            tally.invalid += 1
            yield from_error(exc, file, tally.read)  # the frame's number places it; the error names the data's byte
        else:
            tally.valid += 1


def _hex_bytes(text: str) -> bytes | None:
    digits = _HEX_SEPARATORS.sub("", text)
    try:
        return bytes.fromhex(digits) if digits else None
    except ValueError:
        return None


# ---------------------------------------------------------------- text messages

def text_stream(codec, fh: BinaryIO, file: str, tally: Tally, progress: Progress,
                direction: str | None = None) -> Iterator[Finding]:
    """A text log, one message per line or a raw stream, through the codec's StreamDecoder."""
    decoder = codec.StreamDecoder(direction)
    starts, first_line, consumed = [0], 1, 0  # starts[i]: offset of line first_line + i

    def place(offset):
        k = bisect_right(starts, offset) - 1
        return {"line": first_line + k, "column": offset - starts[k] + 1}

    for chunk in _chunks(fh, TEXT_CHUNK, progress):
        starts.extend(consumed + m.end() for m in re.finditer(b"\n", chunk))
        for m in _NON_ASCII.finditer(chunk):  # the codec reads ASCII only
            yield _problem(file, "text", "non-ASCII bytes in a text protocol", actual=m.group().hex(" "),
                           allowed="ASCII", **place(consumed + m.start()))
        consumed += len(chunk)
        yield from _messages(decoder.feed(chunk.decode("latin-1")), codec, file, tally, place)
        k = bisect_right(starts, decoder.offset) - 1
        if k > 0:
            del starts[:k]
            first_line += k
    yield from _messages(decoder.finish(), codec, file, tally, place)


def _messages(items, codec, file: str, tally: Tally, place) -> Iterator[Finding]:
    for item in items:
        tally.read += 1
        if isinstance(item, codec.DecodeError):
            tally.invalid += 1
            if item.rule == "text" and item.allowed == "ASCII":
                continue  # reported with its bytes when the chunk was read
            where = place(item.offset) if isinstance(item.offset, int) else {}
            yield from_error(item, file, tally.read, **where)
        else:
            tally.valid += 1


# ---------------------------------------------------------------- sequences

def _document(fh: BinaryIO, file: str, progress: Progress) -> tuple[bytes, Finding | None]:
    data = fh.read(MAX_DOCUMENT + 1)
    progress(len(data))
    if len(data) > MAX_DOCUMENT:
        return b"", _problem(file, "length", f"larger than {MAX_DOCUMENT} bytes: not a single sequence",
                             actual=len(data), allowed=f"at most {MAX_DOCUMENT} bytes")
    return data, None


def text_sequence(codec, sequence: str, fh: BinaryIO, file: str, tally: Tally,
                  progress: Progress) -> Iterator[Finding]:
    """A text-form sequence file (an exchange file, one message a line): every line and the grammar."""
    data, too_big = _document(fh, file, progress)
    if too_big:
        yield too_big
        return
    text = data.decode("latin-1")
    lines = text.splitlines()
    sentences = [n for n, line in enumerate(lines, 1) if not _is_blank_or_comment(line.strip())]
    tally.read = len(sentences)
    bad_lines = set()
    for m in _NON_ASCII.finditer(data):
        line = data.count(b"\n", 0, m.start()) + 1
        bad_lines.add(line)
        yield _problem(file, "text", "non-ASCII bytes in a text file", actual=m.group().hex(" "),
                       allowed="ASCII", line=line)
    decode = getattr(codec, f"decode_{sequence}_text")
    errors = _sequence_errors(codec, decode, text)
    for e in errors:
        line = getattr(e, "line", None)
        column = None
        if line and isinstance(e.offset, int):
            raw = lines[line - 1]
            column = e.offset + 1 + len(raw) - len(raw.lstrip())
        unit = sentences.index(line) + 1 if line in sentences else None
        if line:
            bad_lines.add(line)
        index = getattr(e, "index", None)
        if index is not None and getattr(e, "count", 1) > 1:  # extra lines after the end
            bad_lines.update(sentences[index:index + e.count])
        yield from_error(e, file, unit, line=line, column=column)
    tally.invalid = len(bad_lines & set(sentences))
    tally.valid = tally.read - tally.invalid


def word_sequence(codec, sequence: str, fh: BinaryIO, file: str, tally: Tally, progress: Progress,
                  hex_words: bool, word_bytes: int) -> Iterator[Finding]:
    """A sequence of fixed-size words (a program of command words): raw bytes, or hex words
    separated by white space, several to a line."""
    data, too_big = _document(fh, file, progress)
    if too_big:
        yield too_big
        return
    places: list[dict] = []  # per word: where it is in the file
    if hex_words:
        hex_word = re.compile(rf"(?:0[xX])?([0-9a-fA-F]{{{word_bytes * 2}}})\Z")
        words = bytearray()
        for number, line in enumerate(data.decode("latin-1").splitlines(), 1):
            line = line.split("#", 1)[0]
            for m in re.finditer(r"\S+", line):
                word = hex_word.match(m.group())
                if not word:
                    yield _problem(file, "syntax", f"not a {word_bytes * 8}-bit word in hex",
                                   line=number, column=m.start() + 1, actual=m.group()[:40],
                                   allowed=f"{word_bytes * 2} hex digits")
                    tally.invalid += 1
                    continue
                words += bytes.fromhex(word.group(1))
                places.append({"line": number, "column": m.start() + 1})
        data = bytes(words)
    else:
        places = [{"offset": i} for i in range(0, len(data), word_bytes)]
    syntax_errors = tally.invalid
    words = (len(data) + word_bytes - 1) // word_bytes
    tally.read = words + syntax_errors
    decode = getattr(codec, f"decode_{sequence}")
    bad = set()
    for e in _sequence_errors(codec, decode, data):
        index = getattr(e, "index", None)
        where = dict(places[index]) if index is not None and index < len(places) else {}
        if "offset" in where and isinstance(e.offset, int):
            where["offset"] = e.offset // 8
        if index is not None:  # an error may cover several words (extra data after the end)
            bad.update(range(index, min(words, index + getattr(e, "count", 1))))
        yield from_error(e, file, index + 1 if index is not None else None, **where)
    tally.invalid += len(bad)
    tally.valid = words - len(bad)


def _sequence_errors(codec, decode, data) -> list:
    try:
        decode(data)
    except codec.SequenceError as exc:
        return list(exc.errors)
    except codec.DecodeError as exc:
        return [exc]
    return []
