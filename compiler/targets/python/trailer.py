"""How the Python codec spells a framing's trailer: where its flag sits, each field's
bytes in the trailer, and the keyed hash its signature field carries."""
from __future__ import annotations

from ...model import Protocol


def trailer_view(p: Protocol) -> dict:
    """The trailer's facts as the module template lays them out ({} without one)."""
    t = p.framing.trailer
    if t is None:
        return {}
    control = next(f for f in p.framing.envelope if f.name == t.presence.field)
    fields = []
    for f in t.fields:
        start, size = f.bit_offset // 8, f.bits // 8
        fields.append({"name": f.name, "bytes": f.kind == "bytes", "start": start, "end": start + size,
                       "size": size, "order": f.byte_order or p.framing.byte_order,
                       "most": (1 << f.bits) - 1, "signature": f.signature is not None})
    sig = t.signature
    return {"size": t.size, "flag_byte": t.flag_byte, "flag_end": t.flag_byte + 1, "mask": t.flag_mask, "flag_field": control.name,
            "flag_bit": 8 * t.flag_byte, "says": t.presence.says, "fields": fields,
            "signature": None if sig is None else {
                "name": sig.name, "start": sig.signature.start, "end": sig.signature.end,
                "length": sig.length, "key_length": sig.signature.key_length,
                "at": sig.bit_offset // 8, "algorithm": sig.signature.algorithm}}
