"""Random valid schemas, each determined by its seed and the feature switches."""
from __future__ import annotations

import copy
import random
import re
import string
from typing import Optional

import yaml

from codeword.text_prefix import Pattern, common_prefix

from .features import DEFAULT
from .machines import MACHINE_SHARE, machine_schema
from .can import CAN_SHARE, can_schema

CRCS = {8: ["CRC-8/SMBUS", "CRC-8/MAXIM-DOW"], 16: ["CRC-16/XMODEM", "CRC-16/MODBUS", "CRC-16/CMS"],
        32: ["CRC-32/ISO-HDLC"]}
# the bytes SLIP, COBS and HDLC escape or stand for (delimiters, escapes, escaped codes)
STUFFED = [0x00, 0xC0, 0xDB, 0xDC, 0xDD, 0x7E, 0x7D, 0x5E, 0x5D]
MAX_ARRAY_BYTES = 4096  # the most bytes an array may hold (compiler/resolver/base.py)
SCALES = [0.5, 0.25, 0.125, 2, 4]  # powers of two: logical values are exact doubles
NAMES = ["alpha", "bravo", "charlie", "delta", "echo", "foxtrot", "golf", "hotel", "india", "juliet",
         "kilo", "lima", "mike", "november", "oscar", "papa", "quebec", "romeo", "sierra", "tango"]


# constants of each float width, its edges among them: every one a value of that width
# (an f32 constant that no binary32 holds is refused at its line; the mutants try those)
FLOAT_CONSTANTS = {
    "f32": [0.0, -0.0, 1.5, -2.25, 2.0 ** -149, 1.1754943508222875e-38, 3.4028234663852886e38, 0.10000000149011612],
    "f64": [0.0, -0.0, 0.1, -1e-310, 5e-324, 1.7976931348623157e308, -2.2250738585072014e-308],
}


def fixed_size(fields: list[dict]) -> bool:
    """Whether fields take the same bytes in every frame: nothing counted, sized by another
    field, optional, conditional or filling the rest of the payload, in groups too."""
    for f in fields:
        if any(isinstance(f.get(key), dict) for key in ("count", "length")) \
                or {"present_if", "optional", "to_end", "max_length"} & set(f):
            return False
        if not fixed_size(f.get("fields", [])):
            return False
    return True


MAVLINK_TYPED = re.compile(r"[ui](8|16|32|64)|f(32|64)")


def mavlink_typed(f: dict) -> bool:
    """Whether MAVLink has a type for a generated field (its crc_extra can be derived):
    an integer of 8..64 bits or a float, an array of at most 255 of them, or bytes of a
    fixed length; an extension field takes no part."""
    if f.get("extension"):
        return True
    if any(k in f for k in ("present_if", "start_bit", "to_end", "multiplexed_by")):
        return False
    count = f.get("count")
    if count is not None and not (isinstance(count, int) and count <= 255):
        return False
    if f.get("type") == "bytes":
        return isinstance(f.get("length"), int)
    return bool(MAVLINK_TYPED.fullmatch(str(f.get("type"))))


class Generator:
    def __init__(self, seed: int, features: frozenset[str] = DEFAULT):
        self.rng = random.Random(seed)
        self.on = features
        self.seed = seed
        self.little = False  # the byte framing's order, once chosen
        self.lsb = False  # bytes framing, least significant bit first: fields cross bytes
        self.enums: dict = {}
        self.flags: dict = {}
        self.directions = False  # messages have directions (an envelope byte depends on them)
        self.used: set[str] = set()
        self.depth = 0  # arrays of groups being generated, one inside another
        # one schema in three: arrays long enough for generated code to loop over their elements
        self.long = "long_arrays" in features and random.Random(f"long_arrays {seed}").random() < 0.3

    def has(self, feature: str, chance: float = 0.5) -> bool:
        return feature in self.on and self.rng.random() < chance

    def name(self) -> str:
        for _ in range(2000):
            candidate = self.rng.choice(NAMES) + ("" if self.rng.random() < 0.5 else f"_{self.rng.randrange(10)}")
            if candidate not in self.used:
                self.used.add(candidate)
                return candidate
        # every name of the pool is taken (a schema of hundreds of fields): number the others
        candidate = f"{self.rng.choice(NAMES)}_{len(self.used)}"
        self.used.add(candidate)
        return candidate

    # -- the document -----------------------------------------------------------------------
    def schema(self) -> dict:
        doc = self.drawn()
        if "nonfinite" in self.on:
            nonfinite_floats(doc, random.Random(f"nonfinite {self.seed}"))
        if "many_messages" in self.on:
            many_messages(doc, random.Random(f"many_messages {self.seed}"))
        return doc

    def drawn(self) -> dict:
        if "machines" in self.on and random.Random(f"machines {self.seed}").random() < MACHINE_SHARE:
            return machine_schema(self)  # its own draw: the other seeds' schemas stay as they were
        if "can" in self.on and random.Random(f"can framing {self.seed}").random() < CAN_SHARE:
            return can_schema(self, placed_signals, multiplexed_signals)
        kinds = [k for k in ("bytes", "text", "bits") if k in self.on] or ["bytes"]
        kind = self.rng.choice(kinds)
        doc: dict = {"codeword": 1, "protocol": f"fz{self.seed}", "title": f"fuzz schema {self.seed}",
                     "source": "fuzz/schema"}
        framing, messages = {"text": self.text, "bytes": self.binary, "bits": self.bits}[kind]()
        if self.enums:
            doc["enums"] = self.enums
        if self.flags:
            doc["flags"] = self.flags
        if self.directions:
            doc["roles"] = {"host": {"doc": "host"}, "device": {"doc": "device"}}
            doc["directions"] = {"up": {"from": "device", "to": "host"}, "down": {"from": "host", "to": "device"}}
        doc["framing"] = framing
        doc["messages"] = messages
        return doc

    # -- bytes framing ----------------------------------------------------------------------
    def binary(self) -> tuple[dict, dict]:
        rng = self.rng
        layout: list[dict] = []
        single = self.has("no_dispatch", 0.2)
        sync = self.has("sync", 0.8)
        self.lsb = self.has("lsb_first", 0.25)
        if self.lsb:  # its 11-bit length holds at most 2,047 bytes: no arrays long enough to loop over
            self.long = False
        if sync:
            layout.append({"name": "sync", "type": "u8", "const": rng.choice([0xA5, 0x55, 0x7E, 0xAA])})
            if self.has("sync2", 0.3):  # a sync of two bytes, such as UBX's B5 62
                layout.append({"name": "sync_b", "type": "u8", "const": rng.choice([0x62, 0x00, 0xA5, 0xFF])})
        two_keys = not single and not self.lsb and self.has("two_keys", 0.3)
        id_bits = 8
        shortens = False  # a length of the payload alone, so frames may be cut short
        if not single:
            length = self.has("length", 0.5)
            if self.lsb:  # an 11-bit length and a 5-bit id share two bytes, as on a CAN-like bus
                id_bits = 5
                if length:
                    layout.append({"name": "len", "type": "u11", "length_of": {"from": "len", "to": "payload"}})
                layout.append({"name": "kind", "type": "u5", "dispatch": True})
                if not length:
                    layout.append(self.padding(3))
            else:
                key = "group" if two_keys else "kind"  # the first dispatch field
                shortens = length and bool({"extension", "truncate", "counted", "conditional"} & self.on) \
                    and rng.random() < 0.8
                if shortens:
                    key = "payload"
                if length:  # arrays make payloads of more than 255 bytes
                    width = "u16" if {"arrays", "counted", "conditional"} & self.on else "u8"
                    layout.append({"name": "len", "type": width, "length_of": {"from": key, "to": "payload"}})
                    if shortens and self.has("length_range", 0.4):  # counting itself (CRSF, MSP v2)
                        layout[-1]["length_of"] = {"from": "len", "to": "payload", "adjust": rng.randint(-1, 3)}
                if two_keys:  # messages told apart by a group and a kind, as UBX's class and id
                    layout.append({"name": "group", "type": rng.choice(["u8", "u4"]), "dispatch": True})
                    layout.append({"name": "kind", "type": "u8" if layout[-1]["type"] == "u8" else "u4",
                                   "dispatch": True})
                else:
                    layout.append({"name": "kind", "type": self.id_type(), "dispatch": True})
            self.directions = self.has("by_direction", 0.25)
            if self.directions:  # a byte that says the direction, as MSP's `<` and `>`
                # next to the other dispatch fields: a key is read from at most 4 bytes
                first = next(i for i, f in enumerate(layout) if f.get("dispatch"))
                layout.insert(rng.choice([first, len(layout)]) if not sync else len(layout),
                              {"name": "mark", "type": "u8", "by_direction": {"up": 0x3E, "down": 0x3C}})
        elif "single_length" in self.on:
            shortens = self.single_length(layout)
        layout.append({"payload": True})
        algorithms = [a for a in ("sum", "xor", "crc", "fletcher") if a in self.on]
        if algorithms and (sync or not single) and rng.random() < 0.7:  # `from: payload` is its end
            algorithm = rng.choice(algorithms)
            first = layout[1 if sync else 0]["name"] if not single else ("sync" if sync else "payload")
            if algorithm == "crc":
                width = rng.choice(sorted(CRCS))
                check = {"algorithm": self.crc_name(rng.choice(CRCS[width])),
                         "covers": {"from": first, "to": "payload"}}
                if self.has("crc_extra", 0.3):  # each message's byte after the coverage (MAVLink)
                    check["extra"] = "message"
            elif algorithm == "fletcher":  # sums modulo 2**(width/2) - 1 (classic) or 2**(width/2)
                width = rng.choice([8, 16])
                check = {"algorithm": algorithm, "modulo": (1 << width // 2) - rng.randint(0, 1),
                         "covers": {"from": first, "to": "payload"}}
            else:
                width = rng.choice([8, 16])
                check = {"algorithm": algorithm, "covers": {"from": first, "to": "payload"}}
                width = self.final_step(check, width)
            layout.append({"name": "check", "type": f"u{width}", "checksum": check})
            self.internet_checksum(layout[-1])
            counter = next((f for f in layout if f.get("length_of", {}).get("adjust") is not None), None)
            if counter is not None and rng.random() < 0.5:  # and the checksum after the payload
                counter["length_of"]["to"] = "check"
            self.checksum_in_place(layout)
        self.end_marker(layout)
        self.little = self.lsb or self.has("little")
        framing = {"kind": "bytes", "byte_order": "little" if self.little else "big", "layout": layout}
        if shortens and self.has("truncate", 0.35):
            framing["truncate"] = "trailing_zeros"
        if self.lsb:
            framing["bit_order"] = "lsb_first"
            if rng.random() < 0.5:  # little-endian is its default
                del framing["byte_order"]
        count = 1 if single else rng.randint(1, 4)
        if two_keys:  # few values of each, so that messages share a group or a kind
            ids = [{"group": g, "kind": k} for g, k in rng.sample([(g, k) for g in range(3) for k in range(3)], count)]
        else:
            ids = rng.sample(range(1 << id_bits), count)
        messages = {}
        for i in range(count):
            body: dict = {} if single else {"id": ids[i]}
            if self.directions:
                body["direction"] = rng.choice(["up", "down"])
            body["fields"] = self.binary_fields(at_least=1 if single else 0)  # a frame is never empty
            gapped = ({"counted", "conditional"} & self.on) and "truncate" not in framing
            if shortens and gapped and rng.random() < 0.7:
                body["fields"] = self.gapped_fields(body["fields"])
            elif shortens and self.has("extension", 0.6):
                body["fields"] += self.extension_fields()
            elif not shortens and not single and not any("length_of" in f for f in layout) \
                    and self.has("counted", 0.25):
                body["fields"] += self.counted_fields()
            self.named_payload(body["fields"])
            self.float_constants(body["fields"], layout)
            messages[self.name()] = body
        self.share_an_id(messages, layout)
        self.ids_across_directions(messages)
        if any(f.get("checksum", {}).get("extra") for f in layout):
            for body in messages.values():
                body["crc_extra"] = rng.randrange(256)
        if self.has("encoding", 0.4):
            self.encode_frames(framing, messages, ids if not two_keys and not single and id_bits == 8 else None)
        if not any("length_of" in f for f in layout) and "encoding" not in framing and "large_frame" in self.on:
            self.large_frame(messages)  # a length field or an encoding holds less
        if "mixed_bit_order" in self.on and "truncate" not in framing:
            self.mixed_bit_order(messages)
        if "multiplexed" in self.on and "truncate" not in framing:
            self.multiplexed(messages)
        self.pattern_stuffing(framing, messages)  # after them: it widens a message they leave as it is
        self.signed_trailer(framing)
        self.derived_crc_extra(layout, messages)  # last: the fields are then those the messages keep
        return framing, messages

    def derived_crc_extra(self, layout: list, messages: dict) -> bool:
        """Where the CRC takes an extra byte and every message's fields have MAVLink types, at
        times that byte is derived from each message's definition as MAVLink's CRC_EXTRA is
        (`extra: mavlink`, the declared values dropped), with some messages and fields under a
        `mavlink_name`; whether it was."""
        own = random.Random(f"derived_crc_extra {self.seed}")
        if "derived_crc_extra" not in self.on or not any(f.get("checksum", {}).get("extra") for f in layout) \
                or own.random() >= 0.8 or not all(isinstance(body["fields"], list)
                                                  and all(map(mavlink_typed, body["fields"])) for body in messages.values()):
            return False
        for f in layout:
            if f.get("checksum", {}).get("extra"):
                f["checksum"]["extra"] = "mavlink"
        for name, body in messages.items():
            del body["crc_extra"]  # derived
            if own.random() < 0.3:
                body["mavlink_name"] = f"{name.upper()}_{own.randrange(100)}"
            for f in body["fields"]:
                if own.random() < 0.2:
                    f["mavlink_name"] = f"{f['name']}_{own.choice(['raw', 'mav', 'x'])}"
        return True

    def single_length(self, layout: list[dict]) -> bool:
        """In two schemas of five of one message, a length field before the payload (a lone
        sensor's reports): stream decoders size its frames by it, and it may let them be cut
        short (the result says whether). Drawn from a generator of its own, so the other
        schemas of a seed stay as they were."""
        own = random.Random(f"single_length {self.seed}")
        if own.random() >= 0.4 or self.lsb:
            return False
        wide = bool({"arrays", "counted", "conditional"} & self.on)  # payloads of more than 255 bytes
        layout.append({"name": "len", "type": "u16" if wide else own.choice(["u8", "u16"]),
                       "length_of": {"from": "payload", "to": "payload"}})
        return bool({"extension", "truncate", "conditional"} & self.on) and own.random() < 0.6

    def mixed_bit_order(self, messages: dict) -> None:
        """In one schema of three, some messages become CAN-style payloads of 1 to 8 bytes:
        signals of both byte orders at random DBC start bits, 1 to 64 bits wide, signed or
        not, some scaled, never overlapping, with unused bits between them. Messages that
        share an id keep their fields (their sizes tell them apart). Drawn from a generator
        of its own, so the other schemas of a seed stay as they were."""
        own = random.Random(f"mixed_bit_order {self.seed}")
        if own.random() >= 0.35:
            return
        ids = [repr(body.get("id")) for body in messages.values()]
        for body in messages.values():
            if ids.count(repr(body.get("id"))) > 1 or own.random() < 0.3:
                continue
            size = own.randint(1, 8)
            body["payload_bytes"] = size
            floats = random.Random(f"placed_float {self.seed}") if "placed_float" in self.on else None
            body["fields"] = placed_signals(own, size, floats)

    def multiplexed(self, messages: dict) -> None:
        """In one schema of three, some messages become multiplexed CAN payloads: a
        multiplexor whose values select groups of signals sharing bits, signals carried for
        several values or a range, multiplexed multiplexors, plain signals beside them.
        Drawn from a generator of its own, so the other schemas of a seed stay as they were."""
        own = random.Random(f"multiplexed {self.seed}")
        if own.random() >= 0.35:
            return
        ids = [repr(body.get("id")) for body in messages.values()]
        for body in messages.values():
            if ids.count(repr(body.get("id"))) > 1 or own.random() < 0.4:
                continue
            size = own.randint(1, 8)
            body["payload_bytes"] = size
            body["fields"] = multiplexed_signals(own, size)


    # (pattern, inserted byte) pairs a receiver reads back one way: Dynamixel's, a sync
    # byte's, two-byte ones and one that shares a byte with the pattern's end
    PATTERNS = [("FF FF FD", 0xFD), ("AA", 0x00), ("7E", 0x7D), ("C0 DB", 0xDB), ("55 AA", 0x01), ("00", 0xFF)]

    def pattern_stuffing(self, framing: dict, messages: dict) -> None:
        """In three schemas of five that have a length field of whole bytes and no other
        stuffing: a byte inserted after a pattern in the bytes from the first dispatch field
        (or the payload) through the payload, the length field widened to count it, and a
        message a few bytes more, so the pattern fits (the vectors hold frames that need
        stuffing). Drawn from a generator of its own, so the other
        schemas of a seed stay as they were."""
        own = random.Random(f"pattern_stuffing {self.seed}")
        layout = framing["layout"]
        length = next((f for f in layout if "length_of" in f), None)
        plain = sorted(n for n, m in messages.items() if "payload_bytes" not in m)  # not placed by start bit
        if "pattern_stuffing" not in self.on or own.random() >= 0.6 or length is None or self.lsb \
                or "encoding" in framing or "truncate" in framing or not plain \
                or any(f.get("checksum", {}).get("extra") for f in layout):
            return
        names = [f.get("name", "payload") if not f.get("payload") else "payload" for f in layout]
        first = length["length_of"]["from"]
        start = names.index(first) if first in names else names.index("payload")
        after_length = names.index(length["name"]) + 1
        keys = [i for i, f in enumerate(layout) if f.get("dispatch") and i >= max(start, after_length)]
        begin = names[keys[0]] if keys and layout[keys[0]]["type"] == "u8" and own.random() < 0.7 else "payload"
        if any("checksum" in f for f in layout[names.index(begin):names.index("payload")]):
            begin = "payload"  # a checksum moved before the payload stays outside the stuffed bytes
        pattern, insert = own.choice(self.PATTERNS)
        length["type"] = "u16"  # room for the bytes inserted
        framing["stuffing"] = {"after": pattern, "insert": insert, "covers": {"from": begin, "to": "payload"}}
        body = messages[own.choice(plain)]  # a message whose frames the pattern fits
        body["fields"].insert(0, {"name": "pattern_room", "type": "bytes", "length": own.randint(3, 6)})

    def crc_name(self, name: str) -> str:
        """The catalogue name, or one of its aliases that names nothing else, in any case."""
        if not self.has("crc_alias", 0.5):
            return name
        from codeword import crc
        aliases = sorted(k for k, p in crc.catalogue().items() if p.name == name and crc.lookup(k) is not None)
        if not aliases:
            return name
        chosen = self.rng.choice(aliases)
        return self.rng.choice([chosen, chosen.lower(), chosen.title()])

    def share_an_id(self, messages: dict, layout: list[dict]) -> None:
        """With no length field but a checksum, a second message with the first one's id and
        a byte more: stream decoders try each size of the id, as Modbus RTU's are found."""
        bodies = list(messages.values())
        if len(bodies) < 2 or any("length_of" in f for f in layout) or not any("checksum" in f for f in layout) \
                or not self.has("shared_id", 0.4):
            return
        first, second = bodies[0], bodies[1]
        if not fixed_size(first["fields"]):
            return
        second["id"] = first["id"]
        second["fields"] = copy.deepcopy(first["fields"]) + [{"name": self.name(), "type": "u8"}]

    def ids_across_directions(self, messages: dict) -> None:
        """Sometimes a message takes another's id (or prefix) in the other direction, as a
        reply shares its request's command number: decoders need the direction to tell."""
        rng = random.Random(f"direction_ids {self.seed}")
        bodies = list(messages.values())
        if "direction_ids" not in self.on or not self.directions or len(bodies) < 2 or rng.random() < 0.5:
            return
        if len({repr(b.get("id")) for b in bodies}) < len(bodies):  # one id at two sizes already
            return
        first, second = rng.sample(bodies, 2)
        second["id"] = copy.deepcopy(first["id"])
        second["direction"] = "up" if first["direction"] == "down" else "down"

    def text_directions(self, messages: dict) -> None:
        """Sometimes text messages get directions, and one prefix is used in both."""
        rng = random.Random(f"text directions {self.seed}")
        if "direction_ids" not in self.on or rng.random() < 0.6:
            return
        self.directions = True
        for body in messages.values():
            body["direction"] = rng.choice(["up", "down"])
        self.ids_across_directions(messages)

    def internet_checksum(self, check: dict) -> None:
        """Sometimes the frame's checksum becomes RFC 1071's, on a u16 in either byte order."""
        own = random.Random(f"internet {self.seed}")
        if "internet" not in self.on or "extra" in check["checksum"] or own.random() >= 0.3:
            return
        check["type"] = "u16"
        check["checksum"] = {"algorithm": "internet", "covers": check["checksum"]["covers"]}
        if "field_order" in self.on and own.random() < 0.4:
            check["byte_order"] = own.choice(["big", "little"])

    def checksum_in_place(self, layout: list[dict]) -> None:
        """Sometimes an internet checksum moves into its coverage, just before the payload,
        as IPv4's header checksum: there when it sits a whole 16-bit word from the start."""
        own = random.Random(f"internet in place {self.seed}")
        check = layout[-1]
        if check.get("checksum", {}).get("algorithm") != "internet" or own.random() >= 0.5 \
                or any(f.get("length_of", {}).get("to") == "check" for f in layout):
            return
        names = [f.get("name") for f in layout]
        first = check["checksum"]["covers"]["from"]
        if first not in names:
            return
        widths = [int(f["type"][1:]) for f in layout[names.index(first):-2]]
        if sum(widths) % 16 == 0:
            layout.insert(len(layout) - 2, layout.pop())

    def end_marker(self, layout: list[dict]) -> None:
        """A constant byte after the payload (and its checksum) that closes each frame, as
        tr24's stop byte: no part of the sync, even right after it."""
        if self.has("end_marker", 0.3):
            layout.append({"name": "end_mark", "type": "u8", "const": self.rng.choice([0x03, 0x0A, 0x55, 0xAA, 0x7E])})

    def large_frame(self, messages: dict) -> None:
        """In one schema of 40, fields of 4 KiB (the most a field holds) first in a message:
        its frame is over 64 KiB, and the fields after them lie past bit 65,535. Drawn from
        a generator of its own, so the other schemas of a seed stay as they were."""
        own = random.Random(f"large_frame {self.seed}")
        if own.random() >= 0.025:
            return
        body = messages[own.choice(sorted(messages))]
        body["fields"][:0] = [{"name": f"block_{i}", "type": "bytes", "length": 4096} for i in range(17)]

    def signed_trailer(self, framing: dict) -> None:
        """A flags byte before the payload whose flag puts a trailer after the frame: numbers
        and a truncated SHA-256 over a key and the frame's bytes (MAVLink 2's signing), in
        three schemas of five that have a length field and no byte or pattern stuffing. Drawn from a
        generator of its own, so the other schemas of a seed stay as they were."""
        own = random.Random(f"signed_trailer {self.seed}")
        layout = framing["layout"]
        if "signed_trailer" not in self.on or own.random() >= 0.6 or self.lsb or "encoding" in framing \
                or "stuffing" in framing or not any("length_of" in f for f in layout):
            return
        layout.insert(next(i for i, f in enumerate(layout) if f.get("payload")),
                      {"name": "trailer_flags", "type": "u8", "flags": "trailer_set"})
        self.flags["trailer_set"] = {"type": "u8", "bits": [{"name": "signing", "bit": own.randrange(8)}]}
        numbers = [{"name": name, "type": own.choice(["u8", "u16", "u24", "u32", "u48", "u64"])}
                   for name in ("link_no", "stamp")[:own.randint(1, 2)]]
        for f in numbers:
            if f["type"] != "u8" and own.random() < 0.3:
                f["byte_order"] = own.choice(["big", "little"])
        signature = {"name": "mac", "type": "bytes", "length": own.randint(1, 32),
                     "signature": {"algorithm": "SHA-256", "key_length": own.randint(1, 64),
                                   "covers": {"from": own.choice(self.whole_head(layout)),
                                              "to": own.choice(numbers)["name"]}}}
        after = [{"name": "tail_no", "type": "u8"}] if own.random() < 0.3 else []
        framing["trailer"] = {"present_if": {"field": "trailer_flags", "has": "signing"},
                              "fields": numbers + [signature] + after}

    @staticmethod
    def whole_head(layout: list[dict]) -> list[str]:
        """The layout's leading fields of whole bytes, each at a whole byte: where hashed bytes may start."""
        out = []
        for f in layout:
            if f.get("payload") or f["type"] not in ("u8", "u16"):
                break
            out.append(f["name"])
        return out

    def final_step(self, check: dict, width: int) -> int:
        """A sum's complement (in 8, 16, 32 or 64 bits) and a sum's or xor's xorout; the width."""
        rng = self.rng
        if "complement" not in self.on or rng.random() < 0.5:
            return width
        if check["algorithm"] == "sum" and rng.random() < 0.7:
            check["complement"] = rng.choice(["ones", "twos"])
            width = rng.choice([width, 32, 64])
        if rng.random() < 0.5:
            check["xorout"] = rng.randrange(1 << width)
        return width

    def encode_frames(self, framing: dict, messages: dict, ids: list | None) -> None:
        """Byte stuffing on the link, and frames that hold the bytes it escapes: each
        message starts with one as a constant, and ids are often one."""
        rng = self.rng
        framing["encoding"] = rng.choice(["slip", "cobs", "hdlc"])
        free = [b for b in STUFFED if ids is None or b not in ids]
        for body in messages.values():
            body["fields"].insert(0, {"name": self.name(), "type": "u8", "const": rng.choice(STUFFED)})
            if ids is not None and free and rng.random() < 0.5:
                body["id"] = free.pop(rng.randrange(len(free)))
        self.control_map(framing, messages)

    def control_map(self, framing: dict, messages: dict) -> None:
        """HDLC: often an async control character map (PPP's, XON/XOFF or any), and frames
        that start with a mapped character."""
        own = random.Random(f"accm {self.seed}")
        if framing["encoding"] != "hdlc" or own.random() < 0.4:
            return
        framing["accm"] = own.choice([0xFFFFFFFF, 0x000A0000, own.getrandbits(32) | 1])
        mapped = [c for c in range(32) if framing["accm"] >> c & 1]
        for body in messages.values():
            if own.random() < 0.5:
                body["fields"][0]["const"] = own.choice(mapped)

    def binary_fields(self, at_least: int = 0) -> list[dict]:
        return self.sized_fields(at_least)[0]

    def sized_fields(self, at_least: int = 0) -> tuple[list[dict], int]:
        """Fields of whole bytes start on a byte; narrower ones do not cross one, but
        least significant bit first little-endian integers of any width may; and their
        bits, a whole number of bytes."""
        rng = self.rng
        fields, bits = [], 0
        for _ in range(rng.randint(at_least, 5)):
            field, width = self.binary_field()
            room = 8 - bits % 8
            crosses = self.lsb and field["type"][0] in "ui" and field.get("byte_order", "little") == "little"
            if bits % 8 and (width >= 8 or width > room) and not crosses:
                fields.append(self.padding(room))
                bits += room
            fields.append(field)
            bits += width
        if bits % 8:
            fields.append(self.padding(8 - bits % 8))
            bits += 8 - bits % 8
        return fields, bits

    def counted_fields(self) -> list[dict]:
        """A count and the array it counts, last in the payload (Modbus's byte count and
        its registers): the count in elements or in bytes, up to a maximum; or a bytes
        field whose length the count gives."""
        rng = self.rng
        count = self.name()
        if rng.random() < 0.3:
            most = rng.choice([rng.randint(1, 20), 300])
            return [{"name": count, "type": "u8" if most < 256 else "u16"},
                    {"name": self.name(), "type": "bytes", "length": {"from": count}, "max_length": most}]
        element = rng.choice(["u8", "u16", "i16", "u32"])
        unit = rng.choice(["elements", "bytes"])
        max_count = rng.randint(1, 20)
        most = max_count * (int(element[1:]) // 8 if unit == "bytes" else 1)
        return [{"name": count, "type": "u8" if most < 256 else "u16"},
                {"name": self.name(), "type": element, "count": {"from": count, "unit": unit},
                 "max_count": max_count}]

    def gapped_fields(self, fields: list[dict]) -> list[dict]:
        """Counted arrays (of numbers or groups, checked or not) and conditional fields between
        runs of whole bytes, their control fields first: a frame leaves out what they say."""
        rng = self.rng
        controls: list[dict] = []
        out = list(fields)
        for _ in range(rng.randint(1, 3)):
            kinds = [k for k in ("counted", "conditional") if k in self.on]
            if rng.choice(kinds) == "counted":
                control, gap = self.counted_gap()
            else:
                control, gap = self.conditional_gap()
            controls += control
            out += [gap] + self.binary_fields()
        if "counted" in self.on and rng.random() < 0.3:  # and the rest of the payload
            element, _ = self.number_field()
            if rng.random() < 0.4:
                out.append({"name": self.name(), "type": "bytes", "to_end": True, "max_length": rng.randint(1, 20)})
            else:
                out.append({**element, "to_end": True, "max_count": rng.randint(1, 6)})
        return controls + out

    def counted_gap(self) -> tuple[list[dict], dict]:
        """A count (in elements or bytes) and an array of numbers or of a group that it counts."""
        rng = self.rng
        count, max_count = self.name(), rng.randint(4, 40) if self.long else rng.randint(1, 6)
        element, size = None, 0
        if rng.random() < 0.4:  # a group of whole bytes, checked members included
            fields, bits = self.sized_fields(at_least=1)
            size = bits // 8
            if size <= MAX_ARRAY_BYTES:
                element, unit = {"name": self.name(), "type": "group", "fields": fields}, "elements"
                # the whole array within its most bytes, and within the 4,096 values an array may hold
                max_count = min(max_count, MAX_ARRAY_BYTES // size, max(1, 4096 // values_in(element)))
        if element is None:
            element, _ = self.number_field()
            size, unit = int(element["type"][1:]) // 8, rng.choice(["elements", "bytes", 2])
            if unit == 2 and size == 1:  # whole 2-byte units of single bytes
                max_count += max_count % 2
        most = max_count * size // {"elements": size, "bytes": 1}.get(unit, unit)
        return ([{"name": count, "type": "u8" if most < 256 else "u16"}],
                {**element, "count": {"from": count, "unit": unit}, "max_count": max_count})

    def conditional_gap(self) -> tuple[list[dict], dict]:
        """A control field (flags with a named bit, or a plain or enum value) and a field of
        whole bytes sent only when it says so."""
        rng = self.rng
        name = self.name()
        if rng.random() < 0.5:
            fields, bits = self.sized_fields(at_least=1)
            gap = {"name": self.name(), "type": "group", "fields": fields}
        else:
            gap, bits = self.number_field()
        if self.long and rng.random() < 0.5:  # an array sent whole or not at all
            gap["count"] = min(rng.randint(2, 24), max(1, MAX_ARRAY_BYTES * 8 // bits))
        if "flags" in self.on and rng.random() < 0.5:
            flag_set = self.flag_set(8)
            control = {"name": name, "type": "u8", "flags": flag_set}
            gap["present_if"] = {"field": name, "has": rng.choice(self.flags[flag_set]["bits"])["name"]}
            return [control], gap
        width = rng.choice([8, 4])
        control = [{"name": name, "type": f"u{width}"}] + ([self.padding(4)] if width == 4 else [])
        values = rng.sample(range(1 << width), rng.randint(1, 3))
        gap["present_if"] = {"field": name, "equals": values if len(values) > 1 else values[0]}
        return control, gap

    def number_field(self) -> tuple[dict, int]:
        """A number of whole bytes, sometimes with a range."""
        rng = self.rng
        kind = rng.choice(["u8", "i8", "u16", "i16", "u32", "f32"])
        field = {"name": self.name(), "type": kind}
        if kind[0] != "f" and "range" in self.on and rng.random() < 0.3:
            field["range"] = [0, 100]
        return field, int(kind[1:])

    def extension_fields(self) -> list[dict]:
        """Fields a later version of the message added at its end, of whole bytes."""
        fields = [{"name": self.name(), "type": self.rng.choice(["u8", "u16", "i16", "u32", "i32"]), "extension": True}
                  for _ in range(self.rng.randint(1, 3))]
        return fields + self.extension_arrays()

    def id_type(self) -> str:
        """A one-byte id, or one of three bytes (MAVLink 2's msgid): a constant of an odd number
        of bytes, which decoders compare as bytes."""
        own = random.Random(f"wide_id {self.seed}")
        return "u24" if "wide_id" in self.on and own.random() < 0.3 else "u8"

    def named_payload(self, fields: list[dict]) -> None:
        """A first field named `payload`, as the envelope's payload marker is (MAVLink's
        TUNNEL.payload): tools that look fields up by name must not take one for the other."""
        own = random.Random(f"payload_name {self.seed} {len(self.used)}")
        if "payload_name" not in self.on or own.random() < 0.8 or "payload" in self.used \
                or any("start_bit" in f for f in fields):
            return
        self.used.add("payload")
        kind = own.choice(["u8", "u16", "i32"])
        fields.insert(0, {"name": "payload", "type": kind, "count": own.randint(2, 9)} if own.random() < 0.5
                      else {"name": "payload", "type": kind})

    def extension_arrays(self) -> list[dict]:
        """An array or bytes added as an extension (MAVLink's AUTOPILOT_VERSION.uid2): a frame
        that ends before it reads it as zeros."""
        own = random.Random(f"extension_arrays {self.seed} {len(self.used)}")
        if "extension_arrays" not in self.on or own.random() < 0.6:
            return []
        n = own.randint(1, 6)
        if own.random() < 0.3:
            return [{"name": self.name(), "type": "bytes", "length": n, "extension": True}]
        return [{"name": self.name(), "type": own.choice(["u8", "u16", "i32", "f32"]), "count": n, "extension": True}]

    def padding(self, width: int) -> dict:
        return {"name": self.name(), "type": f"u{width}", "reserved": True}

    def array(self, element: dict, width: int, room: int = 8 * 4096) -> tuple[dict, int]:
        """The field as an array of a few elements (as many as fit `room` bits), each
        where the one before it ends; an array holds at most 4096 bytes."""
        counts = [1, 2, 3, 4, 16] + ([8, 12, 40] if self.long else [])
        # nor more than 4096 values in all (the resolver's limit): an element may hold arrays itself
        count = min(self.rng.choice(counts), max(1, room // width), max(1, 4096 // values_in(element)))
        return {**element, "count": count}, count * width

    def binary_field(self) -> tuple[dict, int]:
        rng = self.rng
        if self.depth < 2 and self.has("arrays", 0.3 if self.long else 0.1):  # an array of a scalar or of a group of whole bytes
            self.depth += 1
            if rng.random() < 0.3:
                fields, width = self.sized_fields(at_least=1)
                element = {"name": self.name(), "type": "group", "fields": fields}
            else:
                element, width = self.binary_scalar()
            self.depth -= 1
            return self.array(element, width)
        return self.binary_scalar()

    def binary_scalar(self) -> tuple[dict, int]:
        rng = self.rng
        name = self.name()
        choice = rng.random()
        if choice < 0.1 and "enum" in self.on:
            width = rng.choice([2, 3, 4, 8]) if "bitfields" in self.on else 8
            return {"name": name, "type": f"u{width}", "enum": self.enum(width)}, width
        if choice < 0.2 and "flags" in self.on:
            width = rng.choice([3, 8, 16]) if "bitfields" in self.on else rng.choice([8, 16])
            return {"name": name, "type": f"u{width}", "flags": self.flag_set(width)}, width
        if choice < 0.27 and "bool" in self.on:
            return {"name": name, "type": "bool"}, 1
        if choice < 0.34 and "bytes_field" in self.on:
            length = rng.randint(1, 4)
            return {"name": name, "type": "bytes", "length": length}, 8 * length
        if choice < 0.41 and "f32" in self.on:
            return self.binary32(name), 32
        if choice < 0.46 and "f64" in self.on:
            return self.binary64(name), 64
        return self.integer(name)

    def float_constants(self, fields: list[dict], layout: list[dict]) -> None:
        """`float_const`: some f32 and f64 fields of a message made constants (their IEEE 754
        bits on the wire), and at times a sum or xor over the message's fields before them,
        which adds those bits in. A generator of its own, so other seeds draw as before."""
        if "float_const" not in self.on:
            return
        own = random.Random(f"float_const {self.seed} {len(fields)}")
        made = False
        for f in fields:
            given = {"count", "to_end", "max_count", "present_if", "multiplexed_by", "extension"} & set(f)
            if f.get("type") in ("f32", "f64") and not given and own.random() < 0.4:  # a scalar always sent
                f.pop("range", None)
                f["const"] = own.choice(FLOAT_CONSTANTS[f["type"]] + [own.randint(-99999, 99999) / 8])
                made = True
        plain = all(not ({"count", "to_end", "present_if", "extension", "length_of", "counts"} & set(f))
                    and f.get("type") != "bytes" for f in fields)  # a sum over fields adds numbers
        checked = any("checksum" in f for f in layout)  # a sum over every field would cover it
        if made and plain and not checked and own.random() < 0.5:
            width, name = own.choice([8, 16]), f"field_sum_{len(self.used)}"  # not drawn: the names stay as they were
            self.used.add(name)
            fields.insert(0, {"name": name, "type": f"u{width}",
                              "checksum": {"algorithm": own.choice(["sum", "xor"]), "modulo": 1 << width,
                                           "over": "fields", "covers": "all"}})

    def binary32(self, name: str) -> dict:
        """An f32 field, sometimes with a range: integer ends (C spells them as float
        literals), decimals that fall between floats, or integers past 2**24."""
        rng = self.rng
        field: dict = {"name": name, "type": "f32"}
        if self.has("f32_range", 0.4):
            kind = rng.random()
            if kind < 0.5:
                ends = [rng.randint(-1000, 1000) for _ in range(2)]
            elif kind < 0.8:
                ends = [round(rng.uniform(-1e4, 1e4), rng.randint(1, 4)) for _ in range(2)]
            else:
                ends = [rng.randint(-(1 << 40), 1 << 40) for _ in range(2)]
            field["range"] = sorted(ends)
        return field

    def binary64(self, name: str) -> dict:
        """An f64 field: sometimes in its own byte order, sometimes with a range
        (ends that are decimals or integers, which may fall between doubles)."""
        rng = self.rng
        field: dict = {"name": name, "type": "f64"}
        if self.has("field_order", 0.2):
            field["byte_order"] = rng.choice(["big", "little"])
        if self.has("range", 0.4):
            ends = [round(rng.uniform(-1e6, 1e6), rng.randint(0, 6)) for _ in range(2)]
            if rng.random() < 0.3:
                ends = [rng.randint(-(1 << 60), 1 << 60) for _ in range(2)]
            field["range"] = sorted(ends)
        return field

    def integer(self, name: str) -> tuple[dict, int]:
        rng = self.rng
        signed = self.has("signed")
        if self.has("wide", 0.15):  # little-endian fields are whole bytes, unless lsb first
            width = rng.choice([40, 48, 56, 64]) if self.little and not self.lsb else rng.randint(33, 64)
        elif "bitfields" in self.on and rng.random() < 0.4:
            width = rng.randint(1, 31 if self.lsb else 7)  # i1 holds -1 and 0
        else:
            width = rng.choice([8, 16, 24, 32])
        field: dict = {"name": name, "type": f"{'i' if signed else 'u'}{width}"}
        if width % 8 == 0 and width > 8 and self.has("field_order", 0.2):
            field["byte_order"] = rng.choice(["big", "little"])
        lo, hi = (-(1 << (width - 1)), (1 << (width - 1)) - 1) if signed else (0, (1 << width) - 1)
        scale = rng.choice(SCALES) if width <= 53 and self.has("scale", 0.3) else None
        offset = rng.choice([-100, 1, 1000]) if width <= 53 and self.has("offset", 0.15) else None
        if scale is not None:
            field["scale"] = scale
        if offset is not None:
            field["offset"] = offset
        if self.has("range", 0.3):
            a, b = sorted(rng.randint(lo, hi) for _ in range(2))
            field["range"] = [a * (scale or 1) + (offset or 0), b * (scale or 1) + (offset or 0)]
        return field, width

    def enum(self, width: int, text: bool = False) -> str:
        rng = self.rng
        name = self.name()
        if text and rng.random() < 0.5:
            chars = rng.sample(string.ascii_lowercase, rng.randint(2, 5))
            self.enums[name] = {"type": "char", "values": [{"name": self.name(), "value": c} for c in chars]}
            return name
        values = rng.sample(range(1 << min(width, 8)), rng.randint(2, min(5, 1 << min(width, 8))))
        self.enums[name] = {"type": f"u{width}", "values": [{"name": self.name(), "value": v} for v in sorted(values)]}
        if "open_enum" in self.on and random.Random(f"open_enum {self.seed} {name}").random() < 0.35:
            self.enums[name]["open"] = True  # values no member has decode as numbers
        return name

    def flag_set(self, width: int) -> str:
        name = self.name()
        bits = sorted(self.rng.sample(range(width), self.rng.randint(1, min(width, 6))))
        self.flags[name] = {"type": f"u{width}", "bits": [{"name": self.name(), "bit": b} for b in bits]}
        return name

    # -- bits framing -----------------------------------------------------------------------
    def bits(self) -> tuple[dict, dict]:
        """Bit records: every message exactly `word_bits` long, or fitting `max_bits`;
        a leading dispatch field of a few bits; bit fields of any width; a checksum
        over the fields (parity, sum or xor); an optional text form."""
        rng = self.rng
        exact = rng.random() < 0.5
        word = rng.choice([8, 16, 24, 32] + ([40, 48, 64] if "wide" in self.on else []))
        framing: dict = {"kind": "bits", "word_bits" if exact else "max_bits": word, "byte_order": "big"}
        if self.has("text_form", 0.3):
            framing["text_form"] = {"separator": " ", "comment": "#"}
        count = 1 if word <= 8 else rng.randint(1, 4)
        tag_bits = max(1, (count - 1).bit_length()) + rng.randint(0, 2)
        tags = rng.sample(range(1 << tag_bits), count)
        messages = {}
        for tag in tags:
            fields: list[dict] = [{"name": "tag", "type": f"u{tag_bits}", "const": tag, "dispatch": True}]
            room = word - tag_bits
            if "field_sum" in self.on and room >= 2 and rng.random() < 0.4:
                fields.append(self.field_checksum())
                room -= int(fields[-1]["type"][1:])
            while room > 0 and rng.random() < 0.85:
                field, width = self.bit_field(min(room, 32))
                if width < room and self.has("arrays", 0.15):  # consecutive values of one field
                    field, width = self.array(field, width, room)
                fields.append(field)
                room -= width
            while exact and room:  # in pieces of at most 32 bits, as a text form needs
                fields.append(self.padding(min(room, 32)))
                room -= min(room, 32)
            body: dict = {"fields": fields}
            if exact:
                body["bits"] = word
            messages[self.name()] = body
        return framing, messages

    def field_checksum(self) -> dict:
        rng = self.rng
        kind = rng.choice(["parity", "sum", "xor"])
        if kind == "parity":
            return {"name": self.name(), "type": "u1",
                    "checksum": {"algorithm": "parity", "parity": rng.choice(["even", "odd"]), "covers": "all"}}
        width = rng.randint(2, 4)
        return {"name": self.name(), "type": f"u{width}",
                "checksum": {"algorithm": kind, "modulo": 1 << width, "over": "fields", "covers": "all"}}

    def bit_field(self, room: int) -> tuple[dict, int]:
        rng = self.rng
        name = self.name()
        choice = rng.random()
        if choice < 0.12 and "enum" in self.on and room >= 2:
            width = rng.randint(2, min(room, 8))
            return {"name": name, "type": f"u{width}", "enum": self.enum(width)}, width
        if choice < 0.22 and "flags" in self.on and room >= 2:
            width = rng.randint(2, min(room, 12))
            return {"name": name, "type": f"u{width}", "flags": self.flag_set(width)}, width
        if choice < 0.3 and "bool" in self.on:
            return {"name": name, "type": "bool"}, 1
        if choice < 0.38 and "one_hot" in self.on and room >= 2:
            width = rng.randint(2, min(room, 16))
            lo = rng.randrange(width)
            return {"name": name, "type": f"u{width}", "one_hot": True,
                    "range": [lo, rng.randint(lo, width - 1)]}, width
        signed = self.has("signed")
        width = rng.randint(1, room)
        field: dict = {"name": name, "type": f"{'i' if signed else 'u'}{width}"}
        if width <= 53 and self.has("scale", 0.2):
            field["scale"] = rng.choice(SCALES)
        if self.has("range", 0.3):
            lo, hi = (-(1 << (width - 1)), (1 << (width - 1)) - 1) if signed else (0, (1 << width) - 1)
            a, b = sorted(rng.randint(lo, hi) for _ in range(2))
            scale = field.get("scale", 1)
            field["range"] = [a * scale, b * scale]
        return field, width

    # -- text framing -----------------------------------------------------------------------
    def text(self) -> tuple[dict, dict]:
        rng = self.rng
        terminator = "\n" if self.has("newline", 0.3) else rng.choice([";", "*", "#"])
        separator = rng.choice([",", "|"])
        framing = {"kind": "text", "prefix_separator": rng.choice([":", "="]), "separator": separator,
                   "terminator": terminator, "trim": rng.random() < 0.5}
        if self.has("long_marks", 0.3):  # NMEA-like: `$`, `\r\n`; or marks of two characters
            framing.update(rng.choice([{"start": "$", "prefix_separator": ",", "separator": ",", "terminator": "\r\n",
                                        "keep_empty": True},
                                       {"start": "!", "separator": "||", "terminator": ";;"},
                                       {"prefix_separator": "::", "separator": ", ", "terminator": "\n"}]))
            terminator = framing["terminator"]
        if self.has("line_checksum", 0.3):
            framing["checksum"] = {"algorithm": rng.choice(["xor", "sum"]), "over": "line",
                                   "suffix": rng.choice([x for x in ("*", "#", "*~", "@") if not set(x) & set(terminator)])}
        if terminator != "\n" and "\n" not in terminator:
            framing["ignore_between"] = "\r\n"
        prefixes = set()
        while len(prefixes) < rng.randint(1, 4):
            prefixes.add("".join(rng.choice(string.ascii_uppercase) for _ in range(rng.randint(1, 5))))
        messages = {}
        for prefix in sorted(prefixes):
            fields = [self.text_field() for _ in range(rng.randint(1, 5))]
            if self.has("optional", 0.3):
                for field in fields[rng.randint(1, len(fields)):]:
                    field["optional"] = True
            if self.has("empty_values", 0.3):  # absent in the middle of a line: an empty value
                for field in fields:
                    if field["type"] != "str" and rng.random() < 0.4:
                        field["optional"] = True
            if framing.get("keep_empty"):  # an empty str would not read back as absent
                for field in fields:
                    if field["type"] == "str":
                        field.pop("optional", None)
            if self.has("text_const", 0.4):
                self.text_constants(fields, terminator + separator + framing.get("separator", ""))
            messages[self.name()] = {"id": prefix, "fields": fields}
        self.text_directions(messages)
        if "keep_spelling" in self.on:
            self.keep_spellings(framing, messages)
        if "text_places" in self.on:
            self.text_places(framing, messages)
        if "talker" in self.on:
            self.talkers(messages)
        return framing, messages

    def talkers(self, messages: dict) -> None:
        """Prefix fields before some messages' ids (NMEA's talker): any uppercase letters of
        their length, or a listed set; a message whose prefix another one could read keeps
        its fixed id."""
        rng = random.Random(f"talker {self.seed}")
        if rng.random() < 0.3:
            return
        patterns = {name: Pattern(m["id"]) for name, m in messages.items()}
        for name, message in messages.items():
            if rng.random() < 0.4:
                continue
            length = rng.choice([1, 2, 2, 3])
            values = None
            if rng.random() < 0.4:
                values = sorted({"".join(rng.choice(string.ascii_uppercase) for _ in range(length))
                                 for _ in range(rng.randint(1, 3))})
            mine = Pattern(message["id"], length, tuple(values) if values else None)
            if any(common_prefix(mine, other) for n, other in patterns.items() if n != name):
                continue
            patterns[name] = mine
            taken = {f["name"] for f in message["fields"]}
            field = {"name": next(x for x in ("talker", "talker_id", "source") if x not in taken),
                     "type": "str", "length": length, "prefix": True}
            if values:
                field["values"] = values
            message["fields"].insert(0, field)

    def text_places(self, framing: dict, messages: dict) -> None:
        """Extension fields a line may end before (a later version's, as NMEA's RMC mode) and
        optional fields with their own keep_empty, drawn from the end of the line back, so
        that no place left out comes before one always written, nor an optional str before it."""
        rng = random.Random(f"text_places {self.seed}")
        if rng.random() < 0.3:
            return
        framing_keeps = bool(framing.get("keep_empty"))
        for name, message in messages.items():
            fields = message["fields"]
            if rng.random() < 0.3 or any(f.get("to_end") for f in fields):
                continue
            added = [{"name": f"{name}_later_{i}", **rng.choice([{"type": "u8"}, {"type": "i16"}, {"type": "char"},
                                                                  {"type": "str", "max_length": 4}]),
                      "optional": True, "extension": True} for i in range(rng.randint(0, 2))]
            fields += added
            with_str = any(f["type"] == "str" and f.get("optional") and "const" not in f for f in fields[:len(fields) - len(added)])
            placed_later = False  # a later field always has its place
            for f in reversed(fields):
                if not f.get("optional") or "const" in f:
                    break
                is_str = f["type"] == "str"
                if is_str and placed_later and f in added:
                    f.pop("max_length")
                    f["type"] = "u8"
                    is_str = False
                choices = [None, False, True] if not placed_later else [None, True]
                if is_str or with_str:  # an empty str reads as "": its place, and those after it, may be left out
                    choices = [False] if framing_keeps else [None, False]
                keep = rng.choice(choices)
                if keep is not None:
                    f["keep_empty"] = keep
                placed_later = placed_later or (framing_keeps if keep is None else keep)

    def keep_spellings(self, framing: dict, messages: dict) -> None:
        """Numbers that keep the text they were read from: on the framing (which then does
        not trim), with some messages opting out, or on some messages alone."""
        rng = random.Random(f"keep_spelling {self.seed}")
        if rng.random() < 0.3:
            return
        on_framing = rng.random() < 0.6
        if on_framing or rng.random() < 0.5:
            framing["trim"] = False  # whitespace around a value is not kept
        if on_framing:
            framing["keep_spelling"] = True
        for message in messages.values():
            if rng.random() < 0.3 and (on_framing or not framing["trim"]):
                message["keep_spelling"] = not on_framing if rng.random() < 0.7 else on_framing

    def text_constants(self, fields: list[dict], marks: str) -> None:
        """Constants among the values (NMEA's unit letters), some a line may leave empty;
        none after an optional str (whose empty value is an empty str)."""
        rng = self.rng
        before_str = next((i for i, f in enumerate(fields) if f["type"] == "str" and f.get("optional")), len(fields))
        for _ in range(rng.randint(1, 2)):
            letters = [x for x in "KMNTV" if x not in marks]
            const = rng.choice([
                {"type": "char", "const": rng.choice(letters)},
                {"type": "u8", "const": rng.randrange(256)},
                {"type": "i16", "const": rng.randint(-300, 300)},
                {"type": "str", "max_length": 4, "const": "".join(rng.choice(letters) for _ in range(rng.randint(1, 4)))},
            ])
            field = {"name": self.name(), **const}
            if rng.random() < 0.6:
                field["optional"] = True
            at = rng.randint(0, before_str)
            fields.insert(at, field)
            before_str += 1

    def text_field(self) -> dict:
        rng = self.rng
        name = self.name()
        choice = rng.random()
        if choice < 0.15 and "enum" in self.on:
            enum = self.enum(8, text=True)
            return {"name": name, "type": self.enums[enum]["type"], "enum": enum}
        if choice < 0.3 and "str" in self.on:
            size = rng.randint(1, 20)
            if "str_length" in self.on and random.Random(f"str_length {self.seed} {name}").random() < 0.3:
                return {"name": name, "type": "str", "length": size}  # a fixed length: the most it holds
            return {"name": name, "type": "str", "max_length": size}
        if choice < 0.4 and "char" in self.on:
            return {"name": name, "type": "char"}
        if choice < 0.55 and "text_float" in self.on:
            return {"name": name, "type": "f64"}
        if self.has("fixed_spelling", 0.15):  # NMEA-like: 4807.038, 08
            field = {"name": name, "type": rng.choice(["u8", "u16", "i16", "i32"])}
            if rng.random() < 0.7:
                field["decimals"] = rng.randint(0, 4)
            if rng.random() < 0.7 or "decimals" not in field:
                field["width"] = rng.randint(1, 12)
            if "receiver_spelling" in self.on:
                self.decimal_range(field)
            return field
        types = ["u8", "u16", "i8", "i16", "i32"] + (["u32", "i64", "u64"] if "wide" in self.on else [])
        field: dict = {"name": name, "type": rng.choice(types)}
        if self.has("range", 0.3):
            bits = int(field["type"][1:])
            signed = field["type"][0] == "i"
            lo, hi = (-(1 << (bits - 1)), (1 << (bits - 1)) - 1) if signed else (0, (1 << bits) - 1)
            field["range"] = sorted(rng.randint(lo, hi) for _ in range(2))
        return field


    def decimal_range(self, field: dict) -> None:
        """A fixed-point field's range with ends written in its decimals (NMEA's 999.9), which
        readers compare exactly: the largest value is read back whatever its spelling."""
        rng = random.Random(f"receiver_spelling {self.seed} {field['name']}")
        if rng.random() < 0.5:
            return
        decimals = field.get("decimals", 0)
        bits = int(field["type"][1:])
        lo = -(1 << (bits - 1)) if field["type"][0] == "i" else 0
        ends = sorted(rng.randint(lo, lo + (1 << bits) - 1) for _ in range(2))
        field["range"] = [end / 10 ** decimals if decimals else end for end in ends]


def values_in(field: dict) -> int:
    """How many values a drawn field holds: one, or its elements' and members' values."""
    each = sum(values_in(f) for f in field["fields"]) if field.get("type") == "group" else 1
    count = field.get("count", 1)
    return each * (count if isinstance(count, int) else 1)


def generate(seed: int, features: frozenset[str] = DEFAULT) -> str:
    """The YAML text of schema number `seed`."""
    return yaml.safe_dump(Generator(seed, features).schema(), sort_keys=False, allow_unicode=True, width=100)


def many_messages(doc: dict, own: random.Random) -> None:
    """`many_messages`: in a third of the byte framings with a 3-byte id (MAVLink 2's
    msgid), more messages than a byte counts (256 to 300 in all, as MAVLink's all.xml has):
    small ones added after those drawn, at ids none has. Drawn from a generator of its own."""
    framing = doc.get("framing", {})
    layout = framing.get("layout", [])
    keys = [f for f in layout if f.get("dispatch")]
    if framing.get("kind") != "bytes" or framing.get("encoding") or framing.get("stuffing") \
            or [f.get("type") for f in keys] != ["u24"] or own.random() >= 1 / 3:
        return
    messages = doc["messages"]
    first = next(iter(messages.values()))
    taken = {body.get("id") for body in messages.values()}
    extra = next((f["checksum"].get("extra") for f in layout if "checksum" in f), None)
    for n in range(own.randint(256, 300) - len(messages)):
        body: dict = {"id": next(i for i in iter(lambda: own.randrange(1 << 24), None) if i not in taken)}
        taken.add(body["id"])
        if "direction" in first:
            body["direction"] = own.choice(["up", "down"])
        if extra == "message":
            body["crc_extra"] = own.randrange(256)
        body["fields"] = [{"name": "value", "type": own.choice(["u8", "i16", "u32"])}]
        messages[f"many_{n}"] = body


def nonfinite_floats(doc: dict, own: random.Random) -> None:
    """`nonfinite`: some binary f32 and f64 fields (in groups and arrays too) may hold NaN and
    the infinities (`finite: false`); those with a range, values or a constant cannot. Drawn
    from a generator of its own, after the rest: the schemas stay as they were otherwise."""
    if doc.get("framing", {}).get("kind") == "text":
        return

    def walk(fields: list) -> None:
        for f in fields:
            if not isinstance(f, dict):
                continue
            if f.get("type") in ("f32", "f64") and not {"range", "values", "const"} & set(f) and own.random() < 0.4:
                f["finite"] = False
            walk(f.get("fields", []))

    for body in (doc.get("messages") or {}).values():
        walk(body.get("fields", []))


def msb_position(start: int) -> int:
    """A DBC Motorola start bit as its place counted most significant bit first (its own inverse)."""
    return 8 * (start // 8) + 7 - start % 8


def placed_bits(rng: random.Random, size: int, taken: set[int], widest: int) -> Optional[dict]:
    """A signal of at most `widest` bits in bits of the payload not in `taken` (None if
    none fits after a few draws); its field's `_bits` are the DBC bits it takes."""
    for _ in range(20):
        length = rng.randint(1, min(widest, 8 * size))
        order = rng.choice(("big", "little"))
        first = rng.randint(0, 8 * size - length)
        bits = {first + k if order == "little" else msb_position(first + k) for k in range(length)}
        if not taken & bits:
            start = first if order == "little" else msb_position(first)
            return {"type": f"u{length}", "start_bit": start, "byte_order": order, "_bits": bits}
    return None


def multiplexed_signals(rng: random.Random, size: int) -> list[dict]:
    """A multiplexed payload of `size` bytes (or two multiplexors side by side): each
    multiplexor of 1 to 3 bits; a group of signals per value (some a range of values),
    each group apart from what may be carried with it, not from the other groups."""
    out: list[dict] = []

    def add(taken: set[int], widest: int, mux: Optional[dict], values: Optional[list]) -> Optional[dict]:
        field = placed_bits(rng, size, taken, widest)
        if field is None:
            return None
        field["name"] = f"sig_{len(out)}"
        length = int(field["type"][1:])
        if mux is None and values is None or widest == 3:
            pass  # a multiplexor: plain unsigned
        elif length == 1 and rng.random() < 0.4:
            field["type"] = "bool"
        elif rng.random() < 0.4:
            field["type"] = f"i{length}"
        if widest > 3 and field["type"] != "bool" and rng.random() < 0.2:
            field["scale"] = rng.choice((0.5, 0.25, 2))
        if mux is not None:
            field["multiplexed_by"] = {"field": mux["name"], "values": values}
        out.append(field)
        return field

    def fill(taken: set[int], mux: dict, depth: int) -> set[int]:
        most = (1 << int(mux["type"][1:])) - 1
        values = sorted(rng.sample(range(most + 1), min(most + 1, rng.randint(1, 3))))
        per = {v: set(taken) for v in values}
        for v in values:
            ends = v if v == most or rng.random() < 0.7 else f"{v}..{rng.randint(v + 1, most)}"
            for _ in range(rng.randint(1, 3)):
                nested = depth < 1 and rng.random() < 0.25
                field = add(per[v], 3 if nested else 16, mux, [ends])
                if field is None:
                    break
                per[v] |= field["_bits"]
                if nested:
                    per[v] = fill(per[v], field, depth + 1)
            if isinstance(ends, str):  # the range reaches other groups' values: keep their bits apart
                for w in values:
                    if w != v and v <= w <= int(ends.split("..")[1]):
                        per[w] |= per[v]
                        per[v] |= per[w]
        if len(values) > 1 and rng.random() < 0.5:  # one signal for two of the values
            both = rng.sample(values, 2)
            field = add(per[both[0]] | per[both[1]], 16, mux, sorted(both))
            if field is not None:
                for v in both:
                    per[v] |= field["_bits"]
        return set().union(*per.values())

    taken: set[int] = set()
    for _ in range(rng.randint(1, 2)):
        mux = add(taken, 3, None, None)
        if mux is None:
            break
        taken |= mux["_bits"]
        if rng.random() < 0.5:
            plain = add(taken, 16, None, [])
            if plain is not None:
                taken |= plain["_bits"]
        taken = fill(taken, mux, 0)
    for field in out:
        del field["_bits"]
    return out


def placed_signals(rng: random.Random, size: int, floats: Optional[random.Random] = None) -> list[dict]:
    """Signals that do not overlap in a payload of `size` bytes, at least one; with
    `floats` (a generator of their own), some are f32 or f64 (DBC's SIG_VALTYPE_)."""
    taken: set[int] = set()
    out: list[dict] = []
    for _ in range(10):
        length = min(64, rng.choice((rng.randint(1, 8 * size), rng.randint(1, min(12, 8 * size)))))
        real = floats is not None and size >= 4 and floats.random() < 0.25
        if real:
            length = 64 if size >= 8 and floats.random() < 0.4 else 32
        order = rng.choice(("big", "little"))
        first = rng.randint(0, 8 * size - length)  # in the order's own numbering
        start = first if order == "little" else msb_position(first)
        bits = {first + k if order == "little" else msb_position(first + k) for k in range(length)}
        if taken & bits:
            continue
        taken |= bits
        signed = rng.random() < 0.5
        field = {"name": f"sig_{len(out)}", "type": f"{'i' if signed else 'u'}{length}", "start_bit": start,
                 "byte_order": order}
        if real:
            field["type"] = f"f{length}"
        elif length == 1 and not signed and rng.random() < 0.5:
            field["type"] = "bool"
        elif length <= 53 and rng.random() < 0.3:
            field["scale"] = rng.choice((0.5, 0.25, 2, 0.125))
            if rng.random() < 0.5:
                field["offset"] = rng.randint(-100, 100)
        out.append(field)
    return out
