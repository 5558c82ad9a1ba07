"""The end of a byte stream: whole frames after a false start are decoded. A stream of
a valid frame, the first half of the longest valid frame (a header that promises more
bytes than ever come) and whole frames shorter together than it promises: at the end
(StreamDecoder.finish) every frame sent whole is decoded, in order, where it was sent.
The false start's own bytes may hold a frame (a run of zeros where a message of zeros
is valid, its checksum zero too): a frame decoded inside them is no error.

An oracle rather than a comparison of Python with C (the vectors' streams hold both to
the same events): both once dropped those frames alike."""
from __future__ import annotations

from typing import Any

from codeword.model import Protocol


def applies(p: Protocol) -> bool:
    """Frames found by their length or size in a plain byte stream, protected by a checksum
    of 16 bits or more: bytes between frames then never decode as a frame by chance."""
    if p.framing.kind != "bytes" or p.framing.encoding or p.framing.stuffing or p.framing.trailer:
        return False
    return all(any(leaf.field.checksum and (leaf.field.bits or 0) >= 16 for leaf in m.wire.leaves)
               for m in p.messages)


def stream_end_problem(mod: Any, p: Protocol, vectors: dict) -> str:
    """How a stream ending in a false start and whole frames is decoded wrongly; "" if the
    frames are all decoded (or no such stream can be made of the vectors)."""
    if not applies(p) or not hasattr(mod, "StreamDecoder"):
        return ""
    direction = next((c.get("direction") for c in vectors["valid"]), None)
    frames = [bytes.fromhex(c["hex"]) for c in vectors["valid"]
              if c.get("direction") == direction and "canonical" not in c and "hex" in c]
    if len(frames) < 2:
        return ""
    longest = max(frames, key=len)
    false_start = longest[:max(1, len(longest) // 2)]
    room = len(longest) - len(false_start) - 1  # the bytes after it stay fewer than it promises
    tail = []
    for frame in sorted(frames, key=len):
        if sum(map(len, tail)) + len(frame) <= room:
            tail.append(frame)
    if not tail:
        return ""
    stream = frames[0] + false_start + b"".join(tail)
    decoder = mod.StreamDecoder(direction)
    found: list[tuple[int, int]] = []
    for end in (False, True):
        items = decoder.finish() if end else decoder.feed(stream)
        found += [span for item, span in zip(items, decoder.spans) if not isinstance(item, mod.DecodeError)]
    whole, at = [(0, len(frames[0]))], len(frames[0]) + len(false_start)
    for frame in tail:
        whole.append((at, len(frame)))
        at += len(frame)
    inside = range(len(frames[0]), len(frames[0]) + len(false_start) + 1)  # the false start's bytes
    wrong = [(start, size) for start, size in found
             if (start, size) not in whole and not (start in inside and start + size in inside)]
    if [span for span in found if span in whole] != whole or wrong:
        return (f"stream {stream.hex()} (a frame, a false start {false_start.hex()}, {len(tail)} whole frames): "
                f"decoded {[stream[s:s + n].hex() for s, n in found]}, "
                f"not {[stream[s:s + n].hex() for s, n in whole]}")
    return ""
