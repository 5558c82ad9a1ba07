"""C target: generated/c/codeword.h (shared runtime) and one header per protocol."""
from __future__ import annotations

from ...fingerprint import fingerprint, fingerprint32
from ...model import Protocol
from . import crc
from . import repeats as crepeats
from .machines import machines_view
from .sequences import sequences_view
from .stuffing import stuffing_view
from .text_stream import text_stream_view
from .trailer import trailer_view
from ..can import can_view
from .view import CView, cchar, clit, comment, cstr
from .wordform import word_type
from ..render import environment, tidy
from ..wire import stream_facts


def constants(v: CView) -> list[tuple[str, str, str]]:
    p = v.p
    out: list[tuple[str, str, str]] = []
    for param in p.parameters:
        if isinstance(param.default, int):
            out.append((v.upper(param.name), clit(param.default), comment(param.doc or "")))
    sync = stream_facts(p).get("sync")
    if sync is not None:
        out.append((v.upper("SYNC"), f"{sync:#04x}u", "first byte of every frame"))
    for m in p.messages:
        if m.size is not None:
            out.append((v.upper(m.name, "SIZE"), f"{m.size}u", "bytes"))
        if v.fr.text_form:
            out.append((v.upper(m.name, "MAX_TEXT_FORM"), f"{v.max_text_form(m) + 1}u",
                        f"chars, with the NUL: buffer size for {v.fn(m, 'to_text')}"))
        elif v.text:
            out.append((v.upper(m.name, "MAX_TEXT"), f"{v.max_text(m) + 1}u",
                        "chars, with the NUL: buffer size for encode"))
        for i, value in enumerate(m.ids):
            made_of = ", ".join(name for name, _ in m.id_fields)
            out.append((v.id_const(m, i), v.id_literal(value),
                        f"the key {made_of} make together" if made_of else "the prefix" if v.text else ""))
    sizes = [m.size for m in p.messages if m.size is not None]
    if sizes:
        trailer = p.framing.trailer.size if p.framing.trailer else 0
        out.append((v.upper("MAX_FRAME"), f"{max(sizes) + trailer}u",
                    "bytes: largest frame" + (", its trailer included" if trailer else "")))
    if v.text:
        out.append((v.upper("MAX_TEXT"), f"{max(v.max_text(m) for m in p.messages) + 1}u",
                    "chars, with the NUL: largest encoded message"))
    if v.word_bits():
        out.append((v.upper("WORD_BITS"), f"{v.word_bits()}u", "bits in a word"))
    return out


def largest_on_wire(v: CView, encoding: dict, stuffing: dict) -> int:
    """The most bytes (chars, for text) a frame of the protocol takes, stuffed and with
    its trailer: every size the header handles is a size_t, so a target must hold it."""
    p = v.p
    trailer = p.framing.trailer.size if p.framing.trailer else 0
    sizes = [m.size + trailer for m in p.messages if m.size is not None]
    if v.text:
        sizes += [v.max_text(m) + 1 for m in p.messages]
    sizes += [facts["wire_max"] for facts in (encoding, stuffing) if facts]
    return max(sizes, default=0)


def enums(v: CView) -> list[dict]:
    out = []
    for e in v.p.enums:
        out.append({"doc": comment(e.doc or e.name), "members": [
            (v.enum_const(e.name, m.name), cchar(m.value) if isinstance(m.value, str) else str(m.value),
             comment(m.doc or "")) for m in e.members]})
    return out


def flags(v: CView) -> list[dict]:
    out = []
    for fl in v.p.flags:
        ctype = "uint8_t" if fl.bits <= 8 else "uint16_t" if fl.bits <= 16 else "uint32_t"
        out.append({"doc": comment(fl.doc or fl.name), "ctype": ctype, "all": v.upper(fl.name, "ALL"),
                    "mask": clit(fl.mask, True),
                    "members": [(v.upper(fl.name, b.name), clit(1 << b.bit, True), comment(b.doc or ""))
                                for b in fl.members]})
    return out


def message_views(v: CView) -> list[dict]:
    out = []
    for m in v.p.messages:
        if v.text:
            functions = [v.text_encode_function(m), v.text_body_function(m), v.text_decode_function(m)]
            if m.prefix_field is not None:
                functions.insert(2, v.text_prefix_function(m))
        else:
            functions = crepeats.functions(v, m) + [v.raw_function(m), v.encode_function(m),
                                                     v.check_raw_function(m), v.decode_function(m)]
            if v.word_bits():
                functions.append(v.word_functions(m))
            if v.fr.text_form:
                functions.append(v.text_form_functions(m))
        out.append({"name": m.name, "tname": v.tname(m), "fn": f"{v.px}_{m.name}",
                    "kind": v.upper("MSG", m.name), "handles": v.upper("HANDLES", m.name),
                    "select": v.upper("SELECT", m.name), "doc": comment(m.title or m.doc or m.name),
                    "struct": v.struct_lines(m.layout) + v.places_lines(m), "functions": [f for f in functions if f],
                    "units": v.unit_helpers(m)})
    return out


def line_view(v: CView) -> dict:
    """The marks of a text line as C literals and lengths, for <proto>_split."""
    fr = v.fr
    if not v.text:
        return {}
    cs = fr.line_checksum
    shape = f"{fr.start}<prefix>{fr.prefix_separator}<fields>{cs.suffix + 'hh' if cs else ''}{fr.terminator}"
    return dict(v.line, c={
        "shape": comment(shape.encode("unicode_escape").decode("ascii")),
        "terminator": cstr(fr.terminator), "terminator_len": len(fr.terminator),
        "start": cstr(fr.start), "start_len": len(fr.start),
        "prefix_separator": cstr(fr.prefix_separator), "prefix_separator_len": len(fr.prefix_separator),
        "suffix": cstr(cs.suffix) if cs else "", "suffix_len": len(cs.suffix) if cs else 0,
        "algorithm": {"xor": "CW_LINE_XOR", "sum": "CW_LINE_SUM"}[cs.algorithm] if cs else ""})


def render(p: Protocol) -> dict[str, str]:
    v = CView(p)
    fr = p.framing
    messages = message_views(v)
    dispatch = v.dispatch()
    text_form = None
    if fr.text_form and dispatch["kind"] == "bits":
        facts = v.text_form_facts()
        text_form = {**facts, "separator": cchar(fr.text_form.separator),
                     "unfilled": fr.text_form.checksum_unfilled}
    ignore = " || ".join(f"*s == {cchar(ch)}" for ch in fr.ignore_between) or "false"
    ignore_end = " || ".join(f"e[-1] == {cchar(ch)}" for ch in fr.ignore_between) or "false"
    encoding, stuffing = v.encoding(), stuffing_view(v.px, p)
    env = environment()
    header = env.get_template("c/protocol.h.j2").render(
        p=p, v=v, px=v.px, PX=v.PX, fingerprint=fingerprint(p), fingerprint32=f"{fingerprint32(p):#010x}", constants=constants(v), enums=enums(v), flags=flags(v),
        directions=v.directions(), messages=messages, kinds={m["name"]: m["kind"] for m in messages},
        handles={m["name"]: m["handles"] for m in messages},
        kind_t="uint8_t" if len(messages) <= 0xFF else "uint16_t",  # <PX>_MSG_* run from 1
        checksums=v.byte_checksums(), crc_methods=crc.METHODS if v.has_crc() else (), crc_default=crc.DEFAULT_METHOD, text=v.text, dispatch=dispatch, stream=v.stream() if fr.kind == "bytes" else {},
        encoding=encoding, stuffing=stuffing, trailer=trailer_view(p), can=can_view(p),
        largest=largest_on_wire(v, encoding, stuffing),
        wrapped=bool(fr.encoding or fr.stuffing),
        word_bits=v.word_bits(), word_type=word_type(v.word_bits() or 32), text_form=text_form,
        word_max=(1 << v.word_bits()) - 1 if v.word_bits() else None,
        word_shift=v.word_bits() - dispatch["head_bits"] if v.word_bits() and dispatch["kind"] == "bits" else None, cstr=cstr, ignore=ignore, ignore_end=ignore_end,
        terminator=cchar(fr.terminator) if v.text and v.line["simple"] else "",
        prefix_separator=cchar(fr.prefix_separator) if v.text and v.line["simple"] else "",
        text_ascii=v.text and v.text_ascii(), line=line_view(v),
        machines=machines_view(p), sequences=sequences_view(v), text_stream=text_stream_view(p))
    runtime = env.get_template("c/codeword.h.j2").render()
    return {f"c/{p.name}.h": tidy(header, max_blank=1), "c/codeword.h": runtime}
