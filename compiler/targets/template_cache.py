"""Compiled templates kept beside their sources, as Python keeps compiled modules.

Compiling the templates is a fair share of a small build. Jinja keeps each
template's code in templates/__pycache__ and uses it only while the template's
source checksum and the Jinja and Python versions match; the file names add the
environment's options and filters, which the code also depends on. As with
modules, the cache is read whenever it is current and written unless Python is
told not to write bytecode (PYTHONDONTWRITEBYTECODE); scripts/setup writes it
either way. A cache that cannot be read or written only costs the compile.
"""
from __future__ import annotations

import hashlib
import sys
from pathlib import Path

import jinja2


class TemplateCache(jinja2.FileSystemBytecodeCache):
    def __init__(self, directory: Path, settings: str):
        tag = hashlib.sha256(f"{jinja2.__version__}|{settings}".encode("utf-8")).hexdigest()[:16]
        super().__init__(str(directory), f"{tag}-%s.cache")
        self.write = not sys.dont_write_bytecode

    def load_bytecode(self, bucket: jinja2.bccache.Bucket) -> None:
        try:
            super().load_bytecode(bucket)
        except Exception:  # damaged: compile from the source instead
            bucket.reset()

    def dump_bytecode(self, bucket: jinja2.bccache.Bucket) -> None:
        if not self.write:
            return
        try:
            Path(self.directory).mkdir(exist_ok=True)
            super().dump_bytecode(bucket)
        except OSError:  # a read-only tree builds all the same
            pass
