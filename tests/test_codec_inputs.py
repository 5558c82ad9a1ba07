"""The generated Python codecs raise only their CodecError subclasses, for any input
of any type: every public entry point of every seed protocol is called with values
of the wrong type, shape and size, and every field of every message (of the seed
protocols and the examples) is set to them before encoding. A decoder may return
normally (it may accept what it can read); an encoder given a value of the wrong
type, shape or size for its field raises its EncodeError; any other exception is a
defect."""
from __future__ import annotations

import dataclasses
import enum
import importlib.util
import itertools
import json
import sys

import pytest

from conftest import PROTOCOLS, ROOT, load_generated
from wrong_values import member_paths, with_value, wrong_values

EXAMPLES = ("dynamixel2", "mavlink1", "mavlink2", "modbus_rtu", "nmea0183", "ubx")

def released_view() -> memoryview:
    view = memoryview(b"\xaa\x08\x03\x01" * 3)
    view.release()
    return view


HOSTILE = [
    None, 0, 5, -1, 2 ** 70, 10 ** 400, 1.5, float("nan"), float("inf"), True, False,
    "", "x", "\u00a0", "\u0661", "9" * 5000, "$:" + "9" * 5000 + ";",
    b"", b"\x00", b"\x02" * 40, b"9" * 5000, bytearray(b"\xaa\x08"), memoryview(b"abcdefgh")[::2],
    memoryview(bytes(range(16))).cast("I"), [], [1, 2], {}, {"a": 1}, (1,), object(), type, ...,
    # memoryviews whose items are not ints 0..255, or not in one row, or gone
    *(memoryview(frame).cast(form) for frame in (b"\xaa\x08\x03\x01" * 3, b"\x02\x03\x03\x01" * 3,
                                                 b"\xb5\x62\x01\x07" * 25) for form in ("c", "b")),
    memoryview(b"\xaa\x08\x03\x01" * 3).cast("B", (3, 4)), released_view(),
]


def call(codec, fn, *args, **kwargs):
    try:
        result = fn(*args, **kwargs)
        if hasattr(result, "__next__"):  # generators raise as they run
            list(itertools.islice(result, 100))
    except codec.CodecError:
        pass


def entry_points(codec):
    """(name, one-argument callable) for every decoder-like entry point."""
    out = [("decode", codec.decode), ("encode", codec.encode)]
    for name in ("decode_text", "decode_lines", "decode_word", "decode_all", "encode_text"):
        if hasattr(codec, name):
            out.append((name, getattr(codec, name)))
    for name in dir(codec):
        if name.startswith("decode_") and name not in dict(out) and callable(getattr(codec, name)):
            out.append((name, getattr(codec, name)))
    if hasattr(codec, "StreamDecoder"):
        out.append(("StreamDecoder.feed", lambda x: codec.StreamDecoder().feed(x)))
        out.append(("StreamDecoder(direction)", lambda x: codec.StreamDecoder(direction=x).feed(b"\x02" * 64)))
    out.append(("decode(direction=)", lambda x: codec.decode(b"\xaa" * 12, direction=x)))
    out.append(("from_dict(name)", lambda x: codec.from_dict(x, {})))
    for cls in codec.MESSAGES.values():
        out.append((f"{cls.__name__}.decode", cls.decode))
        out.append((f"from_dict({cls.NAME}, x)", lambda x, n=cls.NAME: codec.from_dict(n, x)))
    return out


@pytest.mark.parametrize("name", PROTOCOLS)
def test_entry_points_raise_only_codec_errors(name):
    codec = load_generated(name)
    for label, fn in entry_points(codec):
        for value in HOSTILE:
            try:
                call(codec, fn, value)
            except Exception as exc:  # noqa: BLE001 - the point of the test
                raise AssertionError(f"{name}.{label}({value!r:.40}) raised {type(exc).__name__}: {exc}") from exc


GENERATED = {**{name: (ROOT / "generated" / "python", ROOT / "generated" / "vectors") for name in PROTOCOLS},
             **{name: (ROOT / "generated" / "examples" / "python", ROOT / "generated" / "examples" / "vectors")
                for name in EXAMPLES}}


def codec_of(name: str):
    """A seed protocol's module (conftest's), or an example's, imported the same stand-alone way."""
    if name in PROTOCOLS:
        return load_generated(name)
    key = f"generated_example_{name}"
    if key not in sys.modules:
        spec = importlib.util.spec_from_file_location(key, GENERATED[name][0] / f"{name}.py")
        module = importlib.util.module_from_spec(spec)
        sys.modules[key] = module
        spec.loader.exec_module(module)
    return sys.modules[key]


def example_objects(codec):
    """One valid object per message: decoded from the vectors the build wrote."""
    vectors = json.loads((GENERATED[codec.PROTOCOL][1] / f"{codec.PROTOCOL}.json").read_text())
    seen = {}
    for case in vectors["valid"]:
        if case["message"] not in seen:
            seen[case["message"]] = codec.from_dict(case["message"], case["values"])
    return seen.values()


def leaf_paths(obj, prefix=()):
    for f in dataclasses.fields(obj):
        if not f.compare:  # the kept text of numbers, not a value
            continue
        value = getattr(obj, f.name)
        if dataclasses.is_dataclass(value):
            yield from leaf_paths(value, prefix + (f.name,))
        else:
            yield prefix + (f.name,)


ALL = PROTOCOLS + EXAMPLES


@pytest.mark.parametrize("name", ALL)
def test_every_field_refuses_hostile_values_with_an_encode_error(name):
    """Any value: an EncodeError or a frame. A value of the wrong type, shape or size for
    the field: an EncodeError, never a frame."""
    codec = codec_of(name)
    checked = 0
    for obj in example_objects(codec):
        for path in member_paths(obj):
            where = f"{name} {type(obj).__name__}.{'.'.join(path)}"
            wrong = wrong_values(codec, obj, path)
            for value in HOSTILE + wrong:
                bad = with_value(obj, path, value)
                try:
                    codec.encode(bad)
                except codec.EncodeError:
                    checked += any(value is w for w in wrong)
                    continue
                except Exception as exc:  # noqa: BLE001
                    raise AssertionError(f"{where} = {value!r:.40}: {type(exc).__name__}: {exc}") from exc
                assert not any(value is w for w in wrong), f"{where} = {value!r:.40} was encoded, not refused"
    assert checked > 100, name


@pytest.mark.parametrize("name", [p for p in PROTOCOLS if p != "tr24"])  # tr24 has no enums or flags
def test_enum_and_flag_fields_take_only_their_own_members(name):
    """A bool or another set's member compares equal to an int, yet is not a value of this set."""
    codec = load_generated(name)
    sets = [cls for cls in vars(codec).values() if isinstance(cls, type) and issubclass(cls, enum.Enum)
            and cls.__module__ == codec.__name__]
    checked = 0
    for obj in example_objects(codec):
        for path in leaf_paths(obj):
            current = obj
            for part in path:
                current = getattr(current, part)
            if not isinstance(current, enum.Enum):
                continue
            others = [member for cls in sets if cls is not type(current) for member in cls][:4]
            for value in [True, False, *others]:
                with pytest.raises(codec.EncodeError):
                    codec.encode(with_value(obj, path, value))
                checked += 1
    assert checked, f"{name}: no enum or flag field in the examples"


def test_a_broken_schema_rule_is_named_by_its_id():
    """Not "breaks rule rule": the message names the schema's rule (CAR-D3, schemas/car.yaml)."""
    car = load_generated("car")
    with pytest.raises(car.EncodeError) as err:
        car.encode(car.Header(h1=0, h2_count=0, h2_time=0))
    assert str(err.value).startswith("header.h2_time: 0 breaks rule CAR-D3 (expected if h2_count == 0 then")


def integer_limits(field):
    """The schema's bounds of a plain integer field: its range, else its type's width
    (uN: 0..2**N - 1, iN: -2**(N-1)..2**(N-1) - 1); None for any other field."""
    if field.kind not in ("uint", "int") or not field.is_member or field.dispatch or not field.bits \
            or field.scale is not None or field.offset or field.one_hot or field.values or field.enum or field.flags:
        return None
    if field.range:
        return field.range
    if field.kind == "uint":
        return 0, (1 << field.bits) - 1
    return -(1 << (field.bits - 1)), (1 << (field.bits - 1)) - 1


@pytest.mark.parametrize("name", ALL)
def test_integer_fields_refuse_one_past_either_end_of_their_range(name):
    """lo - 1 and hi + 1 of each plain integer field, bounds read from the schema: an
    EncodeError, never a frame, nor a value masked into its neighbours' bits."""
    from codeword.build import compile_schema
    codec = codec_of(name)
    schema = (ROOT / "schemas" if name in PROTOCOLS else ROOT / "examples") / f"{name}.yaml"
    protocol = compile_schema(schema)
    checked = 0
    for obj in example_objects(codec):
        message = next(m for m in protocol.messages if m.name == obj.NAME)
        fields = {leaf.path: leaf.field for leaf in message.wire.leaves if all(isinstance(p, str) for p in leaf.path)}
        for path in leaf_paths(obj):
            limits = integer_limits(fields[path]) if path in fields else None
            if limits is None:
                continue
            for value in (limits[0] - 1, limits[1] + 1):
                with pytest.raises(codec.EncodeError):
                    codec.encode(with_value(obj, path, value))
                checked += 1
    assert checked >= 4, name
