"""Messages and dispatch: how a decoder tells them apart, and their examples."""
from __future__ import annotations

from typing import Optional

from ..dispatch_pairs import candidate_pairs
from ..text_prefix import common_prefix, pattern_of
from ..model import Example, ExpectedError, Field, Framing, Message, places_member
from .text import text
from .base import ResolverBase
from .crc_extra import derived, mavlink_type
from .layout import key_of, key_read, leaves_of, wire_of
from .repeats import looped_arrays


class MessagesMixin(ResolverBase):
    def resolve_message(self, name: str, m: dict, framing: Framing) -> Message:
        path = ("messages", name)
        self.check_name(name, path, "message")
        layout_type = None
        if isinstance(m["fields"], str):
            layout_type = m["fields"]
            t = self.data.get("types", {}).get(layout_type)
            if t is None or self.base_type(t, ()) != "group":
                self.error(path + ("fields",), f"message {name!r}: {layout_type!r} is not a group type",
                           "declare it under `types` with `type: group` and `fields`")
                own: tuple[Field, ...] = ()
            else:
                merged, _ = self.merged(t, ("types", layout_type))
                own = self.resolve_fields(merged["fields"], ("types", layout_type, "fields"),
                                          allow_payload=False)
        else:
            own = self.resolve_fields(m["fields"], path + ("fields",), allow_payload=False)
        for key in ("direction", "role"):
            table = "directions" if key == "direction" else "roles"
            if key in m and m[key] not in self.data.get(table, {}):
                self.error(path + (key,), f"message {name!r}: unknown {key} {m[key]!r}",
                           f"declare it under `{table}`")
        ids = m.get("id")
        if isinstance(ids, dict) and framing.kind != "bytes":
            self.error(path + ("id",), f"message {name!r}: an `id` that names fields is for bytes framing "
                                       "with several dispatch fields")
            ids = None
        ids = () if ids is None else tuple(ids) if isinstance(ids, list) else ids if isinstance(ids, dict) else (ids,)
        ids = self.can_ids(name, m, ids, path)
        own = self.bind_controls(name, own, path)
        own = self.kept_spellings(name, m, own, framing, path)
        payload_bytes = m.get("payload_bytes")
        layout, dispatch_key = self.place(name, own, ids, framing, path, m.get("direction"), payload_bytes)
        if framing.kind != "bytes":
            payload_bytes = None
        if len(dispatch_key) > 1 and framing.kind == "bytes":  # the key the dispatch fields' values make together
            values = dict((k, v[0]) for k, v in dispatch_key if len(v) == 1 and isinstance(v[0], int))
            read = key_read(leaves_of(framing.envelope), framing.byte_order, framing.wire_order)
            ids = (key_of(read, values),) if read and set(values) == set(read["places"]) else ()
        bits = shortening = places = None
        keeps_places = False
        if framing.kind == "text":
            places = self.text_places(name, own, framing.keep_empty, path)
            body = [f for f in own if not f.prefix]
            # a decoded line keeps its number of values as it keeps its numbers' text (constants,
            # always written, need no keeping)
            keeps_places = any(f.const is None for f in body[places.least:]) \
                and bool(m.get("keep_spelling", framing.keep_spelling)) and not framing.trim
            clash = next((f for f in own if f.name == places_member()), None) if keeps_places else None
            if clash is not None:
                self.report.error(clash.loc, f"message {name!r}: field {clash.name!r} has the name of the C member "
                                             "that keeps how many values a decoded line had (keep_spelling)",
                                  f"rename {clash.name!r}")
        else:
            widths = [f.bits for f in layout if f.start_bit is None or not payload_bytes]
            bits = sum(widths) + 8 * (payload_bytes or 0) if all(w is not None for w in widths) else None
            self.check_size(name, m, layout, bits, framing, path)
            layout = self.bind_checksums(name, layout, framing, path)
            self.check_field_checksums(name, layout)
            if framing.kind == "bytes" and bits is not None:
                shortening = self.shortening(name, layout, framing, path)
                self.check_fixed_self_cover(name, layout, shortening)
        if framing.kind != "text":
            self.check_can_size(name, None if bits is None else (bits + 7) // 8, shortening is not None,
                                path + (("payload_bytes",) if "payload_bytes" in m else ()))
        self.check_generated_members(name, layout)
        crc_extra = self.crc_extra(name, m, own, layout, path)
        rules = tuple(self.resolve_rule(r, path + ("rules", i), layout)
                      for i, r in enumerate(m.get("rules", [])))
        examples = tuple(self.resolve_example(e, path + ("examples", i))
                         for i, e in enumerate(m.get("examples", [])))
        return Message(
            name=name, loc=self.loc(*path), title=text(m.get("title")), doc=text(m.get("doc")),
            ids=ids, direction=m.get("direction"), role=m.get("role"),
            answered_by=tuple(m.get("answered_by", [])), fields=own, layout=layout, bits=bits,
            rules=rules, examples=examples, dispatch_key=dispatch_key, crc_extra=crc_extra,
            wire=wire_of(layout, bits, framing.wire_order, looped_arrays(layout, rules) if framing.kind == "bytes" else frozenset()),
            payload_bytes=payload_bytes,
            layout_type=layout_type, shortening=shortening, text_places=places, keeps_places=keeps_places)

    def check_generated_members(self, name: str, fields: tuple[Field, ...]) -> None:
        """The C struct adds `has_<f>` beside an optional or one-hot field and `<f>_count`
        beside one that varies: no other member of the same struct may be called so."""
        owners: dict[str, Field] = {}
        for f in fields:
            for member in f.generated_members:
                owners.setdefault(member, f)
        for f in fields:
            owner = owners.get(f.name) if f.is_member else None
            if owner is not None:
                self.report.error(f.loc, f"message {name!r}: field {f.name!r} has the name of the C member "
                                         f"that field {owner.name!r} brings ({f.name})",
                                  f"rename {f.name!r}; the C struct declares {f.name} for {owner.name!r}")
        generated = [m for f in fields for m in f.generated_members]
        for member in {m for m in generated if generated.count(m) > 1}:
            first, *others = [f for f in fields if member in f.generated_members]
            for f in others:
                self.report.error(f.loc, f"message {name!r}: fields {first.name!r} and {f.name!r} would both "
                                         f"bring the C member {member}", f"rename {f.name!r}")
        for f in fields:
            if f.kind == "group":
                self.check_generated_members(name, f.fields)

    def crc_extra(self, name: str, m: dict, own: tuple[Field, ...], layout: tuple[Field, ...],
                  path: tuple) -> Optional[int]:
        """The byte a CRC with `extra` takes after its coverage: declared by every message
        (`extra: message`), or derived from the message's definition as MAVLink derives its
        CRC_EXTRA (`extra: mavlink`), a declared value then checked against it."""
        extra = next((f.checksum.extra for f in layout if f.checksum and f.checksum.extra), None)
        self.check_mavlink_names(name, m, own, path, extra == "mavlink")
        if extra is None:
            if "crc_extra" in m:
                self.error(path + ("crc_extra",), f"message {name!r}: no checksum takes its crc_extra",
                           "drop it, or give the frame's CRC `extra: message`")
            return None
        if extra == "message":
            if "crc_extra" not in m:
                self.error(path, f"message {name!r} needs `crc_extra`: the frame's CRC takes one more byte, "
                                 "the message's", "add crc_extra: <0..255>, or give the CRC `extra: mavlink` "
                                                  "to derive it as MAVLink does")
            return m.get("crc_extra")
        fields = []
        for f in own:
            if f.extension:
                continue
            spelt = mavlink_type(f)
            if spelt is None:
                self.report.error(f.loc, f"message {name!r}: field {f.name!r} has no MAVLink type, so the "
                                         "message's crc_extra cannot be derived (`extra: mavlink`)",
                                  "use fields of u8..u64, i8..i64, f32, f64 (or arrays of them) and bytes, or "
                                  "give the CRC `extra: message` and each message its crc_extra")
                return m.get("crc_extra")
            fields.append((spelt[0], f.mavlink_name or f.name, spelt[1]))
        message_name = m.get("mavlink_name", name.upper())
        value = derived(message_name, fields)
        if "crc_extra" in m and m["crc_extra"] != value:
            said = ", ".join(f"{t} {n}" + (f"[{k}]" if k else "") for t, n, k in fields)
            self.error(path + ("crc_extra",), f"message {name!r}: crc_extra {m['crc_extra']} is not {value}, "
                                              f"MAVLink's CRC_EXTRA of its definition ({message_name}: {said})",
                       f"write crc_extra: {value}, or drop it: the CRC derives it (`extra: mavlink`)")
        return value

    def check_mavlink_names(self, name: str, m: dict, own: tuple[Field, ...], path: tuple, read: bool) -> None:
        """`mavlink_name` is read only where a CRC derives crc_extra from it."""
        if read:
            return
        if "mavlink_name" in m:
            self.error(path + ("mavlink_name",), f"message {name!r}: mavlink_name is read only by a CRC with "
                                                 "`extra: mavlink`", "drop mavlink_name")
        for f in own:
            if f.mavlink_name is not None:
                self.report.error(f.loc, f"message {name!r}: field {f.name!r}: mavlink_name is read only by a CRC "
                                         "with `extra: mavlink`", "drop mavlink_name")

    def resolve_example(self, e: dict, path: tuple) -> Example:
        raw_hex = None
        if "hex" in e:
            digits = "".join(e["hex"].split())
            if len(digits) % 2:
                self.error(path + ("hex",), "hex has an odd number of digits")
            else:
                raw_hex = bytes.fromhex(digits)
        errors = []
        if "error" in e:
            errors.append(ExpectedError(e["error"]["field"], e["error"]["rule"]))
        for x in e.get("errors", []):
            errors.append(ExpectedError(x["field"], x["rule"], x["line"]))
        forms = [k for k in ("hex", "word", "text") if k in e]
        if not forms:
            self.error(path, "an example needs a wire form: hex, word or text")
        if "values" not in e and not errors and "sequence" not in path[0]:
            self.error(path, "an example needs `values` (or an expected `error`)")
        return Example(name=e.get("name", f"example {path[-1] + 1}"), loc=self.loc(*path),
                       values=e.get("values"), hex=raw_hex, word=e.get("word"), text=e.get("text"),
                       direction=e.get("direction"), decode_only=bool(e.get("decode_only")),
                       errors=tuple(errors), source=e.get("source"))

    def check_messages(self, messages: tuple[Message, ...], d: dict) -> None:
        names = {m.name for m in messages}
        for m in messages:
            for i, other in enumerate(m.answered_by):
                if other not in names:
                    self.error(("messages", m.name, "answered_by", i),
                               f"message {m.name!r} is answered by unknown message {other!r}")
        keyed = [m for m in messages if m.dispatch_key]
        if keyed and len(keyed) != len(messages):
            for m in messages:
                if not m.dispatch_key:
                    self.error(("messages", m.name), f"message {m.name!r} has no dispatch value, "
                                                     "but the others do", "give it its dispatch field(s)")
        framing = d["framing"]["kind"]
        offsets: dict[str, tuple[int, str]] = {}
        for m in keyed:
            for f in m.layout:
                if f.dispatch and f.bit_offset is not None and framing == "bits":
                    first = offsets.setdefault(f.name, (f.bit_offset, m.name))
                    if first[0] != f.bit_offset:
                        self.error(("messages", m.name), f"dispatch field {f.name!r} is at bit "
                                   f"{f.bit_offset} here but at bit {first[0]} in {first[1]!r}",
                                   "dispatch fields must sit at the same place in every message")
        if framing == "bits" and keyed and all(m.size for m in keyed):
            # the decoder reads the dispatch fields before it knows the message: every one
            # must lie inside the shortest message
            shortest = min(keyed, key=lambda m: m.size)
            for name, (offset, owner) in offsets.items():
                field = next(f for f in next(m for m in keyed if m.name == owner).layout if f.name == name)
                if offset + (field.bits or 0) > 8 * shortest.size:
                    self.error(("messages", owner), f"dispatch field {name!r} ends at bit "
                               f"{offset + (field.bits or 0)}, past the end of the shortest message "
                               f"{shortest.name!r} ({8 * shortest.size} bits)",
                               "put the dispatch fields first, where every message has them")
                elif offset + (field.bits or 0) > 32:  # a C decoder reads them into a uint32_t
                    self.error(("messages", owner), f"dispatch field {name!r} ends at bit "
                               f"{offset + (field.bits or 0)}; dispatch fields are read from a "
                               "message's first 32 bits", "move the dispatch fields to the front of the message")
        if framing == "bits" and d["framing"].get("text_form"):
            if not keyed:  # with dispatch fields missing somewhere, the error above says where
                self.error(("framing", "text_form"), "a text form finds each line's message from its "
                           "dispatch fields, and no message has any",
                           "give the messages `dispatch: true` const fields, or drop text_form")
            for m in messages:
                for f in (f.element for f in m.layout):  # an array's values are its elements
                    if f.bits and f.bits > 32:  # the C text-form reader holds 32-bit values
                        self.error(("messages", m.name), f"message {m.name!r}: field {f.name!r} has "
                                   f"{f.bits} bits; a text form carries values of at most 32 bits",
                                   "split the field, or drop text_form")
            if keyed:
                self.check_text_form_heads(keyed)
        if framing == "bytes" and len(messages) > 1 and not keyed:
            self.error(("framing", "layout"), f"{len(messages)} messages, but no layout field is marked "
                       "`dispatch: true`: a decoder could not tell them apart",
                       "add an id field marked `dispatch: true` and give each message an `id`")
        elif framing == "bytes":
            self.check_sizes_without_length(messages)
        for i, j in candidate_pairs(keyed, framing):
            a, b = keyed[i], keyed[j]
            if a.direction and b.direction and a.direction != b.direction:
                continue
            if framing == "text" and self.ambiguous(a, b, framing):
                shared = common_prefix(pattern_of(a.ids[0], a.prefix_field), pattern_of(b.ids[0], b.prefix_field))
                self.error(("messages", b.name, "id"),
                           f"ambiguous dispatch: messages {a.name!r} and {b.name!r} both read a line whose "
                           f"prefix is {shared!r} ({self.describe_prefix(a)} / {self.describe_prefix(b)})",
                           "give them ids that no prefix value turns into one another, or list the prefix "
                           "field's `values`")
            elif self.ambiguous(a, b, framing):
                self.error(("messages", b.name),
                           f"ambiguous dispatch: messages {a.name!r} and {b.name!r} cannot be "
                           f"told apart ({self.describe_key(a)} / {self.describe_key(b)})",
                           "give them different ids/constants, directions or sizes")

    def check_text_form_heads(self, messages: list[Message]) -> None:
        """A text-form line is dispatched on the bits of its leading values that hold the
        dispatch fields: they must have the same widths in every message."""
        head = max((f.bit_offset + (f.bits or 0) for m in messages for f in m.layout
                    if f.dispatch and f.bit_offset is not None), default=0)
        if not head:
            return

        def widths(fields) -> list[int]:
            out, used = [], 0
            stack = list(reversed(fields))
            while stack and used < head:
                f = stack.pop()
                if f.kind == "group":
                    stack.extend(reversed(f.fields))
                elif f.bits:
                    out.append(f.bits)
                    used += f.bits
            return out

        first = messages[0]
        expected = widths(first.layout)
        for m in messages[1:]:
            got = widths(m.layout)
            if got != expected:
                self.error(("messages", m.name),
                           f"message {m.name!r}: its text form starts with values of {got} bits, "
                           f"{first.name!r}'s with {expected}; a text line is told apart by its first "
                           f"{head} bits, so the values that hold them must have the same widths in "
                           "every message", "start every message with fields of the same widths")

    def check_sizes_without_length(self, messages: list[Message]) -> None:
        """With no length field, a stream decoder knows a frame's size only from its id."""
        if any(f.length_of for m in messages for f in m.layout) or len({m.size for m in messages}) < 2 \
                or any(m.size is None for m in messages):  # a field without a width says why itself
            return
        # with a checksum, a stream decoder tries each fixed size of an id, smallest first,
        # and takes the first frame whose checksum holds
        checked = any(f.checksum for f in messages[0].layout if f.from_envelope)
        size_of: dict = {}
        for m in messages:  # a counted array's size is read from its count, by direction and id
            counted = bool(m.shortening and m.shortening.counter)
            for value in m.ids or (None,):
                first = size_of.setdefault((m.direction, value) if counted else value, m)
                fixed = not m.shortening and not first.shortening
                if first.sizes != m.sizes and not (fixed and checked):
                    self.error(("messages", m.name), f"message {m.name!r} is {m.size} bytes but {first.name!r}, "
                               f"with the same id, is {first.size}; with no length field a stream decoder "
                               "finds a frame's size from its id" + ("" if checked else ", and with no checksum "
                                                                     "it could not tell one size from another"),
                               "give them different ids, or add a length field (or a checksum) to the framing"
                               if fixed else "give them different ids, or add a length field to the framing")
                    return

    @staticmethod
    def describe_prefix(m: Message) -> str:
        f = m.prefix_field
        if f is None:
            return f"id {m.ids[0]!r}"
        held = "/".join(f.values) if f.values else f"any {f.length} uppercase letters"
        return f"{f.name} ({held}) then id {m.ids[0]!r}"

    @staticmethod
    def describe_key(m: Message) -> str:
        sizes = f"{m.min_size}..{m.size}" if m.shortening else m.size
        return ", ".join(f"{k}={v}" for k, v in m.dispatch_key) + (f", {sizes} bytes" if m.size else "")

    @staticmethod
    def ambiguous(a: Message, b: Message, framing: str) -> bool:
        ka, kb = dict(a.dispatch_key), dict(b.dispatch_key)
        if framing == "bits":
            common = set(ka) & set(kb)
            return all(ka[k] == kb[k] for k in common)
        if framing == "text":  # a prefix field's values before the id: one prefix both read
            if not (isinstance(a.ids[0], str) and isinstance(b.ids[0], str)):
                return False  # an id that is not a string is refused at its line
            return common_prefix(pattern_of(a.ids[0], a.prefix_field), pattern_of(b.ids[0], b.prefix_field)) is not None
        overlap = all(set(ka[k]) & set(kb.get(k, ())) for k in ka)
        if None in (a.min_size, a.size, b.min_size, b.size):
            return False  # a size the layout could not give: its error is reported at the field
        return overlap and a.min_size <= b.size and b.min_size <= a.size
