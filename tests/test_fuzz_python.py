"""Fuzz properties of the generated Python decoders, for every message of every protocol.

1. each message class's own `decode` raises nothing but the codec's CodecError on
   arbitrary bytes or text (any Unicode, not just printable ASCII), and a frame it
   accepts re-encodes to the same bytes;
2. a stream decoder never loses valid frames that follow garbage: for byte framings
   with a CRC, any garbage; without a CRC (tr24), garbage without the sync byte,
   since garbage that starts a frame can swallow the next one undetected; for
   text framings, garbage closed by the terminator (text has no start marker);
3. a stream decoder's memory stays bounded on endless garbage.

Example counts are small by default; CODEWORD_FUZZ_LONG=1 multiplies them by 50.
fuzz/python/ holds the atheris harnesses for longer, coverage-guided runs.
"""
from __future__ import annotations

import os
import random

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from test_roundtrip import (PHASES, PROTOCOL_NAMES, decoder_inputs, is_text, model, module,
                            valid_messages)

LONG = os.environ.get("CODEWORD_FUZZ_LONG") == "1"
FUZZ = settings(max_examples=4000 if LONG else 80, deadline=None, phases=PHASES,
                suppress_health_check=[HealthCheck.filter_too_much, HealthCheck.too_slow])


def message_params():
    return [pytest.param(p, m.name, id=f"{p}-{m.name}") for p in PROTOCOL_NAMES for m in model(p).messages]


def streaming():
    return [p for p in PROTOCOL_NAMES if hasattr(module(p), "StreamDecoder")]


def has_crc(proto) -> bool:
    return all(any(f.checksum is not None and f.checksum.algorithm == "crc" for f in m.layout)
               for m in proto.messages)


def sync_byte(proto) -> int:
    first = proto.framing.envelope[0]
    assert first.const is not None, f"{proto.name}: first envelope field is not a sync constant"
    return int(first.const)


def arbitrary_input(proto_name):
    if is_text(model(proto_name)):
        return st.one_of(decoder_inputs(proto_name), st.text(max_size=80))
    return decoder_inputs(proto_name)


# ---------------------------------------------------------------- 1. message decoders


@pytest.mark.parametrize("proto_name,msg_name", message_params())
@FUZZ
@given(data=st.data())
def test_message_decode_raises_only_codec_errors(proto_name, msg_name, data):
    mod = module(proto_name)
    cls = mod.MESSAGES[msg_name]
    wire = data.draw(arbitrary_input(proto_name))
    try:
        obj = cls.decode(wire)
    except mod.CodecError:
        return
    assert type(obj) is cls
    again = obj.encode()
    if isinstance(wire, bytes):
        assert again == wire, f"{msg_name}: {wire.hex()} decoded to {obj!r}, re-encodes to {again.hex()}"
    else:
        assert cls.decode(again) == obj


# ---------------------------------------------------------------- 2. resynchronisation


def chunked(data, cuts):
    points = sorted({c % (len(data) + 1) for c in cuts})
    pieces, last = [], 0
    for p in points + [len(data)]:
        pieces.append(data[last:p])
        last = p
    return pieces


@st.composite
def garbage_then_frames(draw, proto_name):
    proto, mod = model(proto_name), module(proto_name)
    names = [m.name for m in proto.messages]
    objs = [draw(valid_messages(proto_name, draw(st.sampled_from(names)))) for _ in range(draw(st.integers(1, 4)))]
    wires = [mod.encode(o) for o in objs]
    if is_text(proto):
        term = proto.framing.terminator
        garbage = draw(st.text(max_size=60)) + term
    else:
        garbage = draw(st.binary(max_size=80))
        if not has_crc(proto):
            garbage = bytes(b for b in garbage if b != sync_byte(proto))
    stream = garbage + "".join(wires) if is_text(proto) else garbage + b"".join(wires)
    cuts = draw(st.lists(st.integers(0, 10_000), max_size=6))
    return objs, chunked(stream, cuts)


@pytest.mark.parametrize("proto_name", streaming())
@FUZZ
@given(data=st.data())
def test_stream_decoder_keeps_frames_after_garbage(proto_name, data):
    mod = module(proto_name)
    objs, pieces = data.draw(garbage_then_frames(proto_name))
    decoder = mod.StreamDecoder()
    events = [e for piece in pieces for e in decoder.feed(piece)]
    messages = [e for e in events if not isinstance(e, mod.CodecError)]
    assert all(isinstance(e, (mod.CodecError, *mod.MESSAGES.values())) for e in events)
    assert messages[-len(objs):] == objs, f"lost or changed frames after garbage: {events!r}"


# ---------------------------------------------------------------- 3. bounded memory


def buffered(decoder) -> int:
    return len(decoder._buffer)


@pytest.mark.parametrize("proto_name", streaming())
def test_stream_decoder_memory_is_bounded_on_endless_garbage(proto_name):
    mod = module(proto_name)
    proto = model(proto_name)
    rng = random.Random(proto_name)  # fixed seed: the same garbage every run
    decoder = mod.StreamDecoder()
    chunk = 1024
    if is_text(proto):
        bound = decoder.MAX_MESSAGE + chunk
        alphabet = "".join(chr(c) for c in range(0x20, 0x7F) if chr(c) != proto.framing.terminator)
        make = lambda: "".join(rng.choice(alphabet) for _ in range(chunk))  # noqa: E731
    else:
        bound = max(m.size for m in proto.messages)  # one largest frame
        sync = sync_byte(proto)
        # Garbage rich in sync bytes keeps the decoder hunting for a frame all the time.
        make = lambda: bytes(sync if rng.random() < 0.2 else rng.randrange(256) for _ in range(chunk))  # noqa: E731
    peak = 0
    for _ in range(300 if not LONG else 10_000):
        for event in decoder.feed(make()):
            assert isinstance(event, mod.CodecError) or type(event) in mod.MESSAGES.values()
        peak = max(peak, buffered(decoder))
    assert peak <= bound, f"{proto_name}: buffer grew to {peak} (bound {bound})"
