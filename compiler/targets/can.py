"""What the views of every target say of a CAN framing."""
from __future__ import annotations

from typing import Any, Optional

from ..can import EXTENDED_FLAG, HEADER_BYTES, lengths
from ..model import Protocol


def can_view(p: Protocol) -> Optional[dict[str, Any]]:
    """The CAN facts generated code needs, or None for other framings."""
    if p.framing.can is None:
        return None
    return {"fd": p.framing.can == "fd", "max_data": max(lengths(p.framing.can)),
            "header": HEADER_BYTES, "extended_flag": EXTENDED_FLAG}
