"""The docs' worked checksum example for every algorithm over bytes, recomputed by
hand here: the README's own demo schema (a sum over bytes) and an xor."""
from __future__ import annotations

import re
from pathlib import Path

import pytest

from codeword.build import compile_schema, render_with_codec

ROOT = Path(__file__).resolve().parent.parent
README = (ROOT / "README.md").read_text(encoding="utf-8")
DEMO = re.search(r"`schemas/demo.yaml`:\n\n```yaml\n(.*?)```", README, re.S).group(1)
# its temperature message alone: the tests below change the checksum, and the log
# message's example frame carries the sum's value
TEMPERATURE = DEMO[:DEMO.index("  log:")]


def docs_of(tmp_path: Path, text: str, name: str) -> str:
    path = tmp_path / f"{name}.yaml"
    path.write_text(text, encoding="utf-8")
    files = render_with_codec(compile_schema(path))[0]
    return files[f"docs/{name}.md"]


def test_the_readme_demo_sum_over_bytes_is_worked_out(tmp_path):
    page = docs_of(tmp_path, DEMO, "demo")
    # frame 55 01 2b 00 2c: the sum covers kind..payload = 01 2b 00
    assert "covered bytes: B1 = 1, B2 = 43, B3 = 0" in page
    assert "1 + 43 + 0 = 44 mod 256 = 44" in page
    assert "sent in `sum` (B4): 44" in page


@pytest.mark.parametrize("algorithm,checksum,line", [
    ("xor", "2a", "1 ⊕ 43 ⊕ 0 = 42"),  # 0x01 ^ 0x2b ^ 0x00
])
def test_an_xor_over_bytes_is_worked_out(tmp_path, algorithm, checksum, line):
    text = TEMPERATURE.replace("protocol: demo", "protocol: demoxor").replace("algorithm: sum", f"algorithm: {algorithm}")
    text = text.replace('hex: "55 01 2b 00 2c"', f'hex: "55 01 2b 00 {checksum}"')
    page = docs_of(tmp_path, text, "demoxor")
    assert line in page and f"(B4): {int(checksum, 16)}" in page


def test_a_sixteen_bit_little_endian_sum_is_read_in_its_byte_order(tmp_path):
    text = TEMPERATURE.replace("protocol: demo", "protocol: demo16").replace("{name: sum, type: u8,", "{name: sum, type: u16,")
    # 01 + 2b + 00 = 0x002c, sent low byte first
    text = text.replace('hex: "55 01 2b 00 2c"', 'hex: "55 01 2b 00 2c 00"')
    page = docs_of(tmp_path, text, "demo16")
    assert "1 + 43 + 0 = 44 mod 65536 = 44" in page and "(B4–B5): 44" in page


def test_a_twos_complement_sum_is_worked_out(tmp_path):
    text = TEMPERATURE.replace("protocol: demo", "protocol: demolrc").replace(
        "algorithm: sum,", "algorithm: sum, complement: twos,")
    # 01 + 2b + 00 = 44; 256 - 44 = 212 = 0xd4
    text = text.replace('hex: "55 01 2b 00 2c"', 'hex: "55 01 2b 00 d4"')
    page = docs_of(tmp_path, text, "demolrc")
    assert "1 + 43 + 0 = 44 mod 256 = 44" in page
    assert "two's complement in 8 bits: (256 − 44) mod 256 = 212" in page
    assert "sent in `sum` (B4): 212" in page
    assert "| then | `two's complement in the field's width` |" in page


def test_a_fletcher16_is_worked_out_byte_by_byte(tmp_path):
    text = TEMPERATURE.replace("protocol: demo", "protocol: demofl").replace(
        "{name: sum, type: u8, checksum: {algorithm: sum,", "{name: sum, type: u16, checksum: {algorithm: fletcher,")
    # bytes 01 2b 00 mod 255: A 1, 44, 44; B 1, 45, 89; (89 << 8) | 44 = 0x592c, low byte first
    text = text.replace('hex: "55 01 2b 00 2c"', 'hex: "55 01 2b 00 2c 59"')
    page = docs_of(tmp_path, text, "demofl")
    assert "A = sum of the bytes mod 255 = 44; B = sum of A after each step mod 255 = 89" in page
    assert "(B << 8) | A = `0x592c`" in page
    assert "sent low byte (A) first at B4–B5: `2c 59`" in page
    assert "| byte | A | B |" in page and "| value | `B in the high byte, A in the low one` |" in page
    for row in ("| 01 | `0x01` | `0x01` |", "| 2b | `0x2c` | `0x2d` |", "| 00 | `0x2c` | `0x59` |"):
        assert row in page


def test_a_line_checksum_is_worked_out_character_by_character():
    """NMEA's `*hh` on the published GGA sentence, whose checksum 47 the sentence itself carries."""
    page = (ROOT / "generated" / "docs" / "examples" / "nmea0183.md").read_text(encoding="utf-8")
    section = page[page.index("### Line checksum (XOR)"):page.index('<a id="framing"></a>')]
    assert "characters covered: `GPGGA,123519,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,` (61)" in section
    assert "XOR of their codes: `0x47`, written `*47`" in section
    assert "| 'G' | `0x47` |\n| 'P' | `0x17` |" in section  # 0x47 ^ 0x50
