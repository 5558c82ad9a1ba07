"""Import generated Python source as a module without writing it to disk.

A codec for thousands of messages is megabytes of source, and compiling it in
one go builds a syntax tree of over a hundred bytes per source byte. It is
compiled a run of top-level definitions at a time instead, each at its own
line numbers, then run in order: the same module, a fraction of the memory.
The compiled code is kept in the build cache (cache.py) under the source's
hash, as Python keeps a module's in __pycache__: a build of an unchanged
schema does not compile it again.
"""
from __future__ import annotations

import __future__
import hashlib
import marshal
import sys
import types

from . import cache

CHUNK_LINES = 4000
_FUTURE_FLAGS = 0
for _feature in __future__.all_feature_names:
    _FUTURE_FLAGS |= getattr(__future__, _feature).compiler_flag


def _chunks(source: str) -> list[tuple[int, str]]:
    """(first line index, text) of runs of whole top-level statements: cut only
    before a `def`, `class` or decorator line at column 0 not itself decorated."""
    lines = source.split("\n")  # as the compiler counts lines (splitlines also cuts at \f and others)
    out: list[tuple[int, str]] = []
    start = 0
    previous = ""
    for i, line in enumerate(lines):
        if i - start >= CHUNK_LINES and line.startswith(("def ", "class ", "async def ", "@")) \
                and not previous.startswith("@"):
            out.append((start, "\n".join(lines[start:i]) + "\n"))
            start = i
        if line.strip():
            previous = line
    out.append((start, "\n".join(lines[start:])))
    return out


def _compile(source: str, filename: str) -> list[types.CodeType]:
    chunks = _chunks(source)
    if len(chunks) == 1:
        return [compile(source, filename, "exec")]
    try:
        first = compile(chunks[0][1], filename, "exec")
        flags = first.co_flags & _FUTURE_FLAGS  # `from __future__` lines hold for the whole module
        return [first] + [compile("\n" * start + text, filename, "exec", flags) for start, text in chunks[1:]]
    except SyntaxError:
        # a cut inside a statement, or a real error: the whole source says which
        return [compile(source, filename, "exec")]


def _code(source: str, filename: str, digest: str) -> list[types.CodeType]:
    place, wanted = cache.slot("codec", filename), cache.key("codec", digest, filename)
    data = cache.load(place, wanted)
    if data is not None:
        try:
            return marshal.loads(data)
        except (EOFError, ValueError, TypeError):  # damaged: compile it
            pass
    code = _compile(source, filename)
    cache.store(place, wanted, marshal.dumps(code))
    return code


def load_module(name: str, source: str, filename: str) -> types.ModuleType:
    module = types.ModuleType(name)
    module.__file__ = filename
    # what a result computed with the module (and cached, see cache.py) depends on
    module.__source_sha256__ = digest = hashlib.sha256(source.encode("utf-8", "surrogatepass")).hexdigest()
    sys.modules[name] = module  # dataclasses look the module up while processing classes
    try:
        for code in _code(source, filename, digest):
            exec(code, module.__dict__)
    except BaseException:
        del sys.modules[name]
        raise
    return module
