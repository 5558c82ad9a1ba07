"""Plausible bugs, each a small textual patch to the generator, and the tests that should
catch it. A patch is (file, find, replace) with `find` present exactly once in the file
(tests/test_mutants_apply.py checks it, so the list follows the sources)."""
from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Mutant:
    name: str
    what: str  # the bug, as a reader of the table needs it
    patches: tuple[tuple[str, str, str], ...]  # (file, find, replace)
    tests: tuple[str, ...]  # pytest arguments: files or node ids, -k expressions
    note: str = ""  # e.g. the change elsewhere that adds the test which catches it


MUTANTS = (
    Mutant(
        "diff-values-subset-reversed",
        "codeword diff: a narrowed `values:` list is reported as widened (compatible, exit 0)",
        (("compiler/diff/compare.py", "b is not None and not sa <= sb:", "b is not None and not sb <= sa:"),),
        ("tests/test_diff.py",)),
    Mutant(
        "diff-range-both-ends",
        "codeword diff: a range is narrowed only when both ends move in (0..100 to 10..120 passes)",
        (("compiler/diff/compare.py", "elif b[0] > a[0] or b[1] < a[1]:", "elif b[0] > a[0] and b[1] < a[1]:"),),
        ("tests/test_diff.py",)),
    Mutant(
        "c-portable-le16-swapped",
        "C runtime: cw_put_le16 without __BYTE_ORDER__ (the portable path) writes the high byte first",
        (("templates/c/codeword.h.j2",
          "    p[0] = (uint8_t)(v & 0xFFu);\n    p[1] = (uint8_t)(v >> 8);\n#endif",
          "    p[0] = (uint8_t)(v >> 8);\n    p[1] = (uint8_t)(v & 0xFFu);\n#endif"),),
        ("tests/test_c.py", "tests/test_c_big_endian.py", "-k", "portable_byte_access or big_endian"),
        "the conformance drivers are also built with -U__BYTE_ORDER__ on the host, and run on "
        "s390x (big-endian) under qemu-user"),
    Mutant(
        "python-resync-skips-claimed-size",
        "Python StreamDecoder: after a frame that fails to decode it skips the whole claimed size, "
        "not one byte (a real frame inside it is lost)",
        (("templates/python/module.py.j2",
          "                skipped += 1\n                pos += 1\n                continue\n            out.append(message)",
          "                skipped += size\n                pos += size\n                continue\n            out.append(message)"),),
        ("tests/test_resynchronisation.py", "tests/test_hand_worked_streams.py"),
        "caught by the hand-worked false sync, as by mtv4's noise streams"),
    Mutant(
        "c-resync-skips-claimed-size",
        "C stream parser: after a frame that fails to decode it skips the whole claimed size, not one byte",
        (("templates/c/stream_parser.h.j2",
          "        pos += 1u;  /* no frame starts at this byte */\n        s->skipped += 1u;",
          "        pos += size > 0u ? size : 1u;\n        s->skipped += (uint32_t)(size > 0u ? size : 1u);"),),
        ("tests/test_resynchronisation.py", "tests/test_hand_worked_streams.py"),
        "caught by the hand-worked false sync and the C scan's stretches"),
    Mutant(
        "python-one-hot-takes-bool",
        "Python encoders: a one-hot field takes True as the value 1",
        (("compiler/targets/python/view.py",
          '(not isinstance({v}, int) or {v}.__class__ is bool) "\n              f"or not {lo} <= {v} <= {hi}:")',
          'not isinstance({v}, int) "\n              f"or not {lo} <= {v} <= {hi}:")'),),
        ("tests/test_codec_inputs.py",)),
    Mutant(
        "python-group-unchecked",
        "Python encoders: a group's object is read by attribute without checking its class",
        (("compiler/targets/python/view.py",
          "                    else:\n                        self.check_group(out, prefix, absent_ok)\n", ""),),
        ("tests/test_codec_inputs.py",)),
    Mutant(
        "c-crc-no-xorout",
        "C CRC: the final XOR (xorout) is left out (every seed CRC has xorout 0)",
        (("compiler/targets/c/crc.py", 'c(f"return ({t})(reg ^ {clit_hex(p.xorout, 1, t)});")',
          'c(f"return ({t})(reg);")'),),
        ("tests/test_crc_catalogue.py", "tests/test_c.py", "-k", "crc or host")),
    Mutant(
        "python-range-upper-off-by-one",
        "Python encoders: an integer field takes one more than its largest value",
        (("compiler/targets/python/view.py",
          'return ("int", leaf.path[-1], lo, hi, f.scale is not None, f.rule) + \\',
          'return ("int", leaf.path[-1], lo, hi + 1, f.scale is not None, f.rule) + \\'),),
        ("tests/test_vectors.py", "tests/test_codec_inputs.py")),
    Mutant(
        "python-sign-extension-half",
        "Python decoders: a negative bit field is sign-extended by half its span",
        (("compiler/targets/python/view.py", 'c(f"    {leaf.var} -= {1 << bits:#x}")',
          'c(f"    {leaf.var} -= {1 << (bits - 1):#x}")'),),
        ("tests/test_vectors.py", "tests/test_signed_enum.py", "tests/test_bitstruct_oracle.py")),
    Mutant(
        "c-lsb-first-bit-order",
        "C: a bit field counted least significant bit first is shifted one bit off in each byte",
        (("compiler/targets/c/bitbytes.py",
          "return [(b, 8 * b - pos) for b in range(first, last + 1)]",
          "return [(b, 8 * b - pos + 1) for b in range(first, last + 1)]"),),
        ("tests/test_c_bit_bytes.py", "tests/test_lsb_first.py")),
)
