"""The protocol model: one immutable, fully computed description of a protocol.

The resolver builds it from a schema document; every backend reads only this.
Sizes, bit offsets, checksum coverage and dispatch keys are computed here once.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from fractions import Fraction
from typing import Any, Optional, Union

from .diagnostics import Loc

Scalar = Union[int, float, str, bool, None]


@dataclass(frozen=True)
class Text:
    """English text with optional translations (ru, zh, pl …)."""

    en: str
    translations: tuple[tuple[str, str], ...] = ()

    def __str__(self) -> str:
        return self.en

    def get(self, lang: str) -> Optional[str]:
        return self.en if lang == "en" else dict(self.translations).get(lang)


@dataclass(frozen=True)
class Note:
    id: str
    text: Text


@dataclass(frozen=True)
class HistoryEntry:
    version: str
    date: str
    author: str
    changes: tuple[Text, ...]


@dataclass(frozen=True)
class Role:
    name: str
    doc: Optional[Text]


@dataclass(frozen=True)
class Direction:
    name: str
    source: str
    target: str
    doc: Optional[Text]


@dataclass(frozen=True)
class Transport:
    name: str
    kind: str
    doc: Optional[Text]
    params: tuple[tuple[str, Scalar], ...]


@dataclass(frozen=True)
class Parameter:
    name: str
    default: Optional[Union[int, float]]
    range: Optional[tuple[float, float]]
    unit: Optional[str]
    doc: Optional[Text]

    @property
    def integers(self) -> Optional[tuple[int, int]]:
        """The lowest and highest integer the range admits; None without a range."""
        return (math.ceil(self.range[0]), math.floor(self.range[1])) if self.range else None


@dataclass(frozen=True)
class EnumMember:
    name: str
    value: Union[int, str]
    doc: Optional[Text]


@dataclass(frozen=True)
class Enum:
    name: str
    kind: str  # "int" or "char"
    bits: Optional[int]
    members: tuple[EnumMember, ...]
    doc: Optional[Text]
    open: bool = False  # other values of its type are valid too, kept as numbers

    @property
    def values(self) -> tuple:
        return tuple(m.value for m in self.members)


@dataclass(frozen=True)
class FlagBit:
    name: str
    bit: int
    doc: Optional[Text]

    @property
    def mask(self) -> int:
        return 1 << self.bit


@dataclass(frozen=True)
class FlagSet:
    name: str
    bits: int
    members: tuple[FlagBit, ...]
    doc: Optional[Text]

    @property
    def mask(self) -> int:
        mask = 0
        for member in self.members:
            mask |= 1 << member.bit
        return mask


@dataclass(frozen=True)
class CrcParams:
    """Rocksoft model parameters (Williams 1993), as in the RevEng catalogue."""

    name: str
    width: int
    poly: int
    init: int
    refin: bool
    refout: bool
    xorout: int
    check: Optional[int] = None


@dataclass(frozen=True)
class Checksum:
    algorithm: str  # parity | sum | xor | fletcher | internet | crc
    over: str  # fields | bytes | bits
    covers: Optional[tuple[str, str]]  # (from, to) field names; None = every other field
    parity: str = "even"
    modulo: Optional[int] = None
    crc: Optional[CrcParams] = None
    # Byte range [start, end) of the frame covered, computed for bytes framing.
    byte_span: Optional[tuple[int, int]] = None
    loc: Optional[Loc] = None
    # A sum's final step: "ones" or "twos" complement in the field's width, then XOR with xorout.
    complement: Optional[str] = None
    xorout: Optional[int] = None
    # The field's width, for arithmetic that depends on it (fletcher, a complemented sum).
    width: Optional[int] = None
    # "message": a CRC that takes one more byte after its coverage, the message's crc_extra.
    extra: Optional[str] = None
    # internet (RFC 1071): "big" or "little", the byte order its 16-bit words are read in.
    word_order: Optional[str] = None
    # internet: the field lies inside its coverage (as IPv4's header checksum). Encoders
    # count its bytes as zero; decoders run RFC 1071's receiver check, the covered bytes
    # with the field summing to all ones.
    covers_self: bool = False

    def final(self, value: int) -> int:
        """The finished checksum from a sum or xor reduced by the modulo."""
        if self.complement == "ones":
            value ^= (1 << self.width) - 1
        elif self.complement == "twos":
            value = -value & ((1 << self.width) - 1)
        return value ^ (self.xorout or 0)


@dataclass(frozen=True)
class Field:
    """One field in its final place: type, constraints, and (binary) its bit offset."""

    name: str
    kind: str  # uint | int | bool | float | char | str | bytes | group
    loc: Loc
    bits: Optional[int] = None  # wire width; None for text-only kinds
    doc: Optional[Text] = None
    title: Optional[Text] = None
    type_name: Optional[str] = None  # the named type it came from, if any
    unit: Optional[str] = None
    const: Scalar = None
    reserved: bool = False
    default: Any = None
    has_default: bool = False
    range: Optional[tuple[Union[int, float], Union[int, float]]] = None
    values: Optional[tuple] = None
    enum: Optional[Enum] = None
    flags: Optional[FlagSet] = None
    scale: Optional[float] = None
    offset: Optional[Union[int, float]] = None
    one_hot: bool = False
    exactly_one: bool = False
    byte_order: Optional[str] = None
    length: Optional[int] = None  # bytes/str; the payload marker of a message placed by start_bit: its bytes
    length_param: Optional[str] = None
    max_length: Optional[int] = None
    optional: bool = False
    to_end: bool = False
    decimals: Optional[int] = None  # text: the raw integer written with this many decimals
    width: Optional[int] = None  # text: an integer written at least this wide, zero-padded
    dispatch: bool = False
    by_direction: tuple[tuple[str, int], ...] = ()  # envelope: (direction, value); a dispatch field
    length_of: Optional[tuple[str, str]] = None
    length_adjust: int = 0  # added to the bytes length_of counts (the field's value is the sum)
    checksum: Optional[Checksum] = None
    fields: tuple["Field", ...] = ()
    message: Optional[Text] = None
    rule: Optional[str] = None
    is_payload: bool = False
    bit_offset: Optional[int] = None  # from the start of the frame/record
    from_envelope: bool = False
    extension: bool = False  # added in a later version: a frame may end before it (bytes: reads as 0; text: absent)
    count: Optional[int] = None  # an array of this many elements; `bits` is then the whole array's
    counted_by: Optional[str] = None  # an earlier field gives how many elements (count is then the most)
    count_unit: Optional[int] = None  # bytes one unit of the count stands for (None: an element)
    counts: Optional[str] = None  # the array this field gives the count of: the encoder sets it
    present_if: Optional["Presence"] = None  # in the frame only when an earlier field says so
    # Placed as a CAN DBC signal (in a message of `payload_bytes`): bit k is bit k % 8 of payload
    # byte k // 8, 0 the least significant; the field's least significant bit when `byte_order`
    # is little (Intel), its most significant when big (Motorola). `bit_offset` is then its first
    # bit in its own order's numbering (see Leaf.order).
    start_bit: Optional[int] = None
    multiplexed_by: Optional["Multiplex"] = None  # placed: in the frame only for some multiplexor values
    keep_spelling: bool = False  # text number: the decoded message keeps its text, written back unchanged
    signature: Optional["Signature"] = None  # a trailer field holding a keyed hash of the frame
    prefix: bool = False  # text: written in the line's prefix, before the message's id (NMEA's talker)
    keep_empty: Optional[bool] = None  # text, optional: its absent value keeps an empty place (None: the framing's)
    mavlink_name: Optional[str] = None  # its name in MAVLink's CRC_EXTRA (`extra: mavlink`), where not its own
    finite: bool = True  # float: False when NaN and the infinities are values too (sent as they are, NaN as the quiet NaN)

    @property
    def fixed_spelling(self) -> bool:
        """A text integer written with fixed decimals or padding (`decimals: 0` included);
        readers take any spelling of it, rounded to its decimals."""
        return self.decimals is not None or self.width is not None

    @property
    def varies(self) -> bool:
        """An array or bytes field whose frames carry from none to all of it: counted by an
        earlier field, or filling the rest of the payload (binary `to_end`)."""
        return self.counted_by is not None or self.to_end and (self.count is not None or self.kind == "bytes")

    @property
    def element(self) -> "Field":
        """One element of an array field (the field itself when it is not one)."""
        if self.count is None:
            return self
        return replace(self, count=None, counted_by=None, count_unit=None, to_end=False,
                       bits=None if self.bits is None else self.bits // self.count)

    @property
    def is_member(self) -> bool:
        """Whether the field is an attribute of the decoded object."""
        return not (self.is_payload or self.reserved or self.checksum or self.length_of
                    or self.const is not None or self.counts)

    @property
    def generated_members(self) -> tuple[str, ...]:
        """Struct members C declares beside this field's own: the presence flag of an
        optional or one-hot value, and the count in use of an array or bytes that varies."""
        if not self.is_member or self.kind == "group":
            return (count_member(self.name),) if self.is_member and self.varies else ()
        flag = (presence_member(self.name),) if self.optional or self.one_hot else ()
        spelling = (spelling_member(self.name),) if self.keep_spelling else ()
        return flag + ((count_member(self.name),) if self.varies else ()) + spelling

    @property
    def signed(self) -> bool:
        return self.kind == "int"

    @property
    def range_bounds(self) -> Optional[tuple[int, int]]:
        """The stored integers the schema's range allows (None without one): raw ones for a
        scaled field, whose range a decimal field reads as the decimals it is written in
        (999.9 at 1 decimal is 9999), else the values themselves. Every target and the
        vectors take these ends, which agree with the decoders' test of the value."""
        if self.range is None:
            return None
        lo, hi = self.range
        if self.decimals:
            lo, hi = Fraction(repr(lo)), Fraction(repr(hi))
        scale = Fraction(1, 10 ** self.decimals) if self.decimals else \
            Fraction(self.scale) if self.scale is not None else Fraction(1)
        off = Fraction(self.offset or 0) if self.scale is not None else Fraction(0)
        first, last = math.ceil((Fraction(lo) - off) / scale), math.floor((Fraction(hi) - off) / scale)
        if self.scale is None or self.decimals:
            return first, last
        # a scaled value is the double raw * scale + offset, checked against the range as such: the
        # ends are the raw values whose doubles fall inside it (the exact quotient may miss by one)
        def value(raw: int) -> float:
            return raw * self.scale + (self.offset or 0)
        while value(first - 1) >= lo:
            first -= 1
        while value(first) < lo:
            first += 1
        while value(last + 1) <= hi:
            last += 1
        while value(last) > hi:
            last -= 1
        return first, last

    @property
    def closed_enum(self) -> bool:
        """A field of an enum whose members are its only valid values."""
        return self.enum is not None and not self.enum.open

    @property
    def raw_range(self) -> Optional[tuple[int, int]]:
        """The range of raw wire integers the width allows."""
        if self.bits is None or self.kind not in ("uint", "int", "bool"):
            return None
        if self.kind == "int":
            return (-(1 << (self.bits - 1)), (1 << (self.bits - 1)) - 1)
        return (0, (1 << self.bits) - 1)


def field_at(fields: tuple[Field, ...], dotted: str) -> Optional[Field]:
    """The field a dotted path names, walking into groups; None if there is none."""
    found = None
    for part in dotted.split("."):
        found = next((f for f in fields if f.name == part), None)
        if found is None:
            return None
        fields = found.fields
    return found


def array_on(fields: tuple[Field, ...], dotted: str) -> Optional[Field]:
    """The array field a dotted path names or passes through, if any."""
    for part in dotted.split("."):
        found = next((f for f in fields if f.name == part), None)
        if found is None:
            return None
        if found.count is not None:
            return found
        fields = found.fields
    return None


@dataclass(frozen=True)
class Condition:
    """`path` compared with `op` (eq, ne, in, range, eq_var, eq_param …) to `value`."""

    path: str
    op: str
    value: Any


@dataclass(frozen=True)
class Rule:
    id: Optional[str]
    when: tuple[Condition, ...]
    require: tuple[Condition, ...]
    message: Optional[Text]
    loc: Loc


@dataclass(frozen=True)
class ExpectedError:
    field: str
    rule: str
    line: Optional[int] = None


@dataclass(frozen=True)
class Example:
    name: str
    loc: Loc
    values: Optional[dict] = None
    hex: Optional[bytes] = None
    word: Optional[int] = None
    text: Optional[str] = None
    direction: Optional[str] = None
    decode_only: bool = False
    errors: tuple[ExpectedError, ...] = ()
    source: Optional[str] = None

    def __hash__(self) -> int:  # values is a dict; identity is enough for a model node
        return id(self)


@dataclass(frozen=True)
class StreamEvent:
    """What a stream decoder gives, worked out by hand: a message (and the offset
    just past its frame, when the example states it) or an error (of a rule, or
    of any rule where several faults could be reported first)."""

    message: Optional[str] = None
    end: Optional[int] = None
    rule: Optional[str] = None  # an error's rule; None with message None: any error


@dataclass(frozen=True)
class StreamExample:
    """Bytes in, events out: a stream case the build runs through the stream decoder."""

    name: str
    loc: Loc
    data: bytes
    events: tuple[StreamEvent, ...]
    doc: Optional[Text] = None
    text: bool = False  # written as text in the schema (a text framing's lines)


@dataclass(frozen=True)
class Leaf:
    """A field with a wire value of its own (groups are flattened into leaves) and
    where it sits."""

    field: Field
    path: tuple[Union[str, int], ...]  # attribute path from the message object; an int indexes an array
    pos: Optional[int]  # first bit in the frame; None where widths are not fixed (text)
    # The bit order `pos` counts in and the field's bits run in: "big" most significant first (bit 0
    # is the top bit of byte 0), "little" least significant first (bit 0 is the low bit of byte 0).
    # None: the frame's (Framing.wire_order); a field placed by start_bit has its own.
    order: Optional[str] = None

    @property
    def bits(self) -> int:
        return self.field.bits or 0

    @property
    def var(self) -> str:
        """The local variable generated code keeps its raw wire value in."""
        return "r_" + path_name(self.path)

    @property
    def dotted(self) -> str:
        """The path as Python and C spell an access to it: `pts[1].x`."""
        return dotted(self.path)


def presence_member(name: str) -> str:
    """The C member that says whether an optional (or one-hot) field `name` is present."""
    return "has_" + name


def spelling_member(name: str) -> str:
    """The C member that holds the text a kept-spelling number `name` was read from."""
    return name + "_spelling"


# The longest spelling of a number a decoded message keeps: the longest any writer emits
# (a 64-bit integer, 20 characters; a text float, 22; a `width` of 20), with room to spare.
SPELLING_MAX = 24


def places_member() -> str:
    """The C member of a message that keeps how many values its decoded line had."""
    return "line_values"


def count_member(name: str) -> str:
    """The C member that holds how many elements (or bytes) of field `name` are in use."""
    return name + "_count"


def length_argument(name: str) -> str:
    """The C parameter that carries the length of a machine event's bytes argument `name`."""
    return name + "_len"


# Parameters every generated machine event function takes before its arguments (C: the
# machine, the time, the outputs; Python: self and the time): no argument may share them.
EVENT_PARAMETERS = ("m", "now", "out", "self")
# The local a Python event method keeps the current state in: an argument so named would be lost.
EVENT_LOCALS = ("state",)
# The parameters of the functions that pack and unpack a machine's packets besides the
# packet's fields and the parameters its length depends on (C: the buffer b, its size n;
# Python: the buffer b): no such field or parameter may share them.
PACKET_PARAMETERS = ("b", "n")
# What every generated machine holds besides its variables and parameters (C struct
# members, Python slots and class attributes) and what its constructor takes besides its
# parameters (C: the machine m, the application's execute function and its context).
MACHINE_MEMBERS = ("state", "kept", "kept_len", "timer_on", "deadline", "execute", "execute_ctx", "m", "STATES")
# The functions (C) and methods (Python) every machine has besides one per event; the
# timer event's is `tick`.
MACHINE_FUNCTIONS = ("init", "reset", "tick")


def path_name(path: tuple[Union[str, int], ...]) -> str:
    """A path as one identifier, the only path spelt so and with no `__` (C++ reserves
    it): a top-level field is its name (`speed`); a deeper path is each name led by
    its length and each index in digits, `_` between them but after a name that ends
    in `_`: `ch[3]` is `2ch_3`, `pts[1].x` is `3pts_1_1x`, `led.red` is `3led_3red`.
    A name starts with a letter, so a deeper path never meets a top-level name, and
    the lengths keep `a.b_c` (`1a_3b_c`) apart from `a_b.c` (`3a_b_1c`)."""
    if len(path) == 1:
        return str(path[0])
    out = ""
    for part in path:
        if out and not out.endswith("_"):
            out += "_"
        out += str(part) if isinstance(part, int) else f"{len(part)}{part}"
    return out


def dotted(path: tuple[Union[str, int], ...]) -> str:
    """`pts[1].x` for ("pts", 1, "x")."""
    return "".join(f"[{p}]" if isinstance(p, int) else f".{p}" if i else p for i, p in enumerate(path))


def shift_in(order: str, start: int, size: int, pos: int, bits: int) -> int:
    """Where the `bits` bits from frame bit `pos` sit, from bit 0, in the integer that
    bytes start..start+size read in `order`. The wire counts bits as its integers
    read them: "big" most significant bit first (bit 0 is the top bit of byte 0),
    "little" least significant bit first (bit 0 is the low bit of byte 0)."""
    return (start + size) * 8 - pos - bits if order == "big" else pos - 8 * start


@dataclass(frozen=True)
class Run:
    """Bytes of a frame moved as one unit. "bytes" and "number": one field of whole
    bytes starting on a byte boundary, in its own byte order; "packed": bit fields
    that together fill whole bytes, as one integer read in `order`: big-endian when
    the frame counts bits most significant first, little-endian when least
    significant first (a frame's trailing padding completes the last byte)."""

    kind: str  # bytes | number | packed
    start: int  # first byte
    size: int  # bytes
    leaves: tuple[Leaf, ...]
    order: str = "big"  # packed: byte order of the run's integer (the frame's bit order)
    # packed: bits no leaf holds read as anything and are written as 0 (the unused bits of a
    # payload placed by start_bit); otherwise they are the frame's padding, which must be 0
    free: bool = False

    def order_of(self, leaf: Leaf) -> str:
        """The byte order of the integer `leaf` is read from: its own, or the run's."""
        return leaf.order or self.order

    def shift(self, leaf: Leaf) -> int:
        """Where `leaf` sits, from bit 0, in the run's bytes read as one integer in its order."""
        return shift_in(self.order_of(leaf), self.start, self.size, leaf.pos, leaf.bits)

    @property
    def mixed(self) -> bool:
        """Leaves of both bit orders share the run (a run of over one byte then holds two integers)."""
        return self.size > 1 and len({self.order_of(leaf) for leaf in self.leaves}) > 1


class Each(int):
    """The index in a Leaf's path that stands for every element of a Repeat's array: generated
    code spells it `i`, the variable of the loop over the elements."""

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Each)

    def __hash__(self) -> int:
        return hash("Each")

    def __str__(self) -> str:
        return "i"

    def __format__(self, spec: str) -> str:
        return "i"

    def __repr__(self) -> str:
        return "EACH"


EACH = Each(0)


@dataclass(frozen=True)
class Repeat:
    """An array whose elements generated code reads and writes in a loop rather than one by
    one, so that the code grows with the schema and not with the count: each element is whole
    bytes from a byte boundary, and nothing outside the array reads its elements' values.
    `leaves` and `runs` are one element's, its index EACH in their paths, their bits and bytes
    counted from the element's first byte; element k starts at byte `start + k * stride`.
    The message's own leaves and runs still hold every element, for targets that list them."""

    field: Field  # the array, a field of the message itself
    start: int  # first byte of element 0
    stride: int  # bytes of one element
    count: int  # elements in the whole frame (a counted array's most)
    leaves: tuple[Leaf, ...]
    runs: tuple[Run, ...]

    def holds(self, leaf: Leaf) -> bool:
        """Whether `leaf` is part of one of the array's elements."""
        return len(leaf.path) > 1 and leaf.path[0] == self.field.name

    @property
    def end(self) -> int:
        """The byte after the last element."""
        return self.start + self.count * self.stride


@dataclass(frozen=True)
class Wire:
    """A message's wire layout, computed once for every target."""

    leaves: tuple[Leaf, ...]
    runs: tuple[Run, ...]  # binary framings; empty in text framing
    order: str = "big"  # byte order of the frame read as one integer: its bit order
    repeats: tuple[Repeat, ...] = ()  # binary framings: the arrays generated code loops over

    def repeat_of(self, leaf: Leaf) -> Optional[Repeat]:
        """The Repeat whose elements hold `leaf`, if any."""
        return next((r for r in self.repeats if r.holds(leaf)), None)

    def unrepeated_runs(self) -> tuple[Run, ...]:
        """The runs outside every Repeat: what code that loops over the repeats writes one by one."""
        return tuple(run for run in self.runs if not any(r.holds(run.leaves[0]) for r in self.repeats))


@dataclass(frozen=True)
class Counter:
    """An array (or bytes field) whose length an earlier field, or the frame's size, gives:
    a frame sends `count × unit` of its bytes, the rest of its `most` elements are left off."""

    field: str  # the counted array or bytes field
    count_field: Optional[str]  # the earlier field whose value gives its length (None: the frame's size does)
    element_bytes: int  # bytes of one element (1 for a bytes field)
    most: int  # the most elements it holds
    unit_bytes: Optional[int] = None  # bytes one unit of the count stands for (None: an element)

    @property
    def unit(self) -> int:
        """Bytes one unit of the count field's value stands for."""
        return self.unit_bytes or self.element_bytes

    @property
    def most_value(self) -> int:
        """The largest value the count field may hold."""
        return self.most * self.element_bytes // self.unit

    @property
    def step(self) -> int:
        """The count field's value is a multiple of this: its bytes hold whole elements."""
        return self.element_bytes // math.gcd(self.element_bytes, self.unit)

    @property
    def element_step(self) -> int:
        """The elements sent are a multiple of this: they fill whole units of the count."""
        return self.unit // math.gcd(self.element_bytes, self.unit)


@dataclass(frozen=True)
class Presence:
    """When a conditional field is in the frame: the raw value of the earlier field
    `field`, masked with `mask`, is one of `values`. `has` and `equals` keep what the
    schema said, for docs and errors."""

    field: str  # the earlier field whose value says
    has: Optional[str] = None  # a flag of its flag set that must be set
    equals: tuple = ()  # values (numbers or enum member names), one of which it must hold
    mask: int = 0  # the bits of its raw value that are tested (all of them for a value)
    values: tuple[int, ...] = ()  # present when the masked raw value is one of these

    @property
    def says(self) -> str:
        """The condition in words: "flags has gps", "kind is 3 or 4"."""
        if self.has is not None:
            return f"{self.field} has {self.has}"
        return f"{self.field} is {' or '.join(str(v) for v in self.equals)}"


@dataclass(frozen=True)
class Multiplex:
    """When a field placed by start_bit is in the frame (CAN DBC multiplexing): the raw
    value of the earlier placed field `field`, its multiplexor, lies in one of `ranges`,
    and the multiplexor is itself in the frame (`outer`: its own condition, for extended
    multiplexing). Fields present for disjoint values share bits; the decoded message
    holds only those present."""

    field: str  # the multiplexor
    ranges: tuple[tuple[int, int], ...]  # [lo, hi] raw values, sorted, disjoint and not touching
    outer: Optional["Multiplex"] = None  # the multiplexor's own condition, if it is multiplexed
    most: int = 0  # the multiplexor's largest raw value

    @property
    def bounds(self) -> tuple[tuple[Optional[int], Optional[int]], ...]:
        """`ranges` as the comparisons a test needs: None where the multiplexor's width
        already bounds it (a test that always holds is one no compiler warns about)."""
        return tuple((lo, hi) if lo == hi else (lo or None, None if hi >= self.most else hi) for lo, hi in self.ranges)

    @property
    def chain(self) -> tuple["Multiplex", ...]:
        """Every condition that must hold, the outermost multiplexor's first."""
        return (self.outer.chain if self.outer else ()) + (self,)

    def holds(self, raw: int) -> bool:
        """Whether the multiplexor's raw value `raw` selects the field (`outer` aside)."""
        return any(lo <= raw <= hi for lo, hi in self.ranges)

    @property
    def values_text(self) -> str:
        """The values as the schema writes them: "0, 2..5"."""
        return ", ".join(str(lo) if lo == hi else f"{lo}..{hi}" for lo, hi in self.ranges)

    @property
    def says(self) -> str:
        """The whole condition in words: "mode is 1 and page is 0, 2..5"."""
        return " and ".join(f"{x.field} is {x.values_text}" for x in self.chain)


@dataclass(frozen=True)
class Gap:
    """Bytes of the whole frame that a frame carries in part or not at all, as an earlier
    field says: a counted array's elements past its count, or a conditional field that is
    absent. A decoder puts the missing bytes back as zeros and reads the whole frame; an
    encoder writes the whole frame and leaves them out."""

    span: tuple[int, int]  # byte span [start, end) of the field in the whole frame
    field: str  # the counted or conditional field
    counter: Optional[Counter] = None  # counted: how the count field gives the bytes sent
    presence: Optional[Presence] = None  # conditional: when all of it is sent

    @property
    def control(self) -> Optional[str]:
        """The earlier field whose value says how many of the bytes are sent (None: the frame's size)."""
        return self.counter.count_field if self.counter else self.presence.field

    @property
    def fills_rest(self) -> bool:
        """The field takes what the frame holds after the fields before it."""
        return self.counter is not None and self.counter.count_field is None

    @property
    def size(self) -> int:
        return self.span[1] - self.span[0]


@dataclass(frozen=True)
class Shortening:
    """A frame whose payload may end early: its extension fields left off, or (with
    `truncate: trailing_zeros`) its trailing zero bytes dropped by the sender. The
    length field counts the payload bytes sent; a decoder puts the missing bytes back
    as zeros before it reads the fields, an encoder that truncates drops them."""

    payload: tuple[int, int]  # byte span [start, end) of the whole payload in the full frame
    least: int  # the fewest payload bytes a frame may carry
    length_field: Optional[str]  # the envelope field that counts the payload bytes sent, if any
    trailing_zeros: bool = False  # the encoder drops the payload's trailing zero bytes
    gaps: tuple[Gap, ...] = ()  # counted and conditional fields, in wire order

    @property
    def counter(self) -> Optional[Counter]:
        """The counted array when it is the frame's only gap: a frame's size then follows
        from its count field alone, which a stream decoder without a length field reads."""
        return self.gaps[0].counter if len(self.gaps) == 1 else None

    @property
    def most_cut(self) -> int:
        """The most payload bytes a frame may leave off."""
        return self.payload[1] - self.payload[0] - self.least


@dataclass(frozen=True)
class TextPlaces:
    """How many values a text line of a message carries (its body, the prefix field aside).
    Values from `written` on are written only up to the last one present; values from
    `least` on may be missing from a line altogether, and then read as absent."""

    least: int  # the fewest values a reader takes: the line may end before any later one
    written: int  # the values a writer always writes, absent ones as empty places (at least `least`)
    total: int  # the values of a whole line

    @property
    def varies(self) -> bool:
        """Whether lines of this message may carry different numbers of values."""
        return self.least < self.total


@dataclass(frozen=True)
class Message:
    name: str
    loc: Loc
    title: Optional[Text]
    doc: Optional[Text]
    ids: tuple  # values of the envelope's dispatch field (bytes/text framing)
    direction: Optional[str]
    role: Optional[str]
    answered_by: tuple[str, ...]
    fields: tuple[Field, ...]  # as declared, without the envelope
    layout: tuple[Field, ...]  # the whole frame in wire order, offsets computed
    bits: Optional[int]  # total bits of the frame (binary framings)
    rules: tuple[Rule, ...]
    examples: tuple[Example, ...]
    dispatch_key: tuple[tuple[str, Any], ...]  # (field, value) pairs that identify it
    wire: Wire
    crc_extra: Optional[int] = None  # the byte a checksum with `extra: message` takes last
    payload_bytes: Optional[int] = None  # fields placed by start_bit in a payload of this many bytes
    layout_type: Optional[str] = None  # the shared group type its fields come from
    shortening: Optional[Shortening] = None  # set when a frame may carry less than the whole payload
    text_places: Optional[TextPlaces] = None  # text framing: how many values a line carries
    keeps_places: bool = False  # text: a decoded message keeps how many values its line had, written back so

    @property
    def size(self) -> Optional[int]:
        """Bytes of the whole frame (the largest, when frames may be shorter)."""
        return None if self.bits is None else (self.bits + 7) // 8

    @property
    def min_size(self) -> Optional[int]:
        """Bytes of the shortest frame a decoder accepts."""
        return self.size - self.shortening.most_cut if self.shortening else self.size

    @property
    def sizes(self) -> range:
        """Every frame size a decoder accepts (a counted array's frames step by its elements;
        with several gaps, a superset: the decoder checks the size against what it reads)."""
        counter = self.shortening.counter if self.shortening else None
        return range(self.min_size, self.size + 1, counter.element_bytes if counter else 1)

    @property
    def members(self) -> tuple[Field, ...]:
        return tuple(f for f in self.layout if f.is_member)

    def counts_sent(self, cs: Checksum) -> bool:
        """Whether checksum `cs` ends with a payload that may be cut short, and so covers
        the bytes sent rather than the whole frame."""
        return self.shortening is not None and cs.byte_span[1] == self.shortening.payload[1]

    @property
    def prefix_field(self) -> Optional[Field]:
        """Text framing: the field written before the id in the line's prefix (NMEA's talker)."""
        return next((f for f in self.layout if f.prefix), None)

    @property
    def id_fields(self) -> tuple[tuple[str, int], ...]:
        """With several dispatch fields (bytes framing), each one's value; `ids` then
        holds the one key they make together, as a decoder reads it."""
        if len(self.dispatch_key) < 2 or not self.ids:
            return ()
        return tuple((name, values[0]) for name, values in self.dispatch_key)

    def shift(self, leaf: Leaf) -> int:
        """Where `leaf` sits in the whole frame read as one integer (in `wire.order`)."""
        return shift_in(self.wire.order, 0, self.size, leaf.pos, leaf.bits)

    def padding(self) -> tuple[int, int]:
        """(shift, bits) of the padding that completes the last byte, in that byte."""
        pad = 8 * self.size - self.bits
        return shift_in(self.wire.order, self.size - 1, 1, self.bits, pad), pad


@dataclass(frozen=True)
class TextForm:
    """A bits protocol written as a line of decimal integers (a text exchange file)."""

    separator: str
    comment: Optional[str]
    checksum_unfilled: Optional[int]


@dataclass(frozen=True)
class LineChecksum:
    """Text framing: a checksum of the line's characters between the start marker (or
    the line's start) and `suffix`, written after `suffix` as two uppercase hex digits
    (NMEA 0183's `*hh`)."""

    algorithm: str  # xor | sum (modulo 256)
    suffix: str
    digits: str = "hex2"


@dataclass(frozen=True)
class PatternStuffing:
    """Bytes framing: after each occurrence of `pattern` in the bytes from field `covers[0]`
    through field `covers[1]`, the sender inserts the byte `insert` and the receiver removes
    it (Dynamixel Protocol 2.0: FD after FF FF FD, from the instruction to the last
    parameter). Length fields and checksums count the frame as sent, stuffed bytes
    included. The resolver admits only patterns a receiver reads back one way: the pattern
    does not overlap itself, and the inserted byte never forms part of an occurrence."""

    pattern: bytes
    insert: int
    covers: tuple[str, str]  # (from, to) field names; `payload` for the message's own fields
    head: int  # bytes of the frame before the stuffed ones
    tail: int  # bytes of the frame after them
    loc: Optional[Loc] = None

    def most_inserted(self, stuffed: int) -> int:
        """The most bytes stuffing adds to `stuffed` bytes: the pattern's occurrences cannot
        overlap, so at most one per pattern length."""
        return stuffed // len(self.pattern)


@dataclass(frozen=True)
class Signature:
    """A field whose bytes are the first bytes of a keyed hash: `algorithm` over a
    secret key of `key_length` bytes the application gives, then the frame's bytes
    from the envelope field `covers[0]` through the trailer field `covers[1]`."""

    algorithm: str  # SHA-256
    key_length: int
    covers: tuple[str, str]
    start: int  # the first byte hashed after the key, from the frame's start
    end: int  # the byte after the last one hashed, from the trailer's start


@dataclass(frozen=True)
class Trailer:
    """Fields sent after the frame's last byte only when a flag of an envelope field
    before the payload is set (MAVLink 2's signature). Decoders find the flag at a
    fixed byte, take the trailer off the end and read the rest as an unflagged frame."""

    presence: Presence  # the envelope flags field and the flag that puts the trailer in
    flag_byte: int  # the frame byte that holds the flag
    flag_mask: int  # the flag's bit in that byte
    fields: tuple[Field, ...]  # whole bytes each, bit_offset from the trailer's first bit
    doc: Optional[Text] = None
    loc: Optional[Loc] = None

    @property
    def size(self) -> int:
        return sum(f.bits for f in self.fields) // 8

    @property
    def signature(self) -> Optional[Field]:
        """The field that carries a keyed hash, if one does."""
        return next((f for f in self.fields if f.signature), None)


@dataclass(frozen=True)
class Framing:
    kind: str  # bits | bytes | text
    byte_order: str = "big"
    bit_order: str = "msb_first"  # msb_first | lsb_first (bytes framing)

    @property
    def wire_order(self) -> str:
        """The byte order of the frame read as one bit stream: big-endian when bits
        count most significant first, little-endian when least significant first."""
        return "little" if self.bit_order == "lsb_first" else "big"
    word_bits: Optional[int] = None
    max_bits: Optional[int] = None
    text_form: Optional[TextForm] = None
    envelope: tuple[Field, ...] = ()  # bytes framing: layout with a payload item
    encoding: Optional[str] = None  # bytes framing: slip | cobs | hdlc byte stuffing around each frame
    # hdlc: bit n set escapes control character n (0x00-0x1F) too, and decoders drop it
    # where it comes unescaped (RFC 1662's async control character map)
    accm: int = 0
    stuffing: Optional[PatternStuffing] = None  # bytes framing: a byte inserted after a pattern, in a span
    prefix_separator: str = ":"
    separator: str = ","
    terminator: str = ";"
    ignore_between: str = ""
    trim: bool = False
    float_format: str = "shortest"
    keep_empty: bool = False  # text: absent values at the end keep their empty places (NMEA)
    keep_spelling: bool = False  # text: decoded numbers keep the text they were read from (each message may say otherwise)
    start: str = ""  # text: a marker every line starts with, before the prefix (NMEA's `$`)
    line_checksum: Optional[LineChecksum] = None  # text: `<suffix><hh>` before the terminator
    line_max: int = 0  # text: the longest line a stream reader holds (resolver/line_bound.py)
    truncate: Optional[str] = None  # bytes: "trailing_zeros", senders drop the payload's trailing zeros
    trailer: Optional[Trailer] = None  # bytes: fields after the frame that a flag puts in
    can: Optional[str] = None  # "classic" or "fd": a CAN framing, the bytes framing of resolver/can.py


@dataclass(frozen=True)
class SequenceItem:
    name: str
    loc: Loc
    message: Optional[str] = None
    count: Optional[str] = None  # "item.field" of an earlier item
    repeat: bool = False
    items: tuple["SequenceItem", ...] = ()
    doc: Optional[Text] = None

    @property
    def may_take_nothing(self) -> bool:
        """Whether the item can match no message: a repeat takes zero or more, a
        count may be zero, a group may hold only such items."""
        if self.repeat or self.count is not None:
            return True
        return bool(self.items) and all(c.may_take_nothing for c in self.items)


@dataclass(frozen=True)
class SequenceRule:
    id: Optional[str]
    kind: str  # consecutive | equal | member | unique
    path: str
    loc: Loc
    start: Optional[int] = None
    to: Optional[str] = None
    of: Optional[str] = None
    key: tuple[str, ...] = ()
    message: Optional[Text] = None


@dataclass(frozen=True)
class Sequence:
    name: str
    loc: Loc
    doc: Optional[Text]
    items: tuple[SequenceItem, ...]
    rules: tuple[SequenceRule, ...]
    examples: tuple[Example, ...]


@dataclass(frozen=True)
class Transition:
    to: str
    guard: tuple[Condition, ...]
    actions: tuple[str, ...]


@dataclass(frozen=True)
class Handler:
    event: str
    kind: str  # ignore | error | transitions
    transitions: tuple[Transition, ...] = ()


@dataclass(frozen=True)
class State:
    name: str
    doc: Optional[Text]
    handlers: tuple[Handler, ...]


@dataclass(frozen=True)
class Variable:
    name: str
    bits: int
    initial: int


@dataclass(frozen=True)
class Event:
    name: str
    message: Optional[str]  # receive events: the message a packet must decode as
    timer: bool
    doc: Optional[Text]
    request: Optional[str] = None  # application requests: the message whose fields `args` name
    args: tuple[str, ...] = ()


@dataclass(frozen=True)
class Source:
    """Where an action takes a value: var, param, packet (field), request (arg),
    result (of execute) or const."""

    kind: str
    name: Optional[str] = None
    value: Optional[int] = None


@dataclass(frozen=True)
class Action:
    """A named step of a machine (set, flip, increment, keep, transmit, start_timer,
    stop_timer, deliver, execute, fail) on `target`: a variable, message, parameter,
    packet field or failure reason."""

    name: str
    kind: str
    target: Optional[str]
    value: Optional[Source] = None
    fields: tuple[tuple[str, Source], ...] = ()
    doc: Optional[Text] = None


@dataclass(frozen=True)
class Machine:
    name: str
    loc: Loc
    role: Optional[str]
    doc: Optional[Text]
    parameters: tuple[str, ...]
    variables: tuple[Variable, ...]
    events: tuple[Event, ...]
    initial: str
    final: tuple[str, ...]
    states: tuple[State, ...]
    actions: tuple[Action, ...] = ()

    def action(self, name: str) -> Action:
        return next(a for a in self.actions if a.name == name)

    def event(self, name: str) -> Event:
        return next(e for e in self.events if e.name == name)


@dataclass(frozen=True)
class DeliveryNotes:
    """The notes that state the delivery guarantee and each of its limits."""

    guarantee: str
    retry_limit: str
    restart: str


@dataclass(frozen=True)
class Delivery:
    """A sender machine that sends each application request and resends it until
    answered, and a receiver machine that executes it once: what the lossy-link
    simulator drives and the docs' delivery section describes. Names refer to
    the protocol's machines, parameters and notes; the resolver checks them."""

    sender: str  # machine
    receiver: str  # machine
    address: str  # parameter both machines take: a device's own address
    timeout: str  # sender parameter: ticks before a resend
    retry_limit: str  # sender parameter: resends before failure, 0 = no limit
    request: str  # the sender's one application request event
    address_arg: str  # its argument that addresses the receiver
    data_arg: str  # its argument that carries the data the receiver executes
    addresses: tuple[int, ...]  # the simulator's device addresses: a sender's, then receivers' (1 to 4)
    notes: DeliveryNotes
    loc: Loc


@dataclass(frozen=True)
class Protocol:
    name: str
    file: str
    sha256: str
    title: Text
    version: Optional[str]
    source: str
    doc: Optional[Text]
    notes: tuple[Note, ...]
    history: tuple[HistoryEntry, ...]
    roles: tuple[Role, ...]
    directions: tuple[Direction, ...]
    transports: tuple[Transport, ...]
    parameters: tuple[Parameter, ...]
    enums: tuple[Enum, ...]
    flags: tuple[FlagSet, ...]
    framing: Framing
    messages: tuple[Message, ...]
    sequences: tuple[Sequence, ...] = ()
    machines: tuple[Machine, ...] = ()
    group_types: tuple[tuple[str, Field], ...] = field(default=())
    delivery: Optional[Delivery] = None
    streams: tuple[StreamExample, ...] = ()  # hand-worked stream cases

    def message(self, name: str) -> Message:
        for message in self.messages:
            if message.name == name:
                return message
        raise KeyError(name)

    def machine(self, name: str) -> Machine:
        for machine in self.machines:
            if machine.name == name:
                return machine
        raise KeyError(name)

    @property
    def dispatch_fields(self) -> tuple[str, ...]:
        names: list[str] = []
        for message in self.messages:
            for name, _ in message.dispatch_key:
                if name not in names:
                    names.append(name)
        return tuple(names)

    @property
    def self_identifying(self) -> bool:
        """Whether a decoder can tell which message a frame holds."""
        return all(m.dispatch_key for m in self.messages)
