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


def python_text_events(mod, data: bytes, piece: int = 0) -> list[tuple]:
    """The events of a text protocol's StreamDecoder on `data`, fed whole or in pieces
    of `piece` characters, then finish(): each as (kind, NAME or rule, start, length),
    where its line lies in the stream."""
    d = mod.StreamDecoder()
    out = []
    step = piece or max(1, len(data))

    def take(items: list) -> None:
        for item, (start, length) in zip(items, d.spans):
            if isinstance(item, mod.DecodeError):
                out.append(("error", item.rule, start, length))
            else:
                out.append(("message", type(item).NAME, start, length))
    for at in range(0, len(data), step):
        take(d.feed(data[at:at + step]))
    take(d.finish())
    return out


def c_text_events(where: Path, name: str, messages: list[str], data: bytes,
                  chunk: int = 0) -> tuple[list[tuple], list[tuple]]:
    """The events of <name>_scan, its characters arriving `chunk` at a time (0: all at
    once) into a window it reads in place, and of the parser fed one at a time, each
    then told the stream ended: as python_text_events gives them."""
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
static void show(char who, int rc, const {px}_message_t *m, uint32_t at, uint32_t length) {{
    if (rc == 1) printf("%c message %s %lu %lu\\n", who, kind_name((int)m->kind), (unsigned long)at, (unsigned long)length);
    else printf("%c error %s %lu %lu\\n", who, cw_error_name(rc), (unsigned long)at, (unsigned long)length);
}}
static const uint8_t data[] = {{ {c_bytes(data) or "0"} }};
static char window[{PX}_STREAM_MAX + {max(chunk, len(data))}u];
int main(void) {{
    size_t n = {len(data)}u, next = 0, have = 0, at, used, i, chunk = {chunk or len(data) or 1}u;
    {px}_scan_state_t s;
    {px}_parser_t p;
    {px}_message_t m;
    int rc;
    {px}_scan_start(&s, {PX}_DIR_ANY);
    while (next < n) {{
        size_t take = n - next < chunk ? n - next : chunk;
        for (i = 0; i < take; i++) window[have + i] = (char)data[next + i];
        next += take;
        have += take;
        at = 0;
        while ((rc = {px}_scan(&s, window + at, have - at, &used, &m)) != 0) {{
            at += used;
            show('S', rc, &m, s.at, s.length);
        }}
        at += used;
        memmove(window, window + at, have - at);
        have -= at;
    }}
    if ((rc = {px}_scan_finish(&s, window, have)) != 0) show('S', rc, &m, s.at, s.length);
    {px}_parser_init(&p, {PX}_DIR_ANY);
    for (i = 0; i < n; i++) {{
        if ({px}_parser_feed(&p, (char)data[i]) != CW_OK) {{ printf("P full\\n"); return 1; }}
        while ((rc = {px}_parser_next(&p, &m)) != 0) show('P', rc, &m, p.scan.at, p.scan.length);
    }}
    if ((rc = {px}_parser_finish(&p)) != 0) show('P', rc, &m, p.scan.at, p.scan.length);
    return 0;
}}
"""
    scan, parser = [], []
    for line in run_c(where, driver):
        who, kind, what, start, length = line.split()
        (scan if who == "S" else parser).append((kind, what, int(start), int(length)))
    return scan, parser
