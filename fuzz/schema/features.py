"""The parts of the language the generator draws from, each one a switch.

FULL is everything the generator knows. KNOWN_OPEN lists features switched off
by default because a target does not serve them yet; each names what fails.
The default run (and tests/test_schema_fuzz.py) uses DEFAULT = FULL - KNOWN_OPEN;
`--features all` runs everything, to see whether an open one is fixed.
"""
from __future__ import annotations

FULL = frozenset({
    "bytes", "text", "bits",                # framings
    "text_form", "field_sum", "one_hot",    # bits framing: a text form, checksums over fields, one-hot
    "sync", "length", "no_dispatch",        # envelope parts (bytes)
    "length_range",                         # a length that counts itself (and the checksum), adjusted
    "sync2", "two_keys", "by_direction",    # a sync of two bytes; two dispatch fields; a direction byte
    "single_length",                        # bytes: a length field in a protocol of one message without an id
    "sum", "xor", "crc", "fletcher",        # checksums over bytes
    "internet",                             # bytes: the frame's checksum RFC 1071's, in either byte order, at times in place
    "crc_alias",                            # a CRC named by a catalogue alias with one meaning, in any case
    "complement", "crc_extra",              # a sum's complement, xorout; a CRC's per-message extra byte
    "derived_crc_extra",                    # bytes: that byte derived from each message as MAVLink's CRC_EXTRA, mavlink_name
    "encoding",                             # SLIP, COBS or HDLC byte stuffing around frames
    "pattern_stuffing",                     # bytes: a byte inserted after a pattern in a span (Dynamixel 2.0)
    "end_marker",                           # bytes: a constant byte after the payload closes each frame
    "shared_id",                            # bytes without length: two messages of one id at two sizes
    "direction_ids",                        # one id (bytes) or prefix (text) used by a message of each direction
    "extension", "truncate",                # bytes: extension fields at a message's end; trailing zeros not sent
    "extension_arrays",                     # bytes: arrays and bytes among the extension fields
    "payload_name",                         # bytes: a message field named `payload`, as the envelope's marker is
    "wide_id",                              # bytes: a 3-byte message id (MAVLink 2's msgid)
    "many_messages",                        # bytes, a 3-byte id: 256 to 300 messages (MAVLink's all.xml)
    "little", "field_order",                # byte orders: the framing's, and per field
    "bitfields",                            # fields narrower than a byte, packed
    "arrays",                               # fields of a fixed count: scalars, groups (bytes), bit fields
    "long_arrays",                          # bytes: arrays long enough that generated code loops over them, fixed, counted or conditional
    "counted",                              # bytes: arrays counted by an earlier field, anywhere in the payload
    "conditional",                          # bytes: fields present when an earlier field says so
    "signed_trailer",                       # bytes: a flag puts a trailer with a SHA-256 signature after the frame
    "lsb_first",                            # bytes framing: bit fields least significant bit first
    "mixed_bit_order",                      # bytes: payloads of 1..8 bytes placed by DBC start bit, both orders
    "multiplexed",                          # bytes: placed payloads whose multiplexors select signals sharing bits
    "placed_float",                         # bytes: f32 and f64 fields among those placed by start bit (SIG_VALTYPE_)
    "float_const",                          # bytes: f32 and f64 constants, at times under a sum or xor over the fields
    "can",                                  # CAN framing: standard and extended identifiers, classic and FD lengths
    "large_frame",                          # bytes: a message of over 64 KiB (4 KiB fields first)
    "stream_end",                           # check: whole frames after a false start at a stream's end are decoded
    "selected_messages",                    # check: C built with some messages selected, and with none
    "signed", "scale", "offset", "range",   # integer options
    "enum", "flags", "bool", "bytes_field", "f32", "f64",
    "open_enum",                            # integer enums whose other values are valid, kept as numbers
    "f32_range",                            # f32 fields with a range: integer or decimal ends
    "nonfinite",                            # binary f32 and f64 fields that may hold NaN and the infinities
    "collisions",                           # mutants: protocol named like a system header, has_/_count fields
    "wide",                                 # integers of 33..64 bits
    "optional", "str", "char", "text_float", "newline",  # text options
    "str_length",                           # text: str fields of a fixed length
    "long_marks", "line_checksum",          # text: marks of several characters, a start marker; `*hh`
    "empty_values",                         # text: optional values anywhere, absent ones empty
    "fixed_spelling",                       # text: integers with fixed decimals and zero padding
    "receiver_spelling",                    # text: fixed-point ranges ending in decimals; vectors respell numbers
    "keep_spelling",                        # text: decoded numbers keep their received text (framing or message)
    "text_places",                          # text: extension fields a line may end before; a field's own keep_empty
    "talker",                               # text: a prefix field before some messages' ids (NMEA's talker)
    "text_const",                           # text: char, str and integer constants, some optional (unit letters)
    "machines",                             # a master and a slave machine over a command and its reply
    "delivery_ranges",                      # machines: narrow ranges of the address, timeout and retry limit
})

KNOWN_OPEN = {
}

DEFAULT = FULL - set(KNOWN_OPEN)


def parse(spec: str | None) -> frozenset[str]:
    """`all`, or a comma-separated list with optional `-name` removals from the default."""
    if not spec:
        return DEFAULT
    if spec == "all":
        return FULL
    chosen = set(DEFAULT)
    for part in spec.split(","):
        part = part.strip()
        if part.startswith("-"):
            chosen.discard(part[1:])
        elif part.startswith("+"):
            chosen.add(part[1:])
        elif part:
            chosen.add(part)
    unknown = chosen - FULL
    if unknown:
        raise ValueError(f"unknown features: {', '.join(sorted(unknown))} (known: {', '.join(sorted(FULL))})")
    return frozenset(chosen)
