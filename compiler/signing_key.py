"""The secret key `check`, `decode`, `monitor` and `encode` verify or sign frames
with, for a schema whose trailer has a signature: `--key-file FILE` or `--key HEX`.

The key is never shown: messages about it name the file and describe what it
holds (a size, how many hex digits), never its bytes. The environment is not a
source: no other option of the command line reads one.
"""
from __future__ import annotations

import argparse
import re
from typing import Optional

from .model import Protocol
from .usage import UsageError

MAX_KEY_FILE = 4096  # read no further: a key file is tiny, and /dev/urandom never ends
_WHITE = re.compile(rb"\s+")
_HEX = re.compile(rb"[0-9a-fA-F]*\Z")


def add_arguments(parser: argparse.ArgumentParser, verb: str) -> None:
    """--key-file and --key, one or the other; `verb` says what the key does."""
    source = parser.add_mutually_exclusive_group()
    source.add_argument("--key-file", metavar="FILE",
                        help=f"{verb} with the secret key of the schema's signature, read from FILE: "
                             "the key's raw bytes, or its bytes in hex (white space allowed)")
    source.add_argument("--key", metavar="HEX",
                        help="the secret key in hex on the command line; other users of the machine can "
                             "see it in the process list, and it stays in shell history: prefer --key-file")


def signing_key(args: argparse.Namespace, protocol: Protocol) -> Optional[bytes]:
    """The key the options give, checked against the schema's signature; None without one."""
    path, text = getattr(args, "key_file", None), getattr(args, "key", None)
    if path is None and text is None:
        return None
    option = "--key-file" if path is not None else "--key"
    length = key_length(protocol)
    if length is None:
        raise UsageError(f"{option}: {protocol.name} ({protocol.file}) declares no signature to verify or "
                         "sign with (a `signature` in framing.trailer)")
    if path is not None:
        return _from_file(path, length)
    return _from_hex(text.encode("ascii", "replace"), length, "--key", raw=False)


def key_length(protocol: Protocol) -> Optional[int]:
    """The bytes of the key the schema's signature takes, or None when it has none."""
    trailer = protocol.framing.trailer
    field = trailer.signature if trailer is not None else None
    return field.signature.key_length if field is not None else None


def _from_file(path: str, length: int) -> bytes:
    try:
        with open(path, "rb") as fh:
            data = fh.read(MAX_KEY_FILE + 1)
    except OSError as exc:
        raise UsageError(f"--key-file {path}: cannot read: {exc.strerror}") from None
    if len(data) == length:  # the raw key
        return data
    if len(data) > MAX_KEY_FILE:
        raise UsageError(f"--key-file {path}: holds more than {MAX_KEY_FILE} bytes: "
                         f"{_wanted(length, raw=True)}")
    return _from_hex(data, length, f"--key-file {path}", raw=True)


def _from_hex(data: bytes, length: int, where: str, raw: bool) -> bytes:
    """The key from hex digits (white space ignored); the error says what `data` holds, not what it is."""
    digits = _WHITE.sub(b"", data)
    if not digits:
        raise UsageError(f"{where}: holds no key (empty): {_wanted(length, raw)}")
    if not _HEX.match(digits):
        what = "neither the raw key nor hex digits" if raw else "not hex digits"
        raise UsageError(f"{where}: holds {len(data)} byte(s), {what}: {_wanted(length, raw)}")
    if len(digits) != 2 * length:
        raise UsageError(f"{where}: holds {len(digits)} hex digit(s): {_wanted(length, raw)}")
    return bytes.fromhex(digits.decode("ascii"))


def _wanted(length: int, raw: bool) -> str:
    forms = f"{length} raw bytes, or {2 * length} hex digits" if raw else f"{2 * length} hex digits"
    return f"the schema's signature takes a key of {length} bytes ({forms})"
