"""`codeword diff` on a framing's trailer: adding one is compatible (an old frame leaves
its flag clear), removing it or changing its key length, a field's width or its flag
breaks; the fingerprint follows the trailer."""
from __future__ import annotations

from pathlib import Path

from codeword.build import compile_schema
from codeword.diff import BREAKING, COMPATIBLE, compare
from codeword.fingerprint import fingerprint

SCHEMA = Path(__file__).resolve().parent.parent / "examples" / "mavlink2.yaml"
TRAILER = SCHEMA.read_text(encoding="utf-8")


def protocol(tmp_path: Path, name: str, text: str):
    path = tmp_path / f"{name}.yaml"
    path.write_text(text, encoding="utf-8")
    return compile_schema(path)


def without_trailer(text: str) -> str:
    start = text.index("  trailer:\n")
    return text[:start] + text[text.index("\nflags:\n") + 1:]


def verdicts(old, new) -> set[tuple[str, str]]:
    return {(c.kind, c.subject) for c in compare(old, new).changes if c.subject == "framing"}


def test_adding_a_trailer_is_compatible_and_removing_it_breaks(tmp_path):
    signed = protocol(tmp_path, "signed", TRAILER)
    plain = protocol(tmp_path, "plain", without_trailer(TRAILER))
    assert verdicts(plain, signed) == {(COMPATIBLE, "framing")}
    assert verdicts(signed, plain) == {(BREAKING, "framing")}
    assert fingerprint(plain) != fingerprint(signed)


def test_a_changed_trailer_breaks(tmp_path):
    signed = protocol(tmp_path, "signed", TRAILER)
    for name, old, new in (("key", "key_length: 32", "key_length: 16"),
                           ("width", "{name: timestamp, type: u48", "{name: timestamp, type: u40"),
                           ("cut", "        length: 6\n", "        length: 8\n"),
                           ("flag", "{name: signing, bit: 0", "{name: signing, bit: 1")):
        assert TRAILER.count(old) == 1, name
        changed = protocol(tmp_path, name, TRAILER.replace(old, new))
        assert (BREAKING, "framing") in verdicts(signed, changed), name
        assert fingerprint(changed) != fingerprint(signed), name
