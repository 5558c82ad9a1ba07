"""Check every schema example against the generated Python codec, both ways.

An example's wire forms are written by hand from the seed or by hand
calculation; decoding them must give the example's values and encoding the
values must give them back. Error examples must fail with the named field/rule.
"""
from __future__ import annotations

import math
import struct
import types
from typing import Any, Optional

from .diagnostics import Diagnostic
from .model import Example, Field, Message, Protocol, Sequence, SequenceItem, StreamEvent, StreamExample
from .names import camel


def _matches(error: Any, field: str, rule: str) -> bool:
    fields = {error.field or "", (error.field or "").split(".")[-1]}
    return field in fields and rule in (error.rule, error.decision)


def _on_wire(f: Field, value: Any) -> Any:
    """What the wire carries of a logical number: a scaled or offset integer's raw step
    (rounded half up, as the encoder rounds), an f32's single-precision value; any other
    value itself. So 12.6 and 12.600000000000001 on a field of scale 0.1 are both raw 126."""
    if not isinstance(value, (int, float)) or isinstance(value, bool) or not math.isfinite(value):
        return value
    if f.kind in ("uint", "int") and f.enum is None and f.flags is None \
            and (f.scale is not None or (f.offset and not float(f.offset).is_integer())):
        return math.floor((value - (f.offset or 0)) / (f.scale or 1) + 0.5)
    if f.kind == "float" and f.bits == 32:
        try:
            return struct.unpack("<f", struct.pack("<f", value))[0]
        except OverflowError:
            return value
    return value


def same_on_wire(fields: tuple[Field, ...], got: dict, want: dict) -> bool:
    """Whether two messages (as to_dict gives them) carry the same values on the wire."""
    if got.keys() != want.keys():
        return False
    by_name = {f.name: f for f in fields}
    return all(_same_value(by_name.get(key), got[key], want[key]) for key in got)


def _same_value(f: Optional[Field], got: Any, want: Any) -> bool:
    if f is None or got == want:
        return got == want
    if isinstance(got, list) and isinstance(want, list) and f.count is not None:
        return len(got) == len(want) and all(_same_value(f.element, a, b) for a, b in zip(got, want))
    if isinstance(got, dict) and isinstance(want, dict):
        return same_on_wire(f.fields, got, want)
    return _on_wire(f, got) == _on_wire(f, want)


def _describe(error: BaseException) -> str:
    return f"{type(error).__name__}: {error}"


class ExampleChecker:
    def __init__(self, p: Protocol, module: types.ModuleType):
        self.p = p
        self.mod = module
        self.problems: list[Diagnostic] = []

    def fail(self, ex: Example, message: str, hint: str = "") -> None:
        self.problems.append(Diagnostic(ex.loc, f"example {ex.name!r}: {message}",
                                        hint or "fix the example or the schema"))

    # -- wire forms of one message ---------------------------------------------------------
    def forms(self, m: Message, ex: Example) -> list[tuple[str, Any, Any, Any]]:
        """(form, wire value, decoder, encoder) for each wire form the example gives."""
        cls = self.mod.MESSAGES[m.name]
        out = []
        if ex.hex is not None:
            decoder = (lambda d: self.mod.decode(d, ex.direction)) if self.p.self_identifying else cls.decode
            out.append(("hex", ex.hex, decoder, self.mod.encode))
        if ex.word is not None:
            out.append(("word", ex.word, self.mod.decode_word, self.mod.encode_word))
        if ex.text is not None:
            if self.p.framing.kind == "text":
                out.append(("text", ex.text, lambda t: self.mod.decode(t, ex.direction), self.mod.encode))
            else:
                out.append(("text", ex.text, self.mod.decode_text, self.mod.encode_text))
        return out

    def check_message(self, m: Message, ex: Example) -> None:
        codec_error = self.mod.CodecError
        if ex.errors:
            expected = ex.errors[0]
            for form, wire, decode, _ in self.forms(m, ex):
                try:
                    got = decode(wire)
                except codec_error as exc:
                    if not _matches(exc, expected.field, expected.rule):
                        self.fail(ex, f"{form} fails with {_describe(exc)}, expected field "
                                      f"{expected.field!r} rule {expected.rule!r}")
                    continue
                except Exception as exc:  # a crash is a codec bug, reported as such
                    self.fail(ex, f"{form}: decoder crashed with {_describe(exc)}")
                    continue
                self.fail(ex, f"{form} decodes to {got!r} but should fail on {expected.field} "
                              f"({expected.rule})")
            return
        try:
            value = self.mod.from_dict(m.name, ex.values or {})
        except Exception as exc:
            self.fail(ex, f"values do not build a {m.name}: {_describe(exc)}")
            return
        for form, wire, decode, encode in self.forms(m, ex):
            try:
                got = decode(wire)
            except Exception as exc:
                self.fail(ex, f"{form} {self.show(wire)} does not decode: {_describe(exc)}")
                continue
            if got != value and not self.same_message(m, got, value):
                self.fail(ex, f"{form} {self.show(wire)} decodes to {got!r}, expected {value!r}",
                          "scaled and f32 values are compared at the field's resolution, as the "
                          "wire carries them: fix the example or the schema")
            if ex.decode_only:
                continue
            try:
                out = encode(value)
            except Exception as exc:
                self.fail(ex, f"values do not encode: {_describe(exc)}")
                continue
            if out != wire:
                self.fail(ex, f"values encode to {self.show(out)}, the example says {self.show(wire)}",
                          "the wire form is written by hand: check the calculation and the schema")

    @staticmethod
    def same_message(m: Message, got: Any, want: Any) -> bool:
        try:
            return same_on_wire(m.layout, got.to_dict(), want.to_dict())
        except Exception:  # a value to_dict cannot show is compared exactly
            return False

    @staticmethod
    def show(wire: Any) -> str:
        if isinstance(wire, (bytes, bytearray)):
            return bytes(wire).hex(" ")
        if isinstance(wire, int):
            return hex(wire)
        return repr(wire)

    # -- sequences -------------------------------------------------------------------------
    def sequence_value(self, s: Sequence, values: dict) -> Any:
        def build(items: tuple[SequenceItem, ...], data: dict, cls_name: str) -> Any:
            kwargs = {}
            for item in items:
                raw = data.get(item.name)
                many = item.repeat or item.count is not None
                if item.message:
                    make = lambda v: self.mod.from_dict(item.message, v or {})  # noqa: E731
                else:
                    inner = cls_name + camel(item.name)
                    make = lambda v, inner=inner, item=item: build(item.items, v or {}, inner)  # noqa: E731
                kwargs[item.name] = [make(v) for v in raw or []] if many else make(raw)
            return getattr(self.mod, cls_name)(**kwargs)
        return build(s.items, values, camel(s.name))

    def check_sequence(self, s: Sequence, ex: Example) -> None:
        forms = []
        if ex.hex is not None:
            forms.append(("hex", ex.hex, getattr(self.mod, f"decode_{s.name}"),
                          getattr(self.mod, f"encode_{s.name}")))
        if ex.text is not None:
            forms.append(("text", ex.text, getattr(self.mod, f"decode_{s.name}_text"),
                          getattr(self.mod, f"encode_{s.name}_text")))
        decoded = []
        for form, wire, decode, encode in forms:
            try:
                got = decode(wire)
            except self.mod.SequenceError as exc:
                if ex.errors:
                    want = sorted((e.line, e.field, e.rule) for e in ex.errors)
                    have = sorted((getattr(e, "line", None), (e.field or "").split(".")[-1],
                                   e.rule if e.rule in {x.rule for x in ex.errors} else e.decision)
                                  for e in exc.errors)
                    if want != have:
                        self.fail(ex, f"{form} gives errors {have}, expected {want}")
                else:
                    self.fail(ex, f"{form} does not decode: {exc}")
                continue
            except Exception as exc:
                self.fail(ex, f"{form}: decoder crashed with {_describe(exc)}")
                continue
            if ex.errors:
                self.fail(ex, f"{form} decodes but should give {len(ex.errors)} error(s)")
                continue
            decoded.append(got)
            if not ex.decode_only:
                try:
                    out = encode(got)
                except Exception as exc:
                    self.fail(ex, f"decoded {s.name} does not re-encode: {_describe(exc)}")
                    continue
                expected = wire if form == "hex" else "".join(l.strip() + "\n" for l in wire.splitlines() if l.strip())
                if out != expected:
                    self.fail(ex, f"re-encoding gives {self.show(out)}, the example says {self.show(wire)}")
        if ex.values is not None and not ex.errors:
            try:
                value = self.sequence_value(s, ex.values)
            except Exception as exc:
                self.fail(ex, f"values do not build a {s.name}: {_describe(exc)}")
                return
            for got in decoded:
                if got != value:
                    self.fail(ex, f"decodes to {got!r}, expected {value!r}")
        if len(decoded) > 1 and decoded[0] != decoded[1]:
            self.fail(ex, "the hex and text forms decode to different sequences")

    # -- streams ---------------------------------------------------------------------------
    def check_stream(self, s: StreamExample) -> None:
        """The StreamDecoder, fed the whole stream and then one byte at a time, gives the
        hand-worked events (without finish(): a stream decoder never knows it has ended)."""
        for piece in (len(s.data), 1):
            try:
                got = stream_events(self.mod, s.data, piece)
            except Exception as exc:  # a crash is a codec bug, reported as such
                self.problems.append(Diagnostic(s.loc, f"stream {s.name!r}: the decoder crashed with "
                                                       f"{_describe(exc)}", "this is a codeword bug; please report it"))
                return
            wrong = first_difference(got, s.events)
            if wrong is not None:
                fed = "whole" if piece == len(s.data) else "one byte at a time"
                self.problems.append(Diagnostic(
                    s.loc, f"stream {s.name!r} (fed {fed}): {wrong}; the decoder gives "
                           f"{', '.join(map(show_event, got)) or 'nothing'}",
                    "the events are worked out by hand from the framing rules: check them and the schema"))
                return

    def run(self) -> list[Diagnostic]:
        for m in self.p.messages:
            for ex in m.examples:
                self.check_message(m, ex)
        for s in self.p.sequences:
            for ex in s.examples:
                self.check_sequence(s, ex)
        for stream in self.p.streams:
            self.check_stream(stream)
        return self.problems


def stream_events(mod: types.ModuleType, data: bytes, piece: int) -> list[StreamEvent]:
    """A StreamDecoder's events on `data` fed in pieces of `piece` bytes: each message
    with the offset just past its frame, each error with its rule."""
    decoder = mod.StreamDecoder()
    out = []
    for at in range(0, len(data), max(1, piece)):
        items = decoder.feed(data[at:at + piece])
        for item, (start, length) in zip(items, decoder.spans):
            if isinstance(item, mod.DecodeError):
                out.append(StreamEvent(rule=item.rule))
            else:
                out.append(StreamEvent(message=type(item).NAME, end=start + length))
    return out


def first_difference(got: list[StreamEvent], want: tuple[StreamEvent, ...]) -> Optional[str]:
    """How the decoder's events first differ from the expected ones, or None."""
    for i, (g, w) in enumerate(zip(got, want), 1):
        if w.message is None and g.message is None and w.rule in (None, g.rule):
            continue
        if w.message is not None and g.message == w.message and w.end in (None, g.end):
            continue
        return f"event {i} is {show_event(g)}, expected {show_event(w)}"
    if len(got) != len(want):
        return f"{len(got)} events, expected {len(want)}"
    return None


def show_event(e: StreamEvent) -> str:
    if e.message is not None:
        return e.message + (f" (its frame ends at offset {e.end})" if e.end is not None else "")
    return f"error ({e.rule})" if e.rule else "an error"


def check_examples(p: Protocol, module: types.ModuleType) -> list[Diagnostic]:
    return ExampleChecker(p, module).run()
