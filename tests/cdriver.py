"""Writes a C conformance driver for one protocol from its model and its vector
file (generated/vectors/<protocol>.json). The same driver runs on the host,
under simavr (ATmega32) and under qemu (Cortex-M3); it prints one line per
failure and a final `CONFORMANCE <protocol> PASS <n>` or `... FAIL <n>`.

Expected structs come from the vectors' decoded values (the Python codec's
view), turned into C initialisers here; nothing is computed by the C code
under test.
"""
from __future__ import annotations

import json
import math
from decimal import Decimal
from fractions import Fraction
from pathlib import Path
from typing import Any

from codeword.model import Field, Protocol
from codeword.binary64 import bits_of
from codeword.targets.c.scalars import clit, clit_signed
from codeword.targets.c.view import ERR, CView, cchar, cstr

ROOT = Path(__file__).resolve().parent.parent
TEMPLATE = Path(__file__).resolve().parent / "c" / "driver.c.j2"


def load_vectors(name: str) -> dict:
    return json.loads((ROOT / "generated" / "vectors" / f"{name}.json").read_text())


class Driver:
    def __init__(self, p: Protocol):
        self.p = p
        self.v = CView(p)
        self.text = p.framing.kind == "text"

    # -- expected values as C initialisers ------------------------------------------------
    def init(self, fields: tuple[Field, ...], values: dict) -> str:
        parts = []
        for f in fields:
            if not f.is_member:
                continue
            value = values.get(f.name)
            if (f.present_if or f.multiplexed_by) and value is None:  # absent: zeros, as the decoder leaves it
                continue
            if f.count is not None:  # an array: one initialiser per element
                element = f.element
                if value:  # an empty list: zeros, as a missing initialiser leaves them
                    parts.append(f".{f.name} = {{{', '.join(self.one(element, x) for x in value)}}}")
                if f.varies:  # elements past the count are 0, as the decoder leaves them
                    parts.append(f".{f.name}_count = {len(value)}u")
                if self.v.rep(element).has_flag and value:
                    parts.append(f".has_{f.name} = {{{', '.join('false' if x is None else 'true' for x in value)}}}")
                continue
            if f.kind == "group":
                parts.append(f".{f.name} = {self.init(f.fields, value)}")
                continue
            r = self.v.rep(f)
            if r.has_flag:
                parts.append(f".has_{f.name} = {'false' if value is None else 'true'}")
                if value is None:
                    continue
            parts.append(f".{f.name} = {self.scalar(f, value)}")
            if f.varies:  # counted bytes: the bytes past the count are 0, as the decoder leaves them
                parts.append(f".{f.name}_count = {len(bytes.fromhex(value))}u")
        return "{" + ", ".join(parts) + "}" if parts else "{0}"

    def one(self, f: Field, value: Any) -> str:
        """The initialiser of one array element (0 for an absent one)."""
        if f.kind == "group":
            return self.init(f.fields, value)
        return "0" if value is None else self.scalar(f, value)

    def scalar(self, f: Field, value: Any) -> str:
        if f.kind == "bool":
            return "true" if value else "false"
        if f.enum is not None:
            member = next((m for m in f.enum.members if value in (m.name, m.value)), None)
            if member is None:  # an open enum's other value
                return int_literal(int(value))
            return self.v.enum_const(f.enum.name, member.name)
        if f.flags is not None:
            mask = 0
            for name in value:
                mask |= 1 << next(b.bit for b in f.flags.members if b.name == name)
            return f"{mask:#x}u"
        if f.kind == "float" and self.text:
            d = Decimal(repr(float(value)))
            sign, digits, exp = d.as_tuple()
            number = int("".join(map(str, digits)) or "0")
            while number and number % 10 == 0:
                number //= 10
                exp += 1
            if number == 0:
                exp = 0
            return f"{{{number}ULL, {exp}, {'true' if sign else 'false'}}}"
        if f.kind == "float" and f.bits == 64:  # the member is a double or its bits (codeword.h)
            return f"CW_F64_CONST({bits_of(float(value)):#018x}ULL, {c_real(float(value))})"
        if f.kind == "float":
            return c_real(float(value), "f")
        if f.kind == "char":
            return cchar(value)
        if f.kind == "str":
            return cstr(value)
        if f.kind == "bytes":
            return "{" + (", ".join(f"0x{b:02x}" for b in bytes.fromhex(value)) or "0") + "}"
        if f.decimals:  # decoded as raw / 10**decimals, correctly rounded: the nearest raw
            return int_literal(round((Fraction(value) - Fraction(f.offset or 0)) * 10 ** f.decimals))
        if f.scale is not None:
            raw = (Fraction(value) - Fraction(f.offset or 0)) / Fraction(f.scale)
            if raw.denominator != 1:  # a decimal scale: the raw value whose product is this double
                raw = Fraction(round(raw))
                assert int(raw) * f.scale + (f.offset or 0) == value, (f.name, value)
            return int_literal(int(raw))
        return int_literal(int(value))

    # -- equality of two decoded structs ----------------------------------------------------
    def equal_lines(self, fields: tuple[Field, ...], prefix: str, index: str = "") -> list[str]:
        out = []
        for f in fields:
            if not f.is_member:
                continue
            if f.count is not None:  # an array: each element as a field of its own
                element = f.element
                if f.varies:
                    out.append(f"if (a->{prefix}{f.name}_count != b->{prefix}{f.name}_count) return false;")
                for i in range(f.count):
                    out += self.equal_lines((element,), prefix, f"[{i}]")
                continue
            a, b = f"a->{prefix}{f.name}{index}", f"b->{prefix}{f.name}{index}"
            if f.kind == "group":
                out += self.equal_lines(f.fields, f"{prefix}{f.name}{index}.")
                continue
            r = self.v.rep(f)
            guard = ""
            if r.has_flag:
                out.append(f"if (a->{prefix}has_{f.name}{index} != b->{prefix}has_{f.name}{index}) return false;")
                guard = f"a->{prefix}has_{f.name}{index} && "
            if f.kind == "float" and self.text:
                cond = f"!eq_decimal(&{a}, &{b})"
            elif f.kind == "float":
                to_bits = "cw_f64_to_bits" if f.bits == 64 else "cw_f32_to_bits"
                cond = f"{to_bits}({a}) != {to_bits}({b})"
            elif f.kind == "str":
                cond = f"strcmp({a}, {b}) != 0"
            elif f.kind == "bytes" and f.varies:
                out.append(f"if ({a}_count != {b}_count) return false;")
                cond = f"memcmp({a}, {b}, {f.length}) != 0"
            elif f.kind == "bytes":
                cond = f"memcmp({a}, {b}, {f.length}) != 0"
            else:
                cond = f"{a} != {b}"
            out.append(f"if ({guard}{cond}) return false;")
        return out

    # -- vector tables ----------------------------------------------------------------------
    def wire_bytes(self, case: dict, key: str = "") -> bytes:
        if key == "kept":  # what encoding the decoded message writes, kept spellings and all
            return self.wire_bytes(case, "canonical") if "kept" not in case else case["kept"].encode("ascii")
        if key == "canonical":
            value = case.get("canonical")
            if value is None:
                return self.wire_bytes(case)
            return value.encode("ascii") if self.text else bytes.fromhex(value)
        return case["text"].encode("latin-1") if self.text else bytes.fromhex(case["hex"])

    def direction(self, case: dict) -> str:
        d = case.get("direction")
        return self.v.upper("DIR", d) if d and self.v.p.directions else "0"

    def source(self, vectors: dict, part: int = 0, parts: int = 1) -> str:
        import jinja2
        p = self.p

        def mine(items: list) -> list:
            return [x for i, x in enumerate(items) if i % parts == part]

        trailer = p.framing.trailer.fields if p.framing.trailer else ()
        messages = []
        for m in p.messages:
            cases = mine([c for c in vectors["valid"] if c["message"] == m.name])
            messages.append({
                "m": m, "t": self.v.tname(m), "fn": f"{p.name}_{m.name}",
                "kind": self.v.upper("MSG", m.name),
                "equal": self.equal_lines(m.layout, ""),
                "cases": [{"wire": self.wire_bytes(c), "canon": self.wire_bytes(c, "canonical"),
                           "kept": self.wire_bytes(c, "kept"),
                           "expected": self.init(m.layout, c["values"]), "word": c.get("word"),
                           "trailer": self.init(trailer, c["values"]), "verify": int(bool(c.get("verify"))),
                           "trailered": int(any(c["values"].get(f.name) is not None for f in trailer)),
                           "text_form": c.get("text_form"), "dir": self.direction(c),
                           "name": c["name"]} for c in cases],
            })
        invalid = [{"wire": self.wire_bytes(c), "error": c["error"], "dir": self.direction(c),
                    "verify": int(bool(c.get("verify"))),
                    "kind": self.v.upper("MSG", c["message"]), "name": c["name"],
                    "fn": f"{p.name}_{c['message']}"} for c in mine(vectors["invalid"])]
        streams = []
        for s in mine(vectors.get("streams", [])):  # spread over the parts, as the frames are
            events = []
            for e in s["events"]:
                span = {"at": e.get("at", 0), "length": e.get("length", 0)}  # text: where its line lies
                if "error" in e:
                    events.append({"error": e["error"], **span})
                else:
                    m = p.message(e["message"])
                    events.append({"kind": self.v.upper("MSG", m.name), "name": m.name,
                                   "expected": self.init(m.layout, e["values"]),
                                   "trailer": self.init(trailer, e["values"]), **span})
            data = s["text"].encode("latin-1") if "text" in s else bytes.fromhex(s["hex"])
            streams.append({"bytes": data, "events": events, "name": s["name"]})
        sequences = self.sequences(mine(vectors.get("sequences", [])))
        seq_wires = [c["wire"] for s in sequences for c in s["cases"]]
        kept = any(leaf.field.keep_spelling for m in p.messages for leaf in m.wire.leaves) \
            or any(m.keeps_places for m in p.messages)
        wires = list(dict.fromkeys([c["wire"] for mm in messages for c in mm["cases"]]
                                   + [c["canon"] for mm in messages for c in mm["cases"]]
                                   + [c["kept"] for mm in messages for c in mm["cases"] if kept]
                                   + [c["wire"] for c in invalid] + seq_wires))
        env = jinja2.Environment(undefined=jinja2.StrictUndefined, trim_blocks=True, lstrip_blocks=True,
                                 keep_trailing_newline=True)  # clang -Wpedantic: a file ends with a newline
        env.filters["cbytes"] = lambda b: "{" + ", ".join(f"0x{x:02x}" for x in b) + "}" if b else "{0}"
        env.filters["cstr"] = cstr
        wire_max = max([len(c["wire"]) for mm in messages for c in mm["cases"]]
                       + [len(c["canon"]) for mm in messages for c in mm["cases"]]
                       + [len(c["kept"]) for mm in messages for c in mm["cases"]]
                       + [len(c["wire"]) for c in invalid] + [len(w) for w in seq_wires] + [1]
                       # an encoder writes the largest frame before it leaves out what is not sent
                       + [m.size for m in p.messages if m.size is not None and p.framing.kind == "bytes"])
        return env.from_string(TEMPLATE.read_text()).render(
            p=p, px=p.name, PX=p.name.upper(), messages=messages, invalid=invalid, streams=streams,
            ids=self.id_checks() if part == 0 else [],
            wires=wires, wire_index={w: i for i, w in enumerate(wires)},
            decimals=self.text and any(leaf.field.kind == "float" for m in p.messages for leaf in m.wire.leaves),
            text=self.text, wire_max=wire_max + 1, self_identifying=p.self_identifying,
            # a byte stream without an encoding: the frames a stream's last bytes hold come at its end
            ends_frames=not self.text and not p.framing.encoding,
            len_t="uint16_t" if wire_max < 1 << 16 else "uint32_t",  # frames over 64 KiB need more
            has_dir=p.framing.kind != "bits",  # decode takes a direction (PX_DIR_ANY: any)
            word=self.v.word_bits() is not None and p.framing.kind == "bits",
            word_type="uint64_t" if (self.v.word_bits() or 0) > 32 else "uint32_t",
            text_form=p.framing.text_form is not None,
            error_const=ERR, sequences=sequences, kept=kept, can=p.framing.can is not None,
            # an encoded stream's scan consumes every byte; any other leaves less than a frame
            scan_window=f"{p.name.upper()}_STREAM_MAX + 8u" if not p.framing.encoding else "16u",
            scan_left=f"{p.name.upper()}_STREAM_MAX" if not p.framing.encoding else "1u",
            seq_cap=self.seq_cap(sequences), trailer=bool(trailer),
            trailer_equal=self.equal_lines(trailer, ""),
            key=bytes.fromhex(vectors["signing_key"]) if "signing_key" in vectors else b"")

    def id_checks(self) -> list[str]:
        """Conditions true when a message's id constant (`<P>_<MSG>_ID`, `_ID<i>` for one
        of several) is not the schema's id: a text prefix is a string, any other an integer."""
        out = []
        for m in self.p.messages:
            for i, value in enumerate(m.ids):
                name = f"{self.p.name}_{m.name}_ID".upper() if len(m.ids) == 1 else f"{self.p.name}_{m.name}_ID{i}".upper()
                if isinstance(value, str):
                    out.append(f"strcmp({name}, {cstr(value)}) != 0")
                else:
                    out.append(f"(unsigned long){name} != {value}UL")
        return out

    def seq_cap(self, sequences: list[dict]) -> int:
        """Room for the messages of any sequence vector: a rejected one is decoded up to
        its error, which can be its last unit, and has at most a unit per smallest message."""
        smallest = min([m.size for m in self.p.messages if m.size] or [1])
        counts = [len(c["wire"]) // smallest if c["error"] else len(c["messages"])
                  for sq in sequences for c in sq["cases"]]
        return max(counts + [0]) + 2

    def sequences(self, cases: list[dict]) -> list[dict]:
        """Whole-sequence vectors by sequence; expected messages as initialisers of
        the protocol's message union, laid out one after another."""
        out = []
        for s in self.p.sequences:
            mine = []
            for c in (c for c in cases if c["sequence"] == s.name):
                messages = [{"kind": self.v.upper("MSG", u["message"]), "name": u["message"],
                             "expected": self.init(self.p.message(u["message"]).layout, u["values"])}
                            for u in c.get("messages", [])]
                mine.append({"name": c["name"], "wire": bytes.fromhex(c["hex"]), "messages": messages,
                             "error": c.get("error"), "index": c.get("index"),
                             "rule": c.get("error") in ("consecutive", "equal", "member", "unique")})
            if mine:
                out.append({"name": s.name, "fn": f"{self.p.name}_{s.name}", "cases": mine})
        return out


def c_real(value: float, suffix: str = "") -> str:
    """A C expression of a float: NaN (the quiet NaN of <math.h>) and the infinities by name."""
    if value != value:
        return "NAN"
    if value in (math.inf, -math.inf):
        return "INFINITY" if value > 0 else "-INFINITY"
    return repr(value) + suffix


def int_literal(value: int) -> str:
    """A C literal of `value` for a member of any integer type: INT64_MIN and values
    above INT64_MAX have no plain decimal spelling."""
    return clit(value, True) if value >= 1 << 63 else clit_signed(value) if value >= 0 else clit(value)


def firmware_source(p: Protocol, include: bool = True) -> str:
    """A translation unit as firmware writes it: each message encoded from a struct
    it is handed into a buffer on the stack, and decoded from a frame into a struct
    on the stack, both handed on to functions of another unit. With the codec inlined
    into them, the compiler's flow analysis (-Wmaybe-uninitialized) sees the locals of
    the encoder and decoder; the conformance driver's buffers are static. Every name
    starts with the protocol's or `fw_`, so these units go in one file with several
    protocols' or with the conformance driver."""
    px, text = p.name, p.framing.kind == "text"
    unit = "char" if text else "uint8_t"
    lines = [f'#include "{px}.h"', ""] if include else []
    lines += [f"int {px}_fw_send(const void *fw_frame, int fw_n);", ""]
    for m in p.messages:
        t, fn = f"{px}_{m.name}_t", f"{px}_{m.name}"
        room = f"{px.upper()}_{m.name.upper()}_MAX_TEXT" if text else f"{2 * (m.size or 1) + 8}u"  # room to stuff
        lines += [f"int {fn}_fw_use(const {t} *fw_m);",
                  f"int {fn}_fw_send(const {t} *fw_m);",
                  f"int {fn}_fw_send(const {t} *fw_m)", "{", f"    {unit} fw_out[{room}];",
                  f"    return {px}_fw_send(fw_out, {fn}_encode(fw_m, fw_out, sizeof fw_out));", "}", "",
                  f"int {fn}_fw_receive(const {unit} *fw_frame, size_t fw_n);",
                  f"int {fn}_fw_receive(const {unit} *fw_frame, size_t fw_n)", "{", f"    {t} fw_m;",
                  f"    int fw_rc = {fn}_decode(fw_frame, fw_n, &fw_m);",
                  f"    return fw_rc < 0 ? fw_rc : {fn}_fw_use(&fw_m);", "}", ""]
    return "\n".join(lines)


def selection_flags(px: str, names) -> tuple[str, ...]:
    """The -D flags of a build that selects `names` of protocol `px` (upper case), none if empty."""
    return (f"-D{px}_SELECTED_MESSAGES", *(f"-D{px}_SELECT_{n.upper()}" for n in names))


def selection_applies(p: Protocol) -> bool:
    """A protocol whose dispatching decoder reads the frames of the vectors as they are:
    found by id or prefix, not stuffed, signed or carried in CAN frames."""
    fr = p.framing
    return p.self_identifying and not fr.encoding and not fr.trailer and fr.can is None and not fr.stuffing


def selection_source(p: Protocol, vectors: dict, selected: list[str]) -> str:
    """A program built with only `selected` messages (`<PX>_SELECTED_MESSAGES`): each valid
    frame of the vectors through the dispatching decoder is its message where selected
    (and encodes back to the same frame), CW_ERR_DISPATCH where not, as is encoding a
    message that is not selected. Prints `SELECTION <px> PASS <checks>` or each failure."""
    px, PX, text = p.name, p.name.upper(), p.framing.kind == "text"
    directed = p.framing.kind != "bits"
    cases = [c for c in vectors["valid"] if "canonical" not in c and "kept" not in c and ("text" in c or "hex" in c)]
    rows = []
    for c in cases:
        wire = c["text"] if text else bytes.fromhex(c["hex"])
        literal = cstr(wire) if text else "{" + ", ".join(f"0x{b:02x}" for b in wire) + "}"
        direction = f"{PX}_DIR_{c['direction'].upper()}" if c.get("direction") else f"{PX}_DIR_ANY"
        kind = f"{PX}_MSG_{c['message'].upper()}"
        rows.append(f"    {{{literal}, {len(wire)}u, {direction if directed else 0}, {kind}, "
                    f"{int(c['message'] in selected)}}},")
    unit = "char" if text else "uint8_t"
    longest = max((len(c["text"] if text else bytes.fromhex(c["hex"])) for c in cases), default=1)
    unselected = [m.name for m in p.messages if m.name not in selected]
    encodes = "\n".join(f"    any.kind = {PX}_MSG_{name.upper()};\n"
                        f"    checks++;\n"
                        f"    if ({px}_encode(&any, out, sizeof out) != CW_ERR_DISPATCH) {{\n"
                        f"        printf(\"FAIL encode {name}\\n\");\n"
                        f"        failures++;\n"
                        f"    }}" for name in unselected)
    return f"""#include <stdio.h>
#include <string.h>
#include "{px}.h"

static const struct {{
    {unit} wire[{longest + 1}];
    size_t len;
    int direction;
    int kind;
    int selected;
}} CASES[] = {{
{chr(10).join(rows) or "    {{0}, 0u, 0, 0, 0},"}
}};

int main(void)
{{
    static {px}_message_t any;
    static {unit} out[{longest + 16}];
    unsigned checks = 0, failures = 0;
    size_t i;
    for (i = 0; i < {len(rows)}u; i++) {{
        int rc;
        memset(&any, 0, sizeof any);
        rc = {px}_decode(CASES[i].wire, CASES[i].len, {"CASES[i].direction, " if directed else ""}&any);
        checks++;
        if (CASES[i].selected ? rc != CW_OK || any.kind != CASES[i].kind : rc != CW_ERR_DISPATCH) {{
            printf("FAIL decode %u rc=%d\\n", (unsigned)i, rc);
            failures++;
        }} else if (CASES[i].selected && ({px}_encode(&any, out, sizeof out) != (int)CASES[i].len
                                         || memcmp(out, CASES[i].wire, CASES[i].len) != 0)) {{
            printf("FAIL encode %u\\n", (unsigned)i);
            failures++;
        }}
    }}
    memset(&any, 0, sizeof any);
{encodes}
    if (failures == 0) {{
        printf("SELECTION {px} PASS %u\\n", checks);
    }}
    return failures != 0;
}}
"""
