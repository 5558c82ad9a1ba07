"""What the framing section says a decoder refuses, and with which error: each
statement made from the facts module-level decode runs on (the bytes it reads the
id from, the frame sizes each id may have, the line's terminator and checksum),
so the page says what the decoder does. tests/test_docs_error_statements.py holds
every statement against the error kinds the vectors carry."""
from __future__ import annotations

from ...model import Protocol
from ..wire import dispatch_facts
from .layout import presence_text, shown
from .text import code


def error_claims(p: Protocol) -> list[dict]:
    """Each claim: `kind` (the error), `when` (which frames: a name with its facts in
    `args`) and `text` (the sentence the page prints)."""
    fr = p.framing
    facts = dispatch_facts(p)
    claims: list[dict] = []
    if fr.kind == "bytes" and facts["kind"] == "bytes" and not fr.encoding and not fr.stuffing:
        head = facts["last"]
        sizes = sorted({n for m in p.messages
                        for n in range(facts["least"].get(m.name, m.size), m.size + 1, facts["steps"].get(m.name, 1))})
        claims.append({"kind": "length", "when": "shorter_than", "args": {"bytes": head},
                       "text": f"A frame of fewer than {head} bytes (too short to hold the id) is refused "
                               "with error `length`."})
        args: dict = {"sizes": sizes, "least": head}
        without = ""
        if fr.trailer:  # decoders take the trailer off before they look at the size
            t = fr.trailer
            args["trailer"] = {"byte": t.flag_byte, "mask": t.flag_mask, "size": t.size}
            without = f" (without its trailer of {t.size} bytes when {presence_text(t.presence)})"
        claims.append({"kind": "dispatch", "when": "size_not_in", "args": args,
                       "text": f"A frame{without} of {head} bytes or more of a size that no message with its id has "
                               "(see each message's size; a frame cut short, or with bytes added) is refused with "
                               "error `dispatch`; its checksum and fields are not read."})
    if fr.kind == "text":
        claims.append({"kind": "terminator", "when": "no_terminator", "args": {"terminator": fr.terminator},
                       "text": "A line that does not end with the terminator is refused with error `terminator`."})
        cs = fr.line_checksum
        if cs:
            claims.append({"kind": "checksum", "when": "line_checksum_differs",
                           "args": {"start": fr.start, "suffix": cs.suffix, "algorithm": cs.algorithm,
                                    "terminator": fr.terminator},
                           "text": f"A line that starts with its start marker and ends with {code(shown(cs.suffix + 'hh'))} "
                                   "and the terminator, hh two uppercase hex digits that differ from the checksum of its "
                                   "characters, is refused with error `checksum`, whatever else is wrong in it."})
    return claims
