"""CAN framing: a message is found by its arbitration identifier, its data is its payload.

`framing: {kind: can}` is a bytes framing whose envelope is the CAN frame's own header,
written out here once so that every backend serves it as any other bytes framing: the
identifier in 32 bits (bit 31 set for an extended, 29-bit identifier, as SocketCAN's
`can_id` and a DBC file's message ids), the data length in a byte, then the data. A
frame's bytes in vectors and examples are that header and the data; `decode_can` and
`encode_can` take and give the identifier and the data apart."""
from __future__ import annotations

from typing import Any, Optional

from ..can import EXTENDED_FLAG, HEADER_BYTES, MAX_EXTENDED_ID, MAX_STANDARD_ID, lengths

ENVELOPE = (
    {"name": "can_id", "type": "u32", "dispatch": True,
     "doc": "the arbitration identifier; bit 31 set for an extended (29-bit) identifier, as SocketCAN's can_id"},
    {"name": "data_length", "type": "u8", "length_of": {"from": "payload", "to": "payload"},
     "doc": "the number of data bytes"},
    {"payload": True},
)


def expand(data: dict) -> tuple[dict, Optional[str]]:
    """The document with a CAN framing written as the bytes framing it stands for, and
    which CAN it is ("classic" or "fd"; None for other framings)."""
    framing = data.get("framing")
    if not isinstance(framing, dict) or framing.get("kind") != "can":
        return data, None
    expanded: dict[str, Any] = {"kind": "bytes", "byte_order": "big", "layout": [dict(f) for f in ENVELOPE]}
    return {**data, "framing": expanded}, "fd" if framing.get("fd") else "classic"


class CanMixin:
    """The rules a CAN framing adds: identifiers in range, data of a length CAN carries."""

    def check_can_framing(self) -> None:
        """A CAN framing's header is CAN's own: no key of a bytes framing shapes it."""
        for key in self.doc.data["framing"]:
            if key not in ("kind", "fd"):
                self.error(("framing", key), f"framing: {key!r} does not apply to can framing",
                           "keys for this framing: fd, kind")

    def can_ids(self, name: str, m: dict, ids: Any, path: tuple) -> Any:
        """A message's dispatch value: its identifier, with the extended flag if it says so."""
        if "extended" in m and self.can is None:
            self.error(path + ("extended",), f"message {name!r}: `extended` is for can framing",
                       "drop `extended`, or write framing: {kind: can}")
        if self.can is None:
            return ids
        if not isinstance(ids, tuple) or len(ids) != 1 or not isinstance(ids[0], int):
            self.error(path + ("id",), f"message {name!r}: a CAN message has one identifier, a number",
                       "write id: 0x123 (and extended: true for a 29-bit identifier)")
            return ids
        extended = bool(m.get("extended"))
        most = MAX_EXTENDED_ID if extended else MAX_STANDARD_ID
        if ids[0] > most:
            self.error(path + ("id",), f"message {name!r}: id 0x{ids[0]:X} does not fit a "
                       + ("29-bit extended identifier" if extended else "standard (11-bit) identifier"),
                       "write extended: true for a 29-bit identifier" if not extended and ids[0] <= MAX_EXTENDED_ID
                       else f"identifiers go up to 0x{most:X}")
            return ids
        return (ids[0] | EXTENDED_FLAG,) if extended else ids

    def check_can_size(self, name: str, size: Optional[int], variable: bool, path: tuple) -> None:
        """A CAN frame's data has one length, from those its CAN carries."""
        if self.can is None:
            return
        if size is None or variable:
            self.error(path, f"message {name!r}: a CAN message has one data length; this one's varies",
                       "give arrays a fixed count, or split the message")
        elif size - HEADER_BYTES not in lengths(self.can):
            data = size - HEADER_BYTES
            fits = "up to 64 bytes in the CAN FD steps (12, 16, 20, 24, 32, 48, 64)" if self.can == "fd" \
                else "up to 8 bytes (classic CAN)"
            self.error(path, f"message {name!r}: {data} bytes of data, but a CAN frame carries {fits}",
                       "set payload_bytes to a length CAN carries" + ("" if self.can == "fd" else
                                                                      ", or write fd: true in the framing"))
