"""Transport parameters become module constants, each on its own line, with or
without a doc."""
from __future__ import annotations


from codeword.build import compile_schema, render_protocol
from conftest import load_generated
from schema_in_a_test import load

SCHEMA = """codeword: 1
protocol: params
title: t
source: s
parameters:
  timeout: {default: 100}
  retry_limit: {default: 3}
framing:
  kind: bytes
  byte_order: big
  layout:
    - {name: sync, type: u8, const: 0x55}
    - {payload: true}
messages:
  a:
    fields:
      - {name: x, type: u8}
"""


def test_tr24_parameters_are_constants_of_its_module():
    tr24 = load_generated("tr24")
    assert (tr24.TIMEOUT, tr24.RETRY_LIMIT, tr24.OWN_ID) == (100, 0, None)


def test_two_parameters_without_a_doc_are_two_constants(tmp_path):
    path = tmp_path / "params.yaml"
    path.write_text(SCHEMA, encoding="utf-8")
    module = tmp_path / "params.py"
    module.write_text(render_protocol(compile_schema(path))["python/params.py"], encoding="utf-8")
    params = load(module)
    assert (params.TIMEOUT, params.RETRY_LIMIT) == (100, 3)
