"""The YAML front end: positions, YAML 1.1 traps, and bounded loading."""
from __future__ import annotations

import pytest

from codeword.diagnostics import SchemaError
from codeword import loader
from codeword.loader import MAX_DEPTH, MAX_FILE_BYTES, MAX_NODES, load_text


def test_yaml_1_1_booleans_stay_strings():
    doc = load_text("fields: [no, yes, on, off, y, n, true, false, ~, 0x1F, 0b101, 1.5]\n", "t.yaml")
    assert doc.data["fields"] == ["no", "yes", "on", "off", "y", "n", True, False, None, 31, 5, 1.5]
    doc = load_text("no: 1\non: 2\n", "t.yaml")
    assert doc.data == {"no": 1, "on": 2}


def test_every_node_has_file_line_col():
    doc = load_text("a:\n  - {name: no, type: u3}\n", "x.yaml")
    loc = doc.loc(("a", 0, "type"))
    assert (loc.file, loc.line, loc.col) == ("x.yaml", 2, 16)  # the key `type`
    assert doc.loc(("a", 0, "missing")).line == 2  # nearest located ancestor


def test_alias_expansion_is_bounded(monkeypatch):
    # a billion-laughs document: 10**9 scalars once its aliases are expanded
    levels = ["a0: &a0 [x, x, x, x, x, x, x, x, x, x]"]
    for i in range(1, 9):
        levels.append(f"a{i}: &a{i} [" + ", ".join([f"*a{i - 1}"] * 10) + "]")
    # the bound is on the work, not the wall time: count the scalars the loader
    # converts before it gives up
    converted = [0]
    scalar = loader._scalar

    def counting(node):
        converted[0] += 1
        assert converted[0] <= MAX_NODES, "the loader expanded past its node bound"
        return scalar(node)

    monkeypatch.setattr(loader, "_scalar", counting)
    with pytest.raises(SchemaError) as err:
        load_text("\n".join(levels) + "\n", "bomb.yaml")
    assert "expands to more than" in str(err.value)
    assert converted[0] == 0  # refused from the nodes' expanded sizes, before any is converted


def test_depth_and_size_are_bounded():
    deep = "a: " + "[" * (MAX_DEPTH + 5) + "]" * (MAX_DEPTH + 5) + "\n"
    with pytest.raises(SchemaError, match="nesting deeper"):
        load_text(deep, "deep.yaml")
    with pytest.raises(SchemaError, match="larger than"):
        load_text("a: " + "x" * MAX_FILE_BYTES + "\n", "big.yaml")


@pytest.mark.parametrize("opening, closing", [("[", "]"), ("{a: ", "}")])
def test_nesting_far_past_the_bound_is_a_diagnostic_not_a_recursion_error(opening, closing):
    # a recursive composer overflows Python's stack long before 5,000 levels
    deep = "a: " + opening * 5000 + "1" * (opening == "{a: ") + closing * 5000 + "\n"
    with pytest.raises(SchemaError) as err:
        load_text(deep, "deep.yaml")
    (diagnostic,) = err.value.diagnostics
    assert diagnostic.message == f"nesting deeper than {MAX_DEPTH}"
    # the top-level mapping is the first collection, so the one past the bound is the
    # MAX_DEPTH-th opening after `a: `
    assert (diagnostic.loc.line, diagnostic.loc.col) == (1, 4 + (MAX_DEPTH - 1) * len(opening))


def test_tags_and_duplicate_keys_are_rejected():
    with pytest.raises(SchemaError, match="tag"):
        load_text("a: !!python/object/apply:os.system ['true']\n", "t.yaml")
    with pytest.raises(SchemaError) as err:
        load_text("a: 1\nb: 2\na: 3\n", "d.yaml")
    (diagnostic,) = err.value.diagnostics
    assert diagnostic.loc.line == 3 and "duplicate key" in diagnostic.message


def test_syntax_error_names_the_line():
    with pytest.raises(SchemaError) as err:
        load_text("a: 1\nb: {c: 2\n", "s.yaml")
    assert err.value.diagnostics[0].loc.file == "s.yaml"
    assert err.value.diagnostics[0].loc.line >= 2


def test_an_error_libyaml_finds_is_reported_in_the_pure_parsers_words():
    with pytest.raises(SchemaError) as err:
        load_text("codeword: 1\na: *x\n", "alias.yaml")
    (diagnostic,) = err.value.diagnostics
    assert "found undefined alias 'x'" in diagnostic.message
    assert (diagnostic.loc.line, diagnostic.loc.col) == (2, 4)
