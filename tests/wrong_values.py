"""Values of the wrong type, shape or size for a field of a generated Python codec, from
the field's annotation: an encoder given one must raise its EncodeError. Shared by
tests/test_codec_inputs.py and the schema fuzzer (fuzz/schema/check.py)."""
from __future__ import annotations

import dataclasses
import enum
import typing
from decimal import Decimal
from fractions import Fraction


def member_paths(obj, prefix=()):
    """Every field's path, a group's as well as the fields inside it."""
    for f in dataclasses.fields(obj):
        if not f.compare:  # the kept text of numbers, not a value
            continue
        yield prefix + (f.name,)
        value = getattr(obj, f.name)
        if dataclasses.is_dataclass(value):
            yield from member_paths(value, prefix + (f.name,))


def with_value(obj, path, value):
    if len(path) == 1:
        return dataclasses.replace(obj, **{path[0]: value})
    return dataclasses.replace(obj, **{path[0]: with_value(getattr(obj, path[0]), path[1:], value)})


def declared(codec, obj, path):
    """The annotation of the field at `path`, and its current value."""
    for part in path[:-1]:
        obj = getattr(obj, part)
    return typing.get_type_hints(type(obj), vars(codec))[path[-1]], getattr(obj, path[-1])


class Foreign(enum.IntEnum):
    """A member of no generated set, equal to small ints."""
    zero = 0
    one = 1


# values that are no value of a field of the type, whatever its range: each must be an EncodeError
NOT_A_NUMBER = ["", "5", "1.5", b"\x05", bytearray(b"\x05"), [5], (5,), {}, {"a": 1}, object(), type, ...,
                Decimal("5"), Fraction(1, 2), complex(1, 0)]
WRONG = {
    int: [1.5, 1.0, float("nan"), float("inf"), float("-inf"), True, False, 2 ** 70, -2 ** 70, 10 ** 400,
          *NOT_A_NUMBER],
    float: [True, False, float("nan"), float("inf"), float("-inf"), 10 ** 400, -10 ** 400, *NOT_A_NUMBER],
    bool: [2, -1, 5, 2 ** 70, 1.0, 0.0, 1.5, float("nan"), "True", "1", "", b"\x01", [True], (), {}, object(),
           Decimal(1), Fraction(1)],
    str: [0, 5, 1.5, True, False, b"x", bytearray(b"x"), ["x"], ("x",), {}, object()],
    bytes: [0, 5, 1.5, True, "", "\x00" * 7, [0] * 7, (0,) * 7, {}, object(), bytes(100_000),
            memoryview(bytes(28)).cast("I")],
}
NOT_A_GROUP = [0, 1, True, "x", b"x", {}, (), [], object()]
NOT_A_LIST = [0, 1, True, "x", b"\x00\x00", {}, object()]


def wrong_values(codec, obj, path, nonfinite=frozenset()):
    """Values of the wrong type, shape or size for the field at `path`; `nonfinite` names
    the float fields, as (message, field), whose NaN and infinities are values."""
    hint, current = declared(codec, obj, path)
    args = typing.get_args(hint)
    optional = typing.get_origin(hint) is typing.Union and type(None) in args
    if optional:
        hint = next(a for a in args if a is not type(None))
    out = [] if optional else [None]
    if typing.get_origin(hint) is list:
        (element,) = typing.get_args(hint)
        nullable = typing.get_origin(element) is typing.Union and type(None) in typing.get_args(element)
        size = max(len(current or ()), 1)  # an absent conditional array is None
        out += NOT_A_LIST + [[object()] * size]
        out += [] if nullable else [[None] * size]  # absent elements of one-hot arrays are None
        if current:  # more elements than any count of these schemas
            out.append(current[:1] * 100_000)
    elif dataclasses.is_dataclass(hint):
        out += NOT_A_GROUP + [obj]  # the message is not its own group
    elif isinstance(hint, type) and issubclass(hint, enum.Enum):
        if issubclass(hint, str):
            out += [5, True, 1.5, b"x", ["x"], {}, object()]
        else:
            out += [True, False, 1.5, 1.0, float("nan"), 2 ** 70, -2 ** 70, "1", b"\x01", [1], {}, object()]
        out += [m for cls in vars(codec).values() if isinstance(cls, type) and issubclass(cls, enum.Enum)
                and cls.__module__ == codec.__name__ and cls is not hint for m in cls][:3]
        out += [Foreign.zero, Foreign.one] if not issubclass(hint, str) else []
    elif typing.get_origin(hint) is typing.Union and int in typing.get_args(hint):  # an open enum: a member or an int
        cls = next(a for a in typing.get_args(hint) if a is not int)
        out += [True, False, 1.5, 1.0, float("nan"), 2 ** 70, -2 ** 70, "1", b"\x01", [1], {}, object()]
        out += [m for other in vars(codec).values() if isinstance(other, type) and issubclass(other, enum.Enum)
                and other.__module__ == codec.__name__ and other is not cls for m in other][:3]
        out += [Foreign.zero, Foreign.one]
    elif hint is float and (obj.NAME, next(x for x in reversed(path) if isinstance(x, str))) in nonfinite:
        out += [x for x in WRONG[float] if not isinstance(x, float)]
    elif hint in WRONG:
        out += WRONG[hint]
    else:
        raise TypeError(f"no wrong values are known for a field of type {hint!r}")
    return out


def refusals(codec, objects, nonfinite=frozenset()) -> str:
    """Each member of each object set to each wrong value: "" when every encode raised
    the codec's EncodeError, else what was encoded or what else was raised."""
    for obj in objects:
        for path in member_paths(obj):
            for value in wrong_values(codec, obj, path, nonfinite):
                where = f"{type(obj).__name__}.{'.'.join(path)} = {value!r:.40}"
                try:
                    codec.encode(with_value(obj, path, value))
                except codec.EncodeError:
                    continue
                except Exception as exc:  # noqa: BLE001 - any other is the finding
                    return f"{where}: {type(exc).__name__}: {exc}"
                return f"{where} was encoded, not refused"
    return ""
