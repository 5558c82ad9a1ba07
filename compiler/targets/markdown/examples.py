"""The examples the docs show, produced by the generated Python codec.

Every wire form on a page is the codec's own output for the schema's values,
checked first against the hand-written form with compiler/examples.py; a
mismatch stops the build with the example's file:line.
"""
from __future__ import annotations

import types
from typing import Any

from ...diagnostics import Diagnostic, SchemaError
from ...examples import ExampleChecker
from ...model import Example, Message, Protocol, Sequence
from .text import DecisionLinker, cell, code, decoded_fields


def _wire_text(form: str, wire: Any, p: Protocol) -> str:
    if form == "hex":
        return bytes(wire).hex(" ")
    if form == "word":
        digits = ((p.framing.word_bits or p.framing.max_bits or 32) + 3) // 4
        return f"0x{wire:0{digits}x}"
    return str(wire)


def _same(ex: Example, form: str, produced: Any, written: Any) -> None:
    """The codec's output is what the page shows; it must be the hand-written form."""
    if produced != written:
        raise SchemaError([Diagnostic(ex.loc, f"example {ex.name!r}: the codec writes {produced!r} "
                                              f"but the example says {written!r}",
                                      "fix the example or the schema")])


def message_example(p: Protocol, codec: types.ModuleType, m: Message, ex: Example,
                    linker: DecisionLinker) -> dict:
    checker = ExampleChecker(p, codec)
    forms = checker.forms(m, ex)
    view = {"name": cell(ex.name), "source": linker.link(cell(ex.source or "")), "forms": [],
            "decoded": [], "error": None, "rewritten": []}
    if ex.errors:
        for form, wire, decode, _ in forms:
            try:
                decode(wire)
            except codec.CodecError as exc:
                view["forms"].append((form, code(_wire_text(form, wire, p))))
                view["error"] = linker.link(cell(str(exc)))
        return view
    value = codec.from_dict(m.name, ex.values or {})
    for form, wire, decode, encode in forms:
        if ex.decode_only:
            # A reader's leniency: show what was read and what a writer sends instead.
            view["forms"].append((form, code(_wire_text(form, wire, p))))
            view["rewritten"].append((form, code(_wire_text(form, encode(decode(wire)), p))))
            continue
        produced = encode(value)
        _same(ex, form, produced, wire)
        view["forms"].append((form, code(_wire_text(form, produced, p))))
    decoded = forms[0][2](forms[0][1]) if forms else value
    view["decoded"] = [(name, code(text)) for name, text in decoded_fields(decoded)]
    return view


def sequence_example(p: Protocol, codec: types.ModuleType, s: Sequence, ex: Example,
                     linker: DecisionLinker) -> dict:
    view = {"name": cell(ex.name), "source": linker.link(cell(ex.source or "")), "text": None,
            "hex": None, "errors": [], "units": None}
    if ex.errors:
        decode = getattr(codec, f"decode_{s.name}_text") if ex.text is not None else getattr(codec, f"decode_{s.name}")
        wire = ex.text if ex.text is not None else ex.hex
        try:
            decode(wire)
        except codec.SequenceError as exc:
            view["errors"] = [linker.link(cell((f"line {e.line}: " if getattr(e, "line", None) else "") + str(e)))
                              for e in exc.errors]
        view["text"] = wire.rstrip("\n") if isinstance(wire, str) else None
        view["hex"] = wire.hex(" ") if isinstance(wire, bytes) else None
        return view
    if ex.text is not None:
        seq = getattr(codec, f"decode_{s.name}_text")(ex.text)
    else:
        seq = getattr(codec, f"decode_{s.name}")(ex.hex)
    if ex.text is not None:
        produced = getattr(codec, f"encode_{s.name}_text")(seq)
        _same(ex, "text", produced, "".join(line.strip() + "\n" for line in ex.text.splitlines() if line.strip()))
        view["text"] = produced.rstrip("\n")
    if ex.hex is not None:
        produced = getattr(codec, f"encode_{s.name}")(seq)
        _same(ex, "hex", produced, ex.hex)
        view["hex"] = produced.hex(" ")
    view["units"] = _count_units(seq)
    return view


def _count_units(seq: Any) -> int:
    """Messages in a decoded sequence (nested groups and lists counted through)."""
    import dataclasses
    if isinstance(seq, list):
        return sum(_count_units(x) for x in seq)
    if dataclasses.is_dataclass(seq) and not hasattr(type(seq), "NAME"):
        return sum(_count_units(getattr(seq, f.name)) for f in dataclasses.fields(seq))
    return 1 if seq is not None else 0
