"""`codeword diff`: car v0.2 (tests/data/car_v0.2.yaml, from the seed's version
history) against v0.3, hand-made single changes, output forms and exit codes.

v0.3 added the motor-enable bit at the top of c3 and the ultrasonic duration at
the bottom of c5 (seed history, PROTOCOLS.md section 2). Bit positions count
from the first bit of the word: c1 = 0, c2 = 1, c3 from 2.
"""
from __future__ import annotations

import re
from pathlib import Path

import pytest

from codeword.build import compile_schema
from codeword.cli import main
from codeword.diagnostics import SchemaError
from codeword.diff import BREAKING, COMPATIBLE, DOCS, compare
from conftest import DATA, ROOT, SCHEMAS

V02 = DATA / "car_v0.2.yaml"
V03 = SCHEMAS / "car.yaml"


def changes(d, kind):
    return {(c.subject, c.what) for c in d.of_kind(kind)}


def test_car_v02_to_v03_names_every_field_and_breaks():
    d = compare(compile_schema(V02), compile_schema(V03))
    assert d.breaking
    # v0.2: c1 c2 | c3 dir(2) speed(2) dur(2) = bits 2-7 | c4 bits 8-11 | c5 enable 12, radius 13-14
    #       | c6 15 | c7 16 | c8 17-30 | c9 31
    # v0.3: enable at 2 shifts c3..c5 by one; duration (2 bits) after radius at 16-17 shifts c6, c7 by three
    assert changes(d, BREAKING) == {
        ("field motor.enable", "added at bit 2 (1 bit)"),
        ("field motor.direction", "moved from bits 2–3 to bits 3–4"),
        ("field motor.speed", "moved from bits 4–5 to bits 5–6"),
        ("field motor.duration", "moved from bits 6–7 to bits 7–8"),
        ("field led.led", "moved from bits 8–9 to bits 9–10"),
        ("field led.duration", "moved from bits 10–11 to bits 11–12"),
        ("field ultrasonic.enable", "moved from bit 12 to bit 13"),
        ("field ultrasonic.radius", "moved from bits 13–14 to bits 14–15"),
        ("field ultrasonic.duration", "added at bits 16–17 (2 bits)"),
        ("field voice", "moved from bit 15 to bit 18"),
        ("field body_sensor", "moved from bit 16 to bit 19"),
        ("field reserved_bits", "resized from 14 bits to 11 bits"),
        ("field reserved_bits", "moved from bits 17–30 to bits 20–30"),
    }
    # the control word is shared: every field change applies to both messages that use it
    assert {tuple(c.messages) for c in d.of_kind(BREAKING)} == {("master_control", "slave_control")}
    assert ("version", "0.2 → 0.3") in changes(d, DOCS)
    assert not d.of_kind(COMPATIBLE)
    assert d.old_fingerprint != d.new_fingerprint


def test_cli_exit_status_and_markdown(capsys):
    assert main(["diff", str(V02), str(V03)]) == 1
    out = capsys.readouterr().out
    assert "fingerprint" in out and "(changed)" in out and "result: WIRE-BREAKING" in out
    assert main(["diff", "--format", "markdown", str(V02), str(V03)]) == 1
    md = capsys.readouterr().out
    assert md.startswith("## car 0.3\n") and "### Wire-breaking" in md
    assert "- `field motor.enable` in master_control, slave_control: added at bit 2 (1 bit)" in md
    assert main(["diff", str(V03), str(V03)]) == 0
    assert "unchanged" in capsys.readouterr().out


def edited(tmp_path: Path, source: Path, old: str, new: str) -> Path:
    text = source.read_text(encoding="utf-8")
    assert text.count(old) == 1, old
    path = tmp_path / source.name
    path.write_text(text.replace(old, new), encoding="utf-8")
    return path


def diff_of(tmp_path, source, old, new):
    return compare(compile_schema(source), compile_schema(edited(tmp_path, source, old, new)))


def test_doc_change_is_docs_only_and_keeps_the_fingerprint(tmp_path):
    d = diff_of(tmp_path, V03, "doc: {en: \"1 if the car runs voice recognition.\"",
                "doc: {en: \"1 if the car listens for voice commands.\"")
    assert not d.breaking and d.old_fingerprint == d.new_fingerprint
    assert {c.kind for c in d.changes} == {DOCS}


def test_range_narrowed_is_breaking_widened_is_compatible(tmp_path):
    tank = SCHEMAS / "tank.yaml"
    text = tank.read_text(encoding="utf-8")
    assert "range: [0, 100]" in text  # speed 0..100 (TANK-D3)
    narrowed = diff_of(tmp_path, tank, "range: [0, 100]", "range: [0, 90]")
    assert ("field speed", "range narrowed from 0..100 to 0..90") in changes(narrowed, BREAKING)
    widened = diff_of(tmp_path, tank, "range: [0, 100]", "range: [0, 120]")
    assert not widened.breaking
    assert ("field speed", "range widened from 0..100 to 0..120") in changes(widened, COMPATIBLE)


def test_id_and_checksum_changes_are_breaking(tmp_path):
    mtv4 = SCHEMAS / "mtv4.yaml"
    # MTV4-D1: CRC-16/CMS; another catalogue CRC over the same bytes is a different wire
    d = diff_of(tmp_path, mtv4, "algorithm: CRC-16/CMS,", "algorithm: CRC-16/MODBUS,")
    assert any(s == "field crc" and w == "checksum changed" for s, w in changes(d, BREAKING))


def test_enum_value_added_in_spare_space_is_compatible(tmp_path):
    route = SCHEMAS / "route.yaml"
    text = route.read_text(encoding="utf-8")
    assert "{name: right, value: 3" in text  # pass_side (db) is u3: values 4..7 are spare
    d = diff_of(tmp_path, route, "{name: right, value: 3", "{name: back, value: 4, doc: back}\n      - {name: right, value: 3")
    assert not d.breaking
    assert ("field db", "value 4 (back) added in spare space") in changes(d, COMPATIBLE)


def test_git_revision_source_and_bad_sources(capsys):
    assert main(["diff", "git:HEAD:schemas/route.yaml", str(SCHEMAS / "route.yaml")]) in (0, 1)
    assert "git:HEAD:schemas/route.yaml" in capsys.readouterr().out
    assert main(["diff", "git:no-such-rev:schemas/car.yaml", str(V03)]) == 2
    assert main(["diff", "no/such.yaml", str(V03)]) == 2
    assert main(["diff", str(V03), str(SCHEMAS / "tank.yaml")]) == 2  # different protocols


def test_message_id_and_prefix_changes_are_breaking(tmp_path):
    d = diff_of(tmp_path, SCHEMAS / "mtv4.yaml", "    id: 0x02\n", "    id: 0x04\n")  # SetLED 0x02 -> 0x04
    assert ("message set_led", "id changed from 2 to 4") in changes(d, BREAKING)
    d = diff_of(tmp_path, SCHEMAS / "tank.yaml", '    id: "*"\n', '    id: "&"\n')
    assert ("message payload_command", "id changed from '*' to '&'") in changes(d, BREAKING)


def test_git_revision_is_never_read_as_a_git_option(tmp_path, capsys, monkeypatch):
    """`git:--output=FILE:x` once made `git show` write FILE; a REV must name a revision."""
    monkeypatch.chdir(SCHEMAS.parent)
    target = tmp_path / "written"
    for rev in (f"--output={target}", f"-o{target}", "--help"):
        assert main(["diff", f"git:{rev}:schemas/route.yaml", str(SCHEMAS / "route.yaml")]) == 2
        assert "cannot start with '-'" in capsys.readouterr().err
    assert not any(tmp_path.iterdir())


def test_delivery_section_changes_are_docs_only(tmp_path):
    """The section names what the docs describe and the simulator drives; the wire is the same."""
    tr24 = SCHEMAS / "tr24.yaml"
    cited = diff_of(tmp_path, tr24, "restart: TR24-D5}", "restart: TR24-D4}")
    assert not cited.breaking and cited.old_fingerprint == cited.new_fingerprint
    assert changes(cited, DOCS) == {("delivery", "the notes cited for the guarantee or its limits changed")}
    text = tr24.read_text(encoding="utf-8")
    without = tmp_path / "without" / "tr24.yaml"
    without.parent.mkdir()
    without.write_text(text[:text.index("\ndelivery:")], encoding="utf-8")
    removed = compare(compile_schema(tr24), compile_schema(without))
    assert not removed.breaking and removed.old_fingerprint == removed.new_fingerprint
    assert changes(removed, DOCS) == {("delivery", "removed: the docs no longer state a delivery guarantee")}
    added = compare(compile_schema(without), compile_schema(tr24))
    assert changes(added, DOCS) == {("delivery", "added: the docs state the delivery guarantee of master → slave")}


def test_f32_to_f64_is_a_width_change_and_breaking(tmp_path):
    mtv4 = SCHEMAS / "mtv4.yaml"
    old = "{name: th, type: f32, unit: rad, rule: MTV4-D5, title: {en: orientation Th, pl: Orientacja Th}, doc: heading}"
    d = diff_of(tmp_path, mtv4, old, old.replace("f32", "f64"))
    assert d.breaking and d.old_fingerprint != d.new_fingerprint
    assert {("field th", "resized from 32 bits to 64 bits"),
            ("message odometry_reply", "size changed from 176 to 208 bits")} <= changes(d, BREAKING)


SUMMED = """codeword: 1
protocol: summed
title: t
source: s
framing:
  kind: bytes
  byte_order: little
  layout:
    - {name: sync, type: u8, const: 0x55}
    - {name: kind, type: u8, dispatch: true}
    - {payload: true}
    - {name: ck, type: u16, checksum: {algorithm: sum, covers: {from: kind, to: payload}}}
messages:
  a: {id: 1, fields: [{name: x, type: u8}]}
"""


def test_checksum_family_and_final_step_changes_are_breaking(tmp_path):
    source = tmp_path / "old" / "summed.yaml"
    source.parent.mkdir()
    source.write_text(SUMMED, encoding="utf-8")
    old = "{algorithm: sum,"
    for new in ("{algorithm: fletcher,", "{algorithm: sum, complement: twos,", "{algorithm: sum, xorout: 0xFF,",
                "{algorithm: sum, modulo: 255,"):
        d = diff_of(tmp_path, source, old, new)
        assert ("field ck", "checksum changed") in changes(d, BREAKING), new
        assert d.old_fingerprint != d.new_fingerprint
    fletcher = tmp_path / "fletcher" / "summed.yaml"
    fletcher.parent.mkdir()
    fletcher.write_text(SUMMED.replace(old, "{algorithm: fletcher,"), encoding="utf-8")
    d = diff_of(tmp_path, fletcher, "{algorithm: fletcher,", "{algorithm: fletcher, modulo: 256,")
    assert ("field ck", "checksum changed") in changes(d, BREAKING)
    twos = tmp_path / "twos" / "summed.yaml"
    twos.parent.mkdir()
    twos.write_text(SUMMED.replace(old, "{algorithm: sum, complement: twos,"), encoding="utf-8")
    d = diff_of(tmp_path, twos, "complement: twos", "complement: ones")
    assert ("field ck", "checksum changed") in changes(d, BREAKING)
    # XOR with 0 is no final step: the same wire
    d = diff_of(tmp_path, source, old, "{algorithm: sum, xorout: 0,")
    assert not d.changes and d.old_fingerprint == d.new_fingerprint


def test_a_text_line_mark_checksum_or_spelling_change_breaks(tmp_path):
    base = """codeword: 1
protocol: nmea_like
title: t
source: s
framing: {kind: text, start: "$", prefix_separator: ",", terminator: "\\r\\n",
          checksum: {algorithm: xor, over: line, suffix: "*"}}
messages:
  fix:
    id: GPFIX
    fields:
      - {name: lat, type: i32, decimals: 3, width: 8}
"""
    old = tmp_path / "old.yaml"
    old.write_text(base)
    for edit, subject in [('start: "$"', "framing"), ("algorithm: xor", "framing"),
                          ("decimals: 3, width: 8", "field lat"), ("width: 8", "field lat")]:
        new = tmp_path / "new.yaml"
        replacement = {'start: "$"': 'start: "!"', "algorithm: xor": "algorithm: sum",
                       "decimals: 3, width: 8": "decimals: 2, width: 8", "width: 8": "width: 9"}[edit]
        new.write_text(base.replace(edit, replacement))
        d = compare(compile_schema(old), compile_schema(new))
        assert d.breaking and subject in {c.subject for c in d.of_kind(BREAKING)}, edit


MAVLINK2 = Path(__file__).resolve().parent.parent / "examples" / "mavlink2.yaml"


def mavlink2_with(tmp_path, name: str, field: str) -> Path:
    """examples/mavlink2.yaml with one more field at the end of HEARTBEAT."""
    text = MAVLINK2.read_text(encoding="utf-8")
    last = "      - {name: mavlink_version, type: u8}\n"
    path = tmp_path / f"{name}.yaml"
    path.write_text(text.replace(last, last + field + "\n", 1).replace("protocol: mavlink2", "protocol: " + name),
                    encoding="utf-8")
    return path


def test_an_extension_field_at_the_end_is_compatible_a_plain_one_breaks(tmp_path):
    old = compile_schema(MAVLINK2)
    extended = compile_schema(mavlink2_with(tmp_path, "extended", "      - {name: note, type: u16, extension: true}"))
    d = compare(old, extended)
    assert not d.breaking, d.of_kind(BREAKING)
    assert changes(d, COMPATIBLE) == {("field note", "added as an extension field at bits 152–167")}
    # a plain field changes HEARTBEAT's CRC_EXTRA, which the schema derives (`extra: mavlink`):
    # the value it wrote (50) is refused as stale, and left out the derived one is taken,
    # as pymavlink's own CRC computes it over the fields in the schema's (wire) order
    from pymavlink.generator.mavcrc import x25crc
    crc = x25crc()
    crc.accumulate_str("HEARTBEAT ")
    for field in ("uint32_t custom_mode", "uint8_t type", "uint8_t autopilot", "uint8_t base_mode",
                  "uint8_t system_status", "uint8_t mavlink_version", "uint16_t note"):
        crc.accumulate_str(field + " ")
    derived = (crc.crc & 0xFF) ^ (crc.crc >> 8)
    path = mavlink2_with(tmp_path, "plain", "      - {name: note, type: u16}")
    with pytest.raises(SchemaError, match=f"crc_extra 50 is not {derived}"):
        compile_schema(path)
    path.write_text(path.read_text(encoding="utf-8").replace("    crc_extra: 50\n", "", 1), encoding="utf-8")
    plain = compile_schema(path)
    assert plain.message("heartbeat").shortening is not None
    d = compare(old, plain)
    assert d.breaking
    assert {("field note", "added at bits 152–167 (16 bits)"),
            ("message heartbeat", f"crc_extra changed from 50 to {derived}")} <= changes(d, BREAKING)


def test_a_message_without_the_new_keys_keeps_its_fingerprint(tmp_path):
    """The fingerprint leaves attributes at their defaults out: extension: false and no
    truncation add nothing, so schemas that use neither keep theirs."""
    from codeword.fingerprint import canonical_json
    text = (SCHEMAS.parent / "examples" / "mavlink1.yaml").read_text(encoding="utf-8")
    assert "extension" not in canonical_json(compile_schema(SCHEMAS.parent / "examples" / "mavlink1.yaml"))
    path = tmp_path / "mavlink1.yaml"
    path.write_text(text.replace("{name: type, type: u8}", "{name: type, type: u8, extension: false}"), encoding="utf-8")
    d = compare(compile_schema(SCHEMAS.parent / "examples" / "mavlink1.yaml"), compile_schema(path))
    assert d.old_fingerprint == d.new_fingerprint and not d.changes


def test_a_counted_arrays_maximum_is_part_of_the_wire(tmp_path):
    """Modbus's read response with room for 100 registers instead of 125: frames of
    101..125 registers that old peers send are refused by new ones."""
    modbus = ROOT / "examples" / "modbus_rtu.yaml"
    old = "{name: registers, type: u16, count: {from: byte_count, unit: bytes}, max_count: 125}"
    d = diff_of(tmp_path, modbus, old, old.replace("125", "100"))
    assert d.breaking and d.old_fingerprint != d.new_fingerprint
    assert any("registers" in c.subject and "125" in c.what and "100" in c.what for c in d.of_kind(BREAKING)), \
        d.changes


def test_a_changed_condition_or_maximum_is_breaking(tmp_path):
    tele = tmp_path / "src" / "tele.yaml"
    tele.parent.mkdir()
    tele.write_text((ROOT / "tests" / "test_conditional_fields.py").read_text(encoding="utf-8")
                    .split('SCHEMA = """', 1)[1].split('"""', 1)[0], encoding="utf-8")
    d = diff_of(tmp_path, tele, "present_if: {field: parts, has: battery}", "present_if: {field: parts, has: gps}")
    assert ("field volts", "sent when parts has battery, now parts has gps") in changes(d, BREAKING)
    d = diff_of(tmp_path, tele, "max_count: 3", "max_count: 4")
    assert d.breaking


def verdict(tmp_path: Path, source: Path, old: str, new: str, capsys) -> tuple[int, str]:
    """`codeword diff`'s exit status and text for `source` against it edited."""
    folder = tmp_path / f"edit{len(list(tmp_path.iterdir()))}"
    folder.mkdir()
    status = main(["diff", str(source), str(edited(folder, source, old, new))])
    return status, capsys.readouterr().out


# tank's systemstatus takes 0..4 of its enum's seven values (TANK-D2: 5 and 6 come only from the platform)
SYSTEMSTATUS = "        values: [0, 1, 2, 3, 4]\n"


def test_allowed_values_narrowed_break_the_wire_and_fail_the_gate(tmp_path, capsys):
    """A frame with systemstatus 4 is valid to an old decoder; a new one refuses it. The
    gate (exit 1) must not pass it, nor a list that trades 4 for 5."""
    tank = SCHEMAS / "tank.yaml"
    narrowed = diff_of(tmp_path, tank, SYSTEMSTATUS, SYSTEMSTATUS.replace(", 4]", "]"))
    assert narrowed.breaking
    assert changes(narrowed, BREAKING) == {("field systemstatus", "allowed values narrowed: ['4']")}
    assert not narrowed.of_kind(COMPATIBLE)
    status, out = verdict(tmp_path, tank, SYSTEMSTATUS, SYSTEMSTATUS.replace(", 4]", "]"), capsys)
    assert status == 1 and "result: WIRE-BREAKING" in out
    traded = diff_of(tmp_path, tank, SYSTEMSTATUS, SYSTEMSTATUS.replace(", 4]", ", 5]"))
    assert changes(traded, BREAKING) == {("field systemstatus", "allowed values narrowed: ['4']")}
    assert verdict(tmp_path, tank, SYSTEMSTATUS, SYSTEMSTATUS.replace(", 4]", ", 5]"), capsys)[0] == 1
    # a list where there was none restricts a field that took every value of its enum
    unrestricted = tmp_path / "unrestricted" / "tank.yaml"
    unrestricted.parent.mkdir()
    unrestricted.write_text(tank.read_text(encoding="utf-8").replace(SYSTEMSTATUS, ""), encoding="utf-8")
    restricted = compare(compile_schema(unrestricted), compile_schema(tank))
    assert changes(restricted, BREAKING) == {("field systemstatus", "allowed values narrowed: now restricted")}
    assert main(["diff", str(unrestricted), str(tank)]) == 1


def test_allowed_values_widened_keep_the_wire_and_pass_the_gate(tmp_path, capsys):
    """Every frame valid before (systemstatus 0..4) is valid after: compatible, exit 0."""
    tank = SCHEMAS / "tank.yaml"
    widened = diff_of(tmp_path, tank, SYSTEMSTATUS, SYSTEMSTATUS.replace(", 4]", ", 4, 5]"))
    assert not widened.breaking
    assert changes(widened, COMPATIBLE) == {("field systemstatus", "allowed values widened: ['5']")}
    status, out = verdict(tmp_path, tank, SYSTEMSTATUS, SYSTEMSTATUS.replace(", 4]", ", 4, 5]"), capsys)
    assert status == 0 and "WIRE-BREAKING" not in out
    dropped = diff_of(tmp_path, tank, SYSTEMSTATUS, "")
    assert not dropped.breaking
    assert changes(dropped, COMPATIBLE) == {("field systemstatus", "allowed values widened: no longer restricted")}
    assert verdict(tmp_path, tank, SYSTEMSTATUS, "", capsys)[0] == 0
    # the same set in another order is the same wire
    reordered = diff_of(tmp_path, tank, SYSTEMSTATUS, SYSTEMSTATUS.replace("0, 1, 2, 3, 4", "4, 3, 2, 1, 0"))
    assert not reordered.breaking
    assert changes(reordered, COMPATIBLE) == {("field systemstatus", "allowed values reordered (the same set)")}


SPEED = "    range: [0, 100]\n"  # tank's speed_percent (TANK-D3)


def test_a_range_moved_added_or_removed(tmp_path, capsys):
    """0..100 to 10..120 loses 0..9: breaking though it grew at the top; to -10..90 loses
    91..100. A range where there was none narrows an i32 to it; dropping it widens."""
    tank = SCHEMAS / "tank.yaml"
    for new, what in [("[10, 120]", "range narrowed from 0..100 to 10..120"),
                      ("[-10, 90]", "range narrowed from 0..100 to -10..90"),
                      ("[0, 99]", "range narrowed from 0..100 to 0..99"),
                      ("[1, 100]", "range narrowed from 0..100 to 1..100")]:
        d = diff_of(tmp_path, tank, SPEED, SPEED.replace("[0, 100]", new))
        assert ("field speed", what) in changes(d, BREAKING), new
        assert not d.of_kind(COMPATIBLE), new
        assert verdict(tmp_path, tank, SPEED, SPEED.replace("[0, 100]", new), capsys)[0] == 1
    for new, what in [("[-1, 100]", "range widened from 0..100 to -1..100"),
                      ("[0, 101]", "range widened from 0..100 to 0..101")]:
        d = diff_of(tmp_path, tank, SPEED, SPEED.replace("[0, 100]", new))
        assert not d.breaking and ("field speed", what) in changes(d, COMPATIBLE), new
        assert verdict(tmp_path, tank, SPEED, SPEED.replace("[0, 100]", new), capsys)[0] == 0
    dropped = diff_of(tmp_path, tank, SPEED, "")
    assert not dropped.breaking
    assert ("field speed", "range 0..100 removed (widened)") in changes(dropped, COMPATIBLE)
    assert verdict(tmp_path, tank, SPEED, "", capsys)[0] == 0
    unranged = tmp_path / "unranged" / "tank.yaml"
    unranged.parent.mkdir()
    unranged.write_text(tank.read_text(encoding="utf-8").replace(SPEED, ""), encoding="utf-8")
    added = compare(compile_schema(unranged), compile_schema(tank))
    assert ("field speed", "range 0..100 added (narrowed)") in changes(added, BREAKING)
    assert main(["diff", str(unranged), str(tank)]) == 1


def test_hand_worked_streams_are_docs_only(tmp_path):
    """A stream's bytes and events document the framing; the wire is the same."""
    mtv4 = SCHEMAS / "mtv4.yaml"
    d = diff_of(tmp_path, mtv4, "      - {message: ack, end: 20}", "      - {message: ack}")
    assert not d.breaking and d.old_fingerprint == d.new_fingerprint
    assert changes(d, DOCS) == {("stream 'frames of two sizes'", "changed")}


def test_keeping_spellings_is_compatible_and_named_per_field(tmp_path):
    """keep_spelling reads and writes the same lines; only a decoded line written back
    differs, and the C struct gains the member that holds the text."""
    nmea = ROOT / "examples" / "nmea0183.yaml"
    assert "  keep_spelling: true  # NMEA-D4" in nmea.read_text(encoding="utf-8")
    d = diff_of(tmp_path, nmea, "  keep_spelling: true  # NMEA-D4", "  keep_spelling: false")
    assert not d.breaking and {c.kind for c in d.changes} == {COMPATIBLE}
    assert ("field lat", "no longer keeps the text it was read from (C member lat_spelling removed)") \
        in changes(d, COMPATIBLE)
    assert not any(subject == "field lat_dir" for subject, _ in changes(d, COMPATIBLE))  # a char: one spelling


def test_listing_talkers_narrows_and_a_field_leaving_the_prefix_breaks(tmp_path):
    """A talker field limited to a listed set refuses lines it read before (breaking); a
    field moved out of the prefix into the body moves every value of the line."""
    nmea = ROOT / "examples" / "nmea0183.yaml"
    assert "    prefix: true\n" in nmea.read_text(encoding="utf-8")
    d = diff_of(tmp_path, nmea, "    prefix: true\n", "    prefix: true\n    values: [GP, GN]\n")
    assert changes(d, BREAKING) == {("field talker", "allowed values narrowed: now restricted")}
    d = diff_of(tmp_path, nmea, "    length: 2\n    prefix: true\n", "    max_length: 2\n")
    assert ("field talker", "no longer written in the prefix before the id") in changes(d, BREAKING)


def test_text_extension_fields_and_keep_empty(tmp_path):
    """NMEA's RMC mode: added as an extension field, or made one, it is compatible (lines of
    the old schema still read); no longer one, lines without it are refused (breaking); a
    keep_empty: false that lets writers end a line before what old readers need breaks."""
    nmea = ROOT / "examples" / "nmea0183.yaml"
    mode = "      - {name: mode, type: char, enum: faa_mode, optional: true, extension: true, rule: NMEA-D3}\n"
    status = ("      - {name: nav_status, type: char, enum: nav_status, optional: true, extension: true, keep_empty: false,\n"
              "         rule: NMEA-D3}\n")
    text = nmea.read_text(encoding="utf-8")
    assert mode in text and status in text
    before = tmp_path / "before.yaml"
    before.write_text(text.replace(mode + status, "").replace("mode: null, nav_status: null}", "}")
                      .replace("mode: autonomous, nav_status: null}", "}"), encoding="utf-8")
    without = tmp_path / "without.yaml"
    examples = re.compile(r"(\n  rmc:\n.*?\n    examples:\n).*?\n(\n  vtg:)", re.S)
    without.write_text(examples.sub(r"\1      []\n\2", before.read_text(encoding="utf-8")), encoding="utf-8")
    d = compare(compile_schema(without), compile_schema(nmea))
    assert ("field mode", "added as an extension field: a line may end before it, so the lines of the old "
                          "schema still read") in changes(d, COMPATIBLE)
    assert not any(s.startswith("field mode") or s.startswith("field nav_status") for s, _ in changes(d, BREAKING))
    d = diff_of(tmp_path, nmea, mode, mode.replace(" extension: true,", ""))
    assert ("field mode", "no longer an extension field") in changes(d, BREAKING)
    assert ("message rmc", "readers now need at least 12 values in a line (took 11)") in changes(d, BREAKING)
    d = diff_of(tmp_path, nmea, "extension: true, keep_empty: false,\n", "extension: true,\n")
    assert ("message rmc", "writers now always write 13 values (wrote 12)") in changes(d, COMPATIBLE)
    assert not d.breaking
    d = diff_of(tmp_path, nmea, mode, mode.replace("extension: true", "extension: true, keep_empty: false"))
    assert not d.breaking  # old readers take a line without the mode
    assert ("message rmc", "writers now always write 11 values (wrote 12)") in changes(d, COMPATIBLE)
    vtg = "      - {name: spd_over_grnd_kmph, type: tenths_padded, optional: true, unit: km/h}\n"
    d = diff_of(tmp_path, nmea, vtg + "      - {name: spd_over_grnd_kmph_sym, type: char, enum: speed_kmh}\n"
                "      - {name: faa_mode, type: char, enum: faa_mode, optional: true, extension: true, rule: NMEA-D3}\n",
                vtg.replace("optional: true,", "optional: true, keep_empty: false,")
                + "      - {name: spd_over_grnd_kmph_sym, type: char, enum: speed_kmh, optional: true, keep_empty: false}\n"
                "      - {name: faa_mode, type: char, enum: faa_mode, optional: true, extension: true, keep_empty: false,"
                " rule: NMEA-D3}\n")
    assert ("message vtg", "writers now end a line after 6 values when the later ones are absent, and readers of "
                           "the old schema need 8") in changes(d, BREAKING)


PAYLOAD_FIELD = """codeword: 1
protocol: tunnelled
title: a message field named like the envelope's payload
source: hand-written
framing:
  kind: bytes
  byte_order: little
  layout:
    - {name: sync, type: u8, const: 0xA5}
    - {name: kind, type: u8, dispatch: true}
    - {payload: true}
messages:
  tunnel:
    id: 1
    fields:
      - {name: payload_type, type: u16}
      - {name: payload, type: u8, count: 4}
"""


def test_a_field_named_payload_is_not_taken_for_the_envelopes_payload(tmp_path):
    # MAVLink's TUNNEL has a field `payload`; the envelope's payload marker has that name too
    path = tmp_path / "tunnelled.yaml"
    path.write_text(PAYLOAD_FIELD, encoding="utf-8")
    assert compare(compile_schema(path), compile_schema(path)).changes == []
    wider = tmp_path / "wider.yaml"
    wider.write_text(PAYLOAD_FIELD.replace("count: 4", "count: 6"), encoding="utf-8")
    assert ("field payload", "count changed from 4 to 6") in changes(compare(compile_schema(path),
                                                                            compile_schema(wider)), BREAKING)
