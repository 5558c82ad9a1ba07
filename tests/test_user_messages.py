"""A field's own message for the user reaches the generated errors exactly as
written, whatever quotes its English text and its translations hold."""
from __future__ import annotations

from pathlib import Path

import pytest

import schema_in_a_test as scratch

SCHEMA = """\
codeword: 1
protocol: quot
title: quotes in messages
source: hand-written
framing: {kind: bits, word_bits: 8, byte_order: big}
messages:
  level:
    fields:
      - {name: tag, type: u2, const: 1, dispatch: true}
      - name: v
        type: u6
        range: [0, 40]
        message: {en: "it's over 40", zh: 'say "less"'}
"""


def test_quotes_in_a_message_and_its_translation(tmp_path: Path):
    quot = scratch.load(scratch.render(tmp_path, "quot", SCHEMA) / "quot.py")
    with pytest.raises(quot.EncodeError) as err:
        quot.encode(quot.Level(v=41))
    assert err.value.user_message == "it's over 40 / say \"less\""
