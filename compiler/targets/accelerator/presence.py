"""Whether a conditional or multiplexed field is in a frame, as C tests it on the struct
the accelerator decodes into or encodes from: one test for its decoders and encoders."""
from __future__ import annotations

from typing import Optional

from ...model import Field, Message
from ..c.view import CView


def sent_test(c: CView, m: Message, f: Field, member: str) -> Optional[str]:
    """The C test, on the struct members named `member` + field name, of whether `f` is in
    the frame: from the raw value of the field that says (None: it always is)."""
    if f.present_if:
        gap = next(g for g in m.shortening.gaps if g.field == f.name)
        return c.presence_test(m, gap, f"{member}{gap.control}")
    if f.multiplexed_by:
        raws = {leaf.var: f"{member}{leaf.path[0]}" for leaf in m.wire.leaves if len(leaf.path) == 1}
        return c.multiplex_test(m, f.multiplexed_by, raws)
    return None
