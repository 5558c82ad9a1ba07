"""Frames verified with a secret key by the schema's own codec, for the commands
that read captures (`check`, `decode`, `monitor`).

The codec's stream decoder cuts and decodes frames without a key; each frame it
decodes is decoded again with the key, so a frame whose signature the key does
not make (or that carries none) is the codec's `signature` (or `unsigned`) error
in its place, a bad frame like any other, and the stream carries on after it.
(The codec's signature error names the signature the frame carries, never the one
the key makes: shown, that would sign a forged frame for whoever reads it.)
"""
from __future__ import annotations

from typing import Optional

def decode(codec, frame: bytes, direction: Optional[str], key: bytes):
    """One frame decoded and verified with `key`; raises the codec's DecodeError."""
    return codec.decode(frame, direction, key=key)


class VerifyingDecoder:
    """A codec's StreamDecoder whose messages are verified with a key: the same
    items, spans, offset and skipped bytes, a message replaced by its error."""

    def __init__(self, codec, direction: Optional[str], key: bytes):
        self._codec = codec
        self._direction = direction
        self._key = key
        self._decoder = codec.StreamDecoder(direction)
        self._held = b""  # bytes from stream offset _held_at the decoder has not consumed yet
        self._held_at = 0

    @property
    def offset(self) -> int:
        return self._decoder.offset

    @property
    def skipped(self) -> int:
        return self._decoder.skipped

    @property
    def spans(self) -> list[tuple[int, int]]:
        return self._decoder.spans

    def feed(self, data: bytes) -> list:
        self._held += data
        return self._verified(self._decoder.feed(data))

    def finish(self) -> list:
        return self._verified(self._decoder.finish())

    def _verified(self, items: list) -> list:
        out = []
        for item, (start, length) in zip(items, self._decoder.spans):
            if not isinstance(item, self._codec.CodecError):
                frame = self._held[start - self._held_at:start - self._held_at + length]
                try:
                    decode(self._codec, frame, self._direction, self._key)
                except self._codec.DecodeError as exc:
                    exc.offset = start * 8 + (exc.offset or 0)
                    item = exc
            out.append(item)
        consumed = self._decoder.offset - self._held_at  # the decoder holds the rest itself
        self._held = self._held[consumed:]
        self._held_at = self._decoder.offset
        return out
