"""The MAVLink 1 and 2 framings, as examples/mavlink1.yaml and examples/mavlink2.yaml
write them (tests check those against pymavlink), for imported dialects."""
from __future__ import annotations

# The names these framings give the decoded object: a message field of one of these
# names is renamed.
FRAME_MEMBERS = {
    1: frozenset({"stx", "len", "seq", "sysid", "compid", "msgid", "checksum"}),
    2: frozenset({"stx", "len", "incompat_flags", "compat_flags", "seq", "sysid", "compid", "msgid", "checksum",
                  "link_id", "timestamp", "signature"}),
}
# The flag set the MAVLink 2 framing names
FRAME_FLAGS = {1: frozenset(), 2: frozenset({"incompat_flags"})}

DOC = {
    1: """\
MAVLink v1 packets: a start byte 0xFE, the payload length, a sequence
number, the sender's system and component ids, the message id, the payload
in little-endian order and an X.25 CRC over everything after the start byte,
followed by the message's CRC_EXTRA byte.""",
    2: """\
MAVLink 2 packets: a start byte 0xFD, the payload length, the incompatibility
and compatibility flags, a sequence number, the sender's system and component
ids, a 24-bit message id, the payload in little-endian order without its
trailing zero bytes, and an X.25 CRC over everything after the start byte,
followed by the message's CRC_EXTRA byte. A signed packet (incompatibility
flag 0x01) carries 13 more bytes after the CRC: a link id, a timestamp and a
signature, the first 6 bytes of SHA-256 over a secret key and the packet.""",
}

FRAMING = {
    1: """\
framing:
  kind: bytes
  byte_order: little
  layout:
    - {name: stx, type: u8, const: 0xFE, doc: start of a v1 packet}
    - {name: len, type: u8, length_of: {from: payload, to: payload}, doc: payload length}
    - {name: seq, type: u8, doc: "packet sequence number, wraps at 255"}
    - {name: sysid, type: u8, doc: id of the sending system}
    - {name: compid, type: u8, doc: id of the sending component}
    - {name: msgid, type: u8, dispatch: true, doc: message id}
    - {payload: true}
    - name: checksum
      type: u16
      checksum: {algorithm: CRC-16/MCRF4XX, covers: {from: len, to: payload}, extra: mavlink}
      doc: X.25 CRC of len..payload, then of the message's CRC_EXTRA byte
""",
    2: """\
framing:
  kind: bytes
  byte_order: little
  truncate: trailing_zeros
  layout:
    - {name: stx, type: u8, const: 0xFD, doc: start of a v2 packet}
    - {name: len, type: u8, length_of: {from: payload, to: payload}, doc: payload bytes sent (after truncation)}
    - name: incompat_flags
      type: u8
      flags: incompat_flags
      doc: flags a receiver must understand; a packet with a flag it does not know is refused
    - {name: compat_flags, type: u8, doc: flags a receiver may ignore}
    - {name: seq, type: u8, doc: "packet sequence number, wraps at 255"}
    - {name: sysid, type: u8, doc: id of the sending system}
    - {name: compid, type: u8, doc: id of the sending component}
    - {name: msgid, type: u24, dispatch: true, doc: message id}
    - {payload: true}
    - name: checksum
      type: u16
      checksum: {algorithm: CRC-16/MCRF4XX, covers: {from: len, to: payload}, extra: mavlink}
      doc: X.25 CRC of len..payload as sent, then of the message's CRC_EXTRA byte
  trailer:
    present_if: {field: incompat_flags, has: signing}
    doc: >-
      The signature of a signed packet (https://mavlink.io/en/guide/message_signing.html):
      the sender's link, a timestamp, and the first 6 bytes of SHA-256 over a 32-byte secret key
      then the packet from its start byte through the timestamp.
    fields:
      - {name: link_id, type: u8, doc: the sender's link (channel)}
      - {name: timestamp, type: u48, unit: 10us, doc: "10 microsecond units since 1 January 2015 GMT"}
      - name: signature
        type: bytes
        length: 6
        doc: first 6 bytes of SHA-256(secret key + the packet from stx through timestamp)
        signature: {algorithm: SHA-256, key_length: 32, covers: {from: stx, to: timestamp}}
""",
}

# The MAVLink 2 framing's own flag set, written first under `flags:`
FRAME_FLAG_SETS = {
    1: "",
    2: """\
  incompat_flags:
    type: u8
    bits:
      - {name: signing, bit: 0, doc: "the packet is signed: 13 signature bytes follow the CRC"}
""",
}
