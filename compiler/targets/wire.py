"""Wire facts every backend needs, computed from the model: how a decoder finds
the message in a frame, and how a stream decoder finds frames."""
from __future__ import annotations

from typing import Optional

from ..model import Framing, Gap, Leaf, Message, Protocol, shift_in
from ..resolver.layout import key_read, leaves_of


def text_form_head(p: Protocol) -> list[tuple[int, int]]:
    """How a text-form line's leading values give the dispatch fields' bits: for each
    value, (bits taken, low bits dropped), until the last dispatch bit (the resolver
    makes these widths the same in every message)."""
    end = max((pos + bits for e in dispatch_facts(p).get("entries", ()) for pos, bits, _ in e["tests"]), default=0)
    out, pos = [], 0
    for leaf in p.messages[0].wire.leaves:
        if pos >= end:
            break
        take = min(leaf.field.bits, end - pos)
        out.append((take, leaf.field.bits - take))
        pos += leaf.field.bits
    return out


def talker_clash(shared: list[dict]) -> Optional[tuple[str, ...]]:
    """Of messages in several directions whose prefixes have one shape, the talker values more
    than one of them takes (a message without listed values takes any): None if any value is
    taken by two, else those values (none: the values alone tell the messages apart)."""
    open_ended = sum(1 for t in shared if not t["values"])
    if open_ended > 1:
        return None
    taken: dict[str, int] = {}
    for t in shared:
        for v in t["values"]:
            taken[v] = taken.get(v, 0) + 1
    return tuple(v for v, n in taken.items() if n + open_ended > 1)


def dispatch_facts(p: Protocol) -> dict:
    """How module-level decode finds the message a frame holds."""
    fr = p.framing
    if fr.kind == "bytes" and len(p.messages) == 1 and not p.messages[0].dispatch_key:
        return {"kind": "single", "name": p.messages[0].name}  # every frame holds the one message
    if not p.self_identifying:
        return {"kind": "none"}
    if fr.kind == "text":
        # a message with a prefix field (NMEA's talker) is found by the id at the end of
        # the prefix, after the exact prefixes, in the schema's order
        # a prefix field's values (when it has them) tell apart messages whose prefixes have one shape
        talked = [{"held": m.prefix_field.length, "id": m.ids[0], "name": m.name, "direction": m.direction,
                   "length": m.prefix_field.length + len(m.ids[0]), "shown": "?" * m.prefix_field.length + m.ids[0],
                   "values": tuple(m.prefix_field.values or ())}
                  for m in p.messages if m.prefix_field]
        prefixes = [(m.ids[0], m.name, m.direction) for m in p.messages if not m.prefix_field]
        by_prefix: dict[str, list[tuple[Optional[str], str]]] = {}
        for prefix, name, direction in prefixes:  # a prefix may be used once in each direction
            by_prefix.setdefault(prefix, []).append((direction, name))
        by_talk: dict[tuple[int, str], list[dict]] = {}
        for t in talked:
            by_talk.setdefault((t["held"], t["id"]), []).append(t)
        return {"kind": "text", "prefixes": prefixes, "by_prefix": list(by_prefix.items()),
                "shared": [(prefix, entries[0][1]) for prefix, entries in by_prefix.items() if len(entries) > 1],
                "shared_talked": [dict(ts[0], clash=clash) for ts in by_talk.values()
                                  if len(ts) > 1 and (clash := talker_clash(ts)) != ()],
                "talked": talked, "directed": any(m.direction for m in p.messages)}
    if fr.kind == "bits":
        entries = []
        for m in p.messages:
            tests = []
            for leaf in m.wire.leaves:
                f = leaf.field
                if f.dispatch:  # compared with the raw bits: a negative constant as its two's complement
                    tests.append((leaf.pos, f.bits, f.const & ((1 << f.bits) - 1)))
            entries.append({"name": m.name, "size": m.size, "tests": tests})
        min_size = min(m.size for m in p.messages)  # the resolver keeps dispatch fields inside it
        return with_head_checks({"kind": "bits", "entries": entries, "head_bytes": min_size,
                                 "head_bits": 8 * min_size})
    # bytes: the envelope's dispatch fields, read together as one key
    read = key_read(leaves_of(fr.envelope), fr.byte_order, fr.wire_order)
    keys = []
    for m in p.messages:
        for value in m.ids:
            keys.append((value, m.size, m.direction, m.name))
    # a message whose frames may be cut short takes every size from its shortest up
    least = {m.name: m.min_size for m in p.messages if m.shortening}
    # a counted array's frames grow an element at a time
    steps = {m.name: m.sizes.step for m in p.messages if m.sizes.step > 1}
    return dict(read, kind="bytes", first_bit=8 * read["first"], frames=keys, least=least, steps=steps)


def covering_read(fr: Framing, pos: int, bits: int, own_order: str | None) -> dict:
    """How to read the `bits` bits from frame bit `pos`: the bytes that cover them as
    one integer in `byte_order`, shifted right by `shift` and masked. A field of whole
    aligned bytes reads in its own byte order (shift 0); any other in the frame's bit
    order, which the resolver makes the byte order of every field crossing bytes."""
    first, last = pos // 8, (pos + bits - 1) // 8 + 1
    whole = pos % 8 == 0 and bits % 8 == 0
    order = (own_order or fr.byte_order) if whole and bits > 8 else fr.wire_order
    return {"at": first, "last": last, "bytes": last - first, "byte_order": order,
            "shift": shift_in(order, first, last - first, pos, bits), "mask": (1 << bits) - 1}


def with_head_checks(d: dict, head_bits: int | None = None) -> dict:
    """Bits dispatch read from a head of `head_bits` bits (a target may read fewer than the
    shortest message): each entry's tests as (shift, mask, value) on that head."""
    head_bits = head_bits or d["head_bits"]
    entries = [dict(e, checks=[(head_bits - pos - bits, (1 << bits) - 1, value) for pos, bits, value in e["tests"]])
               for e in d["entries"]]
    return dict(d, entries=entries, head_bits=head_bits)


def stream_facts(p: Protocol) -> dict:
    fr = p.framing
    if fr.kind != "bytes":
        return {}
    # only the fields before the payload can start a frame: a constant after it (an end
    # marker) is no part of the sync
    head = fr.envelope[:next(i for i, f in enumerate(fr.envelope) if f.is_payload)]
    pattern = sync_pattern(leaves_of(head), fr.byte_order)
    sync = pattern[0] if pattern else None
    length = None
    for leaf in p.messages[0].wire.leaves:
        if leaf.field.length_of:
            span = next(x for x in p.messages[0].layout if x.name == leaf.field.name)
            length = dict(covering_read(fr, leaf.pos, leaf.field.bits, leaf.field.byte_order),
                          overhead=p.messages[0].size - span.const)
    sizes = sorted({n for m in p.messages for n in m.sizes})
    by_key = None
    if length is None and len(sizes) > 1:  # no length field: the dispatch value gives the size
        dispatch = dispatch_facts(p)
        counted = counted_sizes(p)
        sizes_of: dict[int, set[int]] = {}
        for value, size, _, name in dispatch["frames"]:
            if name not in counted:
                sizes_of.setdefault(value, set()).add(size)
        # an id of several sizes (the resolver allows it when a checksum tells them apart):
        # each is tried, smallest first, and the first whose frame decodes is taken
        size_of = {value: min(sizes) for value, sizes in sizes_of.items()}
        by_key = {"at": dispatch["first"], "last": dispatch["last"], "bytes": dispatch["bytes"], "shift": dispatch["shift"],
                  "mask": dispatch["mask"], "byte_order": dispatch["byte_order"],
                  "sizes": sorted(size_of.items()), "counted": [],
                  "several": sorted((value, sorted(sizes)) for value, sizes in sizes_of.items() if len(sizes) > 1)}
        if counted:  # the count field gives these frames' sizes, looked up by direction and id
            by_key["counted"] = [dict(counted[name], value=value, direction=direction, any=value not in size_of)
                                 for value, _, direction, name in dispatch["frames"] if name in counted]
    ranges = size_ranges(p)
    if fr.stuffing is not None:  # a stuffed frame is longer than its message by what was stuffed
        ranges = stuffed_size_ranges(p)
        sizes = sorted({n for lo, hi in ranges for n in range(lo, hi + 1)})
    # A sync of several bytes: the decoder finds the first, then checks the rest
    # before it reads a frame there; a mismatch drops the byte as garbage.
    trailer = fr.trailer.size if fr.trailer else 0  # a flag may put it after any frame
    return {"sync": sync, "sync_rest": list(enumerate(pattern))[1:],
            "sync_bytes": pattern, "length": length, "by_key": by_key, "sizes": sizes, "max": max(sizes) + trailer,
            "min": min(sizes), "ranges": ranges,
            # what a stream decoder hands to the decoder: every size within a message's range, so
            # one between the steps of a counted array is a dispatch error in both targets
            "accepted": sorted({n for lo, hi in ranges for n in range(lo, hi + 1)})}


def gap_reads(p: Protocol, m: Message) -> list[dict]:
    """For each gap of `m` (in wire order), how a decoder reads the field that says how much
    of it is sent, from the bytes sent: the covering read at the field's place in the whole
    frame, less the bytes missing from the earlier gaps (`before`, their indices) ahead of it."""
    gaps = m.shortening.gaps if m.shortening else ()
    out = []
    for k, gap in enumerate(gaps):
        if gap.control is None:  # it fills the rest: the frame's size says
            out.append({})
            continue
        leaf = next(x for x in m.wire.leaves if x.path == (gap.control,))
        read = covering_read(p.framing, leaf.pos, leaf.bits, leaf.field.byte_order)
        out.append(dict(read, leaf=leaf, before=[j for j in range(k) if gaps[j].span[1] * 8 <= leaf.pos]))
    return out


def gap_of(m: Message, leaf: Leaf) -> Optional[Gap]:
    """The gap that holds `leaf`, if a frame may leave it out."""
    gaps = m.shortening.gaps if m.shortening else ()
    return next((g for g in gaps if leaf.path[0] == g.field), None)


def counted_sizes(p: Protocol) -> dict[str, dict]:
    """With no length field, how a stream decoder finds the size of a message with a counted
    array: the frame is `least` bytes plus the count field's value times `unit`."""
    out = {}
    for m in p.messages:
        counter = m.shortening.counter if m.shortening else None
        if counter is None or counter.count_field is None:
            continue
        leaf = next(x for x in m.wire.leaves if x.field.counts)
        out[m.name] = {"least": m.min_size, "at": leaf.pos // 8, "bytes": leaf.bits // 8, "unit": counter.unit,
                       "byte_order": leaf.field.byte_order or p.framing.byte_order,
                       "most": counter.most_value, "step": counter.step, "end": leaf.pos // 8 + leaf.bits // 8}
    return out


def size_ranges(p: Protocol) -> list[tuple[int, int]]:
    """The frame sizes a decoder accepts as (shortest, longest) pairs: one per message
    size, those of messages that may be cut short merged where they overlap."""
    out: list[tuple[int, int]] = []
    for lo, hi in sorted({(m.min_size, m.size) for m in p.messages}):
        if out and lo <= out[-1][1]:
            out[-1] = (out[-1][0], max(hi, out[-1][1]))
        else:
            out.append((lo, hi))
    return out


def sync_pattern(leaves: list, byte_order: str) -> bytes:
    """The constant bytes a frame starts with: its leading constant fields of whole bytes."""
    out = b""
    for leaf in leaves:
        f = leaf.field
        if f.const is None or f.dispatch or leaf.pos != 8 * len(out) or leaf.bits % 8 or f.kind != "uint":
            break
        out += f.const.to_bytes(leaf.bits // 8, f.byte_order or byte_order)
    return out


def checksum_name(cs) -> str:
    """A stable identifier for a checksum algorithm and its parameters."""
    if cs.algorithm == "crc":
        c = cs.crc
        return (f"crc{c.width}_{c.poly:x}_{c.init:x}_{'r' if c.refin else 'n'}"
                f"{'r' if c.refout else 'n'}_{c.xorout:x}" + ("_extra" if cs.extra else ""))
    if cs.algorithm == "parity":
        return "parity_odd" if cs.parity == "odd" else "parity"
    if cs.algorithm == "fletcher":
        return f"fletcher{cs.width}_{cs.modulo}"
    if cs.algorithm == "internet":
        return f"internet_{cs.word_order}"
    final = (f"_{cs.complement}{cs.width}" if cs.complement else "") \
        + (f"_x{cs.xorout:x}" if cs.xorout is not None else "")
    return f"{cs.algorithm}{cs.modulo or ''}{final}"


# Each encoding's delimiter, escape and what an escaped byte stands for (RFC 1055,
# RFC 1662; COBS has no escape: a code byte says where the next zero goes).
ENCODINGS = {
    "slip": {"name": "SLIP (RFC 1055)", "delimiter": 0xC0, "escape": 0xDB, "escaped": ((0xDC, 0xC0), (0xDD, 0xDB)),
             "leading": True},
    "hdlc": {"name": "HDLC-like byte stuffing (RFC 1662)", "delimiter": 0x7E, "escape": 0x7D,
             "escaped": ((0x5E, 0x7E), (0x5D, 0x7D)), "leading": True},
    "cobs": {"name": "COBS (Consistent Overhead Byte Stuffing)", "delimiter": 0x00, "escape": None,
             "escaped": (), "leading": False},
}


def encoded_size(encoding: str, size: int) -> int:
    """The most bytes a frame of `size` bytes takes encoded, delimiters included: SLIP and
    HDLC escape every byte at worst and send a delimiter before and after; COBS adds a
    code byte per 254 bytes (at least one) and the closing zero."""
    if encoding == "cobs":
        return size + max(1, -(-size // 254)) + 1
    return 2 * size + 2


def encoding_facts(p: Protocol) -> dict:
    """How frames are stuffed on the link, or {} when they are sent as they are."""
    fr = p.framing
    if fr.kind != "bytes" or not fr.encoding:
        return {}
    frame_max = max(m.size for m in p.messages)
    return dict(ENCODINGS[fr.encoding], kind=fr.encoding, frame_max=frame_max, accm=fr.accm,
                # the control characters the map escapes, and decoders drop where they come unescaped
                mapped=tuple(c for c in range(32) if fr.accm >> c & 1),
                wire_max=encoded_size(fr.encoding, frame_max),
                # a stretch this long without a delimiter cannot unstuff into a frame
                unit_max=2 * frame_max + 2,
                # stuffing never makes a frame shorter: a shorter stretch holds none
                unit_min=min(m.min_size for m in p.messages))


def stuffing_facts(p: Protocol) -> dict:
    """Where a pattern-stuffed frame's stuffed bytes, length fields and checksums sit, or {}
    without pattern stuffing. Fields before the payload are placed by `at`, their offset from
    the frame's start; fields after it by `back`, their offset from its end (a frame's size
    varies with what is stuffed). A checksum covers from `start` to `end` (from the start) or
    to `end_back` bytes before the frame's end; checksums are listed in wire order, the
    order an encoder fills them in."""
    fr = p.framing
    st = fr.stuffing if fr.kind == "bytes" else None
    if st is None:
        return {}
    env = fr.envelope
    payload = next(i for i, f in enumerate(env) if f.is_payload)
    # counted in bits: fields of a few bits share a byte (the fields placed here are whole bytes)
    begin, bit = {}, 0
    for f in env[:payload]:
        begin[f.name], bit = bit // 8, bit + (f.bits or 0)
    begin["payload"] = bit // 8
    back, bit = {}, 0
    for f in reversed(env[payload + 1:]):
        bit += f.bits or 0
        back[f.name] = -(-bit // 8)
    ends_back = {f.name: back[f.name] - (f.bits or 0) // 8 for f in env[payload + 1:]}
    ends_back["payload"] = back[env[payload + 1].name] if payload + 1 < len(env) else 0

    def place(f) -> dict:
        order = f.byte_order or fr.byte_order
        where = {"at": begin[f.name]} if f.name in begin else {"back": back[f.name]}
        return dict(where, name=f.name, bytes=(f.bits or 0) // 8, byte_order=order)

    index = {("payload" if f.is_payload else f.name): i for i, f in enumerate(env)}
    first, last = index[st.covers[0]], index[st.covers[1]]
    # the resolver lets a length field count all of the stuffed bytes or none of them
    lengths = [place(f) for f in env if f.length_of and index[f.length_of[0]] <= first <= index[f.length_of[1]]]
    resolved = {f.name: f.checksum for f in p.messages[0].layout if f.checksum}  # with its width
    checksums = []
    for f in env:
        cs = resolved.get(f.name)
        if cs is None:
            continue
        first, last = cs.covers
        end = {"end_back": ends_back[last]} if last in ends_back else \
            {"end": begin[last] + next(x.bits for x in env if x.name == last) // 8}
        checksums.append(dict(place(f), cs=cs, start=begin[first], **end))
    frame_max = max(m.size for m in p.messages)
    widest = max(m.size + st.most_inserted(m.size - st.head - st.tail) for m in p.messages)
    return {"pattern": st.pattern, "insert": st.insert, "head": st.head, "tail": st.tail,
            "lengths": lengths, "checksums": checksums, "frame_max": frame_max, "wire_max": widest,
            "shortest": min(m.min_size for m in p.messages),
            "name": f"{st.insert:02X} after {st.pattern.hex(' ').upper()}"}


def stuffed_size_ranges(p: Protocol) -> list[tuple[int, int]]:
    """size_ranges, each message's longest frame grown by the most its stuffing adds."""
    st = p.framing.stuffing
    out: list[tuple[int, int]] = []
    for lo, hi in sorted({(m.min_size, m.size + st.most_inserted(m.size - st.head - st.tail)) for m in p.messages}):
        if out and lo <= out[-1][1]:
            out[-1] = (out[-1][0], max(hi, out[-1][1]))
        else:
            out.append((lo, hi))
    return out


def text_line_facts(p: Protocol) -> dict:
    """How a text line is marked: `simple` when every mark is one character and the line
    has neither start marker nor checksum (the codecs' original, fastest form); the
    checksum's suffix, its algorithm and the characters it takes before the terminator."""
    fr = p.framing
    if fr.kind != "text":
        return {}
    cs = fr.line_checksum
    simple = (len(fr.separator) == len(fr.terminator) == len(fr.prefix_separator) == 1
              and not fr.start and cs is None)
    checksum = None
    if cs is not None:
        what = "XOR" if cs.algorithm == "xor" else "sum modulo 256"
        after = f"after {fr.start!r}" if fr.start else "from the line's start"
        checksum = {"algorithm": cs.algorithm, "suffix": cs.suffix, "tail": len(cs.suffix) + 2,
                    "shape": f"{cs.suffix}hh before the terminator (two uppercase hex digits)",
                    "doc": f"The {what} of the characters {after} up to {cs.suffix!r}."}
    return {"simple": simple, "checksum": checksum, "start": fr.start}
