"""The generated Python codecs raise only their CodecError subclasses, for any input
of any type: every public entry point of every seed protocol is called with values
of the wrong type, shape and size, and every field of every message is set to them
before encoding. Returning normally is allowed (a decoder may accept what it can
read); any other exception is a defect."""
from __future__ import annotations

import dataclasses
import enum
import itertools

import pytest

from conftest import PROTOCOLS, load_generated

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


def example_objects(codec):
    """One valid object per message: decoded from the vectors the build wrote."""
    import json
    from conftest import ROOT
    vectors = json.loads((ROOT / "generated" / "vectors" / f"{codec.PROTOCOL}.json").read_text())
    seen = {}
    for case in vectors["valid"]:
        if case["message"] not in seen:
            seen[case["message"]] = codec.from_dict(case["message"], case["values"])
    return seen.values()


def leaf_paths(obj, prefix=()):
    for f in dataclasses.fields(obj):
        value = getattr(obj, f.name)
        if dataclasses.is_dataclass(value):
            yield from leaf_paths(value, prefix + (f.name,))
        else:
            yield prefix + (f.name,)


def with_value(obj, path, value):
    if len(path) == 1:
        return dataclasses.replace(obj, **{path[0]: value})
    return dataclasses.replace(obj, **{path[0]: with_value(getattr(obj, path[0]), path[1:], value)})


@pytest.mark.parametrize("name", PROTOCOLS)
def test_every_field_refuses_hostile_values_with_an_encode_error(name):
    codec = load_generated(name)
    for obj in example_objects(codec):
        for path in leaf_paths(obj):
            for value in HOSTILE:
                bad = with_value(obj, path, value)
                try:
                    codec.encode(bad)
                except codec.EncodeError:
                    pass
                except Exception as exc:  # noqa: BLE001
                    raise AssertionError(f"{name} {type(obj).__name__}.{'.'.join(path)} = {value!r:.40}: "
                                         f"{type(exc).__name__}: {exc}") from exc


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
