"""Pattern stuffing (`framing.stuffing`) spelt in C: the statements that make a frame's
length fields and checksums count it as sent, and that check a frame as received, from
the wire facts of `stuffing_facts`."""
from __future__ import annotations

from ..wire import checksum_name, stuffing_facts


def _at(where: dict, buf: str) -> str:
    """Where a field placed from the frame's start (`at`) or end (`back`) starts, in `buf` of `n` bytes."""
    return f"{buf} + {where['at']}" if "at" in where else f"{buf} + (n - {where['back']}u)"


def _covered(px: str, cs: dict, buf: str) -> str:
    end = f"(n - {cs['end_back']}u)" if "end_back" in cs else f"{cs['end']}u"
    return f"{px}_{checksum_name(cs['cs'])}({buf} + {cs['start']}, {end} - {cs['start']}u)"


def _accessors(f: dict) -> tuple[str, str, str]:
    """(get, put, type) of a field of whole bytes in its byte order."""
    wide = "_wide" if f["bytes"] > 4 else ""
    end = "le" if f["byte_order"] == "little" else "be"
    return f"cw_get_{end}{wide}", f"cw_put_{end}{wide}", "uint64_t" if wide else "uint32_t"


def stuffing_view(px: str, p) -> dict:
    """The constants and statements of the C pattern stuffing, or {} without it."""
    facts = stuffing_facts(p)
    if not facts:
        return facts
    grow, shrink, verify = [], [], []
    for f in facts["lengths"]:  # lengths sit before the stuffed bytes (the resolver's rule)
        get, put, _ = _accessors(f)
        grow.append(f"{put}(b + {f['at']}, {f['bytes']}u, {get}(b + {f['at']}, {f['bytes']}u) + (uint32_t)added);")
        shrink += [f"if ({get}(b + {f['at']}, {f['bytes']}u) < (uint32_t)removed) {{",
                   "    return CW_ERR_LENGTH;",
                   "}",
                   f"{put}(b + {f['at']}, {f['bytes']}u, {get}(b + {f['at']}, {f['bytes']}u) - (uint32_t)removed);"]
    sums = []
    for cs in facts["checksums"]:
        get, put, t = _accessors(cs)
        if cs["cs"].covers_self:  # counted as zero while computed; RFC 1071's receiver check: the sum is all ones
            sums.append(f"memset({_at(cs, 'b')}, 0, {cs['bytes']}u);")
            verify += [f"if ({_covered(px, cs, 'wire')} != 0u) {{", "    return CW_ERR_CHECKSUM;", "}"]
        else:
            verify += [f"if ({get}({_at(cs, 'wire')}, {cs['bytes']}u) != ({t}){_covered(px, cs, 'wire')}) {{",
                       "    return CW_ERR_CHECKSUM;",
                       "}"]
        sums.append(f"{put}({_at(cs, 'b')}, {cs['bytes']}u, ({t}){_covered(px, cs, 'b')});")
    pattern = facts["pattern"]
    return dict(facts, pattern_c=", ".join(f"0x{b:02X}u" for b in pattern), pattern_len=len(pattern),
                insert_c=f"0x{facts['insert']:02X}u", pattern_hex=pattern.hex(" ").upper(),
                insert_hex=f"{facts['insert']:02X}", grow=grow + sums, shrink=shrink + sums, verify=verify)
