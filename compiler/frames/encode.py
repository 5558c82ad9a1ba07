"""`codeword encode`: one message from field values, as hex or raw bytes."""
from __future__ import annotations

import argparse
import json
import sys
from typing import Any

from .. import signing_key
from ..model import Field, Message, Protocol
from ..usage import UsageError
from .stream import open_codec


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("schema", help="schema file, or a protocol name of the project")
    parser.add_argument("message", help="the message to encode (its name in the schema)")
    parser.add_argument("values", nargs="*", metavar="FIELD=VALUE",
                        help="field values: numbers in logical units, enum members by name, flags as "
                             "a|b, bytes in hex, group members as group.field=VALUE")
    parser.add_argument("--json", metavar="FILE", help="take the values from a JSON object in FILE ('-': stdin)")
    parser.add_argument("--raw", action="store_true", help="write the frame's bytes, not hex")
    signing_key.add_arguments(parser, "sign the frame")


def run(args: argparse.Namespace) -> int:
    protocol, codec = open_codec(args.schema)
    key = signing_key.signing_key(args, protocol)
    message = next((m for m in protocol.messages if m.name == args.message), None)
    if message is None:
        raise UsageError(f"{protocol.name} has no message {args.message!r} "
                         f"(messages: {', '.join(m.name for m in protocol.messages)})")
    values = _from_json(args.json) if args.json else {}
    for item in args.values:
        name, sep, text = item.partition("=")
        if not sep:
            raise UsageError(f"{item!r}: write a value as FIELD=VALUE")
        _put(values, name.split("."), _literal(text))
    fields = _fields(protocol, message)
    _check_names(message, values, fields)
    if key is not None:
        _no_signature_given(protocol, values)
    values = _members(fields, values)
    try:
        obj = codec.from_dict(message.name, values)
        wire = codec.encode(obj, key=key) if key is not None else codec.encode(obj)
    except codec.CodecError as exc:
        print(f"codeword encode: {exc}", file=sys.stderr)
        return 1
    except (KeyError, TypeError, ValueError) as exc:  # a value from_dict cannot convert
        print(f"codeword encode: {message.name}: {type(exc).__name__}: {exc}", file=sys.stderr)
        return 1
    if args.raw:
        sys.stdout.buffer.write(wire.encode("utf-8") if isinstance(wire, str) else wire)
    else:
        print(wire.rstrip("\r\n") if isinstance(wire, str) else wire.hex(" "))
    return 0


def _fields(protocol: Protocol, message: Message) -> tuple[Field, ...]:
    """The values a message takes: its members, then the trailer's fields (sent when its flag is set)."""
    trailer = protocol.framing.trailer
    return message.members + (trailer.fields if trailer is not None else ())


def _no_signature_given(protocol: Protocol, values: dict) -> None:
    """With a key the signature is computed: a value given for it would not be sent."""
    name = protocol.framing.trailer.signature.name
    if name in values:
        raise UsageError(f"{name}: the key computes it; leave the value out, or the key")


def _from_json(path: str) -> dict:
    try:
        text = sys.stdin.read() if path == "-" else open(path, encoding="utf-8").read()
        values = json.loads(text)
    except OSError as exc:
        raise UsageError(f"{path}: cannot read: {exc.strerror}") from None
    except ValueError as exc:
        raise UsageError(f"{path}: not JSON: {exc}") from None
    if not isinstance(values, dict):
        raise UsageError(f"{path}: a JSON object of field values is needed")
    return values


def _literal(text: str) -> Any:
    """A number, true/false or a JSON list as such; anything else as text."""
    try:
        value = json.loads(text)
    except ValueError:
        return text
    return value if not isinstance(value, dict) else text


def _put(values: dict, path: list[str], value: Any) -> None:
    for part in path[:-1]:
        inner = values.setdefault(part, {})
        if not isinstance(inner, dict):
            raise UsageError(f"{'.'.join(path)}: {part} is given a value and members")
        values = inner
    values[path[-1]] = value


def _check_names(message: Message, values: dict, fields=None, prefix: str = "") -> None:
    fields = {f.name: f for f in (fields if fields is not None else message.members) if f.is_member}
    for name, value in values.items():
        field = fields.get(name)
        if field is None:
            raise UsageError(f"{message.name} has no field {prefix}{name} "
                             f"(fields: {', '.join(prefix + n for n in fields) or 'none'})")
        if field.kind == "group" and isinstance(value, dict):
            _check_names(message, value, field.fields, f"{prefix}{name}.")


def _members(fields: tuple[Field, ...], values: dict) -> dict:
    """Flags written as a|b become lists of member names; groups recurse."""
    by_name = {f.name: f for f in fields}
    out = {}
    for name, value in values.items():
        field = by_name[name]
        if field.flags is not None and isinstance(value, str):
            value = [] if value in ("", "0") else [part.strip() for part in value.replace(",", "|").split("|")]
        elif field.kind == "group" and isinstance(value, dict):
            value = _members(field.fields, value)
        out[name] = value
    return out
