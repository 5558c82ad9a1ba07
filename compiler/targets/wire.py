"""Wire facts every backend needs, computed from the model: how a decoder finds
the message in a frame, and how a stream decoder finds frames."""
from __future__ import annotations

from ..model import Protocol
from ..resolver.layout import leaves_of


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


def dispatch_facts(p: Protocol) -> dict:
    """How module-level decode finds the message a frame holds."""
    fr = p.framing
    if fr.kind == "bytes" and len(p.messages) == 1 and not p.messages[0].dispatch_key:
        return {"kind": "single", "name": p.messages[0].name}  # every frame holds the one message
    if not p.self_identifying:
        return {"kind": "none"}
    if fr.kind == "text":
        return {"kind": "text", "prefixes": [(m.ids[0], m.name, m.direction) for m in p.messages]}
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
    # bytes: the envelope's dispatch field
    leaf = next(x for x in leaves_of(fr.envelope) if x.field.dispatch)
    start, bits, order = leaf.pos, leaf.bits, leaf.field.byte_order or fr.byte_order
    first, last = start // 8, (start + bits - 1) // 8 + 1
    shift = last * 8 - (start + bits)
    keys = []
    for m in p.messages:
        for value in m.ids:
            keys.append((value, m.size, m.direction, m.name))
    # The field is read in its own byte order; the resolver makes a multi-byte
    # little-endian one whole, aligned bytes (shift 0). One byte reads alike.
    return {"kind": "bytes", "first": first, "last": last, "bytes": last - first, "first_bit": 8 * first,
            "shift": shift, "mask": (1 << bits) - 1, "frames": keys,
            "byte_order": order if bits > 8 else "big"}


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
    leaves = leaves_of(fr.envelope)
    first = leaves[0].field if leaves else None  # an envelope of the payload alone has no leaves
    sync = first.const if first is not None and first.const is not None and first.bits == 8 else None
    length = None
    for leaf in p.messages[0].wire.leaves:
        pos = leaf.pos
        if leaf.field.length_of:
            span = next(x for x in p.messages[0].layout if x.name == leaf.field.name)
            bits = leaf.field.bits
            first, last = pos // 8, (pos + bits - 1) // 8 + 1
            whole = pos % 8 == 0 and bits % 8 == 0
            length = {"at": first, "last": last, "bytes": last - first, "shift": last * 8 - (pos + bits),
                      "mask": (1 << bits) - 1, "overhead": p.messages[0].size - span.const,
                      # a field of whole bytes is read in its byte order, bits inside bytes big-endian
                      "byte_order": (leaf.field.byte_order or fr.byte_order) if whole and bits > 8 else "big"}
    sizes = sorted({m.size for m in p.messages})
    by_key = None
    if length is None and len(sizes) > 1:  # no length field: the dispatch value gives the size
        dispatch = dispatch_facts(p)
        size_of = {value: size for value, size, _, _ in dispatch["frames"]}
        by_key = {"at": dispatch["first"], "last": dispatch["last"], "bytes": dispatch["bytes"], "shift": dispatch["shift"],
                  "mask": dispatch["mask"], "byte_order": dispatch["byte_order"],
                  "sizes": sorted(size_of.items())}
    return {"sync": sync, "length": length, "by_key": by_key, "sizes": sizes, "max": max(sizes),
            "min": min(sizes)}


def checksum_name(cs) -> str:
    """A stable identifier for a checksum algorithm and its parameters."""
    if cs.algorithm == "crc":
        c = cs.crc
        return (f"crc{c.width}_{c.poly:x}_{c.init:x}_{'r' if c.refin else 'n'}"
                f"{'r' if c.refout else 'n'}_{c.xorout:x}")
    if cs.algorithm == "parity":
        return "parity_odd" if cs.parity == "odd" else "parity"
    return f"{cs.algorithm}{cs.modulo or ''}"


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
