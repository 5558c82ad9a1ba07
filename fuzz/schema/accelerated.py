"""The compiled accelerator against the pure-Python module: the same objects (values
and their types, as repr shows them) and the same errors, frame by frame and through
the stream decoder. Shared by the schema fuzzer and tests/test_accelerator.py."""
from __future__ import annotations

import importlib.util
import os
import sys
from pathlib import Path
from typing import Any, Callable, Iterable, Optional


def load(path: Path, key: str, accelerators: Optional[Path]):
    """The generated module at `path`, imported as `key`: with the accelerators built in
    `accelerators`, or in pure Python (None)."""
    saved = os.environ.pop("CODEWORD_PURE_PYTHON", None)
    accelerator = f"_{path.stem}_accel"
    sys.modules.pop(accelerator, None)  # this folder's build, not one imported before
    if accelerators is None:
        os.environ["CODEWORD_PURE_PYTHON"] = "1"
    else:
        sys.path.insert(0, str(accelerators))
    try:
        spec = importlib.util.spec_from_file_location(key, path)
        module = importlib.util.module_from_spec(spec)
        sys.modules[key] = module  # dataclasses look their module up while the class is made
        spec.loader.exec_module(module)
    finally:
        os.environ.pop("CODEWORD_PURE_PYTHON", None)
        if saved is not None:
            os.environ["CODEWORD_PURE_PYTHON"] = saved
        if accelerators is not None:
            sys.path.remove(str(accelerators))
        sys.modules.pop(accelerator, None)  # nor found by a module imported after this one
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
    if hasattr(pure, "StreamDecoder"):
        for data in [bytes.fromhex(s["hex"]) for s in vectors.get("streams", [])] + list(streams):
            problem = stream_difference(fast, pure, data)
            if problem:
                return problem, compared
            compared += 1
    return "", compared
