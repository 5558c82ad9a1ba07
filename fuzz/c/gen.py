"""Writes a libFuzzer harness and a seed corpus for one protocol.

    python3 fuzz/c/gen.py PROTOCOL OUTDIR

The harness (OUTDIR/PROTOCOL_fuzz.c) feeds the input to every decoder the
generated header offers: each message's `_decode`, the dispatching decode, the
text and word forms, the byte-at-a-time parser and the in-place scan. Whatever a decoder
accepts is encoded again and must give the same bytes (binary framings) or,
for text, a line that decodes and re-encodes to itself; a mismatch traps.
The corpus (OUTDIR/corpus/) holds every wire form of generated/vectors/PROTOCOL.json.
"""
from __future__ import annotations

import hashlib
import json
import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent.parent
sys.path.insert(0, str(ROOT))

from codeword.build import compile_schema  # noqa: E402

HEAD = """/* libFuzzer harness for {p}: written by fuzz/c/gen.py from the model. */
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include "{p}.h"

#define CHECK(cond) do {{ if (!(cond)) __builtin_trap(); }} while (0)
#define CAP 8192

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{{
    static unsigned char out[CAP];
    static unsigned char again[CAP];
    int n, k;
    (void)n; (void)k; (void)again;
"""

BINARY_MESSAGE = """    {{
        {t} m;
        if ({f}_decode(data, size, &m) >= 0) {{
            n = {f}_encode(&m, out, CAP);
            CHECK(n >= 0 && (size_t)n == size && memcmp(out, data, size) == 0);
        }}
    }}
"""

TEXT_MESSAGE = """    {{
        {t} m, m2;
        if ({f}_decode((const char *)data, size, &m) >= 0) {{
            n = {f}_encode(&m, (char *)out, CAP);
            CHECK(n >= 0);
            CHECK({f}_decode((const char *)out, (size_t)n, &m2) >= 0);
            k = {f}_encode(&m2, (char *)again, CAP);
            CHECK(k == n && memcmp(out, again, (size_t)n) == 0);
        }}
    }}
"""

WORD = """    if (size >= 4) {{
        uint32_t word = ((uint32_t)data[0] << 24) | ((uint32_t)data[1] << 16) | ((uint32_t)data[2] << 8) | data[3];
        {t} m;
        uint32_t back;
        if ({f}_from_word(word, &m) >= 0) {{
            CHECK({f}_to_word(&m, &back) >= 0 && back == word);
        }}
    }}
"""

DISPATCH_BINARY = """    {{
        {p}_message_t m;
        if ({p}_decode(data, size{dir}, &m) >= 0) {{
            n = {p}_encode(&m, out, CAP);
            CHECK(n >= 0 && (size_t)n == size && memcmp(out, data, size) == 0);
        }}
    }}
"""

DISPATCH_TEXT = """    {{
        {p}_message_t m, m2;
        if ({p}_decode((const char *)data, size{dir}, &m) >= 0) {{
            n = {p}_encode(&m, (char *)out, CAP);
            CHECK(n >= 0);
            CHECK({p}_decode((const char *)out, (size_t)n{dir}, &m2) >= 0 && m2.kind == m.kind);
        }}
    }}
"""

ROUTE_FORMS = """    {{
        {p}_message_t m;
        (void){p}_decode_text((const char *)data, size, &m);
        if (size >= 4) {{
            uint32_t word = ((uint32_t)data[0] << 24) | ((uint32_t)data[1] << 16) | ((uint32_t)data[2] << 8) | data[3];
            (void){p}_decode_word(word, &m);
        }}
    }}
"""

PARSER = """    {{
        {p}_parser_t parser;
        {p}_message_t m;
        size_t i;
        int rc, guard;
        {p}_parser_init(&parser, {P}_DIR_ANY);
        for (i = 0; i < size; i++) {{
            CHECK({p}_parser_feed(&parser, data[i]) == 0);
            for (guard = 0; (rc = {p}_parser_next(&parser, &m)) != 0; guard++) {{
                CHECK(guard <= (int)sizeof parser.buf);  /* every call consumes or returns 0 */
                if (rc == 1) {{
                    n = {p}_encode(&m, out, CAP);
                    CHECK(n > 0);
                }}
            }}
        }}
    }}
    {{
        {p}_scan_state_t scan;
        {p}_message_t m;
        size_t at = 0, used;
        int rc;
        {p}_scan_start(&scan, {P}_DIR_ANY);
        while ((rc = {p}_scan(&scan, data + at, size - at, &used, &m)) != 0) {{  /* in place */
            CHECK(used > 0 && used <= size - at);  /* every event consumes a byte or more */
            at += used;
            if (rc == 1) {{
                n = {p}_encode(&m, out, CAP);
                CHECK(n > 0);
            }}
        }}
    }}
"""


def harness(name: str) -> str:
    p = compile_schema(ROOT / "schemas" / f"{name}.yaml")
    header = (ROOT / "generated" / "c" / f"{name}.h").read_text(encoding="utf-8")
    text = p.framing.kind == "text"
    parts = [HEAD.format(p=name)]
    for m in p.messages:
        f, t = f"{name}_{m.name}", f"{name}_{m.name}_t"
        if f"{f}_decode(" in header:
            parts.append((TEXT_MESSAGE if text else BINARY_MESSAGE).format(f=f, t=t))
        if f"{f}_from_word(" in header and f"{f}_to_word(" in header:
            parts.append(WORD.format(f=f, t=t))
    signature = re.search(rf"static inline int {name}_decode\(([^)]*)\)", header)
    if signature:
        direction = f", {name.upper()}_DIR_ANY" if "direction" in signature.group(1) else ""
        parts.append((DISPATCH_TEXT if text else DISPATCH_BINARY).format(p=name, dir=direction))
    if f"{name}_decode_text(" in header:
        parts.append(ROUTE_FORMS.format(p=name))
    if f"{name}_parser_init(" in header:
        parts.append(PARSER.format(p=name, P=name.upper()))
    parts.append("    return 0;\n}\n")
    return "".join(parts)


def corpus(name: str, out: Path) -> int:
    vectors = json.loads((ROOT / "generated" / "vectors" / f"{name}.json").read_text())
    out.mkdir(parents=True, exist_ok=True)
    count = 0
    for group in ("valid", "invalid", "streams"):
        for case in vectors.get(group, []):
            for key in ("hex", "text", "text_form"):
                if key not in case:
                    continue
                raw = bytes.fromhex(case[key]) if key == "hex" else case[key].encode("utf-8")
                (out / hashlib.sha1(raw).hexdigest()).write_bytes(raw)
                count += 1
    return count


def main(argv: list[str]) -> int:
    name, outdir = argv[0], Path(argv[1])
    outdir.mkdir(parents=True, exist_ok=True)
    (outdir / f"{name}_fuzz.c").write_text(harness(name), encoding="utf-8")
    corpus(name, outdir / "corpus")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
