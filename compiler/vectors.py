"""Conformance vectors: generated/vectors/<protocol>.json.

Valid frames with their decoded values and invalid frames with the error kind
the schema's codec reports, so that any other implementation (the generated C,
a hand-written firmware, a ground station in another language) can be checked
against the schema. The set holds the schema's hand-written examples, edge
values (every field at its minimum and maximum, every enum value, every flag)
and RANDOM_PER_MESSAGE random valid messages per message type, plus mutations
of them (bit flips, truncation, bad checksums, wrong length bytes, unknown ids).
Large messages get fewer cases, within FRAME_BUDGET bytes of frames each, so that
the file grows with the schema rather than with its square. A protocol of more
than FULL_MESSAGES messages shares RANDOM_PER_PROTOCOL random cases and
MUTATED_PER_PROTOCOL mutated frames among them (each message keeps at least
RANDOM_FLOOR random cases and MUTATED_FLOOR mutated frames, and gets a case per
edge with every field at it), so that the vectors cost per message about what
the other outputs do.
Random choices come from a generator seeded by the protocol name, so the file
is the same on every build. The format is documented in docs/vectors.md.
"""
from __future__ import annotations

import dataclasses
import enum
import math
import random
import shutil
import string
import struct
import tempfile
from functools import lru_cache, partial
from typing import Any, Callable, Optional, TextIO

from . import binary32, binary64, jsontext

from .model import Field, Message, Protocol
from . import vector_multiplex
from .respell import respelled, with_values
from .targets.wire import ENCODINGS, encoding_facts
from .vector_sequences import sequence_vectors
from .vector_text_streams import text_stream_vectors

FORMAT = "codeword-vectors/1"
RANDOM_PER_MESSAGE = 200
MUTATIONS_PER_MESSAGE = 24  # frames mutated, each several ways
# up to FULL_MESSAGES messages each get the numbers above; a larger protocol shares these
FULL_MESSAGES = 20
RANDOM_PER_PROTOCOL = FULL_MESSAGES * RANDOM_PER_MESSAGE
MUTATED_PER_PROTOCOL = FULL_MESSAGES * MUTATIONS_PER_MESSAGE
RANDOM_FLOOR = 8
MUTATED_FLOOR = 2
# a message of up to this many fields gets a case for each field at each edge (others random);
# a wider one gets one case per edge with every field there, so that cases grow with the fields
EDGES_ONE_BY_ONE = 32
# bytes of frames a message's random cases, its mutations and the streams each hold at most
FRAME_BUDGET = 1 << 20
STREAM_BYTE_BY_BYTE = 4096  # longer streams are fed in chunks (the C side still feeds bytes)
SPOOL_BYTES = 1 << 22  # invalid cases wait in memory up to this, then on disk


_SCALARS = frozenset({int, float, str, bool, type(None)})

# doubles where encoders go wrong: signed zeros, the smallest and largest subnormals,
# the smallest normal, the largest finite, and values with hand-checked bits
BINARY64_EDGES = (0.0, -0.0, 5e-324, -5e-324, 2.225073858507201e-308, 2.2250738585072014e-308,
                  binary64.LARGEST, -binary64.LARGEST, 1.0, -2.5, math.pi, 0.1)
NON_FINITE = (("NaN", math.nan), ("+inf", math.inf), ("-inf", -math.inf))



@lru_cache(maxsize=None)
def _kind(cls: type) -> tuple[str, tuple[str, ...]]:
    """How plain() treats an instance of cls (the checks in its order, made once
    per class: a failed attribute lookup on an enum class is slow)."""
    if hasattr(cls, "__dataclass_fields__"):
        return "dataclass", tuple(f.name for f in dataclasses.fields(cls) if f.compare)  # values, not kept text
    if issubclass(cls, enum.IntFlag):
        return "flags", ()
    if issubclass(cls, enum.Enum):
        return "enum", ()
    if issubclass(cls, (bytes, bytearray)):
        return "bytes", ()
    return "other", ()


def plain(value: Any) -> Any:
    """A decoded Python value as JSON data (enum names, flag name lists, hex bytes)."""
    cls = type(value)
    if cls in _SCALARS:  # most values
        return value
    if isinstance(value, type):  # a class: only a dataclass one is taken apart
        if dataclasses.is_dataclass(value):
            return {f.name: plain(getattr(value, f.name)) for f in dataclasses.fields(value) if f.compare}
        return value
    if cls is list:  # an array
        return [plain(x) for x in value]
    kind, names = _kind(cls)
    if kind == "dataclass":
        return {name: plain(getattr(value, name)) for name in names}
    if kind == "flags":
        return [m.name for m in cls if m in value]
    if kind == "enum":
        return value.name
    if kind == "bytes":
        return value.hex()
    return value


def read_as_absent(f) -> Any:
    """The value a bytes frame's extension field reads as when the frame ends before it:
    zero, zero bytes, or an array of them."""
    one = "00" * (f.length or 0) if f.kind == "bytes" else 0.0 if f.kind == "float" else 0
    return [one] * f.count if f.count is not None else one


def older_values(m: Message) -> int:
    """The values of a text line that an older writer, which knows no extension field, writes."""
    body = [f for f in m.layout if not f.prefix]
    return next(i for i, f in enumerate(body) if f.extension)


def cases_per_message(messages: int) -> tuple[int, int]:
    """(random cases, mutated frames) of each message of a protocol with this many."""
    n = max(1, messages)
    return (min(RANDOM_PER_MESSAGE, max(RANDOM_FLOOR, RANDOM_PER_PROTOCOL // n)),
            min(MUTATIONS_PER_MESSAGE, max(MUTATED_FLOOR, MUTATED_PER_PROTOCOL // n)))



def inner_ends(f: Field, edge: str, fmt: Any) -> tuple[float, float, Any]:
    """The field's range as the values of a float format (binary32 or binary64) nearest
    inside it, and the value an edge case takes (None for a random one)."""
    lo, hi = f.range or (-fmt.LARGEST, fmt.LARGEST)
    lo, hi = fmt.at_least(lo), fmt.at_most(hi)
    return lo, hi, {"min": lo, "max": hi, "zero": max(lo, min(hi, 0.0))}.get(edge)

class Generator:
    def __init__(self, p: Protocol, module: Any):
        self.p = p
        self.mod = module
        self.rng = random.Random(f"codeword:{p.name}")
        self.text = p.framing.kind == "text"
        # asked for every frame: looked up once (both walk every message)
        self.self_identifying = p.self_identifying
        self.messages = {m.name: m for m in p.messages}
        # per message: the fields values() fills, each with its drawer
        self.members: dict[str, list[tuple[Field, Callable[[str], Any]]]] = {}
        self.alphabets: dict[tuple[bool, bool], str] = {}
        self.choices: dict[tuple, list] = {}  # per enum and allowed values
        self.randoms, self.mutated = cases_per_message(len(p.messages))
        self.shared = len(p.messages) > FULL_MESSAGES  # a case per edge with every field there
        self.plain_classes: dict[str, Any] = {}  # per message: its class, when values need no conversion
        self.bounds: dict[int, tuple] = {}  # per integer field: (the field, its bounds)
        self.trailer = p.framing.trailer
        signature = self.trailer.signature if self.trailer else None
        # the key the vectors' signed frames are signed with, written into the file for every decoder
        self.key = bytes(range(signature.signature.key_length)) if signature else None

    # -- random values from the model ----------------------------------------------------
    def value(self, f: Field, edge: str = "") -> Any:
        rng = self.rng
        if f.count is not None:  # an array: each element at the edge
            element = f.element
            n = f.count
            if f.varies:  # a counted array: none at min, one at zero, the most at max
                n = {"min": 0, "zero": 1, "max": f.count}.get(edge, rng.randint(0, f.count))
                if f.count_unit:  # whole units of the count: a multiple of the elements one holds
                    size = element.bits // 8
                    step = f.count_unit // math.gcd(size, f.count_unit)
                    n = max(n - n % step, step if n else 0) if step <= f.count else 0
            return [self.value(element, edge) for _ in range(n)]
        if f.kind == "group":
            return {s.name: self.value(s) for s in f.fields if s.is_member}
        if f.optional and rng.random() < 0.3 and not edge:
            return None
        if f.kind == "bool":
            return rng.random() < 0.5 if not edge else edge == "max"
        if f.enum is not None:
            key = (f.enum.name, f.values)  # not id(f): an array's element is a new Field each time
            members = self.choices.get(key)
            if members is None:
                members = self.choices[key] = [m for m in f.enum.members
                                               if not f.values or m.value in f.values or m.name in f.values]
            if f.enum.open and not f.values and (edge or rng.random() < 0.4):  # any value of its width
                lo, hi = f.raw_range
                number = {"min": lo, "max": hi}.get(edge, rng.randint(lo, hi))
                return next((m.name for m in members if m.value == number), number)
            return rng.choice(members).name
        if f.flags is not None:
            bits = [b.name for b in f.flags.members]
            if f.exactly_one:
                return [rng.choice(bits)]
            return [b for b in bits if rng.random() < 0.5]
        if f.one_hot:
            lo, hi = f.range or (0, f.bits - 1)
            if not edge and rng.random() < 0.2:
                return None
            return {"min": lo, "max": hi}.get(edge, rng.randint(int(lo), int(hi)))
        if f.kind in ("uint", "int"):
            return self.integer(f, edge)
        if f.kind == "float":
            return self.real(f, edge)
        if f.kind == "char":
            return rng.choice(self.alphabet(f))
        if f.prefix:  # uppercase letters of its length (NMEA's talker), or one it lists
            return rng.choice(f.values) if f.values else "".join(rng.choice(string.ascii_uppercase) for _ in range(f.length))
        if f.kind == "str":
            n = {"min": 0, "max": f.max_length}.get(edge, rng.randint(0, f.max_length or 16))
            chars = self.alphabet(f)
            text = "".join(rng.choice(chars) for _ in range(n))
            return text.strip() if self.p.framing.trim else text
        if f.kind == "bytes" and f.varies:  # none at min, one at zero, the most at max
            return rng.randbytes({"min": 0, "zero": 1, "max": f.length}.get(edge, rng.randint(0, f.length))).hex()
        if f.kind == "bytes":
            return rng.randbytes(f.length).hex()
        raise ValueError(f"no generator for {f.kind}")

    def alphabet(self, f: Field) -> str:
        key = (bool(f.to_end), f.kind == "char")  # all the field decides (asked per character)
        chars = self.alphabets.get(key)
        if chars is None:
            chars = self.alphabets[key] = self._alphabet(f)
        return chars

    def _alphabet(self, f: Field) -> str:
        fr = self.p.framing
        banned = set(fr.terminator) | (set() if f.to_end else set(fr.separator))
        chars = [c for c in string.printable if " " <= c <= "~" and c not in banned]
        if f.kind == "char" and fr.trim:
            chars = [c for c in chars if c != " "]
        return "".join(chars)

    def integer(self, f: Field, edge: str) -> Any:
        got = self.bounds.get(id(f))
        if got is None or got[0] is not f:  # the field is kept, so its id is not reused
            got = self.bounds[id(f)] = (f, *self.integer_bounds(f))
        _, lo, hi, scale, offset = got
        if scale is not None:  # a random raw value is drawn even at an edge
            raw = self.rng.randint(int(lo), int(hi))
            raw = lo if edge == "min" else hi if edge == "max" else raw
            if f.decimals:  # the value its text shows, as the decoder reads it (999999 at 1 decimal: 99999.9)
                return raw / 10 ** f.decimals + offset
            return raw * scale + offset
        if edge:
            return lo if edge == "min" else hi if edge == "max" else max(lo, min(hi, 0))
        if f.values:
            return self.rng.choice(list(f.values))
        return self.rng.randint(lo, hi)

    @staticmethod
    def integer_bounds(f: Field) -> tuple:
        """(lo, hi, scale, offset): the raw bounds of a scaled field, else the value's."""
        if f.scale is not None:  # the width alone limits the value, or the range (exactly: its ends
            raw_lo, raw_hi = f.range_bounds or f.raw_range  # in floats may cross, 1.1..1.2 at 0.1)
            return raw_lo, raw_hi, f.scale, f.offset or 0
        if f.range is not None:
            return (*f.range_bounds, None, 0)
        lo, hi = f.raw_range
        return lo + int(f.offset or 0), hi + int(f.offset or 0), None, 0

    def real(self, f: Field, edge: str) -> float:
        rng = self.rng
        if self.text:
            shape = rng.random()
            if edge == "zero" or shape < 0.1:
                return 0.0
            if shape < 0.2:  # text floats hold 15 significant digits, magnitudes from 1e-307
                return rng.choice([1e-7, -2.5e-5, 1e16, 3.25e22, 12345678.9, 1e-4, 123456789.012345,
                                   1e-307, -1.79769313486231e308])
            if shape < 0.6:
                return round(rng.uniform(-1000, 1000), rng.randint(0, 4))
            return float(f"{rng.uniform(-1e6, 1e6):.{rng.randint(1, 15)}g}")
        if not f.finite:  # its ends are the infinities, and a fifth of the random draws are NaN
            if edge in ("min", "max"):
                return -math.inf if edge == "min" else math.inf
            if not edge and rng.random() < 0.2:  # any NaN, sign and payload too: sent as the quiet NaN
                return struct.unpack("<d", struct.pack("<Q", 0x7FF0000000000000 | rng.getrandbits(52) | 1
                                                       | rng.getrandbits(1) << 63))[0]
        if f.bits == 64:
            return self.binary64(f, edge)
        return self.binary32(f, edge)

    def binary32(self, f: Field, edge: str) -> float:
        """A binary f32 value inside the field's range: its ends as floats, zero, any bit
        pattern that falls inside, or a float drawn across the range."""
        rng = self.rng
        lo, hi, pick = inner_ends(f, edge, binary32)
        if pick is not None:
            return pick
        for _ in range(8):
            x = struct.unpack("<f", struct.pack("<I", rng.getrandbits(32)))[0]
            if rng.random() < 0.5:
                x = struct.unpack("<f", struct.pack("<f", rng.uniform(max(lo, -1e4), min(hi, 1e4))
                                                     if lo <= 1e4 and hi >= -1e4 else rng.uniform(lo, hi)))[0]
            if math.isfinite(x) and lo <= x <= hi:
                return x
        return rng.choice((lo, hi))  # a narrow range far from the draws: one of its ends

    def binary64(self, f: Field, edge: str) -> float:
        """A binary f64 value: the range's ends (or the largest finite doubles), zero, the
        doubles at the edges of the format (signed zeros, subnormals), any bit pattern."""
        rng = self.rng
        lo, hi, pick = inner_ends(f, edge, binary64)
        if pick is not None:
            return pick
        while True:
            shape = rng.random()
            if shape < 0.3:
                x = rng.choice(BINARY64_EDGES)
            elif shape < 0.6:
                x = struct.unpack(">d", rng.getrandbits(64).to_bytes(8, "big"))[0]
            else:
                x = rng.uniform(max(lo, -1e6), min(hi, 1e6)) if lo <= 1e6 and hi >= -1e6 else rng.choice((lo, hi))
            if math.isfinite(x) and lo <= x <= hi:
                return x

    def values(self, m: Message, edge: str = "", focus: str = "", forced: Optional[dict] = None) -> dict:
        members = self.members.get(m.name)
        if members is None:
            members = self.members[m.name] = [(f, self.drawer(f)) for f in m.layout if f.is_member]
        out = {}
        for f, draw in members:
            out[f.name] = draw(edge if (not focus or focus == f.name) else "")
        for f, _ in members:
            if f.present_if:
                self.choose_presence(m, f, out)
        if self.trailer:
            self.trailer_values(m, out)
        if m.payload_bytes and any(f.multiplexed_by for f, _ in members):
            kept = {f.name for f, _ in members if edge and (not focus or focus == f.name)}
            vector_multiplex.settle(m, out, self.rng, forced or {}, kept)
        return out

    def trailer_values(self, m: Message, out: dict) -> None:
        """The trailer's fields where the drawn flag puts the trailer in (about half the
        frames: the flag is set or cleared at random), None elsewhere; a signature is
        left None, for the key to compute."""
        cond = self.trailer.presence
        control = next(x for x in m.layout if x.name == cond.field)
        names = [x for x in out[control.name] if x != cond.has]
        out[control.name] = sorted(names + [cond.has]) if self.rng.random() < 0.5 else names
        present = (self.raw_of(control, out[control.name]) & cond.mask) in cond.values
        for f in self.trailer.fields:
            if not present or f.signature:
                out[f.name] = None
            elif f.kind == "bytes":
                out[f.name] = bytes(self.rng.getrandbits(8) for _ in range(f.length))
            else:
                out[f.name] = self.rng.getrandbits(f.bits)

    def signs(self, values: dict) -> bool:
        """Whether the key signs a frame of these values: its trailer is in, its signature to compute."""
        sig = self.trailer.signature if self.trailer else None
        return sig is not None and values.get(sig.name) is None and any(
            values.get(f.name) is not None for f in self.trailer.fields)

    def drawer(self, f: Field) -> Callable[[str], Any]:
        """How values() draws a field at an edge (or at random for ""): a plain integer
        directly, drawing as value() does, anything else through value()."""
        if f.kind not in ("uint", "int") or f.count is not None or f.enum is not None or f.flags is not None \
                or f.one_hot or f.optional or f.scale is not None or f.values:
            return partial(self.value, f)
        lo, hi, _, _ = self.integer_bounds(f)
        zero, randrange = max(lo, min(hi, 0)), self.rng.randrange

        def draw(edge: str) -> int:
            if not edge:
                return randrange(lo, hi + 1)  # what randint(lo, hi) draws
            return lo if edge == "min" else hi if edge == "max" else zero
        return draw

    def choose_presence(self, m: Message, f: Field, out: dict) -> None:
        """Make a conditional field present or absent at random, by setting its control field;
        a field its control leaves out holds None."""
        cond = f.present_if
        control = next(x for x in m.layout if x.name == cond.field)
        if self.rng.random() < 0.5:  # present: the control takes a value that says so
            if cond.has is not None:
                out[control.name] = sorted(set(out[control.name]) | {cond.has})
            else:
                out[control.name] = self.rng.choice(cond.equals)
        elif cond.has is not None:
            out[control.name] = [x for x in out[control.name] if x != cond.has]
        if (self.raw_of(control, out[control.name]) & cond.mask) not in cond.values:
            out[f.name] = None

    @staticmethod
    def raw_of(f: Field, value: Any) -> int:
        """The raw integer of a control field's value: an enum member's, the bits of flags."""
        if f.flags is not None:
            return sum(b.mask for b in f.flags.members if b.name in value)
        if f.enum is not None:
            return next(e.value for e in f.enum.members if value in (e.name, e.value))
        return int(value)

    # -- vectors --------------------------------------------------------------------------------
    def encode(self, m: Message, values: dict):
        cls = self.plain_classes.get(m.name, False)
        if cls is False:
            cls = self.plain_classes[m.name] = self._plain_class(m)
        obj = cls(**values) if cls is not None else self.mod.from_dict(m.name, values)
        if self.key is not None and self.signs(values):
            return obj, self.mod.encode(obj, key=self.key)
        return obj, self.mod.encode(obj)

    def _plain_class(self, m: Message):
        """The message's class when every member is a plain number, which from_dict
        would pass to the constructor unchanged; None otherwise."""
        plain_number = all(f.kind in ("uint", "int", "bool", "float") and f.count is None and f.enum is None
                           and f.flags is None and not f.one_hot for f in m.layout if f.is_member)
        return self.mod.MESSAGES[m.name] if plain_number else None

    def wire(self, data) -> dict:
        return {"text": data} if isinstance(data, str) else {"hex": data.hex()}

    def valid_case(self, name: str, m: Message, obj, data, decode_only_input=None, kept=None) -> dict:
        case = {"name": name, "message": m.name}
        if m.direction:
            case["direction"] = m.direction
        case.update(self.wire(decode_only_input if decode_only_input is not None else data))
        if decode_only_input is not None:
            case["canonical"] = self.wire(data)[("text" if self.text else "hex")]
        if kept is not None:
            case["kept"] = kept
        case["values"] = plain(obj)
        if self.p.framing.kind == "bits" and m.size <= 8:  # words of up to 64 bits
            encode_word = getattr(self.mod, "encode_word", None)
            case["word"] = encode_word(obj) if encode_word else int.from_bytes(data, "big")
        if self.p.framing.text_form:
            case["text_form"] = self.mod.encode_text(obj)
        return case

    def rewritten(self, obj) -> tuple[Any, Any]:
        """What encoding a decoded message's values writes, and what the message itself
        writes when it keeps its numbers' received text and that differs (else None)."""
        if getattr(obj, "_spelling", None) is None and getattr(obj, "_places", None) is None:
            return self.mod.encode(obj), None
        canonical, kept = self.mod.encode(dataclasses.replace(obj)), self.mod.encode(obj)
        return canonical, kept if kept != canonical else None

    def decode(self, m: Message, data):
        if self.self_identifying:
            return self.mod.decode(data, m.direction) if m.direction else self.mod.decode(data)
        return self.mod.MESSAGES[m.name].decode(data)

    def write(self, out: TextIO) -> None:
        """The vector file, written message by message: only the frames the
        streams are cut from (and, for sequences, the valid values) are kept."""
        p = self.p
        head = {"format": FORMAT, "protocol": p.name, "schema_sha256": p.sha256, "framing": p.framing.kind}
        if self.key is not None:  # cases with "verify" are decoded (and encoded) with it
            head["signing_key"] = self.key.hex()
        out.write("{\n" + "".join(f" {jsontext.dumps(k)}: {jsontext.dumps(v, 1)},\n" for k, v in head.items()))
        frames: list[bytes] = []
        lines: list[str] = []
        pool: list[dict] = []
        # every valid case comes before the first invalid one: those wait in `later`
        with tempfile.SpooledTemporaryFile(SPOOL_BYTES, "w+", encoding="utf-8", newline="") as later:
            out.write(' "valid": ')
            valid_list, invalid_list = jsontext.ListWriter(out, 1), jsontext.ListWriter(later, 1)
            for m in p.messages:
                valid, invalid = self.message_cases(m)
                for case in valid:
                    valid_list.item(case)
                    if "canonical" not in case:
                        if "hex" in case and p.framing.kind == "bytes":
                            frames.append(bytes.fromhex(case["hex"]))
                        if "text" in case and p.framing.kind == "text":
                            lines.append(case["text"])
                        if p.sequences:
                            pool.append({"message": case["message"], "values": case["values"]})
                for case in invalid:
                    invalid_list.item(case)
            valid_list.close()
            invalid_list.close()
            out.write(',\n "invalid": ')
            later.seek(0)
            shutil.copyfileobj(later, out)
        if p.framing.kind == "bytes":
            out.write(',\n "streams": ' + jsontext.dumps(self.streams(frames), 1))
        if p.framing.kind == "text":
            streams = text_stream_vectors(p, self.mod, random.Random(f"text streams {p.name}"), lines, plain)
            out.write(',\n "streams": ' + jsontext.dumps(streams, 1))
        if p.sequences:
            sequences = sequence_vectors(p, self.mod, self.rng, pool, plain)
            out.write(',\n "sequences": ' + jsontext.dumps(sequences, 1))
        out.write("\n}\n")

    def message_cases(self, m: Message) -> tuple[list[dict], list[dict]]:
        """The valid and the invalid cases of one message."""
        valid: list[dict] = []
        invalid: list[dict] = []
        for ex in m.examples:
            # binary protocols: the hex examples (text-form and word examples are
            # covered by every valid case's `text_form` and `word`)
            data = ex.text if self.text else ex.hex
            if data is None or ex.values is None and not ex.errors:
                continue
            if ex.errors:
                try:
                    self.decode(m, data)
                    raise ValueError(f"{ex.name}: error example decodes")
                except self.mod.DecodeError as exc:
                    case = {"name": ex.name, "message": m.name, **self.wire(data), "error": exc.rule}
                if m.direction:
                    case["direction"] = m.direction
                invalid.append(case)
                continue
            obj = self.decode(m, data)
            canonical, kept = self.rewritten(obj)
            valid.append(self.valid_case(ex.name, m, obj, canonical,
                                         data if canonical != data else None, kept))
        made: list[tuple[str, Any, Any]] = []
        members = [f for f in m.layout if f.is_member]
        size = max(1, m.size or 1)
        for edge in ("min", "max", "zero"):
            if len(members) > EDGES_ONE_BY_ONE or len(members) * size > FRAME_BUDGET or self.shared:
                made.append((f"every field {edge}", "edge", (edge, "")))
                continue
            for f in members:
                made.append((f"{f.name} {edge}", "edge", (edge, f.name)))
        for i in range(min(self.randoms, max(1, FRAME_BUDGET // size))):
            made.append((f"random {i}", "random", None))
        for choice in vector_multiplex.choices(m):  # every multiplexor value the schema names
            made.append((vector_multiplex.choice_name(choice), "multiplexed", ("", "", choice)))
        if any(f.extension for f in members):  # as an older sender writes it (truncated, if the framing is)
            made.append(("without its extension fields", "older", None))
        frames = []
        for name, kind, arg in made:
            for _attempt in range(50):
                values = self.values(m, *arg) if arg else self.values(m)
                if kind == "older":  # text: absent; bytes: read as 0
                    values.update((f.name, None if self.text else read_as_absent(f)) for f in members if f.extension)
                try:
                    obj, data = self.encode(m, values)
                except self.mod.EncodeError:
                    continue
                if kind == "older" and self.text:  # the line as an older writer ends it, read as the whole one
                    older = with_values(self.p.framing, m, data, older_values(m))
                    obj = self.decode(m, older)
                    canonical, kept = self.rewritten(obj)
                    valid.append(self.valid_case(f"{m.name} {name}", m, obj, canonical,
                                                 older if canonical != older else None, kept))
                    break
                decoded = self.decode(m, data)
                valid.append(self.valid_case(f"{m.name} {name}", m, decoded, data))
                if self.key is not None and self.signs(values):
                    valid[-1]["verify"] = True
                    if not any(c.get("verify") for c in invalid):  # one message's frame tells
                        invalid += self.unverified(m, data)
                frames.append(data)
                break
        if m.direction and frames:
            invalid += self.undirected(m, frames[0])
        if self.p.framing.stuffing and frames:
            stuffed, damaged = self.stuffed_cases(m, frames[0])
            valid += stuffed
            invalid += damaged
        for i, data in enumerate(frames[:min(self.mutated, max(1, FRAME_BUDGET // (8 * size)))]):
            for label, bad in self.mutations(m, data) + (self.f64_outside(m, data) if i == 0 else []):
                name = f"{m.name} {label} of {i}"
                try:
                    obj = self.decode(m, bad)
                except self.mod.DecodeError as exc:
                    case = {"name": name, "message": m.name, **self.wire(bad), "error": exc.rule}
                    if m.direction:
                        case["direction"] = m.direction
                    invalid.append(case)
                    continue
                canonical, kept = self.rewritten(obj)
                valid.append(self.valid_case(name, self.messages[type(obj).NAME], obj, canonical,
                                             bad if canonical != bad else None, kept))
        return valid, invalid

    def undirected(self, m: Message, data) -> list[dict]:
        """The frame decoded without its direction, when another direction's message has its
        id (or prefix) and size: refused, as the decoder cannot tell which one it holds."""
        if not any(o.direction not in (None, m.direction) and any(i in o.ids for i in m.ids) for o in self.p.messages):
            return []
        try:
            obj = self.mod.decode(data)
        except self.mod.DecodeError as exc:
            return [{"name": f"{m.name} without its direction", "message": m.name, **self.wire(data),
                     "error": exc.rule}]
        if type(obj).NAME != m.name:
            raise ValueError(f"{m.name}: a frame decoded without its direction gives {type(obj).NAME}")
        return []

    def unverified(self, m: Message, data: bytes) -> list[dict]:
        """A signed frame with a byte of its trailer changed, and the frame without its trailer
        (flag cleared, checksum made again): decoded with the key, a signature error and an
        unsigned one. Each decodes without the key, so only a verifying decoder tells."""
        cases = []
        body = len(data) - self.trailer.size
        tampered = data[:body] + bytes([data[body] ^ 0x01]) + data[body + 1:]
        obj = self.decode(m, data)
        control = self.trailer.presence.field
        setattr(obj, control, getattr(obj, control) & ~self.trailer.presence.mask)
        for f in self.trailer.fields:
            setattr(obj, f.name, None)
        for name, wire in (("trailer changed", tampered), ("unsigned", self.mod.encode(obj))):
            try:
                self.mod.decode(wire, key=self.key)
                raise ValueError(f"{m.name}: the {name} frame verifies")
            except self.mod.DecodeError as exc:
                case = {"name": f"{m.name} {name}", "message": m.name, **self.wire(wire), "error": exc.rule,
                        "verify": True}
            if m.direction:
                case["direction"] = m.direction
            cases.append(case)
        return cases

    def f64_outside(self, m: Message, data) -> list[tuple[str, Any]]:
        """The frame with each binary f64 field set to NaN, to each infinity and to the
        doubles just outside its range, which both codecs refuse (NaN and infinities
        as in f32 fields)."""
        out: list[tuple[str, Any]] = []
        if self.text:
            return out
        for leaf in m.wire.leaves:
            f = leaf.field
            if f.kind != "float" or f.bits != 64 or not f.is_member or not f.finite:
                continue
            outside = list(NON_FINITE)
            if f.range is not None:
                below = math.nextafter(binary64.at_least(f.range[0]), -math.inf)
                above = math.nextafter(binary64.at_most(f.range[1]), math.inf)
                outside += [(f"{x!r}", x) for x in (below, above) if math.isfinite(x)]
            order = "<" if (f.byte_order or self.p.framing.byte_order) == "little" else ">"
            start = leaf.pos // 8
            for label, value in outside:
                bad = data[:start] + struct.pack(order + "d", value) + data[start + 8:]
                out.append((f"{leaf.dotted} {label}", bad))
        return out

    def mutations(self, m: Message, data) -> list[tuple[str, Any]]:
        rng = self.rng
        out: list[tuple[str, Any]] = []
        if isinstance(data, str):
            pos = rng.randrange(len(data))
            out.append(("character change", data[:pos] + rng.choice("09a-.;,: x") + data[pos + 1:]))
            out.append(("no terminator", data[:-1]))
            out.append(("field dropped", data.replace(self.p.framing.separator, "", 1)))
            out.append(("field added", data[:-1] + self.p.framing.separator + "1" + data[-1]))
            # a receiver's spelling, drawn apart so that the other draws stay as they were
            other = respelled(self.p.framing, m, data, random.Random(f"respell {self.p.name} {data}"))
            if other is not None:
                out.append(("receiver spelling", other))
            return out
        b = bytearray(data)
        bit = rng.randrange(len(b) * 8)
        b[bit // 8] ^= 0x80 >> (bit % 8)
        out.append((f"bit {bit} flipped", bytes(b)))
        out.append(("truncated", data[:-1]))
        out.append(("extended", data + b"\x00"))
        if self.p.framing.kind == "bytes":
            b = bytearray(data)
            b[-1] ^= 0xFF
            out.append(("last byte changed", bytes(b)))
            if len(data) > 1:
                b = bytearray(data)
                b[1] = (b[1] + 1) & 0xFF
                out.append(("second byte changed", bytes(b)))
        if not self.p.framing.encoding:  # the frame's own bytes, not stuffed
            out += self.other_zero(m, data)
        encoding = self.p.framing.encoding
        if encoding:
            out += self.damaged_escapes(encoding, data)
        return [(label, bad) for label, bad in out if bad != data]

    @staticmethod
    def other_zero(m: Message, data: bytes) -> list[tuple[str, bytes]]:
        """An internet checksum that covers itself, sent as 0000, written as ffff: one's
        complement's other zero, which RFC 1071's receiver check accepts too."""
        out = []
        for leaf in m.wire.leaves:
            cs = leaf.field.checksum
            at = leaf.pos // 8
            if cs and cs.covers_self and data[at:at + 2] == b"\0\0" and not m.shortening:
                out.append((f"{leaf.dotted} as ffff", data[:at] + b"\xff\xff" + data[at + 2:]))
        return out

    def stuffed_cases(self, m: Message, data: bytes) -> tuple[list[dict], list[dict]]:
        """Frames of `m` whose stuffed bytes hold the pattern, so a byte is inserted: the
        pattern written over the first and the last place of a valid frame's stuffed bytes
        where the message's checks still hold; and the first such frame without its
        inserted byte, its length and checksums made to agree (an `escape` error), and
        with them left as they were."""
        st = self.p.framing.stuffing
        frame = self.mod.unstuff(data)
        end = len(frame) - st.tail - len(st.pattern)
        places = list(range(st.head, end + 1))
        valid: list[dict] = []
        found: list[bytes] = []
        for ends in (places, places[::-1]):
            for at in ends[:64]:
                wire = self.mod.stuff(frame[:at] + st.pattern + frame[at + len(st.pattern):])
                try:
                    obj = self.decode(m, wire)
                except self.mod.DecodeError:
                    continue
                if type(obj).NAME != m.name or self.mod.encode(obj) != wire:
                    continue  # the pattern read as another message, or as values written otherwise
                if wire not in found:
                    found.append(wire)
                    valid.append(self.valid_case(f"{m.name} pattern stuffed at byte {at}", m, obj, wire))
                break
        invalid: list[dict] = []
        if found:
            wire = found[0]
            cut = wire.index(st.pattern + bytes((st.insert,)), st.head) + len(st.pattern)
            left = bytearray(wire[:cut] + wire[cut + 1:])
            recounted = bytearray(left)
            self.mod._recount(recounted, -1)
            for label, bad in (("inserted byte left out", bytes(recounted)),
                               ("inserted byte left out, length and checksums as sent", bytes(left))):
                try:
                    self.decode(m, bad)
                except self.mod.DecodeError as exc:
                    case = {"name": f"{m.name} {label}", "message": m.name, **self.wire(bad), "error": exc.rule}
                    if m.direction:
                        case["direction"] = m.direction
                    invalid.append(case)
        return valid, invalid

    def damaged_escapes(self, encoding: str, data: bytes) -> list[tuple[str, bytes]]:
        """An encoded frame with a bad escape (or COBS code) and with a delimiter inside it."""
        facts = ENCODINGS[encoding]
        delimiter = bytes((facts["delimiter"],))
        middle = self.rng.randrange(1, len(data))
        out = [("delimiter inside", data[:middle] + delimiter + data[middle:])]
        if encoding == "cobs":
            if len(data) <= 0xFF:  # the first block claims every byte and the delimiter
                out.append(("COBS code past the end", bytes((len(data),)) + data[1:]))
            return out
        escape = bytes((facts["escape"],))
        out.append(("escape before the delimiter", data[:-1] + escape + delimiter))
        if encoding == "slip":  # only DC and DD may follow SLIP's escape
            out.append(("bad escape", data[:middle] + escape + b"\x41" + data[middle:]))
        return out

    def streams(self, frames: list[bytes]) -> list[dict]:
        """Byte streams mixing valid frames (canonical ones, in vector order), garbage
        and damaged frames, with the events the Python StreamDecoder gives when fed
        one byte at a time (in chunks, for long streams: the events are the same)."""
        rng = self.rng
        # the schema's hand-worked streams first: their events are checked by the build
        out: list[dict] = [self.stream_events(f"worked by hand: {s.name}", s.data) for s in self.p.streams]
        if not frames:  # every valid case has another canonical spelling: no frame to stream
            return out
        largest = max(map(len, frames))
        for n in range(max(1, min(8, FRAME_BUDGET // (16 * largest)))):
            parts = []
            for _ in range(rng.randint(3, 8)):
                frame = rng.choice(frames)
                shape = rng.random()
                if shape < 0.2:
                    parts.append(rng.randbytes(rng.randint(1, 5)))
                elif shape < 0.35 and len(frame) > 1:
                    b = bytearray(frame)
                    b[rng.randrange(1, len(b))] ^= 1 << rng.randrange(8)
                    parts.append(bytes(b))
                elif shape < 0.45 and len(frame) > 1:
                    parts.append(frame[:rng.randint(1, len(frame) - 1)])
                parts.append(frame)
            stream = b"".join(parts)
            out.append(self.stream_events(f"stream {n}", stream))
        if self.p.framing.encoding and frames:
            out.extend(self.short_garbage(frames))
            out.extend(self.mapped_noise(frames))
        return out

    def mapped_noise(self, frames: list[bytes]) -> list[dict]:
        """HDLC with a control character map: frames with mapped characters added inside
        them, and stretches of mapped characters alone between them (an XOFF while idle),
        which decoders drop: the frames decode, and nothing else is reported."""
        mapped = encoding_facts(self.p)["mapped"]
        if not mapped:
            return []
        rng, parts = self.rng, []
        for frame in frames[:4]:
            parts.append(bytes(rng.choices(mapped, k=rng.randint(1, 3))) + frame[-1:])
            for b in frame[:-1]:
                parts.append(bytes((b,)) + (bytes((rng.choice(mapped),)) if rng.random() < 0.2 else b""))
            parts.append(frame[-1:])
        return [self.stream_events("mapped control characters among frames", b"".join(parts))]

    def short_garbage(self, frames: list[bytes]) -> list[dict]:
        """A stream of frames with runs of short stretches between delimiters before each,
        none of them a frame: one error per run, not per stretch."""
        delimiter = encoding_facts(self.p)["delimiter"]
        others = [b for b in range(1, 256) if b != delimiter]
        run = b"".join(bytes((self.rng.choice(others), delimiter)) for _ in range(self.rng.randint(2, 9)))
        for garbage in (run, bytes((others[0], delimiter))):
            if all(self.refused(bytes((b, delimiter))) for b in garbage[::2]):
                stream = b"".join(garbage + frame for frame in frames[:4]) + garbage
                return [self.stream_events("runs of short garbage", stream)]
        return []

    def refused(self, wire: bytes) -> bool:
        try:
            self.mod.decode(wire)
        except self.mod.CodecError:
            return True
        return False

    def stream_events(self, name: str, stream: bytes) -> dict:
        """The stream with the events the Python StreamDecoder gives when fed one byte
        at a time (in chunks, for long streams: the events are the same)."""
        decoder = self.mod.StreamDecoder()
        events = []
        step = 1 if len(stream) <= STREAM_BYTE_BY_BYTE else 997
        for at in range(0, len(stream), step):
            events += self.events(decoder.feed(stream[at:at + step]))
        return {"name": name, "hex": stream.hex(), "events": events + self.events(decoder.finish())}

    def events(self, items: list) -> list[dict]:
        return [{"error": item.rule} if isinstance(item, self.mod.DecodeError) else
                {"message": type(item).NAME, "values": plain(item)} for item in items]


def write_vectors(p: Protocol, module: Any, out: TextIO) -> None:
    Generator(p, module).write(out)

