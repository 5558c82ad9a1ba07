"""Checksums: algorithms and parameters, what each covers, the order they are filled in."""
from __future__ import annotations

from dataclasses import replace
from typing import Optional

from .. import crc
from ..model import Checksum, CrcParams, Field, Framing, Shortening
from .base import ResolverBase

CRC_KEYS = ("width", "poly", "init", "refin", "refout", "xorout")
SIMPLE = ("parity", "sum", "xor", "fletcher", "internet")  # algorithms without CRC parameters


def coverage(layout: tuple[Field, ...], pair: tuple[str, str]) -> Optional[tuple[int, int]]:
    """The bits [start, stop) a coverage {from, to} names in the frame, or None if a name is
    unknown: `payload` starts where the message's own fields start and ends where they end."""
    by_name = {f.name: f for f in layout}
    start_f, end_f = by_name.get(pair[0]), by_name.get(pair[1])
    if start_f is None or end_f is None:
        return None
    marker = next((f for f in layout if f.is_payload), None)
    own = [f for f in layout if not f.from_envelope and not f.is_payload]
    if marker is not None and marker.length:  # placed by start_bit: the payload's bytes end at the marker
        payload_start = marker.bit_offset - 8 * marker.length
    else:
        payload_start = own[0].bit_offset if own else marker.bit_offset if marker else None
    start = payload_start if start_f.is_payload else start_f.bit_offset
    return start, end_f.bit_offset + (end_f.bits or 0)


class ChecksumsMixin(ResolverBase):
    def resolve_checksum(self, c: dict, path: tuple, bits: Optional[int],
                         byte_order: Optional[str] = None) -> Checksum:
        """`byte_order`: the field's own, when it gives one (else the framing's)."""
        algorithm = c["algorithm"]
        covers = c.get("covers", "all")
        covers = None if covers == "all" else (covers["from"], covers["to"])
        default_over = "fields" if self.framing_kind == "bits" else "bytes"
        over = c.get("over", default_over)
        params: Optional[CrcParams] = None
        if algorithm == "crc":
            missing = [k for k in CRC_KEYS if k not in c]
            if missing:
                self.error(path, f"crc needs Rocksoft parameters: missing {', '.join(missing)}",
                           "or name a RevEng catalogue entry, e.g. algorithm: CRC-16/CMS")
                return Checksum("crc", over, covers, loc=self.loc(*path))
            params = CrcParams("custom", c["width"], c["poly"], c["init"], c["refin"],
                               c["refout"], c["xorout"])
        elif algorithm in SIMPLE:
            # CRC parameters would be ignored: a silent mismatch with the peer
            finals = ("xorout",) if algorithm in ("sum", "xor") else ()
            for key in CRC_KEYS:
                if key in c and key not in finals:
                    self.error(path + (key,), f"{key} is a CRC parameter; {'an' if algorithm == 'internet' else 'a'} "
                                             f"{algorithm} checksum has none",
                               f"drop {key}, or use a CRC")
        else:
            params = crc.lookup(algorithm)
            if params is None:
                self.unknown_crc_name(algorithm, path + ("algorithm",))
                return Checksum("crc", over, covers, loc=self.loc(*path))  # refused: later rules still name its line
        if params is not None:
            algorithm = "crc"
            self.check_crc(params, path, bits, over)
        elif algorithm in ("fletcher", "internet"):
            if over != "bytes":
                what = "a Fletcher checksum" if algorithm == "fletcher" else "the internet checksum"
                self.error(path + ("over",), f"{what} is computed over bytes",
                           "drop `over` (bits framing: write over: bytes), or use a sum or xor over fields")
        elif over != "bytes" and covers is not None:
            # the codecs and docs take a checksum over fields from every other field
            self.error(path + ("covers",), "a checksum over fields covers every other field "
                                           "of the message; `covers: {from, to}` is the byte "
                                           "range of a checksum over bytes",
                       "drop `covers` (or write `covers: all`); to check part of the frame, use "
                       "a CRC over whole bytes, e.g. {algorithm: CRC-8/SMBUS, covers: {from, to}}")
        modulo = c.get("modulo")
        word_order = None
        if algorithm == "fletcher":
            modulo = self.fletcher_modulo(modulo, path, bits)
        elif algorithm == "internet":
            word_order = self.internet_words(c, path, bits, byte_order)
        elif algorithm in ("sum", "xor") and modulo is None and bits:
            modulo = 1 << bits
        if algorithm == "parity" and bits not in (None, 1):
            self.error(path, f"a parity bit is 1 bit wide, not {bits}")
        if algorithm != "fletcher" and modulo is not None and bits and modulo > (1 << bits):
            self.error(path + ("modulo",), f"sum modulo {modulo} does not fit {bits} bits")
        complement = c.get("complement")
        xorout = c.get("xorout") if algorithm in ("sum", "xor") else None  # a CRC's is in its params
        self.check_final_step(algorithm, complement, xorout, over, path, bits)
        xorout = xorout or None  # XOR with 0 changes nothing: the same checksum as none
        width = bits if algorithm == "fletcher" or complement else None
        extra = c.get("extra")
        if extra and (algorithm != "crc" or over != "bytes"):
            self.error(path + ("extra",), f"`extra: {extra}` is for a CRC over bytes (MAVLink's CRC_EXTRA)",
                       "drop `extra`, or use a CRC")
        return Checksum(algorithm, over, covers, c.get("parity", "even"), modulo, params,
                        loc=self.loc(*(path + ("covers",))) if "covers" in c else self.loc(*path),
                        complement=complement, xorout=xorout, width=width, extra=extra,
                        word_order=word_order)

    def unknown_crc_name(self, algorithm: str, path: tuple) -> None:
        meanings = crc.candidates(algorithm)
        if meanings:
            self.error(path, f"CRC name {algorithm!r} is ambiguous: documents use it for "
                             f"{len(meanings)} different CRCs",
                       "name the one your peer computes (compare its check value with your "
                       "reference): " + "; ".join(crc.describe(p) for p in meanings))
            return
        near = crc.near_names(algorithm)
        self.error(path, f"unknown checksum algorithm {algorithm!r}",
                   (f"did you mean {' or '.join(near)}? Otherwise use " if near else "use ")
                   + "parity, sum, xor, fletcher, internet, crc (with parameters) or a RevEng "
                   "catalogue name such as CRC-16/CMS")

    def internet_words(self, c: dict, path: tuple, bits: Optional[int],
                       byte_order: Optional[str]) -> str:
        """RFC 1071's checksum is a 16-bit one's complement sum of 16-bit words, its own
        arithmetic: it takes no modulo, and sums in the field's byte order (RFC 1071 2(B):
        the bytes on the wire are the same in either order)."""
        if bits != 16:
            self.error(path, f"the internet checksum is 16 bits wide, not {bits}",
                       "declare the field as u16")
        if "modulo" in c:
            self.error(path + ("modulo",), "the internet checksum sums 16-bit words with "
                                           "end-around carry; it takes no modulo", "drop modulo")
        framing = self.data["framing"]
        default = "little" if framing.get("bit_order") == "lsb_first" else "big"  # as the framing's
        return byte_order or framing.get("byte_order", default)

    def check_crc(self, params: CrcParams, path: tuple, bits: Optional[int], over: str) -> None:
        mask = (1 << params.width) - 1
        for key in ("poly", "init", "xorout"):
            if getattr(params, key) > mask:
                self.error(path + (key,), f"crc {key} does not fit {params.width} bits")
        if bits is not None and bits != params.width:
            self.error(path, f"a {params.width}-bit CRC needs a {params.width}-bit field, not {bits}",
                       f"declare the field as u{params.width}")
        if over != "bytes":
            self.error(path + ("over",), "a CRC is computed over bytes")

    def fletcher_modulo(self, modulo: Optional[int], path: tuple, bits: Optional[int]) -> Optional[int]:
        """Fletcher-16 keeps two sums of bytes in 8 bits each, Fletcher-8 two sums of
        nibbles in 4 bits: the field holds both, so its width sets the sums' modulo."""
        if bits not in (8, 16):
            self.error(path, f"a Fletcher checksum is 8 or 16 bits wide, not {bits}",
                       "declare the field as u16 (two sums of bytes) or u8 (two sums of nibbles)")
            return modulo
        half = 1 << (bits // 2)
        if modulo is None:
            return half - 1
        if modulo not in (half - 1, half):
            self.error(path + ("modulo",), f"a {bits}-bit Fletcher checksum sums modulo {half - 1} "
                                           f"or {half}, not {modulo}",
                       f"write modulo: {half - 1} (classic Fletcher-{bits}) or modulo: {half} "
                       "(sums that wrap, as u-blox UBX)" if bits == 16 else
                       f"write modulo: {half - 1} (classic Fletcher-{bits}) or modulo: {half}")
        return modulo

    def check_final_step(self, algorithm: str, complement: Optional[str], xorout: Optional[int],
                         over: str, path: tuple, bits: Optional[int]) -> None:
        """`complement` and `xorout` finish a sum (xorout also an xor) over bytes."""
        if complement is not None and algorithm != "sum":
            self.error(path + ("complement",), f"`complement` finishes algorithm: sum, not {algorithm}",
                       "use algorithm: sum, or drop complement"
                       + (" (an xor's one's complement is xorout: 0xFF for 8 bits)" if algorithm == "xor" else ""))
        for key, given in (("complement", complement), ("xorout", xorout)):
            if given is not None and algorithm in ("sum", "xor") and over != "bytes":
                self.error(path + (key,), f"`{key}` finishes a checksum over bytes, not over {over}",
                           f"drop {key}, or compute the checksum over bytes")
        if xorout is not None and algorithm in ("sum", "xor") and bits and xorout >= 1 << bits:
            self.error(path + ("xorout",), f"xorout {xorout:#x} does not fit the {bits}-bit field",
                       f"give a value below {1 << bits:#x}, or widen the field")

    def bind_checksums(self, name: str, layout: tuple[Field, ...], framing: Framing,
                       path: tuple) -> tuple[Field, ...]:
        """Compute each checksum's and length field's byte coverage within this frame."""
        by_name = {f.name: f for f in layout}
        out = []
        for f in layout:
            span, inside = None, False
            pair = f.checksum.covers if f.checksum else f.length_of
            if pair is not None:
                start_f, end_f = by_name.get(pair[0]), by_name.get(pair[1])
                for end_name, end in zip(pair, (start_f, end_f)):
                    if end is None:
                        self.report.error(f.checksum.loc if f.checksum else f.loc,
                                          f"message {name!r}: {f.name!r} covers unknown field "
                                                 f"{end_name!r}", "name envelope fields or `payload`")
                if start_f and end_f:
                    start, stop = coverage(layout, pair)
                    refused = f.checksum and f.checksum.over != "bytes"  # resolve_checksum refuses its range
                    if (start % 8 or stop % 8) and not refused:
                        self.error(path, f"message {name!r}: coverage of {f.name!r} is not whole bytes")
                    if stop < start or stop == start and f.checksum:  # a length may count nothing
                        self.error(path, f"message {name!r}: coverage of {f.name!r} is empty or reversed")
                    if f.checksum and start <= f.bit_offset < stop:
                        inside = self.covers_itself(name, f, start)
                    if f.checksum:
                        self.check_later_checksums(name, f, (start, stop), layout)
                    span = (start // 8, stop // 8)
            if f.checksum:
                if f.checksum.covers is None and f.checksum.over == "bytes" \
                        and framing.kind == "bytes":
                    self.error(path, f"checksum {f.name!r}: give `covers: {{from, to}}` in bytes framing")
                f = replace(f, checksum=replace(f.checksum, byte_span=span, covers_self=inside))
            elif f.length_of and span:
                value = span[1] - span[0] + f.length_adjust
                if value < 0 or not self.int_fits(value, f.kind, f.bits or 0):
                    self.error(path, f"message {name!r}: length {value} does not fit {f.name!r}")
                f = replace(f, const=value)
            out.append(f)
        return tuple(out)

    def covers_itself(self, name: str, f: Field, start: int) -> bool:
        """Whether a checksum inside its own coverage is one the codecs can fill and check:
        only the internet checksum, its bytes counted as zero (RFC 1071), on a 16-bit word
        of what it covers, so the receiver's sum over the whole comes out all ones."""
        cs = f.checksum
        if cs.algorithm != "internet":
            self.report.error(cs.loc, f"message {name!r}: checksum {f.name!r} covers itself",
                              f"only the internet checksum may cover itself (its bytes counted as zero, "
                              f"RFC 1071); end the coverage before {f.name!r}")
            return False
        offset = (f.bit_offset - start) / 8
        if f.bit_offset % 8 or offset % 2:
            self.report.error(cs.loc, f"message {name!r}: internet checksum {f.name!r} covers itself "
                                      f"{offset:g} byte{'s' if offset != 1 else ''} into its coverage, not on a 16-bit word",
                              "RFC 1071's receiver check needs the checksum to be one word of what it "
                              "covers: start the coverage an even number of bytes before it")
            return False
        return True

    def check_fixed_self_cover(self, name: str, layout: tuple[Field, ...],
                               shortening: Optional[Shortening]) -> None:
        """A checksum that covers itself is read and written at one place in the frame:
        none of the bytes a frame may leave off comes before it."""
        if shortening is None:
            return
        moving = min([g.span[0] for g in shortening.gaps] + [shortening.payload[0] + shortening.least])
        for f in layout:
            if f.checksum and f.checksum.covers_self and f.bit_offset // 8 + 2 > moving:
                self.report.error(f.checksum.loc, f"message {name!r}: internet checksum {f.name!r} covers "
                                                  "itself after bytes a frame may leave off",
                                  f"place {f.name!r} before the payload's optional, counted or truncated "
                                  "bytes, or end its coverage before it")

    def check_later_checksums(self, name: str, f: Field, bits: tuple[int, int],
                              layout: tuple[Field, ...]) -> None:
        """The codecs fill checksums in wire order: one whose bits cover a later checksum
        would be computed while that one is still 0, and fail once it is filled in."""
        start, stop = bits
        for other in layout:
            if other.checksum and f.bit_offset < other.bit_offset < stop \
                    and other.bit_offset + (other.bits or 0) > start:
                self.report.error(f.checksum.loc, f"message {name!r}: checksum {f.name!r} covers "
                                                  f"checksum {other.name!r}, which comes after it",
                                  f"end the coverage of {f.name!r} before {other.name!r}, or place "
                                  f"{f.name!r} after {other.name!r} (checksums are filled in wire order)")

    def check_field_checksums(self, name: str, layout: tuple[Field, ...]) -> None:
        """A checksum over fields takes every other field, so another checksum among them
        would have to be computed before it and after it: the two cannot both hold."""
        def walk(fields: tuple[Field, ...]):
            for f in fields:
                yield f
                yield from walk(f.fields)

        sums = [f for f in walk(layout) if f.checksum]
        for f in sums:
            if f.checksum.over == "bytes":
                continue
            # it adds the other fields' raw integers (a float's IEEE 754 bits): bytes and text hold none
            odd = next((x for x in walk(layout) if x is not f and x.kind in ("bytes", "str", "char")), None)
            if odd is not None:
                self.report.error(f.checksum.loc or f.loc,
                                  f"message {name!r}: checksum {f.name!r} over every other field adds their "
                                  f"raw integers; field {odd.name!r} is {odd.kind}",
                                  "cover bytes with a checksum over bytes, or give the message numbers only")
            for other in sums:
                if other is not f:
                    self.report.error(f.checksum.loc or f.loc,
                                      f"message {name!r}: checksum {f.name!r} over every other "
                                      f"field covers checksum {other.name!r}, so the two cannot "
                                      "both be right",
                                      "a checksum over fields must be the message's only checksum")
