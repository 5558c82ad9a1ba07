"""Safe YAML loading that keeps file:line:col for every node.

Scalars are resolved by YAML 1.2 core rules instead of PyYAML's YAML 1.1 rules,
so `no`, `yes`, `on`, `off` stay strings (a field may well be named `no`).
Size, nesting depth and alias expansion are bounded so a hostile schema cannot
exhaust memory.
"""
from __future__ import annotations

import math
import re
import unicodedata
from pathlib import Path
from typing import Any, Optional

import yaml

from .diagnostics import Diagnostic, Loc, SchemaError

MAX_FILE_BYTES = 2 * 1024 * 1024
MAX_DEPTH = 48
MAX_NODES = 200_000  # after alias expansion

Path_ = tuple  # a path into the document: keys and list indexes


MAX_INT_LITERAL = 80  # a 64-bit value needs 66 (0b…); longer ones are mistakes, and slow to convert


class _Loader(yaml.SafeLoader):
    """SafeLoader whose implicit resolvers follow the YAML 1.2 core schema."""


_Loader.yaml_implicit_resolvers = {}
_CORE = [
    ("tag:yaml.org,2002:null", r"^(?:~|null|Null|NULL|)$", list("~nN") + [""]),
    ("tag:yaml.org,2002:bool", r"^(?:true|True|TRUE|false|False|FALSE)$", list("tTfF")),
    ("tag:yaml.org,2002:int", r"^(?:[-+]?[0-9]+|0o[0-7]+|0x[0-9a-fA-F]+|0b[01]+)$",
     list("-+0123456789")),
    ("tag:yaml.org,2002:float",
     r"^(?:[-+]?(?:\.[0-9]+|[0-9]+(?:\.[0-9]*)?)(?:[eE][-+]?[0-9]+)?|[-+]?\.(?:inf|Inf|INF)|\.(?:nan|NaN|NAN))$",
     list("-+.0123456789")),
]
for _tag, _pattern, _first in _CORE:
    _Loader.add_implicit_resolver(_tag, re.compile(_pattern), _first)

# libyaml builds the same nodes, marks included, many times faster. Its error
# messages differ, so a document it rejects is parsed again by _Loader, whose
# messages the diagnostics quote; so is one nested deeper than MAX_DEPTH, which
# libyaml's recursive composer could take to a stack overflow.
if getattr(yaml, "__with_libyaml__", False):
    class _FastLoader(yaml.CSafeLoader):
        """libyaml's parser with _Loader's resolvers."""

    _FastLoader.yaml_implicit_resolvers = _Loader.yaml_implicit_resolvers
else:
    _FastLoader = None

_SCALAR_TAGS = {
    "tag:yaml.org,2002:null", "tag:yaml.org,2002:bool", "tag:yaml.org,2002:int",
    "tag:yaml.org,2002:float", "tag:yaml.org,2002:str",
}


# Schema text flows into generated C and Python. Control characters (other than
# tab, newline and carriage return), line/paragraph separators, lone surrogates
# and invisible format characters (bidirectional overrides, zero-width spaces:
# "Trojan Source") could hide code from a reviewer or break a generated file.
_ALLOWED_CONTROLS = "\t\n\r"
_BANNED_CATEGORIES = {"Cc": "a control character", "Cf": "an invisible format character",
                      "Cs": "a lone surrogate", "Zl": "a line separator", "Zp": "a paragraph separator"}


_ASCII_CONTROL = re.compile(r"[\x00-\x08\x0b\x0c\x0e-\x1f\x7f]")


def _text_problem(text: str) -> str | None:
    if text.isascii() and not _ASCII_CONTROL.search(text):
        return None  # the common case, checked fast (alias expansion repeats scalars)
    for i, ch in enumerate(text):
        what = _BANNED_CATEGORIES.get(unicodedata.category(ch))
        if what and ch not in _ALLOWED_CONTROLS:
            return f"text contains {what} (U+{ord(ch):04X}) at character {i + 1}"
    return None


def _scalar(node: yaml.ScalarNode) -> Any:
    tag, text = node.tag, node.value
    if tag == "tag:yaml.org,2002:null":
        return None
    if tag == "tag:yaml.org,2002:bool":
        return text.lower() == "true"
    if tag == "tag:yaml.org,2002:int":
        return int(text, 0) if text[:2] in ("0x", "0o", "0b") else int(text)
    if tag == "tag:yaml.org,2002:float":
        low = text.lower()
        if low.endswith("inf"):
            return float("-inf") if low.startswith("-") else float("inf")
        return float("nan") if low.endswith("nan") else float(text)
    return text


class Document:
    """A loaded schema: plain data plus the location of every node by path."""

    def __init__(self, file: str, data: Any, locs: dict[Path_, Loc], text: str):
        self.file = file
        self.data = data
        self.locs = locs
        self.text = text

    def loc(self, path: Path_) -> Loc:
        """Location of the node at path, or of its nearest located ancestor."""
        path = tuple(path)
        while path not in self.locs and path:
            path = path[:-1]
        return self.locs.get(path, Loc(self.file, 1, 1))


def _shape_problem(text: str, loader, file: str) -> Diagnostic | None:
    """A collection nested deeper than MAX_DEPTH, or an alias inside the collection
    its anchor names (`a: &x [*x]`, a document without end), found on the parser's
    event stream, which does not recurse (the composers and any walk of the composed
    nodes do, into a stack overflow)."""
    open_anchors: list = []  # the anchor of each collection being read, innermost last
    for event in yaml.parse(text, Loader=loader):
        if isinstance(event, yaml.CollectionStartEvent):
            open_anchors.append(event.anchor)
            if len(open_anchors) > MAX_DEPTH:
                mark = event.start_mark
                return Diagnostic(Loc(file, mark.line + 1, mark.column + 1),
                                  f"nesting deeper than {MAX_DEPTH}", "flatten the schema")
        elif isinstance(event, yaml.CollectionEndEvent):
            open_anchors.pop()
        elif isinstance(event, yaml.AliasEvent) and event.anchor in open_anchors:
            mark = event.start_mark
            return Diagnostic(Loc(file, mark.line + 1, mark.column + 1),
                              f"alias *{event.anchor} refers to the collection that contains it "
                              "(a document without end)",
                              f"write the data out instead of *{event.anchor}, or anchor a "
                              "collection outside this one")
    return None


def _compose(text: str, file: str) -> yaml.Node | None:
    # libyaml first where it is built in; on any error the pure parser runs again, since
    # its messages are the ones the diagnostics quote
    loaders = [_FastLoader, _Loader] if _FastLoader is not None else [_Loader]
    for loader in loaders:
        try:
            problem = _shape_problem(text, loader, file)
            if problem is None:
                return yaml.compose(text, Loader=loader)
        except yaml.YAMLError:
            if loader is _Loader:
                raise
            continue
        raise SchemaError([problem])


def _children(n: yaml.Node) -> list:
    """The nodes `load_text` builds under `n`, in its order (a mapping's values; keys are scalars)."""
    if isinstance(n, yaml.SequenceNode):
        return n.value
    if isinstance(n, yaml.MappingNode):
        return [value for _, value in n.value]
    return []


def _node_over(root: yaml.Node, limit: int) -> Optional[yaml.Node]:
    """The node at which a document with its aliases expanded passes `limit` nodes, or None.
    An alias is one node object met again, so each distinct node's expanded size is
    counted once: a YAML bomb is found without expanding it."""
    sizes: dict[int, int] = {}

    def size(n: yaml.Node) -> int:
        got = sizes.get(id(n))
        if got is None:
            got = sizes[id(n)] = 1 + sum(size(child) for child in _children(n))
        return got

    if size(root) <= limit:
        return None
    count, n = 0, root
    while True:  # descend into the first subtree that does not fit what is left
        count += 1
        if count > limit:
            return n
        for child in _children(n):
            if count + size(child) > limit:
                n = child
                break
            count += size(child)


def _loc(file: str, node: yaml.Node) -> Loc:
    return Loc(file, node.start_mark.line + 1, node.start_mark.column + 1)


def load_text(text: str, file: str) -> Document:
    if len(text.encode("utf-8", "surrogatepass")) > MAX_FILE_BYTES:
        raise SchemaError([Diagnostic(Loc(file, 1, 1),
                                      f"schema is larger than {MAX_FILE_BYTES} bytes",
                                      "split the protocol or remove generated content")])
    try:
        node = _compose(text, file)
    except yaml.MarkedYAMLError as exc:
        mark = exc.problem_mark or exc.context_mark
        loc = Loc(file, mark.line + 1, mark.column + 1) if mark else Loc(file, 1, 1)
        context = ""
        if exc.context and exc.context_mark and exc.context_mark is not mark:
            context = f" ({exc.context} that starts at line {exc.context_mark.line + 1})"
        raise SchemaError([Diagnostic(loc, f"YAML syntax: {exc.problem or exc}{context}",
                                      "fix the YAML syntax here or where the enclosing block starts")]) from None
    except yaml.YAMLError as exc:
        raise SchemaError([Diagnostic(Loc(file, 1, 1), f"YAML: {exc}", "")]) from None
    if node is None:
        raise SchemaError([Diagnostic(Loc(file, 1, 1), "schema is empty",
                                      "start with `codeword: 1` and `protocol: <name>`")])
    over = _node_over(node, MAX_NODES)
    if over is not None:
        raise SchemaError([Diagnostic(_loc(file, over), f"document expands to more than {MAX_NODES} nodes",
                                      "aliases expand too much (YAML bomb?)")])
    locs: dict[Path_, Loc] = {}
    errors: list[Diagnostic] = []
    count = [0]

    def build(n: yaml.Node, path: Path_, depth: int) -> Any:
        count[0] += 1
        if count[0] > MAX_NODES:
            raise SchemaError([Diagnostic(_loc(file, n),
                                          f"document expands to more than {MAX_NODES} nodes",
                                          "aliases expand too much (YAML bomb?)")])
        if depth > MAX_DEPTH:
            raise SchemaError([Diagnostic(_loc(file, n), f"nesting deeper than {MAX_DEPTH}",
                                          "flatten the schema")])
        locs.setdefault(path, _loc(file, n))
        if isinstance(n, yaml.ScalarNode):
            if n.tag not in _SCALAR_TAGS:
                errors.append(Diagnostic(_loc(file, n), f"YAML tag {n.tag!r} is not allowed",
                                         "use plain YAML data without tags"))
                return None
            if n.tag == "tag:yaml.org,2002:int" and len(n.value) > MAX_INT_LITERAL:
                errors.append(Diagnostic(_loc(file, n), f"integer literal of {len(n.value)} characters",
                                         f"no field is wider than 64 bits: write at most {MAX_INT_LITERAL} "
                                         "characters"))
                return 0
            value = _scalar(n)
            if isinstance(value, str):
                problem = _text_problem(value)
                if problem:
                    errors.append(Diagnostic(_loc(file, n), problem,
                                             "remove it; write what it stands for in words"))
            elif isinstance(value, float) and not math.isfinite(value):
                errors.append(Diagnostic(_loc(file, n), f"number {n.value!r} is not finite",
                                         "use a finite number"))
            return value
        if isinstance(n, yaml.SequenceNode):
            if n.tag != "tag:yaml.org,2002:seq":
                errors.append(Diagnostic(_loc(file, n), f"YAML tag {n.tag!r} is not allowed",
                                         "use plain YAML data without tags"))
            return [build(item, path + (i,), depth + 1) for i, item in enumerate(n.value)]
        if n.tag != "tag:yaml.org,2002:map":
            errors.append(Diagnostic(_loc(file, n), f"YAML tag {n.tag!r} is not allowed",
                                     "merge keys (<<) and tags are not supported"))
            return {}
        result: dict[Any, Any] = {}
        for key_node, value_node in n.value:
            if not isinstance(key_node, yaml.ScalarNode):
                errors.append(Diagnostic(_loc(file, key_node), "mapping keys must be scalars",
                                         "use a plain name as the key"))
                continue
            key = _scalar(key_node)
            if isinstance(key, str) and _text_problem(key):
                errors.append(Diagnostic(_loc(file, key_node), "key: " + _text_problem(key),
                                         "remove it; keys are plain names"))
            if not isinstance(key, (str, int)) or isinstance(key, bool):
                key = key_node.value
            if key in result:
                errors.append(Diagnostic(_loc(file, key_node), f"duplicate key {key!r}",
                                         "each key may appear once in a mapping"))
                continue
            locs[path + (key,)] = _loc(file, value_node)
            result[key] = build(value_node, path + (key,), depth + 1)
            locs[path + (key,)] = _loc(file, key_node)
        return result

    data = build(node, (), 0)
    if errors:
        raise SchemaError(errors)
    return Document(file, data, locs, text)


def load_file(path: Path | str, display: str | None = None) -> Document:
    path = Path(path)
    name = display or str(path)
    try:
        raw = path.read_bytes()
    except OSError as exc:
        raise SchemaError([Diagnostic(Loc(name, 1, 1), f"cannot read schema: {exc.strerror}", "")]) from None
    if len(raw) > MAX_FILE_BYTES:
        raise SchemaError([Diagnostic(Loc(name, 1, 1),
                                      f"schema is larger than {MAX_FILE_BYTES} bytes", "")])
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise SchemaError([Diagnostic(Loc(name, 1, 1), f"schema is not UTF-8 ({exc.reason})",
                                      "save the file as UTF-8")]) from None
    return load_text(text, name)
