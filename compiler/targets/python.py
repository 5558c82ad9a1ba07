"""Python target: one stand-alone module per protocol in generated/python/."""
from __future__ import annotations

from ..fingerprint import fingerprint, fingerprint32
from ..model import Protocol
from .pymachine import machines_view
from .pyview import leaves_of, module_view
from .escape import py_docstring
from .render import environment, tidy


def text_head(p: Protocol, head_bits: int) -> list[tuple[str, int]]:
    """Widths of the leading values of a text-form line that cover the dispatch bits.
    They must be the same in every message for a line to be dispatched."""
    shapes = []
    for m in p.messages:
        widths, used = [], 0
        for leaf in leaves_of(m.layout):
            if used >= head_bits:
                break
            widths.append(leaf.field.bits)
            used += leaf.field.bits
        shapes.append(widths)
    if any(s != shapes[0] for s in shapes):
        raise ValueError("text form: messages differ in the widths of their leading fields")
    return [("v%d" % i, w) for i, w in enumerate(shapes[0])]


def render(p: Protocol) -> dict[str, str]:
    view = module_view(p)
    docstring = '"""' + py_docstring(f"{p.title.en}: codec generated from the {p.name} schema.") + '"""'
    head = view["dispatch"].get("head_bits")
    source = environment().get_template("python/module.py.j2").render(
        docstring=docstring, fingerprint=fingerprint(p), fingerprint32=f"{fingerprint32(p):#010x}",
        text_head=text_head(p, head) if p.framing.text_form and head else [],
        machines=machines_view(p), **view)
    return {f"python/{p.name}.py": tidy(source, max_blank=2)}
