"""A byte stream through every stream decoder of a protocol: the Python StreamDecoder
(pure, and with the compiled accelerator when one can be built), the C scan over the
whole buffer and the C byte parser fed one byte at a time. Each gives its events as
("message", NAME, end) with the stream offset after the frame, or ("error", rule);
the byte parser, which says no offsets, gives ("message", NAME) and ("error", rule)."""
from __future__ import annotations

import os
from pathlib import Path

import pytest

from codeword import accelerate as accel
from fuzz.schema.accelerated import load as load_module
from schema_in_a_test import c_bytes, run_c


def python_events(mod, data: bytes, piece: int = 0) -> list[tuple]:
    """The events of mod.StreamDecoder on `data`, fed whole or in pieces of `piece` bytes,
    without finish(): the C decoders have no end of stream."""
    d = mod.StreamDecoder()
    out = []
    step = piece or max(1, len(data))
    for at in range(0, len(data), step):
        items = d.feed(data[at:at + step])
        for item, (start, length) in zip(items, d.spans):
            if isinstance(item, mod.DecodeError):
                out.append(("error", item.rule))
            else:
                out.append(("message", type(item).NAME, start + length))
    return out


def accelerated(where: Path, name: str):
    """The module built from `where/name.yaml` with its compiled accelerator in use; skipped
    on a developer's machine without a C compiler or Python's headers, failed in CI."""
    if accel.compiler() is None or accel.python_headers() is None:
        if os.environ.get("CI"):
            pytest.fail("a C compiler and Python's headers are needed; scripts/install-toolchains installs them")
        pytest.skip("no C compiler or Python headers for the accelerator")
    folder = where / "accelerators"
    accel.accelerate([where / f"{name}.yaml"], folder, ("-O0", "-Wall", "-Wextra", "-Werror"))
    module = load_module(where / f"{name}.py", f"_fast_{name}_{where.name}", folder)
    assert module.ACCELERATOR is not None, "the accelerator was built but is not used"
    return module


def c_events(where: Path, name: str, messages: list[str], data: bytes,
             stuffed: bool = False) -> tuple[list[tuple], list[tuple]]:
    """The events of <name>_scan over `data` in one buffer, and of the byte parser. A
    stuffed frame's scan consumes its closing delimiter, which Python's span leaves out:
    its end is given as Python gives it."""
    px, PX = name, name.upper()
    kinds = "\n".join(f'    case {PX}_MSG_{m.upper()}: return "{m}";' for m in messages)
    driver = f"""#include <stdio.h>
#include "{px}.h"
static const char *kind_name(int kind) {{
    switch (kind) {{
{kinds}
    default: return "?";
    }}
}}
static const uint8_t data[] = {{ {c_bytes(data) or "0"} }};
int main(void) {{
    size_t n = {len(data)}u, at = 0, used = 0, i;
    {px}_scan_state_t s;
    {px}_parser_t p;
    {px}_message_t m;
    int rc;
    {px}_scan_start(&s, {PX}_DIR_ANY);
    while (at < n && (rc = {px}_scan(&s, data + at, n - at, &used, &m)) != 0) {{
        at += used;
        if (rc == 1) printf("S message %s %lu\\n", kind_name((int)m.kind), (unsigned long)at);
        else printf("S error %s\\n", cw_error_name(rc));
    }}
    {px}_parser_init(&p, {PX}_DIR_ANY);
    for (i = 0; i < n; i++) {{
        {px}_parser_feed(&p, data[i]);
        while ((rc = {px}_parser_next(&p, &m)) != 0) {{
            if (rc == 1) printf("P message %s\\n", kind_name((int)m.kind));
            else printf("P error %s\\n", cw_error_name(rc));
        }}
    }}
    return 0;
}}
"""
    scan, parser = [], []
    for line in run_c(where, driver):
        who, kind, what, *end = line.split()
        (scan if who == "S" else parser).append((kind, what, int(end[0]) - stuffed) if end else (kind, what))
    return scan, parser


def without_ends(events: list[tuple]) -> list[tuple]:
    return [e[:2] for e in events]
