"""Python target: one stand-alone module per protocol in generated/python/."""
from __future__ import annotations

from ...fingerprint import fingerprint, fingerprint32
from ...model import Protocol
from .machines import machines_view
from .view import module_view
from ..wire import text_form_head
from ..accelerator.scope import serves, source_tag
from ..escape import py_docstring
from ..render import environment, tidy


def render(p: Protocol) -> dict[str, str]:
    view = module_view(p)
    docstring = '"""' + py_docstring(f"{p.title.en}: codec generated from the {p.name} schema.") + '"""'
    head = view["dispatch"].get("head_bits")
    source = environment().get_template("python/module.py.j2").render(
        docstring=docstring, fingerprint=fingerprint(p), fingerprint32=f"{fingerprint32(p):#010x}",
        text_head=text_form_head(p) if p.framing.text_form and head else [],
        accelerator=source_tag(p) if serves(p) else None, machines=machines_view(p), **view)
    return {f"python/{p.name}.py": tidy(source, max_blank=2)}
