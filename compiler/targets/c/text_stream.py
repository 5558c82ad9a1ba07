"""The C text stream reader's facts: the longest line it holds (the front end's
bound, which Python's StreamDecoder uses too), the terminator it looks for and
the characters it skips between lines."""
from __future__ import annotations

from ...model import Protocol
from .view import cchar, comment, cstr, fill_type


def text_stream_view(p: Protocol) -> dict:
    fr = p.framing
    if fr.kind != "text":
        return {}
    shown = [repr(ch) for ch in fr.ignore_between]
    return {"max": fr.line_max, "fill_type": fill_type(fr.line_max),
            "terminator": cstr(fr.terminator), "terminator_len": len(fr.terminator),
            # what a line too long keeps when dropped: the start of a terminator it may end with
            "terminator_kept": len(fr.terminator) - 1,
            "ignored": " || ".join(f"c == {cchar(ch)}" for ch in fr.ignore_between),
            "skipped_doc": comment(f"{', '.join(shown)} between lines are skipped" if shown
                                   else "nothing between lines is skipped"),
            "blank_doc": comment(", ".join(shown + ["' '", "'\\t'"]))}
