"""A bytes framing's trailer: fields after the frame's last byte that a flag of an
envelope field puts in, and the keyed hash (signature) one of them may carry."""
from __future__ import annotations

from dataclasses import replace
from typing import Optional

from ..model import Field, Presence, Signature, Trailer
from .base import ResolverBase
from .text import text

# The bytes of a SHA-256 digest: a signature keeps at most this many.
DIGEST_BYTES = {"SHA-256": 32}


class TrailerMixin(ResolverBase):
    def resolve_trailer(self, fr: dict, envelope: tuple[Field, ...], path: tuple) -> Optional[Trailer]:
        spec = fr.get("trailer")
        if spec is None or not envelope:
            return None
        path = path + ("trailer",)
        if fr.get("encoding"):
            self.error(path, f"a trailer does not combine with `encoding: {fr['encoding']}`",
                       "drop the encoding or the trailer")
            return None
        if fr.get("stuffing"):  # the trailer's bytes would fall outside what the stuffing's length counts
            self.error(path, "a trailer does not combine with `stuffing`", "drop the stuffing or the trailer")
            return None
        if not any(f.length_of for f in envelope):
            self.error(path, "a trailer needs a length field in the layout (`length_of`): stream decoders "
                             "take a frame's size from it", "add a length field that counts the payload")
            return None
        head = self.head_offsets(envelope)
        control = self.trailer_control(spec["present_if"], envelope, head, path + ("present_if",))
        fields = self.trailer_fields(spec["fields"], envelope, path + ("fields",))
        if control is None or fields is None:
            return None
        presence, flag_byte, flag_mask = control
        fields = tuple(replace(f, present_if=presence) for f in fields)
        return Trailer(presence=presence, flag_byte=flag_byte, flag_mask=flag_mask, fields=fields,
                       doc=text(spec.get("doc")), loc=self.loc(*path))

    @staticmethod
    def head_offsets(envelope: tuple[Field, ...]) -> dict[str, int]:
        """The first byte of each envelope field before the payload that starts on a byte
        boundary (those after a field of no fixed width are left out)."""
        out, pos = {}, 0
        for f in envelope:
            if f.is_payload or f.bits is None:
                break
            if pos % 8 == 0:
                out[f.name] = pos // 8
            pos += f.bits
        return out

    def trailer_control(self, spec: dict, envelope: tuple[Field, ...], head: dict[str, int],
                        where: tuple) -> Optional[tuple[Presence, int, int]]:
        """The flag that puts the trailer in: its field, the frame byte it sits in and its bit."""
        name, has = spec["field"], spec["has"]
        f = next((x for x in envelope if x.name == name and not x.is_payload), None)
        if f is None or name not in head or f.bits % 8:
            self.error(where + ("field",), f"trailer: {name!r} is not a field of whole bytes before the "
                                           "payload in the layout", "name the layout's flags field")
            return None
        flag = next((b for b in f.flags.members if b.name == has), None) if f.flags else None
        if flag is None:
            self.error(where + ("has",), f"trailer: {name!r} has no flag {has!r}",
                       f"give {name!r} a flag set (`flags:`) with a flag {has!r}")
            return None
        if f.const is not None:
            self.error(where + ("field",), f"trailer: {name!r} is a constant, so its flag cannot be set",
                       "drop its `const`")
            return None
        size = f.bits // 8
        order = f.byte_order or self.data["framing"].get("byte_order", "big")
        nth = flag.bit // 8 if order == "little" else size - 1 - flag.bit // 8
        presence = Presence(name, has=has, mask=flag.mask, values=(flag.mask,))
        return presence, head[name] + nth, 1 << flag.bit % 8

    def trailer_fields(self, raw: list, envelope: tuple[Field, ...], where: tuple) -> Optional[tuple[Field, ...]]:
        """The trailer's fields, each an unsigned integer or bytes of whole bytes, with their
        offsets from the trailer's start; the signature's coverage resolved."""
        taken = {f.name for f in envelope} | {f["name"] for m in self.data.get("messages", {}).values()
                                               if isinstance(m, dict) for f in m.get("fields", [])
                                               if isinstance(f, dict) and "name" in f}
        out: list[Field] = []
        ok, pos = True, 0
        for i, r in enumerate(raw):
            path = where + (i,)
            f = self.resolve_field({k: v for k, v in r.items() if k != "signature"}, path, allow_payload=False)
            problem = ("it is a name the layout or a message already uses" if f.name in taken
                       or any(x.name == f.name for x in out) else
                       "a trailer field is an unsigned integer of whole bytes (u8 … u64) or bytes of a fixed "
                       "length" if f.kind not in ("uint", "bytes") or f.bits is None or f.bits % 8
                       or f.enum or f.flags or f.const is not None or f.length_param else None)
            if problem:
                self.error(path, f"trailer field {f.name!r}: {problem}", "rename or retype it")
                ok = False
            out.append(replace(f, bit_offset=pos))
            pos += f.bits or 0
        if not ok:
            return None
        signed = [i for i, r in enumerate(raw) if "signature" in r]
        if len(signed) > 1:
            self.error(where + (signed[1], "signature"), "a trailer carries one signature",
                       "drop the second")
            return None
        for i in signed:
            sig = self.resolve_signature(raw[i]["signature"], out[i], tuple(out[:i]), envelope,
                                         where + (i, "signature"))
            if sig is None:
                return None
            out[i] = replace(out[i], signature=sig)
        return tuple(out)

    def resolve_signature(self, spec: dict, f: Field, before: tuple[Field, ...], envelope: tuple[Field, ...],
                          where: tuple) -> Optional[Signature]:
        algorithm = spec["algorithm"]
        if f.kind != "bytes" or not f.length or f.length > DIGEST_BYTES[algorithm]:
            self.error(where, f"trailer field {f.name!r}: a {algorithm} signature is bytes of 1 to "
                              f"{DIGEST_BYTES[algorithm]} (the digest's first bytes)",
                       f"make it `type: bytes` with a length up to {DIGEST_BYTES[algorithm]}")
            return None
        first, last = spec["covers"]["from"], spec["covers"]["to"]
        head = self.head_offsets(envelope)
        if first not in head:
            self.error(where + ("covers", "from"), f"signature: {first!r} is not a layout field of whole "
                                                   "bytes before the payload", "name where the hashed bytes start")
            return None
        end = next((x.bit_offset // 8 + x.bits // 8 for x in before if x.name == last), None)
        if end is None:
            self.error(where + ("covers", "to"), f"signature: {last!r} is not a trailer field before "
                                                 f"{f.name!r}", "name the last trailer field hashed")
            return None
        return Signature(algorithm=algorithm, key_length=spec["key_length"], covers=(first, last),
                         start=head[first], end=end)
