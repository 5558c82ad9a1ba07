"""The one escaping function per output context.

Schema text (titles, docs, notes, units, user messages, rule ids, example names
and sources, history, the schema's file name, …) reaches a generated file only
through one of these. Identifiers come from names the front end validated and
need none. Each function returns text that cannot leave its context, whatever
the input: no newline in a one-line comment, no comment or string terminator,
no preprocessor line, no HTML.

The template environment (render.py) installs them as filters and refuses to
print a model `Text` object that did not pass through one.
"""
from __future__ import annotations

import html
import json
import re
from typing import Any


def one_line(value: Any) -> str:
    """Every run of whitespace (newlines, CR, form feed, NEL …) becomes one space."""
    return " ".join(str(value).split())


# -- C (and Promela, which goes through the C preprocessor) -------------------------------

def c_comment(value: Any) -> str:
    """Text inside a one-line `/* … */` comment: no newline (a `#` line after it would be
    a directive), no `*/` (ends the comment), no `/*` (-Wcomment), no `??` (trigraphs)."""
    text = one_line(value).replace("*/", "* /").replace("/*", "/ *")
    return re.sub(r"\?(?=\?)", "? ", text)


pml_comment = c_comment


def c_string(value: Any) -> str:
    """A C string literal, quotes included: printable ASCII as is, every other byte of
    the UTF-8 encoding as a hex escape closed by `""` so no hex digit can follow it."""
    out = []
    for ch in str(value):
        if ch in '"\\?':  # '?' escaped: "??>" would be a trigraph in ISO C
            out.append("\\" + ch)
        elif " " <= ch <= "~":
            out.append(ch)
        else:
            out.extend(f'\\x{b:02x}""' for b in ch.encode("utf-8"))
    return '"' + "".join(out) + '"'


def c_char(ch: str) -> str:
    """A C character constant for one character."""
    if ch in "'\\":
        return "'\\" + ch + "'"
    if " " <= ch <= "~":
        return f"'{ch}'"
    return f"'\\x{ord(ch):02x}'"


# -- Python --------------------------------------------------------------------------------

def py_comment(value: Any) -> str:
    """Text after `#`: one line, and no `coding:`/`coding=` that Python would take for the
    file's encoding declaration on its first two lines (UTF-7 turns `+AAo-` into a newline)."""
    return re.sub(r"(?i)(coding)(?=[:=])", r"\1 ", one_line(value))


def py_string(value: Any) -> str:
    """A Python literal for a string (or any repr-able constant), quotes included."""
    return repr(value)


def py_docstring(value: Any) -> str:
    """Text inside a triple-quoted docstring: one line, every backslash and quote escaped,
    so no run of quotes can close it, even at its end."""
    return one_line(value).replace("\\", "\\\\").replace('"', '\\"')


# -- Markdown pages (rendered to HTML by MkDocs) ---------------------------------------------

_CODE_SPAN = re.compile(r"`([^`]+)`")


def _md_plain(text: str) -> str:
    """Markdown source that shows `text` literally: no HTML, no link or image, no code span,
    no table cell break. Backslashes first, so none can escape what follows."""
    text = text.replace("\\", "\\\\")
    text = html.escape(text, quote=False)
    for ch in "[]`|":
        text = text.replace(ch, "\\" + ch)
    return text


def md_text(value: Any) -> str:
    """One line of schema prose in Markdown, safe in a paragraph or a table cell. Single
    backtick pairs stay code spans (Markdown escapes their content itself); everything
    else is shown literally."""
    text = one_line(value)
    out, at = [], 0
    for span in _CODE_SPAN.finditer(text):
        out.append(_md_plain(text[at:span.start()]))
        out.append(md_code(span.group(1)))
        at = span.end()
    out.append(_md_plain(text[at:]))
    return "".join(out)


def md_code(value: Any) -> str:
    """An inline code span that survives inside a table cell: its fence is longer than
    any run of backticks in the text."""
    text = one_line(value).replace("|", "\\|")
    longest = max((len(run) for run in re.findall(r"`+", text)), default=0)
    fence = "`" * (longest + 1)
    pad = " " if text.startswith("`") or text.endswith("`") or not text.strip() else ""
    return f"{fence}{pad}{text}{pad}{fence}"


def md_fence(value: Any) -> str:
    """A fence for a fenced code block holding `value`: longer than any backtick run in it."""
    longest = max((len(run) for run in re.findall(r"`+", str(value))), default=0)
    return "`" * max(3, longest + 1)


_MERMAID = str.maketrans({"`": "'", ";": ",", ":": ",", "%": " percent", "#": "No.", "<": "(", ">": ")",
                          "&": "and", '"': "'", "{": "(", "}": ")", "[": "(", "]": ")", "|": "/"})


def mermaid_text(value: Any) -> str:
    """Text in a Mermaid state description inside a ```mermaid fence: one line, no
    backtick (it would end the fence), nothing Mermaid reads as syntax (`;` ends a
    statement, `:` splits a description, `%%` starts a comment, `#` an entity code,
    brackets and quotes shape nodes) and no HTML."""
    return one_line(value).translate(_MERMAID)


def html_comment(value: Any) -> str:
    """Text inside `<!-- … -->`: one line, no `--` (so no `-->` or `--!>`), no `<` or `>`."""
    text = one_line(value).replace("<", "&lt;").replace(">", "&gt;")
    return re.sub(r"-(?=-)", "- ", text)


def yaml_string(value: Any) -> str:
    """A YAML double-quoted scalar: a JSON string in ASCII, which YAML reads as the same
    text, so that no name or path can be taken for a number, a boolean or syntax."""
    return json.dumps(str(value), ensure_ascii=True)


FILTERS = {"c_comment": c_comment, "c_string": c_string, "c_char": c_char, "pml_comment": pml_comment,
           "py_comment": py_comment, "py_string": py_string, "py_docstring": py_docstring,
           "md_text": md_text, "md_code": md_code, "md_fence": md_fence, "html_comment": html_comment,
           "mermaid_text": mermaid_text, "yaml_string": yaml_string}
