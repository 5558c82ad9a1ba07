"""Names that are distinct in a schema but the same in generated code.

Python class names are CamelCase (`set_led` and `setLed` both give `SetLed`);
C constants are upper case with a prefix (`left` and `LEFT` both give
`P_SIDE_LEFT`; enum `side` member `left_x` and enum `side_left` member `x`
both give `P_SIDE_LEFT_X`). A sequence shares the class namespace with
messages (and its C functions `p_<name>_…` with theirs). C functions and
types are `p_<name>_<suffix>` for messages, sequences and machines next to the
protocol's own `p_<suffix>` (a message `parser` would define `p_parser_t`, the
stream parser's type; a message `log_iter` the iterator type of a sequence
`log`). A second definition would silently replace the first in Python and
fail to compile in C, so such schemas are refused.
"""
from __future__ import annotations

from typing import Any, Iterator

from .names import GENERATED_CLASSES, camel

Clash = tuple[tuple, str]  # (path into the document, message)


def _classes(d: dict[str, Any]) -> Iterator[tuple[str, tuple, str]]:
    for section, what in (("messages", "message"), ("enums", "enum"), ("flags", "flag set"),
                          ("sequences", "sequence")):
        for name in d.get(section, {}) or {}:
            if isinstance(name, str):
                yield camel(name), (section, name), f"{what} {name!r}"
    for name, body in (d.get("sequences", {}) or {}).items():
        if isinstance(name, str) and isinstance(body, dict):
            yield from _group_classes(camel(name), body.get("items"), ("sequences", name), name)


def _group_classes(owner: str, items: Any, path: tuple, dotted: str) -> Iterator[tuple[str, tuple, str]]:
    """A sequence's groups of items are classes named after the path to them."""
    for i, item in enumerate(items if isinstance(items, list) else []):
        if isinstance(item, dict) and isinstance(item.get("name"), str) and "items" in item:
            cls, where = owner + camel(item["name"]), f"{dotted}.{item['name']}"
            yield cls, path + ("items", i, "name"), f"sequence group {where!r}"
            yield from _group_classes(cls, item["items"], path + ("items", i), where)


def _constants(d: dict[str, Any]) -> Iterator[tuple[str, tuple, str]]:
    # What the C header defines on its own: first, so a schema name that meets one is the clash.
    yield "DIR_ANY", (), "the constant that accepts every direction"
    yield "STREAM_MAX", (), "the constant of the largest frame a stream holds"
    yield "SELECTED_MESSAGES", (), "the macro that selects the messages a firmware handles"
    for name in d.get("flags", {}) or {}:
        if isinstance(name, str):
            yield f"{name}_ALL".upper(), (), f"the mask of every bit of flag set {name!r}"
    for name in d.get("messages", {}) or {}:
        if isinstance(name, str):
            yield f"MSG_{name}".upper(), ("messages", name), f"message {name!r}"
            yield f"SELECT_{name}".upper(), ("messages", name), f"the selection macro of message {name!r}"
            yield f"HANDLES_{name}".upper(), ("messages", name), f"the selection macro of message {name!r}"
    for name in d.get("directions", {}) or {}:
        if isinstance(name, str):
            yield f"DIR_{name}".upper(), ("directions", name), f"direction {name!r}"
    for section, key in (("enums", "values"), ("flags", "bits")):
        for set_name, body in (d.get(section, {}) or {}).items():
            members = body.get(key, []) if isinstance(body, dict) else []
            for i, member in enumerate(members):
                if isinstance(member, dict) and isinstance(member.get("name"), str):
                    yield (f"{set_name}_{member['name']}".upper(), (section, set_name, key, i, "name"),
                           f"{set_name}.{member['name']}")


# What templates/c defines for each kind of schema entity, after `p_<name>`.
C_SUFFIXES = {
    "messages": ("t", "encode", "decode", "raw", "check_raw", "from_word", "to_word", "from_values",
                 "to_text", "parse_body"),
    "sequences": ("check", "decode", "expected", "grammar_init", "iter_init", "iter_next", "iter_t",
                  "rules", "split", "step", "unit"),
    "machines": ("t", "init", "receive", "reset", "send", "tick"),
}
# ... and for the protocol itself, after `p_`.
C_PROTOCOL = ("encode", "decode", "decode_kind", "decode_text", "decode_word", "find", "split",
              "message_t", "parser_t", "parser_init", "parser_feed", "parser_drop", "parser_next",
              "scan", "scan_state_t", "scan_start", "scan_byte", "scan_restart", "scan_fail", "frame_at",
              "scan_finish", "parser_finish", "ignored", "line_end",
              "machine_out_t", "machine_out_clear")


def _c_names(d: dict[str, Any]) -> Iterator[tuple[str, tuple, str]]:
    for name in C_PROTOCOL:
        yield name, (), "the protocol's own definitions"
    for section, suffixes in C_SUFFIXES.items():
        what = section[:-1]
        for name in d.get(section, {}) or {}:
            if isinstance(name, str):
                for suffix in suffixes:
                    yield f"{name}_{suffix}", (section, name), f"{what} {name!r}"


def generated_name_clashes(d: dict[str, Any]) -> list[Clash]:
    found: list[Clash] = []
    first_c: dict[str, str] = {}
    for generated, path, what in _c_names(d):
        other = first_c.setdefault(generated, what)
        if other != what and path:
            found.append((path, f"{what} and {other} would both define the C name <p>_{generated}"))
    for kind, names in (("Python class", _classes(d)), ("C constant", _constants(d))):
        first: dict[str, str] = {}
        for generated, path, what in names:
            if kind == "Python class" and generated in GENERATED_CLASSES:
                found.append((path, f"{what} would be the Python class {generated}, which the "
                                    "generated module already defines"))
            elif generated in first and path:
                found.append((path, f"{what} and {first[generated]} would both be the {kind} "
                                    f"{generated}"))
            else:
                first[generated] = what
    return found
