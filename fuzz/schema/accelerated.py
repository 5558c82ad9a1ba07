"""The compiled accelerator against the pure-Python module: the same objects (values
and their types, as repr shows them) and the same errors, frame by frame and through
the stream decoder. Shared by the schema fuzzer and tests/test_accelerator.py."""
from __future__ import annotations

import array
import importlib.util
import mmap
import os
import shutil
import sys
from pathlib import Path
from typing import Any, Callable, Iterable, Optional


def load(path: Path, key: str, accelerators: Optional[Path]):
    """The generated module at `path`, imported as `key`: with the accelerators built in
    `accelerators` (a copy of the module beside them, the only place a module loads its
    accelerator from), or in pure Python (None)."""
    saved = os.environ.pop("CODEWORD_PURE_PYTHON", None)
    if accelerators is None:
        os.environ["CODEWORD_PURE_PYTHON"] = "1"
    elif path.parent.resolve() != accelerators.resolve():
        path = Path(shutil.copyfile(path, accelerators / f"{key}.py"))
    try:
        spec = importlib.util.spec_from_file_location(key, path)
        module = importlib.util.module_from_spec(spec)
        sys.modules[key] = module  # dataclasses look their module up while the class is made
        spec.loader.exec_module(module)
    finally:
        os.environ.pop("CODEWORD_PURE_PYTHON", None)
        if saved is not None:
            os.environ["CODEWORD_PURE_PYTHON"] = saved
    return module


def outcome(call: Callable[..., Any], *args: Any) -> tuple:
    """What a call gives, comparable across two copies of a module: the type and repr of
    the result (repr shows every value with its type: 1, 1.0 and True differ), or the
    error's type, text and attributes."""
    try:
        result = call(*args)
    except Exception as exc:  # noqa: BLE001 - the error is the outcome compared
        return "error", type(exc).__name__, str(exc), sorted((k, repr(v)) for k, v in vars(exc).items())
    return "value", type(result).__name__, repr(result)


def frame_difference(fast, pure, frame: bytes, direction: Optional[str], message: Optional[str]) -> str:
    """How the two modules differ on one frame (as bytes, bytearray and memoryview, with
    and without its direction, and through its message class); "" if they agree."""
    calls = [(fast.decode, pure.decode, (x,)) for x in (frame, bytearray(frame), memoryview(frame))]
    if direction:
        calls.append((fast.decode, pure.decode, (frame, direction)))
    if message in fast.MESSAGES:
        calls.append((fast.MESSAGES[message].decode, pure.MESSAGES[message].decode, (frame,)))
    for a, b, args in calls:
        got, expected = outcome(a, *args), outcome(b, *args)
        if got != expected:
            return f"frame {frame.hex()}: accelerated {got}, pure Python {expected}"
    return ""


def stream_difference(fast, pure, data: bytes, piece: int = 7) -> str:
    """How the two StreamDecoders differ on `data` fed in pieces; "" if they agree."""
    a, b = fast.StreamDecoder(), pure.StreamDecoder()
    for at in range(0, len(data), piece):
        chunk = data[at:at + piece]
        got, expected = [outcome(lambda x=x: x) for x in a.feed(chunk)], [outcome(lambda x=x: x) for x in b.feed(chunk)]
        if got != expected or (a.spans, a.skipped, a.offset) != (b.spans, b.skipped, b.offset):
            return f"stream {data.hex()}: from byte {at} the accelerated decoder gives {got}, pure Python {expected}"
    if [repr(x) for x in a.finish()] != [repr(x) for x in b.finish()]:
        return f"stream {data.hex()}: the decoders finish differently"
    return ""


class _Bytes(bytes):
    """A bytes subclass: read through its own methods, as any object would be."""


class _ByteArray(bytearray):
    pass


class _Name(str):
    """A str subclass spelling a direction: not the protocol's direction name."""


def _released(frame: bytes) -> memoryview:
    view = memoryview(frame)
    view.release()
    return view


def _mapped(frame: bytes) -> object:
    mapped = mmap.mmap(-1, len(frame))
    mapped.write(frame)
    return mapped


def buffer_kinds(frame: bytes) -> list[tuple[str, Callable[[], Any]]]:
    """The frame as every kind of object a caller may pass for bytes (each made anew
    for each call: a decoder may keep none of them), and objects that are not bytes."""
    even = frame + bytes(len(frame) % 2)
    kinds: list[tuple[str, Callable[[], Any]]] = [
        ("bytes", lambda: frame), ("bytearray", lambda: bytearray(frame)),
        ("memoryview", lambda: memoryview(frame)), ("memoryview of a bytearray", lambda: memoryview(bytearray(frame))),
        ("strided memoryview", lambda: memoryview(frame + frame)[::2]),
        ("reversed memoryview", lambda: memoryview(frame)[::-1]),
        ("memoryview 'b'", lambda: memoryview(frame).cast("b")), ("memoryview 'c'", lambda: memoryview(frame).cast("c")),
        ("memoryview 'H'", lambda: memoryview(even).cast("H")),
        ("2-D memoryview", lambda: memoryview(frame).cast("B", (1, len(frame))) if frame else memoryview(frame)),
        ("0-D memoryview", lambda: memoryview(frame[:1] or b"\0").cast("B", ())),
        ("released memoryview", lambda: _released(frame)),
        ("memoryview of array('H')", lambda: memoryview(array.array("H", even))),
        ("array('B')", lambda: array.array("B", frame)), ("array('H')", lambda: array.array("H", even)),
        ("bytes subclass", lambda: _Bytes(frame)), ("bytearray subclass", lambda: _ByteArray(frame)),
        ("str", lambda: frame.decode("latin-1")), ("list of ints", lambda: list(frame)), ("int", lambda: len(frame)),
        ("huge int", lambda: 2 ** 70), ("float", lambda: 1.5), ("None", lambda: None), ("object", object),
    ]
    if frame:  # mmap takes no empty mapping
        kinds.append(("mmap", lambda: _mapped(frame)))
    return kinds


def buffer_difference(fast, pure, frame: bytes, message: Optional[str]) -> str:
    """How the two modules differ on the frame passed as each kind of object, to decode,
    the message's decode and a StreamDecoder; "" if they agree."""
    for label, make in buffer_kinds(frame):
        calls = [("decode", lambda m: m.decode(make()))]
        if message in fast.MESSAGES:
            calls.append((f"{message}.decode", lambda m: m.MESSAGES[message].decode(make())))
        if hasattr(pure, "StreamDecoder"):
            def feed(m):
                decoder = m.StreamDecoder()
                got = [outcome(lambda x=x: x) for x in decoder.feed(make())]
                return got, decoder.spans, decoder.offset, decoder.skipped
            calls.append(("StreamDecoder.feed", feed))
        for name, call in calls:
            got, expected = outcome(call, fast), outcome(call, pure)
            if got != expected:
                return f"{name}({label} of {frame.hex()}): accelerated {got}, pure Python {expected}"
    return ""


HOSTILE_OFFSETS = (sys.maxsize - 1, sys.maxsize, sys.maxsize + 1, 2 ** 70, -2 ** 70, -sys.maxsize - 2, -1,
                   1.5, True, "x", None)


def stream_state_difference(fast, pure, data: bytes, directions: Iterable[str]) -> str:
    """How the two StreamDecoders differ on `data` from any stream offset a caller may
    set (huge, negative, not an int) and any direction (a str subclass, not a str);
    "" if they agree."""
    def run(module, offset, direction):
        decoder = module.StreamDecoder(direction)
        decoder.offset = offset
        return [outcome(decoder.feed, data), outcome(decoder.finish), repr(decoder.spans), repr(decoder.offset)]
    cases = [(offset, None) for offset in HOSTILE_OFFSETS]
    cases += [(0, direction) for name in directions for direction in (_Name(name), name.encode(), 5)]
    for offset, direction in cases:
        got, expected = run(fast, offset, direction), run(pure, offset, direction)
        if got != expected:
            return f"stream {data.hex()} from offset {offset!r}, direction {direction!r}: " \
                   f"accelerated {got}, pure Python {expected}"
    return ""


class _Int(int):
    """An int subclass: no value Python's usual path reads without a conversion."""


class _Float(float):
    pass


_OBJECT = object()  # one object for both modules: errors show its repr


def hostile_values(value: Any) -> list[Any]:
    """Values to put in place of a message's `value`: of each class a caller may pass, at
    and past every width's limits, and the value itself a little changed."""
    out: list[Any] = [None, True, False, 0, 1, -1, 127, 128, 255, 256, 65535, 65536, 2 ** 31, 2 ** 32, 2 ** 63 - 1,
                      2 ** 63, 2 ** 64 - 1, 2 ** 64, -2 ** 63, -2 ** 63 - 1, 0.0, -0.0, 0.5, 1.0, -1.5, 1e300,
                      float("nan"), float("inf"), 3.4028235677973366e38, "x", b"", b"\x00", [], (), _OBJECT,
                      _Int(1), _Float(1.0)]
    if isinstance(value, bool) or value is None:
        return out
    if isinstance(value, int):
        out += [value + 1, value - 1, float(value), _Int(value), value * 2 + 1, -value]
    elif isinstance(value, float):
        out += [value * (1 + 2 ** -52), -value, value + 0.005, value - 0.005, _Float(value)]
        out += [int(value)] if value == value and abs(value) != float("inf") else []
    elif isinstance(value, bytes):
        out += [value + b"\x00", value[:-1], bytearray(value), value.decode("latin-1")]
    elif isinstance(value, list):
        out += [tuple(value), value + value[-1:], value[:-1]] + [[x] + value[1:] for x in (None, 1.5, -1, "x", 2 ** 64)]
    return out


def encode_difference(fast, pure, frames: Iterable[bytes]) -> str:
    """How the two modules' encoders differ on the messages of `frames` (decoded by each),
    as they are and with each value in turn replaced (hostile_values); "" if they agree."""
    for frame in frames:
        try:
            a, b = fast.decode(frame), pure.decode(frame)
        except Exception:  # noqa: BLE001 - only messages are encoded
            continue
        for name in [None] + list(type(b)._NAMES):
            # each module's own value (an enum member of its own class), then the same changes to it
            pairs = list(zip(*[[getattr(x, name)] + hostile_values(getattr(x, name)) for x in (a, b)])) if name else [(0, 0)]
            for value_a, value in pairs:
                if name is not None:
                    a, b = fast.decode(frame), pure.decode(frame)
                    setattr(a, name, value_a)
                    setattr(b, name, value)
                for call in ("module", "method"):
                    got = outcome(fast.encode if call == "module" else type(a).encode, a)
                    expected = outcome(pure.encode if call == "module" else type(b).encode, b)
                    if got != expected:
                        return f"{type(b).__name__}.{name} = {value!r} ({call} encode of {frame.hex()}): " \
                               f"accelerated {got}, pure Python {expected}"
    return ""


def damaged(frame: bytes) -> list[bytes]:
    """The frame with one bit flipped in each byte (in at most 256 bytes spread over a
    longer frame), cut short by one, and one longer."""
    step = max(1, len(frame) // 256)
    out = [frame[:i] + bytes([frame[i] ^ (1 << (i % 8))]) + frame[i + 1:] for i in range(0, len(frame), step)]
    return out + [frame[:-1], frame + b"\x00"]


def difference(fast, pure, vectors: dict, streams: Iterable[bytes] = ()) -> tuple[str, int]:
    """The first difference on the vectors (valid ones also damaged) and the streams
    (the vectors' and those given), and how many frames and streams were compared."""
    compared = 0
    for case in vectors["valid"] + vectors["invalid"]:
        frame = bytes.fromhex(case["hex"])
        for data in [frame] + (damaged(frame) if "values" in case else []):
            problem = frame_difference(fast, pure, data, case.get("direction"), case.get("message"))
            if problem:
                return f"{case['name']}: {problem}", compared
            compared += 1
    firsts = {case.get("message"): bytes.fromhex(case["hex"]) for case in reversed(vectors["valid"])}
    problem = encode_difference(fast, pure, firsts.values())
    if problem:
        return problem, compared
    for message, frame in firsts.items():  # one frame of each message, as every kind of object
        problem = buffer_difference(fast, pure, frame, message)
        if problem:
            return f"{message}: {problem}", compared
        compared += 1
    if hasattr(pure, "StreamDecoder"):
        directions = sorted({case["direction"] for case in vectors["valid"] if case.get("direction")})
        problem = stream_state_difference(fast, pure, b"".join(firsts.values()), directions)
        if problem:
            return problem, compared
        for data in [bytes.fromhex(s["hex"]) for s in vectors.get("streams", [])] + list(streams):
            problem = stream_difference(fast, pure, data)
            if problem:
                return problem, compared
            compared += 1
    return "", compared
