"""Framing and envelopes: where a message's fields sit, alignment, sizes, text fields."""
from __future__ import annotations

from dataclasses import replace
from typing import Optional

from ..model import Field, Framing, LineChecksum, TextForm, TextPlaces
from .trailer import TrailerMixin
from .layout import key_read, leaves_of, whole_bytes

def always_placed(f: Field, keep_empty: bool) -> bool:
    """Whether a text value's place is written whatever it holds: a required value, a
    constant, or an optional one that keeps its empty place (its own keep_empty, or the
    framing's)."""
    return not f.optional or f.const is not None or (keep_empty if f.keep_empty is None else f.keep_empty)


def placed_why(f: Field, keep_empty: bool) -> str:
    """Why `always_placed` holds for a field, in words."""
    if f.const is not None:
        return "is a constant, always written"
    if not f.optional:
        return "is required"
    return "keeps its empty place (" + ("keep_empty: true" if f.keep_empty else "the framing's keep_empty") + ")"


def is_number(f: Field) -> bool:
    """A text value whose number has several spellings (`8`, `08`, `8.0`, `+8`)."""
    plain = f.kind in ("uint", "int") and f.enum is None and f.flags is None and not f.one_hot
    return f.const is None and f.count is None and (plain or f.kind == "float")


# SLIP and HDLC may double a frame, and add two delimiters: 2 * 16382 + 2 fits 16 bits
MAX_ENCODED_FRAME = 16382


class FramingMixin(TrailerMixin):
    def resolve_framing(self, fr: dict) -> Framing:
        kind = fr["kind"]
        path = ("framing",)
        if self.can is not None:
            self.check_can_framing()
        allowed = {"bits": {"kind", "word_bits", "max_bits", "byte_order", "text_form"},
                   "bytes": {"kind", "layout", "byte_order", "bit_order", "encoding", "accm", "stuffing", "truncate", "trailer"},
                   "text": {"kind", "start", "prefix_separator", "separator", "terminator",
                            "ignore_between", "trim", "float_format", "checksum", "keep_empty",
                            "keep_spelling"}}[kind]
        for key in fr:
            if key not in allowed:
                self.error(path + (key,), f"framing: {key!r} does not apply to {kind} framing",
                           "keys for this framing: " + ", ".join(sorted(allowed)))
        envelope: tuple[Field, ...] = ()
        if kind == "bytes":
            if "layout" not in fr:
                self.error(path, "bytes framing needs a `layout` with a `{payload: true}` item")
            else:
                envelope = self.resolve_fields(fr["layout"], path + ("layout",))
                payloads = [f for f in envelope if f.is_payload]
                if len(payloads) != 1:
                    self.error(path + ("layout",), f"layout needs exactly one `{{payload: true}}` item, "
                                                   f"found {len(payloads)}")
                for i, f in enumerate(envelope):
                    if f.start_bit is not None:
                        self.error(path + ("layout", i, "start_bit"), f"layout field {f.name!r}: start_bit places "
                                   "a message's own fields in its payload_bytes", "drop `start_bit`")
                    if f.extension:
                        self.error(path + ("layout", i, "extension"), f"layout field {f.name!r}: only a "
                                   "message's own fields can be extensions", "drop `extension`")
                wire_order = "little" if fr.get("bit_order") == "lsb_first" else "big"
                self.check_dispatch_fields(envelope, fr.get("byte_order", wire_order), wire_order,
                                           path + ("layout",))
        if kind == "bits" and "word_bits" in fr and "max_bits" in fr:
            self.error(path, "give word_bits (every message is one word) or max_bits, not both")
        if kind == "bits" and "word_bits" not in fr and "max_bits" not in fr:
            self.error(path, "bits framing needs word_bits or max_bits")
        tf = fr.get("text_form")
        bit_order = fr.get("bit_order", "msb_first")
        # least significant bit first, a field crossing bytes is little-endian: the default
        default_order = "little" if bit_order == "lsb_first" else "big"
        if kind == "text":
            self.check_text_marks(fr, path)
            if fr.get("keep_spelling") and fr.get("trim"):
                self.error(path + ("keep_spelling",), "framing: keep_spelling with trim: the whitespace "
                           "around a value is not kept, so a line would not be written back as received",
                           "drop trim (receivers that keep their spellings write no whitespace), or keep_spelling")
        cs = fr.get("checksum")
        if "accm" in fr and fr.get("encoding") != "hdlc":
            self.error(path + ("accm",), "accm is HDLC's map of the control characters it escapes "
                                         f"(RFC 1662 §7.1), not {fr.get('encoding') or 'unstuffed'} framing's",
                       "write encoding: hdlc, or drop accm")
        trailer = self.resolve_trailer(fr, envelope, path) if kind == "bytes" else None
        return Framing(
            kind=kind, byte_order=fr.get("byte_order", default_order), bit_order=bit_order,
            word_bits=fr.get("word_bits"),
            max_bits=fr.get("max_bits"),
            text_form=TextForm(tf.get("separator", " "), tf.get("comment"), tf.get("checksum_unfilled"))
            if tf else None,
            envelope=envelope, encoding=fr.get("encoding"), truncate=fr.get("truncate"), trailer=trailer,
            can=self.can,
            accm=fr.get("accm", 0) if fr.get("encoding") == "hdlc" else 0,
            prefix_separator=fr.get("prefix_separator", ":"),
            separator=fr.get("separator", ","), terminator=fr.get("terminator", ";"),
            ignore_between=fr.get("ignore_between", ""), trim=bool(fr.get("trim")),
            float_format=fr.get("float_format", "shortest"), start=fr.get("start", ""),
            keep_empty=bool(fr.get("keep_empty")), keep_spelling=bool(fr.get("keep_spelling")),
            line_checksum=LineChecksum(cs["algorithm"], cs["suffix"], cs.get("digits", "hex2")) if cs else None)

    def check_text_marks(self, fr: dict, path: tuple) -> None:
        """The marks of a text line must not be mistaken for one another: a line ends at
        the first terminator, so no other mark may hold one of its characters."""
        terminator = fr.get("terminator", ";")
        marks = {"start": fr.get("start", ""), "prefix_separator": fr.get("prefix_separator", ":"),
                 "separator": fr.get("separator", ",")}
        if fr.get("checksum"):
            marks["checksum"] = fr["checksum"]["suffix"]
        for key, mark in marks.items():
            shared = sorted(set(mark) & set(terminator))
            if shared:
                self.error(path + (key,), f"framing: {key} {mark!r} holds {shared[0]!r}, a character of the "
                                          f"terminator {terminator!r}", "choose marks that share no character")
        shared = sorted(set(fr.get("ignore_between", "")) & set(terminator))
        if shared:
            self.error(path + ("ignore_between",), f"framing: ignore_between would strip {shared[0]!r} of the "
                                                   f"terminator {terminator!r}",
                       "leave the terminator's characters out of ignore_between")

    def place(self, name: str, own: tuple[Field, ...], ids: tuple, framing: Framing,
              path: tuple, direction: Optional[str] = None,
              payload_bytes: Optional[int] = None) -> tuple[tuple[Field, ...], tuple]:
        """The message's whole frame in wire order with bit offsets, and its dispatch key.
        With `payload_bytes`, the own fields sit where their start bits put them."""
        own = self.place_signals(name, own, payload_bytes, framing, path)
        if framing.kind != "bytes":
            payload_bytes = None
        if framing.kind == "text":
            for i, f in enumerate(own):
                if f.dispatch:
                    self.error(path + ("fields", i, "dispatch"),
                               f"message {name!r}: field {f.name!r} is marked `dispatch: true`, but in "
                               "text framing a message is identified by its `id`, the line's prefix",
                               "drop `dispatch`")
            if len(ids) != 1 or not isinstance(ids[0], str):
                self.error(path + ("id",), f"message {name!r}: text framing needs a string `id` (the prefix)")
            elif framing.prefix_separator in ids[0] or set(ids[0]) & set(framing.terminator):
                self.error(path + ("id",), f"message {name!r}: id {ids[0]!r} holds the prefix separator "
                                           "or a character of the terminator, so it would not be read back",
                           "choose an id without them")
            self.check_prefix_fields(name, own, path)
            self.check_text_fields(name, own, path, framing.keep_empty)
            return own, (("prefix", ids),) if ids else ()
        if framing.kind == "bits":
            if ids:
                self.error(path + ("id",), f"message {name!r}: bits framing identifies messages by "
                                           "`dispatch: true` const fields, not `id`")
            frame = own
            key = tuple((f.name, f.const) for f in own if f.dispatch)
            for i, f in enumerate(own):
                if f.dispatch and f.const is None:
                    self.error(path, f"message {name!r}: dispatch field {f.name!r} needs a const value")
                if f.dispatch and (f.bits or 0) > 8 and (f.byte_order or framing.byte_order) == "little":
                    # header tests read the leading bits most significant first
                    self.error(path + ("fields", i), f"message {name!r}: dispatch field {f.name!r} is "
                               "little-endian; bits framing dispatches on big-endian header bits",
                               "declare it `byte_order: big`, or split it into dispatch fields of 8 bits")
        else:
            for i, f in enumerate(own):
                if f.dispatch:  # would be ignored: the layout's dispatch field and `id` do this
                    self.error(path + ("fields", i, "dispatch"),
                               f"message {name!r}: field {f.name!r} is marked `dispatch: true`, but in "
                               "bytes framing a message is identified by its `id`, the value of the "
                               "layout's dispatch field", "give the message an `id` and drop `dispatch`")
            if ids and not any(f.dispatch and not f.by_direction for f in framing.envelope):
                self.error(path + ("id",), f"message {name!r} has an `id`, but no field of the framing's "
                                           "layout is marked `dispatch: true` to hold it",
                           "mark the layout's id field `dispatch: true`, or drop the id")
            frame = []
            key: tuple = ()
            dispatch = [f.name for f in framing.envelope if f.dispatch and not f.by_direction]
            if len(dispatch) > 1 and ids and not isinstance(ids, dict):
                self.error(path + ("id",), f"message {name!r}: the layout has several dispatch fields, so "
                                           "`id` maps each to its value", "write id: {field: value, …}")
            if isinstance(ids, dict) and sorted(ids) != sorted(dispatch):
                self.error(path + ("id",), f"message {name!r}: `id` names {sorted(ids)}, but the layout's "
                                           f"dispatch fields are {dispatch}", "give a value for each of them")
            for f in framing.envelope:
                if f.is_payload:
                    frame.extend(own)
                    frame.append(replace(f, bits=0, length=payload_bytes))
                    continue
                f = replace(f, from_envelope=True)
                if f.by_direction:
                    f, pair = self.direction_value(name, f, direction, path)
                    key += (pair,)
                elif f.dispatch:
                    f, pair = self.dispatch_value(name, f, ids, len(dispatch) > 1, path)
                    key += (pair,)
                frame.append(f)
            names = [f.name for f in own]
            for f in framing.envelope:
                if f.name in names and not f.is_payload:
                    self.error(path, f"message {name!r}: field {f.name!r} is also an envelope field"
                               + (" (a CAN framing's header is can_id and data_length)" if self.can else ""),
                               f"rename {f.name!r}")
        placed = []
        offset = 0
        for f in frame:
            if f.start_bit is not None and payload_bytes:  # from the payload's start, which is here
                placed.append(replace(f, bit_offset=offset + f.bit_offset))
                continue
            if f.is_payload and payload_bytes:
                if offset % 8:
                    self.error(path + ("payload_bytes",), f"message {name!r}: its payload starts at bit {offset} "
                                                          "of the frame; a payload placed by start_bit starts "
                                                          "on a byte boundary", "make the layout's fields before "
                                                                                "the payload whole bytes")
                offset += 8 * payload_bytes
            placed.append(replace(f, bit_offset=offset))
            offset += f.bits or 0
        self.check_alignment(name, placed, framing, path)
        return tuple(placed), key

    def direction_value(self, name: str, f: Field, direction: Optional[str], path: tuple) -> tuple[Field, tuple]:
        """An envelope field whose value is set by the message's direction (MSP's `<` and `>`)."""
        values = dict(f.by_direction)
        if direction not in values:
            self.error(path, f"message {name!r}: {f.name!r} takes its value from the message's direction, "
                             f"and {'it has none' if direction is None else repr(direction) + ' has no value'}",
                       f"give the message one of the directions {sorted(values)}")
            return f, (f.name, ())
        return replace(f, const=values[direction]), (f.name, (values[direction],))

    def dispatch_value(self, name: str, f: Field, ids, several: bool, path: tuple) -> tuple[Field, tuple]:
        """The envelope's dispatch field `f` fixed to the message's id, and its (name, values)
        pair of the dispatch key. With several dispatch fields, `id` maps each to a value."""
        if isinstance(ids, dict):
            if f.name not in ids:  # reported with the fields the id names
                return f, (f.name, ())
            values = (ids[f.name],)
        elif several and ids:  # reported once, by place()
            return f, (f.name, ())
        else:
            values = ids
        if not values:
            self.error(path, f"message {name!r} needs an `id`: the value of {f.name!r}")
            return f, (f.name, values)
        for v in values:
            if not isinstance(v, int) or isinstance(v, bool):
                self.error(path + ("id",), f"message {name!r}: id {v!r} is not an integer; "
                                           f"it is the value of {f.name!r}")
            elif not self.int_fits(v, f.kind, f.bits or 0):
                self.error(path + ("id",), f"message {name!r}: id {v} does not fit {f.name!r} ({f.bits} bits)")
        f = replace(f, const=values[0]) if len(values) == 1 else replace(f, values=values)
        return f, (f.name, values)

    def check_dispatch_fields(self, envelope: tuple[Field, ...], byte_order: str, wire_order: str,
                              path: tuple) -> None:
        """Several dispatch fields are read together as one key of at most 32 bits."""
        leaves = leaves_of(envelope)
        dispatch = [x for x in leaves if x.field.dispatch]
        if len(dispatch) < 2:
            return
        if any(x.pos is None for x in dispatch):
            self.error(path, "dispatch fields must sit at fixed places in the frame",
                       "move them before any field of variable size")
            return
        read = key_read(leaves, byte_order, wire_order)
        if read["bytes"] > 4:
            self.error(path, f"the dispatch fields span {read['bytes']} bytes; a key is read from at most 4",
                       "move them next to each other")
        orders = {x.field.byte_order or byte_order for x in dispatch if whole_bytes(x) and x.bits > 8}
        if len(orders) > 1:
            self.error(path, "dispatch fields of several bytes must share one byte order",
                       "give them the same `byte_order`")
        elif read["byte_order"] != wire_order and any(
                not whole_bytes(x) and x.pos // 8 != (x.pos + x.bits - 1) // 8 for x in dispatch):
            self.error(path, f"the dispatch fields are read {read['byte_order']}-endian, so a dispatch field "
                             "of part of a byte must not cross a byte boundary", "move it inside one byte")

    def kept_spellings(self, name: str, m: dict, own: tuple[Field, ...], framing: Framing,
                       path: tuple) -> tuple[Field, ...]:
        """The message's numbers marked to keep their received text, as the message (or else
        the framing) says: every integer that is not an enum, flag set or constant, every float."""
        if "keep_spelling" in m and framing.kind != "text":
            self.error(path + ("keep_spelling",), f"message {name!r}: keep_spelling is for text framing "
                       "(a binary value has one spelling)", "drop keep_spelling")
            return own
        keep = m.get("keep_spelling", framing.keep_spelling)
        if framing.kind != "text" or not keep:
            return own
        if framing.trim and "keep_spelling" not in m:
            return own  # refused at the framing's keep_spelling
        if framing.trim:
            self.error(path + ("keep_spelling",), f"message {name!r}: keep_spelling with trim: the whitespace "
                       "around a value is not kept, so a line would not be written back as received",
                       "drop trim from the framing, or keep_spelling")
            return own
        return tuple(replace(f, keep_spelling=True) if is_number(f) else f for f in own)

    def check_prefix_fields(self, name: str, own: tuple[Field, ...], path: tuple) -> None:
        """A prefix field is read from the start of the prefix, before the id: one, first."""
        for i, f in enumerate(own):
            if f.prefix and i:
                self.error(path + ("fields", i, "prefix"), f"message {name!r}: prefix field {f.name!r} is not "
                           "the message's first field" + (", and a message has one prefix field"
                                                          if own[0].prefix else ""),
                           "make it the first field: it is written before the id, as NMEA's talker")

    def check_text_fields(self, name: str, own: tuple[Field, ...], path: tuple, keep_empty: bool) -> None:
        optional_str = None  # an empty value is an empty str, so a str is absent only at the end
        body = [f for f in own if not f.prefix]
        last_placed = max((i for i, f in enumerate(body) if always_placed(f, keep_empty)), default=-1)
        for n, f in enumerate(body):
            i = own.index(f)
            if f.keep_empty is False and n < last_placed:  # it could never be left out
                later = body[last_placed]
                self.error(path + ("fields", i, "keep_empty"),
                           f"message {name!r}: field {f.name!r} leaves out its empty place (keep_empty: false), "
                           f"but {later.name!r} after it {placed_why(later, keep_empty)}, so its place is "
                           "always written", "drop keep_empty, or move the field after "
                                             f"{later.name!r}" + (" and give that one keep_empty: false"
                                                                  if later.optional and later.const is None else ""))
            if f.const is not None:  # written always; read as absent when empty, whatever its kind
                if optional_str is not None:
                    self.error(path + ("fields", i), f"message {name!r}: constant {f.name!r}, which "
                                                     f"writers always write, follows the optional str "
                                                     f"{optional_str.name!r}",
                               "an empty value reads as an empty str, so only trailing str fields may be "
                               "optional; make the str required, or move the constant before it")
                continue
            keeps = keep_empty if f.keep_empty is None else f.keep_empty
            if f.optional and f.kind == "str" and keeps:
                if f.keep_empty:
                    self.error(path + ("fields", i, "keep_empty"), f"message {name!r}: optional str {f.name!r} "
                               "with keep_empty: true: an empty value reads as an empty str",
                               "drop keep_empty (its place is then left out when it is absent), or make it "
                               "a required str")
                else:
                    self.error(path + ("fields", i, "optional"), f"message {name!r}: optional str {f.name!r} in a "
                               "line that keeps empty values (keep_empty): an empty value reads as an empty str",
                               "make it a required str (empty when there is nothing to say), or give it "
                               "keep_empty: false (its place is then left out when it is absent)")
            if f.optional and f.kind == "str":
                optional_str = optional_str or f
            elif optional_str is not None and not f.optional:
                self.error(path + ("fields", i), f"message {name!r}: required field {f.name!r} follows "
                                                 f"the optional str {optional_str.name!r}",
                           "an empty value reads as an empty str, so only trailing str fields may be "
                           "optional; make it a required str, or move it to the end")
            elif optional_str is not None and keeps:
                self.error(path + ("fields", i), f"message {name!r}: field {f.name!r}, which keeps its empty "
                                                 f"place (keep_empty), follows the optional str "
                                                 f"{optional_str.name!r}",
                           "an empty value reads as an empty str, so the str's place must be one a line may "
                           f"leave out; give {f.name!r} keep_empty: false, or move it before the str")
            if f.to_end and i != len(own) - 1:
                self.error(path + ("fields", i), f"message {name!r}: to_end field {f.name!r} must be last")
            if f.kind in ("bytes", "group") or f.checksum or f.length_of:
                self.error(path + ("fields", i), f"field {f.name!r}: {f.kind if f.kind in ('bytes', 'group') else 'checksum/length'} "
                                                 "is not supported in text framing")

    def text_places(self, name: str, own: tuple[Field, ...], keep_empty: bool, path: tuple) -> TextPlaces:
        """How many values a line of the message carries: writers write every value up to the
        last one that always has its place (required, constant, or keeping its empty place),
        and later ones up to the last present; readers take a line that ends after the last
        value they need (those, but an optional constant), or before its first extension
        field (an older writer's line)."""
        self.check_extensions_last(name, own, path)
        body = [f for f in own if not f.prefix]
        written = 1 + max((i for i, f in enumerate(body) if always_placed(f, keep_empty)), default=-1)
        # an optional constant is always written, but read empty or missing as well
        needed = 1 + max((i for i, f in enumerate(body) if always_placed(f, keep_empty)
                          and not (f.optional and f.const is not None)), default=-1)
        first_extension = next((i for i, f in enumerate(body) if f.extension), len(body))
        return TextPlaces(least=min(needed, first_extension), written=written, total=len(body))

    def check_alignment(self, name: str, placed: list[Field], framing: Framing, path: tuple) -> None:
        """Bits inside a byte are counted in the frame's bit order, so a field crossing
        bytes reads in the matching byte order: big-endian most significant bit first,
        little-endian least significant bit first. A field in the other byte order, a
        float or bytes must be whole bytes on a byte boundary."""
        natural = framing.wire_order
        for leaf in leaves_of(tuple(placed)):  # each group member and array element where it sits
            f = leaf.field
            if leaf.pos is None:
                break
            if f.start_bit is not None:  # in its own bit order wherever it sits
                continue
            order = f.byte_order or framing.byte_order
            multibyte = f.bits and f.bits > 8 and f.kind in ("uint", "int") and order != natural
            if (f.kind in ("float", "bytes") or multibyte) and (leaf.pos % 8 or f.bits % 8):
                self.error(path, f"message {name!r}: field {leaf.dotted!r} must be byte-aligned and whole "
                                 f"bytes (it starts at bit {leaf.pos}, {f.bits} bits)",
                           self.alignment_hint(leaf, placed, framing) if multibyte else "add padding bits before it")
                break

    @staticmethod
    def alignment_hint(leaf, placed: list[Field], framing: Framing) -> str:
        """What makes a field that crosses bytes in the other byte order than its bits run
        readable: own byte_order applies to whole bytes only, so either the field becomes
        whole bytes on a boundary, or the framing's byte order becomes the bits' one and
        the whole-byte fields that keep the other order say so themselves."""
        f, natural = leaf.field, framing.wire_order
        other = "big" if natural == "little" else "little"
        if f.byte_order:  # its own order: drop it, or pad a whole-byte field onto a boundary
            return (f"drop its `byte_order: {f.byte_order}` (a field crossing bytes is {natural}-endian with "
                    f"{framing.bit_order} bits)" + (", or add padding bits before it" if f.bits % 8 == 0 else ""))
        keep = [x.dotted for x in leaves_of(tuple(placed)) if x.pos is not None and whole_bytes(x)
                and x.bits > 8 and x.field.kind in ("uint", "int", "float") and not x.field.byte_order]
        advice = (f"set the framing's `byte_order: {natural}` (the default with {framing.bit_order} bits), "
                  f"and give `byte_order: {other}` to the whole-byte fields that stay {other}-endian"
                  + (f" (here: {', '.join(f'`{k}`' for k in keep)})" if keep else ""))
        return ("add padding bits before it, or " + advice) if f.bits % 8 == 0 else advice

    def check_size(self, name: str, m: dict, layout: tuple[Field, ...], bits: Optional[int],
                   framing: Framing, path: tuple) -> None:
        if bits is None:
            return
        listing = " + ".join(f"{f.name}={f.bits}" for f in layout if not f.is_payload)
        if bits == 0:
            self.error(path + ("fields",), f"message {name!r} has no fields: nothing on the wire",
                       "give it at least one field")
            return
        if "bits" in m and m["bits"] != bits:
            self.error(path + ("bits",), f"message {name!r}: fields add up to {bits} bits, "
                                         f"but the message declares {m['bits']} ({listing})",
                       "fix a field width or the declared size")
        if framing.word_bits and bits != framing.word_bits:
            self.error(path + ("fields",), f"message {name!r}: fields add up to {bits} bits, "
                                           f"but a word is {framing.word_bits} bits ({listing})",
                       "every message of this protocol is exactly one word; fix a field width")
        if framing.max_bits and bits > framing.max_bits:
            self.error(path + ("fields",), f"message {name!r}: {bits} bits do not fit one "
                                           f"{framing.max_bits}-bit word ({listing})")
        if framing.kind == "bytes" and bits % 8:
            self.error(path + ("fields",), f"message {name!r}: the frame is {bits} bits, not whole bytes",
                       "add reserved bits")
        if framing.encoding and bits > 8 * MAX_ENCODED_FRAME:
            self.error(path + ("fields",), f"message {name!r}: the frame is {bits // 8} bytes; an encoded "
                                           f"frame holds at most {MAX_ENCODED_FRAME}",
                       "its encoded length (up to twice the frame) is an `int` of 16 bits in C on AVR")
