"""Generated text too large to hold in memory: written once to an anonymous
temporary file, then compared with, or copied to, its place in generated/.

Comparison reads the existing file as text (UTF-8, universal newlines), as the
build does for the outputs it keeps in memory.
"""
from __future__ import annotations

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
            for chunk in self.chunks():
                if current.read(len(chunk)) != chunk:
                    return False
            return current.read(1) == ""

    def write_to(self, path: Path) -> None:
        with open(path, "w", encoding="utf-8") as target:
            for chunk in self.chunks():
                target.write(chunk)

    def close(self) -> None:
        self.file.close()
