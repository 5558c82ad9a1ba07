"""Property tests of every generated codec, with strategies derived from the protocol model.

Nothing here names a protocol's fields: the strategies are built from
`codeword.model` (ranges, enums, flags, scales, text framing …) and the test
cases are collected from `schemas/*.yaml`, so a new schema is covered as soon
as its generated module exists.

1. valid values round-trip (`Cls.decode(encode(obj)) == obj`, the dispatching
   `decode`, and the text/word forms where a module has them);
2. out-of-range values make `encode` raise EncodeError naming the field;
3. decoders raise nothing but CodecError on arbitrary input;
4. any frame a decoder accepts re-encodes to the same bytes (same word, and
   the same text line up to the unfilled checksum of ROUTE-D2); a text message
   a decoder accepts re-encodes to a message that decodes the same;
5. a stream of valid frames, fed in arbitrary chunks, comes out of
   StreamDecoder unchanged.

Frames are mutated where only framing overhead lives (padding, reserved,
const, length, checksum bits) and their checksums recomputed from the model,
so the mutations reach the decoders' field checks.

Known codec bugs are marked `xfail(strict=True)` on just the affected case
(see KNOWN_BUGS); a fix turns them into XPASS failures, so remove the entry then.
"""
from __future__ import annotations

import dataclasses
import enum
import functools
import math
import typing
from fractions import Fraction

import pytest
from hypothesis import HealthCheck, Phase, given, settings
from hypothesis import strategies as st

from conftest import GENERATED, SCHEMAS, load_generated, load_model

# No "explain" phase: its tracing makes a failing case (and so every xfail) take minutes.
PHASES = (Phase.explicit, Phase.reuse, Phase.generate, Phase.shrink)
SLOW_DRAWS = [HealthCheck.filter_too_much, HealthCheck.too_slow]

PRINTABLE = "".join(chr(c) for c in range(0x20, 0x7F))
FLOAT32_MAX = 3.4028234663852886e38

# ---------------------------------------------------------------- cases


def _protocol_names():
    return tuple(sorted(p.stem for p in SCHEMAS.glob("*.yaml") if (GENERATED / f"{p.stem}.py").exists()))


@functools.lru_cache(maxsize=None)
def model(name):
    return load_model(name)


def module(name):
    return load_generated(name)


PROTOCOL_NAMES = _protocol_names()


def is_text(proto) -> bool:
    return proto.framing.kind == "text"


# Known codec bugs: (test, protocol, message or direction[, field path]) -> reason.
# Each marks exactly one parametrized case xfail(strict=True): when the bug is
# fixed the case XPASSes, which fails the run, so delete its entry then.
KNOWN_BUGS: dict[tuple, str] = {}


def _param(test, *key, values=None):
    values = key if values is None else values
    reason = KNOWN_BUGS.get((test, *key))
    marks = [pytest.mark.xfail(strict=True, reason=reason)] if reason else []
    return pytest.param(*values, id="-".join(str(k) for k in key), marks=marks)


def message_cases(test, only=lambda proto, msg: True):
    return [_param(test, p, m.name) for p in PROTOCOL_NAMES for m in model(p).messages
            if only(model(p), m)]


def protocol_cases(test, only=lambda proto: True):
    return [_param(test, p) for p in PROTOCOL_NAMES if only(model(p))]


# ---------------------------------------------------------------- helpers


@functools.lru_cache(maxsize=None)
def hints(cls):
    return typing.get_type_hints(cls)


def unwrap_optional(tp):
    if typing.get_origin(tp) is typing.Union:
        args = [a for a in typing.get_args(tp) if a is not type(None)]
        if len(args) == 1:
            return args[0]
    return tp


def as_type(tp, value):
    """A drawn wire-level value as the annotation's enum/flag class."""
    if value is None:
        return None
    if isinstance(tp, type) and issubclass(tp, enum.Enum):
        return tp(value)
    return value


def leaf_fields(fields, prefix=""):
    """(dotted path, Field) of every member leaf, groups expanded."""
    for f in fields:
        if not f.is_member:
            continue
        path = prefix + f.name
        if f.kind == "group":
            yield from leaf_fields(f.fields, path + ".")
        else:
            yield path, f


def replace_path(obj, path, value):
    head, _, rest = path.partition(".")
    if not rest:
        return dataclasses.replace(obj, **{head: value})
    return dataclasses.replace(obj, **{head: replace_path(getattr(obj, head), rest, value)})


def numeric_bounds(f):
    """Inclusive logical bounds allowed by the wire width and the declared range."""
    scale = Fraction(f.scale) if f.scale else Fraction(1)
    off = Fraction(f.offset) if f.offset else Fraction(0)
    lo = hi = None
    if f.raw_range is not None:
        lo, hi = f.raw_range[0] * scale + off, f.raw_range[1] * scale + off
    if f.range is not None:
        rlo, rhi = Fraction(f.range[0]), Fraction(f.range[1])
        lo = rlo if lo is None else max(lo, rlo)
        hi = rhi if hi is None else min(hi, rhi)
    return lo, hi


def logical(f, raw):
    """Logical value of a raw wire integer, computed as the codecs do."""
    if f.scale:
        value = raw * f.scale
        return value + f.offset if f.offset else value
    return raw + f.offset if f.offset else raw


def plain(value):
    return int(value) if isinstance(value, Fraction) and value.denominator == 1 else float(value)


# ---------------------------------------------------------------- valid values


def text_alphabet(proto, f, *, spaces=True):
    """Characters a text value may hold: printable ASCII without the framing's
    terminator and (unless the field runs to the end) separator."""
    fr = proto.framing
    banned = set(fr.terminator or "") | set(fr.ignore_between or "")
    if not f.to_end:
        banned |= set(fr.separator or "")
    if not spaces:
        banned.add(" ")
    return "".join(c for c in PRINTABLE if c not in banned)


def text_float(x: float) -> float:
    """x as a text float holds it: 15 significant digits, 0 or at least 1e-307 in magnitude."""
    x = float(f"{x:.15g}")
    if math.isinf(x):  # rounded past the largest double
        return math.copysign(1.79769313486231e308, x)
    return 0.0 if abs(x) < 1e-307 else x


def field_strategy(proto, f, tp, path, bias):
    tp = unwrap_optional(tp)
    s = base_strategy(proto, f, tp, path, bias)
    if path in bias:  # values an unconditional message rule requires
        s = st.one_of(st.sampled_from(bias[path]).map(lambda v: as_type(tp, v)), s)
    if f.optional and not f.one_hot:
        s = st.none() | s
    return s


def base_strategy(proto, f, tp, path, bias):
    if f.kind == "group":
        sub = hints(tp)
        return st.builds(tp, **{g.name: field_strategy(proto, g, sub[g.name], f"{path}.{g.name}", bias)
                                for g in f.fields if g.is_member})
    if f.one_hot:
        lo, hi = f.range if f.range else (0, f.bits - 1)
        return st.none() | st.integers(int(lo), int(hi))
    if f.flags is not None:
        bits = [1 << b.bit for b in f.flags.members]
        if f.exactly_one:
            return st.sampled_from(bits).map(lambda v: as_type(tp, v))
        return st.lists(st.sampled_from(bits), unique=True).map(lambda vs: as_type(tp, sum(vs)))
    if f.enum is not None:
        values = [v for v in f.enum.values if f.values is None or v in f.values]
        return st.sampled_from(values).map(lambda v: as_type(tp, v))
    if f.values is not None:
        return st.sampled_from(f.values)
    if f.kind == "bool":
        return st.booleans()
    if f.kind in ("uint", "int"):
        lo, hi = numeric_bounds(f)
        if f.scale:
            scale = Fraction(f.scale)
            off = Fraction(f.offset) if f.offset else Fraction(0)
            raw_lo, raw_hi = math.ceil((lo - off) / scale), math.floor((hi - off) / scale)
            return st.integers(raw_lo, raw_hi).map(lambda r: logical(f, r))
        return st.integers(math.ceil(lo), math.floor(hi))
    if f.kind == "float":
        width = 32 if f.bits == 32 else 64
        kwargs = {}
        if f.range is not None:
            kwargs = {"min_value": float(f.range[0]), "max_value": float(f.range[1])}
        floats = st.floats(width=width, allow_nan=False, allow_infinity=False, **kwargs)
        if proto.framing.kind == "text":  # text floats: 15 significant digits, 0 or from 1e-307
            floats = floats.map(text_float)
            if f.range is not None:
                floats = floats.filter(lambda x: f.range[0] <= x <= f.range[1])
        return floats
    if f.kind == "char":
        return st.sampled_from(text_alphabet(proto, f, spaces=False))
    if f.kind == "str":
        if f.length:
            return st.text(text_alphabet(proto, f, spaces=False), min_size=f.length, max_size=f.length)
        return st.text(text_alphabet(proto, f), max_size=f.max_length or 24).map(lambda s: s.strip(" "))
    if f.kind == "bytes":
        size = f.length if f.length is not None else f.bits // 8
        return st.binary(min_size=size, max_size=size)
    raise NotImplementedError(f"no strategy for {proto.name} field {path} of kind {f.kind}: extend test_roundtrip.py")


def rule_bias(msg):
    """Values that unconditional `require: {field: value}` rules demand."""
    bias: dict[str, list] = {}
    for rule in msg.rules:
        if rule.when:
            continue
        for cond in rule.require:
            if cond.op == "eq":
                bias.setdefault(cond.path, []).append(cond.value)
    return bias


@functools.lru_cache(maxsize=None)
def drawn_messages(proto_name, msg_name):
    """Objects whose fields are each valid (cross-field rules not yet applied)."""
    proto, mod = model(proto_name), module(proto_name)
    msg = proto.message(msg_name)
    cls = mod.MESSAGES[msg_name]
    ann = hints(cls)
    bias = rule_bias(msg)
    return st.builds(cls, **{f.name: field_strategy(proto, f, ann[f.name], f.name, bias) for f in msg.members})


def breaks_a_rule(mod, obj) -> bool:
    try:
        mod.encode(obj)
    except mod.EncodeError as exc:
        return exc.rule == "rule"
    return False


@functools.lru_cache(maxsize=None)
def valid_messages(proto_name, msg_name):
    """Valid message objects: field strategies filtered by the message's cross-field rules."""
    mod = module(proto_name)
    return drawn_messages(proto_name, msg_name).filter(lambda o: not breaks_a_rule(mod, o))


# ---------------------------------------------------------------- checksums from the model


def crc(params, data: bytes) -> int:
    """Rocksoft-model CRC, bit by bit (any width)."""
    width, top, mask = params.width, 1 << (params.width - 1), (1 << params.width) - 1
    reg = params.init
    for byte in data:
        for i in range(8):
            bit = (byte >> i) & 1 if params.refin else (byte >> (7 - i)) & 1
            feedback = bool(reg & top) ^ bit
            reg = (reg << 1) & mask
            if feedback:
                reg ^= params.poly
    if params.refout:
        reg = int(f"{reg:0{width}b}"[::-1], 2)
    return (reg ^ params.xorout) & mask


def layout_leaves(layout):
    """(name, bit offset, bits) of every wire field, groups expanded, in wire order."""
    for f in layout:
        if f.is_payload or f.bit_offset is None:
            continue
        if f.kind == "group":
            off = f.bit_offset
            for g in f.fields:
                yield g.name, (g.bit_offset if g.bit_offset is not None else off), g.bits
                off += g.bits
        else:
            yield f.name, f.bit_offset, f.bits


def fix_checksums(proto, msg, frame: bytearray) -> bool:
    """Recompute msg's checksum fields in frame from the model; False if one is not understood."""
    understood = True
    for f in msg.layout:
        c = f.checksum
        if c is None:
            continue
        if c.over == "bytes" and c.byte_span is not None:
            data = bytes(frame[c.byte_span[0]:c.byte_span[1]])
            if c.algorithm == "crc" and c.crc is not None:
                value = crc(c.crc, data)
            elif c.algorithm == "sum":
                value = sum(data) % (c.modulo or 1 << f.bits)
            elif c.algorithm == "xor":
                value = functools.reduce(lambda a, b: a ^ b, data, 0)
            else:
                understood = False
                continue
            start, size = f.bit_offset // 8, f.bits // 8
            frame[start:start + size] = value.to_bytes(size, f.byte_order or proto.framing.byte_order)
        elif c.over == "fields" and proto.framing.kind == "bits":
            total = len(frame) * 8
            word = int.from_bytes(frame, "big")
            leaves = list(layout_leaves(msg.layout))
            values = [(word >> (total - off - bits)) & ((1 << bits) - 1) for _, off, bits in leaves]
            value = fields_checksum(f, [name for name, _, _ in leaves], values)
            if value is None:
                understood = False
                continue
            shift = total - f.bit_offset - f.bits
            word = word & ~(((1 << f.bits) - 1) << shift) | value << shift
            frame[:] = word.to_bytes(len(frame), "big")
        else:
            understood = False
    return understood


def fields_checksum(f, names, values):
    """The value of checksum field f over the other fields' wire values (None: not understood)."""
    c = f.checksum
    covered = [(n, v) for n, v in zip(names, values) if n != f.name]
    if c.covers is not None:
        order = [n for n, _ in covered]
        covered = covered[order.index(c.covers[0]):order.index(c.covers[1]) + 1]
    values = [v for _, v in covered]
    if c.algorithm == "sum":
        return sum(values) % (c.modulo or 1 << f.bits)
    if c.algorithm == "xor":
        return functools.reduce(lambda a, b: a ^ b, values, 0)
    if c.algorithm == "parity":
        return (sum(bin(v).count("1") for v in values) & 1) ^ (c.parity == "odd")
    return None


def hot_bits(msg, size):
    """Frame bit positions (MSB first) that carry no member value: padding, reserved,
    const, length and checksum bits: where an accepting decoder may ignore something."""
    covered, hot = set(), []
    for f in msg.layout:
        if f.is_payload or f.bit_offset is None or not f.bits:
            continue
        span = range(f.bit_offset, f.bit_offset + f.bits)
        covered.update(span)
        if not f.is_member:
            hot.extend(span)
    hot.extend(p for p in range(size * 8) if p not in covered)
    return sorted(set(hot))


# ---------------------------------------------------------------- inputs for decoders


@st.composite
def mutated_frames(draw, proto_name, msg_names):
    """A valid binary frame with 0-3 bits flipped (often where only the frame's
    overhead lives), its checksums usually recomputed so the change gets through."""
    proto, mod = model(proto_name), module(proto_name)
    name = draw(st.sampled_from(msg_names))
    msg = proto.message(name)
    frame = bytearray(mod.encode(draw(valid_messages(proto_name, name))))
    nbits = len(frame) * 8
    hot = hot_bits(msg, len(frame))
    position = st.integers(0, nbits - 1)
    if hot:
        position = st.one_of(st.sampled_from(hot), position)
    for pos in draw(st.lists(position, max_size=3)):
        frame[pos // 8] ^= 0x80 >> (pos % 8)
    if draw(st.integers(0, 3)):
        fix_checksums(proto, msg, frame)
    return bytes(frame)


TRICKY_TOKENS = ("", " ", " 1 ", "-0", "+1", "01", "-", "1.", ".5", "1e0", "1E+00", "1e999", "-1e999",
                 "1e-999", "nan", "inf", "0x10", "1_0", "9" * 40)
CONTROL = " \t\r\n\x00\x1f\x7f"


def split_text(proto, msg, text):
    """(head, values, terminator) of a text message as its encoder wrote it."""
    fr = proto.framing
    head, colon, body = text.partition(fr.prefix_separator)
    body, term = (body[:-len(fr.terminator)], fr.terminator) if body.endswith(fr.terminator) else (body, "")
    to_end = [i for i, f in enumerate(msg.members) if f.to_end]
    values = body.split(fr.separator, to_end[0]) if to_end else body.split(fr.separator)
    return head + colon, values, term


@st.composite
def mutated_texts(draw, proto_name, msg_names):
    """A valid text message with either a control character, separator or terminator
    put into one of its text values (a char value replaced by it), or one to three
    edits: a character replaced, inserted or deleted anywhere (often a space or
    control character), or a value respelled as a tricky token."""
    proto, mod = model(proto_name), module(proto_name)
    fr = proto.framing
    name = draw(st.sampled_from(msg_names))
    msg = proto.message(name)
    text = mod.encode(draw(valid_messages(proto_name, name)))
    head, values, term = split_text(proto, msg, text)
    textual = [i for i, f in enumerate(msg.members)
               if f.kind in ("char", "str") and f.enum is None and i < len(values)]
    if textual and draw(st.booleans()):
        k = draw(st.sampled_from(textual))
        c = draw(st.sampled_from(CONTROL + fr.separator + fr.terminator))
        if msg.members[k].kind == "char":
            values[k] = c
        else:
            at = draw(st.integers(0, len(values[k])))
            values[k] = values[k][:at] + c + values[k][at:]
        return head + fr.separator.join(values) + term
    char = st.one_of(st.sampled_from(CONTROL), st.sampled_from(PRINTABLE))
    for _ in range(draw(st.integers(1, 3))):
        op = draw(st.sampled_from(["replace", "insert", "delete", "token"]))
        if op == "token":
            head, values, term = split_text(proto, msg, text)
            values[draw(st.integers(0, len(values) - 1))] = draw(st.sampled_from(TRICKY_TOKENS))
            text = head + fr.separator.join(values) + term
            continue
        i = draw(st.integers(0, len(text)))
        if op == "insert":
            text = text[:i] + draw(char) + text[i:]
        elif op == "replace" and i < len(text):
            text = text[:i] + draw(char) + text[i + 1:]
        elif op == "delete":
            text = text[:i] + text[i + 1:]
    return text


def binary_inputs(proto_name, msg_names=None):
    proto = model(proto_name)
    names = msg_names or [m.name for m in proto.messages]
    return st.one_of(st.binary(max_size=64), mutated_frames(proto_name, names))


def text_inputs(proto_name):
    names = [m.name for m in model(proto_name).messages]
    return st.one_of(st.text(PRINTABLE, max_size=64), mutated_texts(proto_name, names))


def decoder_inputs(proto_name):
    return text_inputs(proto_name) if is_text(model(proto_name)) else binary_inputs(proto_name)


# ---------------------------------------------------------------- 1. valid values round-trip

ROUNDTRIP = settings(max_examples=150, deadline=None, phases=PHASES, suppress_health_check=SLOW_DRAWS)


def test_every_protocol_is_covered():
    assert PROTOCOL_NAMES, "no schema with a generated module found"
    for name in PROTOCOL_NAMES:
        proto, mod = model(name), module(name)
        assert set(mod.MESSAGES) == {m.name for m in proto.messages}, name
        for msg in proto.messages:
            fields = [f.name for f in dataclasses.fields(mod.MESSAGES[msg.name])]
            assert set(fields) == {f.name for f in msg.members}, \
                f"{name}.{msg.name}: dataclass fields {fields} are not the model's members"


def test_model_crc_matches_catalogue_check():
    for name in PROTOCOL_NAMES:
        for msg in model(name).messages:
            for f in msg.layout:
                if f.checksum is not None and f.checksum.crc is not None and f.checksum.crc.check is not None:
                    assert crc(f.checksum.crc, b"123456789") == f.checksum.crc.check, f"{name} {f.name}"


@pytest.mark.parametrize("proto_name,msg_name", message_cases("class_roundtrip"))
@ROUNDTRIP
@given(data=st.data())
def test_valid_values_roundtrip(proto_name, msg_name, data):
    proto, mod = model(proto_name), module(proto_name)
    obj = data.draw(valid_messages(proto_name, msg_name), label="message")
    wire = mod.encode(obj)
    assert isinstance(wire, str if is_text(proto) else bytes)
    decoded = mod.MESSAGES[msg_name].decode(wire)
    assert decoded == obj
    assert mod.encode(decoded) == wire
    if not is_text(proto):
        msg = proto.message(msg_name)
        assert len(wire) == msg.size
        frame = bytearray(wire)
        if fix_checksums(proto, msg, frame):
            assert bytes(frame) == wire, "the codec's checksum differs from the model's"


@pytest.mark.parametrize("proto_name,msg_name", message_cases("dispatch_roundtrip", lambda p, m: p.self_identifying))
@ROUNDTRIP
@given(data=st.data())
def test_valid_values_roundtrip_dispatch(proto_name, msg_name, data):
    proto, mod = model(proto_name), module(proto_name)
    obj = data.draw(valid_messages(proto_name, msg_name), label="message")
    wire = mod.encode(obj)
    assert mod.decode(wire, proto.message(msg_name).direction) == obj


def _has_alternate_forms(proto):
    mod = module(proto.name)
    return hasattr(mod, "encode_text") or hasattr(mod, "encode_word")


@pytest.mark.parametrize("proto_name,msg_name",
                         message_cases("form_roundtrip", lambda p, m: _has_alternate_forms(p)))
@ROUNDTRIP
@given(data=st.data())
def test_valid_values_roundtrip_text_and_word_forms(proto_name, msg_name, data):
    mod = module(proto_name)
    obj = data.draw(valid_messages(proto_name, msg_name), label="message")
    if hasattr(mod, "encode_text"):
        line = mod.encode_text(obj)
        assert mod.decode_text(line) == obj
    if hasattr(mod, "encode_word"):
        word = mod.encode_word(obj)
        framing = model(proto_name).framing
        assert 0 <= word < 1 << (framing.max_bits or framing.word_bits)
        assert mod.decode_word(word) == obj


# ---------------------------------------------------------------- 2. out-of-range values raise


def bad_values(proto, f):
    """(label, value) pairs just outside what f allows."""
    fr = proto.framing
    out = []
    if not f.optional and not f.one_hot:
        out.append(("none", None))
    if f.kind == "bool":
        return out + [("two", 2), ("minus_one", -1)]
    if f.one_hot:
        lo, hi = f.range if f.range else (0, f.bits - 1)
        return out + [("above_max", int(hi) + 1), ("below_min", int(lo) - 1)]
    if f.flags is not None:
        mask, width = f.flags.mask, f.flags.bits
        undefined = next((1 << b for b in range(width) if not mask >> b & 1), 1 << width)
        out += [("undefined_bit", undefined), ("negative", -1)]
        if f.exactly_one:
            members = sorted(1 << b.bit for b in f.flags.members)
            out.append(("no_bit", 0))
            if len(members) > 1:
                out.append(("two_bits", members[0] | members[1]))
        return out
    if f.enum is not None and f.enum.kind == "char":
        values = set(f.enum.values) if f.values is None else set(f.values)
        other = next(c for c in "zyxwvutsrqponmkjihgZYX0123456789" if c not in set(f.enum.values))
        out += [("not_in_enum", other), ("two_chars", 2 * next(iter(sorted(values)))),
                ("separator", fr.separator), ("terminator", fr.terminator)]
        out += [(f"not_allowed_{v}", v) for v in sorted(set(f.enum.values) - values)]
        return out
    if f.enum is not None or f.values is not None:
        allowed = sorted(f.values if f.values is not None else f.enum.values)
        out += [("above_max", allowed[-1] + 1), ("below_min", allowed[0] - 1)]
        gaps = [v for v in range(allowed[0], allowed[-1]) if v not in allowed]
        if gaps:
            out.append(("gap", gaps[0]))
        if f.enum is not None:  # members of the enum the field does not allow
            out += [(f"not_allowed_{v}", v) for v in sorted(set(f.enum.values) - set(allowed))]
        return out
    if f.kind in ("uint", "int"):
        lo, hi = numeric_bounds(f)
        if f.scale:  # one step past the ends, as the float a caller would pass
            step = Fraction(f.scale)
            return out + [("above_max", float(hi + step)), ("below_min", float(lo - step))]
        return out + [("above_max", plain(hi + 1)), ("below_min", plain(lo - 1))]
    if f.kind == "float":
        out += [("nan", math.nan), ("inf", math.inf), ("minus_inf", -math.inf)]
        if f.range is not None:
            out += [("above_max", math.nextafter(float(f.range[1]), math.inf)),
                    ("below_min", math.nextafter(float(f.range[0]), -math.inf))]
        elif f.bits == 32:
            out += [("above_f32", math.nextafter(FLOAT32_MAX, math.inf)),
                    ("below_f32", math.nextafter(-FLOAT32_MAX, -math.inf))]
        return out
    if f.kind == "char":
        return out + [("two_chars", "ab"), ("empty", ""), ("separator", fr.separator),
                      ("terminator", fr.terminator), ("space", " "), ("control", "\x00"), ("non_ascii", "é")]
    if f.kind == "str":
        out += [("terminator", f"a{fr.terminator}b"), ("leading_space", " a"), ("trailing_space", "a "),
                ("control", "a\nb"), ("non_ascii", "é")]
        if not f.to_end:
            out.append(("separator", f"a{fr.separator}b"))
        if f.max_length:
            out.append(("too_long", "a" * (f.max_length + 1)))
        if f.length:
            out += [("too_short", "a" * (f.length - 1)), ("too_long", "a" * (f.length + 1))]
        return out
    if f.kind == "bytes":
        size = f.length if f.length is not None else f.bits // 8
        return out + [("too_short", bytes(size - 1)), ("too_long", bytes(size + 1)), ("text", "a" * size)]
    raise NotImplementedError(f"no bad values for {proto.name} field {f.name} of kind {f.kind}")


def bad_value_cases():
    cases = []
    for p in PROTOCOL_NAMES:
        proto = model(p)
        for msg in proto.messages:
            for path, f in leaf_fields(msg.members):
                seen, bad = set(), []
                for label, value in bad_values(proto, f):
                    key = (type(value), repr(value))
                    if key not in seen:
                        seen.add(key)
                        bad.append((label, value))
                cases.append(_param("out_of_range", p, msg.name, path, values=(p, msg.name, path, tuple(bad))))
    return cases


@pytest.mark.parametrize("proto_name,msg_name,path,bad_values", bad_value_cases())
# No shrinking: the report lists every bad value that got through, whatever the message.
@settings(max_examples=6, deadline=None, phases=PHASES[:3], suppress_health_check=SLOW_DRAWS)
@given(data=st.data())
def test_out_of_range_values_raise(proto_name, msg_name, path, bad_values, data):
    """Each value just outside what the field allows, put into a valid message,
    makes encode raise EncodeError naming that field: never a silent encode,
    never another exception."""
    mod = module(proto_name)
    obj = data.draw(valid_messages(proto_name, msg_name), label="valid message")
    name = path.rsplit(".", 1)[-1]
    problems = []
    for label, bad in bad_values:
        broken = replace_path(obj, path, bad)
        try:
            wire = mod.encode(broken)
        except mod.EncodeError as exc:
            named = (exc.field or "").rsplit(".", 1)[-1]
            if exc.rule == "rule" and named != name:
                continue  # the change broke another field's cross-field rule first: inconclusive
            if named != name or exc.message != msg_name:
                problems.append(f"{label} {bad!r}: EncodeError names {exc.message}.{exc.field}: {exc}")
        except Exception as exc:  # noqa: BLE001 - any other exception is the finding
            problems.append(f"{label} {bad!r}: {type(exc).__name__}: {exc} (not an EncodeError)")
        else:
            problems.append(f"{label} {bad!r}: encoded silently as {wire!r}")
    assert not problems, f"{proto_name}.{msg_name}.{path}:\n  " + "\n  ".join(problems)


# ---------------------------------------------------------------- 3. decoders raise only CodecError


def reencode(mod, encoder, obj, accepted):
    """encoder(obj) for an object a decoder accepted from `accepted`; refusing it is a finding."""
    try:
        return encoder(obj)
    except mod.EncodeError as exc:
        pytest.fail(f"the decoder accepted {accepted!r} as {obj}, which {encoder.__name__} refuses: {exc}")


DECODE = settings(max_examples=150, deadline=None, phases=PHASES, suppress_health_check=SLOW_DRAWS)


# Binary class decoders get the same inputs in test_accepted_frames_reencode_to_the_same_bytes,
# which also lets only CodecError through; here the text ones.
@pytest.mark.parametrize("proto_name,msg_name", message_cases("class_decode_errors", lambda p, m: is_text(p)))
@DECODE
@given(data=st.data())
def test_class_decode_raises_only_codec_errors(proto_name, msg_name, data):
    mod = module(proto_name)
    wire = data.draw(decoder_inputs(proto_name), label="input")
    try:
        obj = mod.MESSAGES[msg_name].decode(wire)
    except mod.CodecError:
        return
    assert isinstance(obj, mod.MESSAGES[msg_name])


@pytest.mark.parametrize("proto_name,msg_name", message_cases("text_message_reencode", lambda p, m: is_text(p)))
@DECODE
@given(data=st.data())
def test_accepted_text_messages_reencode(proto_name, msg_name, data):
    """What a text decoder accepts (trimmed, numbers in any accepted spelling) the
    encoder writes back, and that reads as the same message."""
    mod = module(proto_name)
    cls = mod.MESSAGES[msg_name]
    text = data.draw(mutated_texts(proto_name, [msg_name]), label="text")
    try:
        obj = cls.decode(text)
    except mod.CodecError:
        return
    again = reencode(mod, mod.encode, obj, text)
    assert cls.decode(again) == obj
    assert mod.encode(cls.decode(again)) == again


def _check_outputs(mod, out):
    assert isinstance(out, list)
    for item in out:
        assert isinstance(item, (mod.CodecError, *mod.MESSAGES.values())), item


@pytest.mark.parametrize("proto_name", protocol_cases("dispatch_decode_errors"))
@DECODE
@given(data=st.data())
def test_dispatch_and_stream_decoders_raise_only_codec_errors(proto_name, data):
    proto, mod = model(proto_name), module(proto_name)
    wire = data.draw(decoder_inputs(proto_name), label="input")
    if proto.self_identifying:
        for direction in [None, *(d.name for d in proto.directions)]:
            try:
                obj = mod.decode(wire, direction)
            except mod.CodecError:
                continue
            assert type(obj) in mod.MESSAGES.values()
    if hasattr(mod, "decode_all") and not is_text(proto):
        try:
            mod.decode_all(wire)
        except mod.CodecError:
            pass
    if hasattr(mod, "StreamDecoder"):
        cut = data.draw(st.integers(0, len(wire)), label="chunk boundary")
        stream = mod.StreamDecoder()
        _check_outputs(mod, stream.feed(wire[:cut]) + stream.feed(wire[cut:]))
    if is_text(proto):  # bytes in, too: non-ASCII must be a DecodeError
        raw = data.draw(st.binary(max_size=64), label="bytes")
        try:
            mod.decode(raw)
        except mod.CodecError:
            pass


@pytest.mark.parametrize("proto_name", protocol_cases("text_word_errors", lambda p: hasattr(module(p.name), "decode_text")
                                                      or hasattr(module(p.name), "decode_word")))
@DECODE
@given(line=st.text("0123456789 ", max_size=40), word=st.integers(0, 2**30 - 1),
       wide=st.integers(-2**40, 2**40))
def test_text_and_word_decoders_raise_only_codec_errors(proto_name, line, word, wide):
    mod = module(proto_name)
    if hasattr(mod, "decode_text"):
        try:
            mod.decode_text(line)
        except mod.CodecError:
            pass
    if hasattr(mod, "decode_lines"):
        for _, item in mod.decode_lines(line.replace("9", "\n")):
            assert isinstance(item, (mod.CodecError, *mod.MESSAGES.values()))
    if hasattr(mod, "decode_word"):
        for w in (word, wide):
            try:
                mod.decode_word(w)
            except mod.CodecError:
                pass


# ---------------------------------------------------------------- 4. accepted frames re-encode


@pytest.mark.parametrize("proto_name,msg_name", message_cases("frame_reencode", lambda p, m: not is_text(p)))
@DECODE
@given(data=st.data())
def test_accepted_frames_reencode_to_the_same_bytes(proto_name, msg_name, data):
    """Random bytes and mutated frames (checksums usually recomputed from the model):
    Cls.decode and decode raise only CodecError, and what they accept re-encodes
    to the very same bytes: no bit is ignored on the way in."""
    proto, mod = model(proto_name), module(proto_name)
    cls = mod.MESSAGES[msg_name]
    names = [m.name for m in proto.messages]
    wire = data.draw(st.one_of(mutated_frames(proto_name, [msg_name]), binary_inputs(proto_name, names)),
                     label="frame")
    try:
        obj = cls.decode(wire)
    except mod.CodecError:
        obj = None
    if obj is not None:
        assert reencode(mod, mod.encode, obj, wire) == wire, f"{cls.__name__}.decode accepted {wire.hex(' ')} as {obj}"
    if proto.self_identifying:
        try:
            obj = mod.decode(wire, proto.message(msg_name).direction)
        except mod.CodecError:
            return
        if type(obj) is cls:
            assert reencode(mod, mod.encode, obj, wire) == wire, f"decode accepted {wire.hex(' ')} as {obj}"


def _word_of(frame: bytes, word_bits: int) -> int:
    value, bits = int.from_bytes(frame, "big"), 8 * len(frame)
    return value << (word_bits - bits) if bits <= word_bits else value >> (bits - word_bits)


@pytest.mark.parametrize("proto_name,msg_name",
                         message_cases("word_reencode", lambda p, m: hasattr(module(p.name), "decode_word")))
@DECODE
@given(data=st.data())
def test_accepted_words_reencode_to_the_same_word(proto_name, msg_name, data):
    proto, mod = model(proto_name), module(proto_name)
    word_bits = proto.framing.max_bits or proto.framing.word_bits
    mutated = mutated_frames(proto_name, [msg_name]).map(lambda f: _word_of(f, word_bits))
    word = data.draw(st.one_of(mutated, st.integers(0, 2**word_bits - 1)), label="word")
    try:
        obj = mod.decode_word(word)
    except mod.CodecError:
        return
    if type(obj) is mod.MESSAGES[msg_name]:
        assert reencode(mod, mod.encode_word, obj, word) == word, f"decode_word accepted {word:#x} as {obj}"


@st.composite
def mutated_lines(draw, proto_name, msg_name):
    """A valid text-form line with one value just past its field's width, or with
    tokens replaced by other numbers; its checksum then kept, recomputed from the
    new values, or left unfilled (the text form's `checksum_unfilled`)."""
    proto, mod = model(proto_name), module(proto_name)
    msg = proto.message(msg_name)
    tokens = mod.encode_text(draw(valid_messages(proto_name, msg_name))).split(" ")
    leaves = list(layout_leaves(msg.layout))
    if len(leaves) != len(tokens):  # a text form that is not one token per wire field
        return " ".join(tokens)
    if draw(st.booleans()):
        i = draw(st.sampled_from(range(len(tokens))))
        tokens[i] = str((1 << leaves[i][2]) + draw(st.integers(0, 3)))
    else:
        for i, value in draw(st.lists(st.tuples(st.integers(0, len(tokens) - 1),
                                                st.integers(0, 2**20)), min_size=1, max_size=2)):
            tokens[i] = str(value)
    checks = {f.name: f for f in msg.layout if f.checksum is not None}
    how = draw(st.sampled_from(["keep", "recompute", "unfilled"]))
    unfilled = proto.framing.text_form.checksum_unfilled if proto.framing.text_form else None
    for j in [j for j, (name, _, _) in enumerate(leaves) if name in checks]:
        if how == "recompute":
            value = fields_checksum(checks[leaves[j][0]], [n for n, _, _ in leaves], [int(t) for t in tokens])
            tokens[j] = tokens[j] if value is None else str(value)
        elif how == "unfilled" and unfilled is not None:
            tokens[j] = str(unfilled)
    return " ".join(tokens)


@pytest.mark.parametrize("proto_name,msg_name",
                         message_cases("text_reencode", lambda p, m: hasattr(module(p.name), "decode_text")))
@DECODE
@given(data=st.data())
def test_accepted_text_lines_reencode(proto_name, msg_name, data):
    """A line decode_text accepts re-encodes to the same numbers, except a checksum
    written as the text form's `checksum_unfilled` (ROUTE-D2), which is filled in."""
    proto, mod = model(proto_name), module(proto_name)
    cls = mod.MESSAGES[msg_name]
    line = data.draw(st.one_of(mutated_lines(proto_name, msg_name), st.text("0123456789 ", max_size=40)),
                     label="line")
    try:
        obj = mod.decode_text(line)
    except mod.CodecError:
        return
    if type(obj) is not cls:
        return
    again = reencode(mod, mod.encode_text, obj, line)
    assert mod.decode_text(again) == obj
    got, want = [int(t) for t in line.split()], [int(t) for t in again.split()]
    assert len(got) == len(want)
    unfilled = proto.framing.text_form.checksum_unfilled
    msg = proto.message(msg_name)
    checks = {f.name for f in msg.layout if f.checksum is not None}
    for (name, _, _), g, w in zip(layout_leaves(msg.layout), got, want):
        assert g == w or (name in checks and g == unfilled), \
            f"decode_text accepted {line!r} as {obj}, which re-encodes as {again!r}"


# ---------------------------------------------------------------- streams


def stream_cases():
    cases = []
    for p in PROTOCOL_NAMES:
        if not hasattr(module(p), "StreamDecoder"):
            continue
        directions = sorted({m.direction for m in model(p).messages}, key=str)
        cases += [_param("stream", p, d) for d in directions]
    return cases


@pytest.mark.parametrize("proto_name,direction", stream_cases())
@settings(max_examples=60, deadline=None, phases=PHASES, suppress_health_check=SLOW_DRAWS)
@given(data=st.data())
def test_stream_decoder_recovers_every_frame(proto_name, direction, data):
    """Valid messages of one direction, concatenated and fed in arbitrary chunks,
    come out of StreamDecoder unchanged and in order."""
    proto, mod = model(proto_name), module(proto_name)
    names = [m.name for m in proto.messages if m.direction == direction]
    objs = data.draw(st.lists(st.sampled_from(names).flatmap(lambda n: valid_messages(proto_name, n)),
                              min_size=1, max_size=4), label="messages")
    parts = []
    for obj in objs:
        if is_text(proto) and proto.framing.ignore_between:
            parts.append(data.draw(st.text(proto.framing.ignore_between, max_size=2), label="between"))
        parts.append(mod.encode(obj))
    stream = ("" if is_text(proto) else b"").join(parts)
    cuts = sorted(data.draw(st.lists(st.integers(0, len(stream)), max_size=4), label="cuts"))
    decoder = mod.StreamDecoder(direction)
    out = []
    for a, b in zip([0, *cuts], [*cuts, len(stream)]):
        out += decoder.feed(stream[a:b])
    errors = [x for x in out if isinstance(x, Exception)]
    assert not errors, errors
    assert out == objs
