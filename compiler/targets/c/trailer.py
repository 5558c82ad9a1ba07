"""How the C codec spells a framing's trailer: its struct, how each field is read from
and written to the bytes after the frame, and the keyed hash of its signature."""
from __future__ import annotations

from ...model import Protocol
from ..escape import c_comment


def _ctype(bits: int) -> str:
    return next(f"uint{n}_t" for n in (8, 16, 32, 64) if bits <= n)


def trailer_view(p: Protocol) -> dict:
    """The trailer's facts as protocol.h.j2 lays them out ({} without one)."""
    t = p.framing.trailer
    if t is None:
        return {}
    fields = []
    for f in t.fields:
        at, size = f.bit_offset // 8, f.bits // 8
        order = "le" if (f.byte_order or p.framing.byte_order) == "little" else "be"
        wide = "_wide" if size > 4 else ""
        one = {"name": f.name, "at": at, "size": size, "doc": c_comment(str(f.doc)) if f.doc else "",
               "bytes": f.kind == "bytes", "signature": f.signature is not None, "most": None}
        if f.kind == "bytes":
            one["member"] = f"uint8_t {f.name}[{size}];"
        else:
            ctype = _ctype(f.bits)
            one.update(member=f"{ctype} {f.name};",
                       read=f"buf[body + {at}u]" if size == 1 else
                       f"({ctype})cw_get_{order}{wide}(buf + body + {at}u, {size}u)",
                       write=f"buf[body + {at}u] = t->{f.name};" if size == 1 else
                       f"cw_put_{order}{wide}(buf + body + {at}u, {size}u, t->{f.name});",
                       most=f"{(1 << f.bits) - 1:#x}u" if f.bits not in (8, 16, 32, 64) else None)
        fields.append(one)
    sig = t.signature
    return {"size": t.size, "flag_byte": t.flag_byte, "flag_end": t.flag_byte + 1, "mask": f"{t.flag_mask:#04x}u",
            "says": c_comment(t.presence.says), "fields": fields,
            "signature": None if sig is None else {
                "name": sig.name, "at": sig.bit_offset // 8, "length": sig.length,
                "start": sig.signature.start, "end": sig.signature.end,
                "key_length": sig.signature.key_length, "algorithm": sig.signature.algorithm}}
