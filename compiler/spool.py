"""Generated text too large to hold in memory: written once to an anonymous
temporary file, then compared with, or copied to, its place in generated/.

Comparison reads the existing file as text (UTF-8, universal newlines), as the
build does for the outputs it keeps in memory.
"""
from __future__ import annotations

import hashlib
import tempfile
from pathlib import Path
from typing import Iterator

CHUNK = 1 << 20  # characters


class Spool:
    def __init__(self) -> None:
        self.file = tempfile.TemporaryFile("w+", encoding="utf-8", newline="")

    def chunks(self) -> Iterator[str]:
        self.file.flush()
        self.file.seek(0)
        while chunk := self.file.read(CHUNK):
            yield chunk

    def same_as(self, path: Path) -> bool:
        if not path.exists():
            return False
        with open(path, encoding="utf-8") as current:
            try:
                for chunk in self.chunks():
                    if current.read(len(chunk)) != chunk:
                        return False
                return current.read(1) == ""
            except UnicodeDecodeError:  # not text: not these vectors
                return False

    def sha256(self) -> str:
        """The hash of the text as UTF-8, as written to a file on a system with \\n line ends."""
        h = hashlib.sha256()
        for chunk in self.chunks():
            h.update(chunk.encode("utf-8"))
        return h.hexdigest()

    def write_to(self, path: Path) -> None:
        with open(path, "w", encoding="utf-8") as target:
            for chunk in self.chunks():
                target.write(chunk)

    def close(self) -> None:
        self.file.close()


class InPlace:
    """A large output found already in its place: the file there has the hash that
    the build recorded for the same inputs (cache.py), so it is not made again."""

    def __init__(self, path: Path) -> None:
        self.path = path


def file_sha256(path: Path) -> str | None:
    h = hashlib.sha256()
    try:
        with open(path, "rb") as f:
            while chunk := f.read(CHUNK):
                h.update(chunk)
    except OSError:
        return None
    return h.hexdigest()
