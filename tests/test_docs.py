"""The Markdown specs in generated/docs and the MkDocs site built from them.

Expected widths, offsets, times and checksums come from the seeds, PROTOCOLS.md
or hand calculation; the model is used only to enumerate what must be there.
"""
from __future__ import annotations

import re
import shutil
import subprocess
import sys

import pytest

from codeword.build import build, compile_schema, render_with_codec
from codeword.targets import markdown
from conftest import PROTOCOLS, ROOT, SCHEMAS, load_generated, load_model

DOCS = ROOT / "generated" / "docs"
CELL_SPLIT = re.compile(r"(?<!\\)\|")


def page(name: str) -> str:
    return (DOCS / f"{name}.md").read_text(encoding="utf-8")


def section(text: str, anchor: str) -> str:
    """The text from `<a id="anchor">` to the next anchor of a message or top-level section."""
    start = text.index(f'<a id="{anchor}"></a>')
    rest = text[start + 1:]
    ends = [m.start() for m in re.finditer(r'<a id="(msg-|enumerations|checksum|framing)', rest)]
    return rest[:ends[0]] if ends else rest


def table_after(text: str, heading: str) -> list[dict[str, str]]:
    """The Markdown table that follows `heading`, as dicts keyed by the header cells."""
    lines = text[text.index(heading):].splitlines()
    rows = [l for l in lines[1:] if l.startswith("|")]
    block = []
    for line in lines[1:]:
        if line.startswith("|"):
            block.append(line)
        elif block:
            break
    assert rows, f"no table after {heading!r}"
    cells = [[c.strip() for c in CELL_SPLIT.split(line)[1:-1]] for line in block]
    header, body = cells[0], cells[2:]
    return [dict(zip(header, row)) for row in body]


def field_table(protocol: str, message: str) -> dict[str, dict[str, str]]:
    rows = table_after(section(page(protocol), f"msg-{message.replace('_', '-')}"), "**Fields:**")
    out = {}
    for row in rows:
        name = re.search(r"`([^`]+)`", row["field"]).group(1)
        out[name] = row
    return out


def model_fields(fields, start=0, prefix=""):
    """(dotted path, bits, offset) by summing widths in declaration order; the model's own
    offsets, where it has them, must agree."""
    pos = start
    for f in fields:
        if f.is_payload:
            continue
        if f.bit_offset is not None:
            assert f.bit_offset == pos, (prefix + f.name, f.bit_offset, pos)
        yield prefix + f.name, f.bits, pos
        if f.kind == "group":
            yield from model_fields(f.fields, pos, prefix + f.name + ".")
        pos += f.bits or 0


# ---------------------------------------------------------------- generation


def test_six_pages_generated_deterministic_and_current():
    expected = {"index.md", "codeword.css"} | {f"{p}.md" for p in PROTOCOLS}
    assert expected <= {p.name for p in DOCS.iterdir()}
    protocols = [compile_schema(SCHEMAS / f"{name}.yaml", f"schemas/{name}.yaml") for name in PROTOCOLS]
    for p in protocols:
        codec = render_with_codec(p)[1]
        first = markdown.render(p, codec)
        assert first == markdown.render(p, codec)
        assert first[f"docs/{p.name}.md"] == page(p.name), f"generated/docs/{p.name}.md is stale"
    index = markdown.render_index(protocols)["docs/index.md"]
    assert index == (DOCS / "index.md").read_text(encoding="utf-8")


def test_build_check_covers_docs(tmp_path):
    out = tmp_path / "generated"
    shutil.copytree(ROOT / "generated", out)
    (out / "docs" / "car.md").write_text("edited by hand\n", encoding="utf-8")
    result = build([SCHEMAS / "car.yaml"], out, check=True, root=ROOT)
    assert out / "docs" / "car.md" in result.stale


def test_index_lists_every_protocol_once_with_transport_and_message_count():
    index = (DOCS / "index.md").read_text(encoding="utf-8")
    rows = {re.search(r"\[(\w+)\]\((\w+)\.md\)", r["protocol"]).group(1): r
            for r in table_after(index, "# Protocol specifications")}
    assert set(rows) == set(PROTOCOLS)
    # Message counts per PROTOCOLS.md: route 4 sentences, car header + 2 control words,
    # tank 5 prefixes, mtv4 3 commands + 2 replies, tr24 command + reply.
    assert {k: int(v["messages"]) for k, v in rows.items()} == {
        "route": 4, "car": 3, "tank": 5, "mtv4": 5, "tr24": 2}
    assert "rc5" in rows["route"]["transports"] and "zigbee" in rows["route"]["transports"]
    assert "cc2500" in rows["mtv4"]["transports"]


# ---------------------------------------------------------------- field tables


@pytest.mark.parametrize("protocol", PROTOCOLS)
def test_every_field_in_its_table_with_width_and_offset(protocol):
    p = load_model(protocol)
    for m in p.messages:
        table = field_table(protocol, m.name)
        for index, (path, bits, offset) in enumerate(model_fields(m.layout)):
            assert path in table, f"{protocol}.{m.name}: field {path} missing from the table"
            row = table[path]
            if p.framing.kind == "text":
                continue
            assert row["bits"] == str(bits), (m.name, path, row["bits"])
            assert row["offset"] == str(offset), (m.name, path, row["offset"])
        if p.framing.kind == "text":  # text fields are numbered 1, 2, … in line order
            numbers = [table[f.name]["#"] for f in m.layout if not f.is_payload]
            assert numbers == [str(i) for i in range(1, len(numbers) + 1)]


def test_route_object_layout_matches_the_seed_table():
    # Seed table: HDR 2 | ns 3 | nl 3 | no 3 | na 3 | dl 3 | rc 2 | dr 3 | cm 4 | CS 3 = 29 bits.
    table = field_table("route", "object")
    expected = {"hdr": (2, 0), "ns": (3, 2), "nl": (3, 5), "no": (3, 8), "na": (3, 11),
                "dl": (3, 14), "rc": (2, 17), "dr": (3, 19), "cm": (4, 22), "cs": (3, 26)}
    assert {k: (int(table[k]["bits"]), int(table[k]["offset"])) for k in expected} == expected
    assert "10 … 17" in table["na"]["range"] and "− 10" in table["na"]["range"]  # ROUTE-D6
    diagram = section(page("route"), "msg-object")
    assert "| **bits** | 2 | 3 | 3 | 3 | 3 | 3 | 2 | 3 | 4 | 3 |" in diagram


def test_car_control_word_shows_the_width_decision():
    # CAR-D1: c3 motor 7 bits at word bits 29-23, c8 reserved 11 bits at 11-1, c9 parity bit 0.
    table = field_table("car", "master_control")
    assert (table["motor"]["bits"], table["motor"]["word bits"]) == ("7", "29–23")
    assert (table["reserved_bits"]["bits"], table["reserved_bits"]["word bits"]) == ("11", "11–1")
    assert (table["parity"]["bits"], table["parity"]["word bits"]) == ("1", "0")
    assert table["motor.duration"]["offset"] == "7"  # 1 + 1 + enable 1 + direction 2 + speed 2
    text = page("car")
    notes = section(text, "note-car-d1")
    assert "c3=6 and c8=12" in notes and "c3=7, c5=5, c8=11" in notes
    assert "[CAR-D1](#note-car-d1)" in table["motor"]["meaning"]


def test_mtv4_and_tr24_byte_positions():
    # mtv4 frame per the seed: B0 AA, B1 length, B2 group, B3 code, B4-B5 robots, data, CRC.
    t = field_table("mtv4", "set_wheels_velocities")
    assert t["robots"]["bytes"] == "B4–B5" and t["robots"]["type"].startswith("u16 LE")
    assert t["command"]["bytes"] == "B3 bits 6–0" and t["radio_crc_flag"]["bytes"] == "B3 bit 7"
    assert t["vl"]["bytes"] == "B6–B7" and t["crc"]["bytes"] == "B10–B11"
    assert t["crc"]["type"].startswith("u16 BE")  # MTV4-D1: CRC high byte first
    # tr24 service byte (TR24-D1): bits 7-2 reserved, bit 1 type, bit 0 sequence number.
    t = field_table("tr24", "command")
    assert t["reserved"]["bytes"] == "B1 bits 7–2" and t["type"]["bytes"] == "B1 bit 1"
    assert t["seq"]["bytes"] == "B1 bit 0" and t["data"]["bytes"] == "B4–B10"


def test_tank_command_line_shape():
    # Seed: %:move,speed,value,azimutloc,gpio1..gpio4,systemstatus,data; with data optional (TANK-D1).
    text = section(page("tank"), "msg-command")
    assert "%:move,speed,value,azimutloc,gpio1,gpio2,gpio3,gpio4,systemstatus[,data];" in text
    assert field_table("tank", "command")["data"]["#"] == "10"


# ---------------------------------------------------------------- examples


def _example_rows(protocol: str, message: str) -> list[dict[str, str]]:
    return table_after(section(page(protocol), f"msg-{message.replace('_', '-')}"), "**Examples:**")


@pytest.mark.parametrize("protocol", PROTOCOLS)
def test_every_example_shown_is_the_codec_output_and_the_schema_form(protocol):
    p = load_model(protocol)
    codec = load_generated(protocol)
    for m in p.messages:
        rows = _example_rows(protocol, m.name)
        assert len(rows) == len(m.examples), m.name
        for ex, row in zip(m.examples, rows):
            shown = dict(re.findall(r"(hex|word|text) `([^`]*)`", row["wire"].replace("\\|", "|")))
            written = {}
            if ex.hex is not None:
                written["hex"] = ex.hex.hex(" ")
            if ex.word is not None:
                written["word"] = f"0x{ex.word:08x}"
            if ex.text is not None:
                written["text"] = ex.text
            assert shown == written, (m.name, ex.name)
            if ex.errors:
                assert "**rejected:**" in row["decoded"], ex.name
                continue
            if ex.decode_only:
                continue
            value = codec.from_dict(m.name, ex.values)
            if "hex" in shown:
                assert codec.encode(value).hex(" ") == shown["hex"]
            if "word" in shown:
                assert f"0x{codec.encode_word(value):08x}" == shown["word"]
            if "text" in shown:
                encode = codec.encode if p.framing.kind == "text" else codec.encode_text
                assert encode(value) == shown["text"]


def test_decoded_values_beside_the_examples():
    # mtv4 seed example computed by hand: 100.5 mm/s and -20 mm/s to robot 5 of group 3.
    row = _example_rows("mtv4", "set_wheels_velocities")[0]
    assert "vl = `100.5`" in row["decoded"] and "vr = `-20`" in row["decoded"]
    assert "robots = `robot5`" in row["decoded"]
    row = _example_rows("tank", "gpio_config")[1]  # the seed's spacing, read and written back
    assert "`-:1, 2, 0, 3;`" in row["wire"] and "written back as `-:1,2,0,3;`" in row["wire"]


def test_a_wrong_example_fails_the_build_at_its_line(tmp_path):
    schemas = tmp_path / "schemas"
    shutil.copytree(SCHEMAS, schemas)
    mtv4 = schemas / "mtv4.yaml"
    text = mtv4.read_text(encoding="utf-8")
    good = 'hex: "aa 04 0f 02 00 80 6a cb"'
    assert text.count(good) == 1
    line = text[:text.index(good)].count("\n") + 1
    mtv4.write_text(text.replace(good, 'hex: "aa 04 0f 02 00 80 6a cc"'), encoding="utf-8")
    result = build([mtv4], tmp_path / "out", root=tmp_path)
    assert result.errors and not (tmp_path / "out").exists()
    example_line = text[:text.index(good)].rfind("- name:")
    assert any(d.loc.file == "schemas/mtv4.yaml" and d.loc.line in (line, text[:example_line].count("\n") + 1)
               for d in result.errors), [str(d) for d in result.errors]


# ---------------------------------------------------------------- sections


def test_route_page_shows_the_seed_file_breaking_rc():
    text = page("route")
    assert "ROUTE-D3" in section(text, "note-route-d3")
    start = text.index("#### Example: the seed's example file verbatim")
    example = text[start:text.index("#### Example", start + 1)]
    # ROUTE-D3: rc=5, 4, 5, 5 on the object lines 2, 4, 6 and 8 of the seed's file, nothing else.
    assert re.findall(r"^- (.*)$", example, re.M) == [
        f"line {line}: object.rc: {rc} breaks rule range (expected 0..3) \\[[ROUTE-D3](#note-route-d3)\\] at character 12"
        for line, rc in [(2, 5), (4, 4), (6, 5), (8, 5)]]


def test_mtv4_page_shows_the_ack_crc_discrepancy():
    text = page("mtv4")
    assert "B1..B3" in section(text, "note-mtv4-d2")
    coverage = {re.search(r"\[(\w+)\]", r["message"]).group(1): r["covers"]
                for r in table_after(text[text.index('<a id="checksum">'):], "Coverage, per message:")}
    # MTV4-D2: by the general rule B1..BN-2, the 8-byte ack's CRC covers B1..B5 and the
    # 12-byte SetWheelsVelocities frame's B1..B9.
    assert coverage["ack"].startswith("bytes B1–B5")
    assert coverage["set_wheels_velocities"].startswith("bytes B1–B9")
    assert "B1..B3" in section(text, "msg-ack")


def test_checksum_worked_examples():
    # mtv4: CRC-16/CMS of 08 03 01 20 00 24 03 60 ff = 0x4000 (hand-computed in the schema, MTV4-D1).
    text = page("mtv4")
    assert "`08 03 01 20 00 24 03 60 ff`" in text and "CRC `0x4000`" in text
    assert "| poly | `0x8005` |" in text and "| init | `0xffff` |" in text
    # route start of packet: CS = (3 + 1) mod 8 = 4 (ROUTE-D1).
    assert "3 + 1 = 4 mod 8 = 4" in page("route")
    # car idle master word 0x40000001: one 1 besides c9, so c9 = 1 (CAR-D2).
    assert "ones outside the parity bit: 1 → parity bit 1" in page("car")


def test_transport_budgets():
    route = page("route")
    # Seed: Tsend*Freq = 15 sends, Tsend*Nsent = 60 s, Plen*Nsent = 600 bits.
    assert "| sends of each word | **15** |" in route
    assert "| time per sentence | **3 s** |" in route
    assert "| typical route (20 sentences) | **60 s** |" in route
    assert "**600 bits**" in route
    # The exchange file at 9600 baud 8N1: the longest object line "1 7 7 7 7 5 3 5 15 7"
    # as wire values with widest digits is 21 chars with its newline -> 21.9 ms.
    assert "| `object` longest line | **21 chars, 21.9 ms** |" in route
    mtv4 = page("mtv4")
    # Frame sizes per the seed's lengths + 4: 0x08 -> 12, 0x16 -> 26, ack 4 -> 8, 0x12 -> 22; FIFO 64.
    for name, size in [("set_wheels_velocities", 12), ("set_led", 12),
                       ("set_wheels_velocities_with_odometry", 26), ("ack", 8), ("odometry_reply", 22)]:
        assert f"| `{name}` frame | **{size} bytes** | fits, {64 - size} bytes spare |" in mtv4
    # TR24-D1: 5 bytes of framing, so at most 59 data bytes in the 64-byte FIFO.
    assert "| largest `data_length` | **59 bytes** |" in page("tr24")
    assert "| line rate | **9600 baud" in page("tank")


def test_tr24_state_machines_as_mermaid_and_tables():
    text = page("tr24")
    blocks = re.findall(r"```mermaid\n(.*?)```", text, re.S)
    assert len(blocks) == 2 and all(b.startswith("stateDiagram-v2\n") for b in blocks)
    p = load_model("tr24")
    for machine, block in zip(p.machines, blocks):
        table = table_after(section(text, f"machine-{machine.name}"), "Transitions:")
        transitions = sum(len(h.transitions) for s in machine.states for h in s.handlers)
        assert len([r for r in table if r["#"]]) == transitions
        assert block.count("-->") == transitions + 1 + len(machine.final)  # plus [*] --> initial
        assert f"[*] --> {machine.initial}" in block


def test_originals_shown_beside_english():
    assert "## header: Header (头位串)" in page("car")
    assert "*Polish:* Komunikacja MTV4" in page("mtv4")
    assert "| 3 | `right` | on the right | справа |" in page("route")


def test_car_version_history():
    history = table_after(page("car"), "## Version history")
    # Seed revision table: 0.1 2018-03-24, 0.2 2018-03-25, 0.3 2018-04-10.
    assert [(r["version"], r["date"]) for r in history] == [
        ("0.1", "2018-03-24"), ("0.2", "2018-03-25"), ("0.3", "2018-04-10")]


def test_every_note_has_an_anchor():
    for name in PROTOCOLS:
        text = page(name)
        for note in load_model(name).notes:
            assert f'<a id="note-{note.id.lower()}"></a>\n**{note.id}**' in text


# ---------------------------------------------------------------- links and site


def test_links_and_anchors_resolve():
    anchors = {}
    for path in DOCS.glob("*.md"):
        anchors[path.name] = set(re.findall(r'<a id="([^"]+)"></a>', path.read_text(encoding="utf-8")))
    checked = 0
    for path in DOCS.glob("*.md"):
        for target in re.findall(r"\]\(([^)\s]+)\)", path.read_text(encoding="utf-8")):
            file, _, frag = target.partition("#")
            file = file or path.name
            assert file in anchors, f"{path.name}: link to missing page {target}"
            if frag:
                assert frag in anchors[file], f"{path.name}: link to missing anchor {target}"
            checked += 1
    # Non-vacuous: every page links to each of its messages and notes.
    for name in PROTOCOLS:
        text = page(name)
        p = load_model(name)
        for m in p.messages:
            assert f"](#msg-{m.name.replace('_', '-')})" in text
    assert checked > 100


def test_mkdocs_strict_build(tmp_path):
    proc = subprocess.run([sys.executable, "-m", "mkdocs", "build", "--strict", "--site-dir", str(tmp_path / "site")],
                          cwd=ROOT, capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    html = (tmp_path / "site" / "tr24.html").read_text(encoding="utf-8")
    assert html.count('class="mermaid"') == 2  # the diagrams reach the page as Mermaid blocks
