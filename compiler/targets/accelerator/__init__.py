"""Accelerator target: the C source of an optional compiled module that decodes frames
for a protocol's Python module (python/_<name>_accel.c), built from the generated C
decoders by `codeword accelerate`."""
from __future__ import annotations

from ...model import Protocol
from ..render import environment, tidy
from .scope import runs_streams, serves, source_tag
from .view import AcceleratorView

HELPERS = ("acc_none", "acc_lookup", "acc_member_or_number", "acc_flags", "acc_scaled", "acc_slot", "acc_int", "acc_uint", "acc_float")  # written only where a decoder calls them


def render(p: Protocol) -> dict[str, str]:
    if not serves(p):
        return {}
    view = AcceleratorView(p)
    functions, encoders = view.functions(), view.encoders()
    helpers = {name for name in HELPERS if any(f"{name}(" in f["body"] for f in functions + encoders)}
    source = environment().get_template("accelerator/module.c.j2").render(
        p=p, px=p.name, PX=p.name.upper(), stream=runs_streams(p), directions=view.c.directions(), tag=source_tag(p), functions=functions, encoders=encoders, helpers=helpers, globals=view.names.globals,
        attributes=view.names.attributes, slots=view.names.slots, constants=view.constants(),
        classes=sorted(view.names.classes), dicts=sorted(view.names.dicts))
    return {f"python/_{p.name}_accel.c": tidy(source, max_blank=1)}
