"""The Jinja2 environment shared by every target: strict, with the escaping filters of
escape.py, and refusing model text that skipped them."""
from __future__ import annotations

from functools import lru_cache
from pathlib import Path

import jinja2

from ..model import Text
from .escape import FILTERS
from .template_cache import TemplateCache

def _templates() -> Path:
    """The templates: inside the installed package (codeword/templates), or beside
    the package's source folder in a checkout (templates/)."""
    package = Path(__file__).resolve().parent.parent
    inside = package / "templates"
    return inside if inside.is_dir() else package.parent / "templates"


TEMPLATES = _templates()


def finalize(value):
    """Every `{{ … }}` passes here: schema text held as a model `Text` must have gone
    through the escaping filter of its context (escape.py) first."""
    if isinstance(value, Text):
        raise TypeError(f"schema text {value.en[:40]!r} reaches a template unescaped: "
                        "pass it through the filter of its output context")
    return value


OPTIONS = dict(undefined=jinja2.StrictUndefined, trim_blocks=True, lstrip_blocks=True,
               keep_trailing_newline=True, autoescape=False, finalize=finalize)


@lru_cache(maxsize=1)
def environment() -> jinja2.Environment:
    # by name: a function's repr holds its address, which would change the cache key every run
    settings = repr((sorted((k, getattr(v, "__qualname__", v)) for k, v in OPTIONS.items()), sorted(FILTERS)))
    env = jinja2.Environment(loader=jinja2.FileSystemLoader(str(TEMPLATES)),
                             bytecode_cache=TemplateCache(TEMPLATES / "__pycache__", settings), **OPTIONS)
    env.filters.update(FILTERS)
    return env


def compile_templates() -> None:
    """Compile every template into the cache, whatever PYTHONDONTWRITEBYTECODE says
    (scripts/setup, next to byte-compiling the package)."""
    env = environment()
    env.bytecode_cache.write = True
    for name in env.list_templates(filter_func=lambda name: "__pycache__" not in name.split("/")):
        env.get_template(name)


def tidy(source: str, max_blank: int) -> str:
    """Collapse the blank-line runs left by template control blocks; no trailing spaces."""
    out: list[str] = []
    blank = 0
    for line in source.splitlines():
        line = line.rstrip()
        blank = blank + 1 if not line else 0
        if blank <= max_blank:
            out.append(line)
    while out and not out[-1]:
        out.pop()
    while out and not out[0]:
        out.pop(0)
    return "\n".join(out) + "\n"
