"""The mutation run's patches still fit the sources: each text to replace occurs exactly
once in its file, so a mutant cannot silently stop applying (python -m tests.mutation
runs them; tests/mutation/RESULTS.md has the last results)."""
from __future__ import annotations

import pytest

from conftest import ROOT
from mutation.mutants import MUTANTS


@pytest.mark.parametrize("mutant", MUTANTS, ids=lambda m: m.name)
def test_each_patch_applies_once_and_changes_the_text(mutant):
    for file, find, replace in mutant.patches:
        text = (ROOT / file).read_text(encoding="utf-8")
        assert text.count(find) == 1, f"{mutant.name}: {file} has {text.count(find)} of {find[:60]!r}"
        assert find != replace
    for test in mutant.tests:
        if test.startswith("tests/"):
            assert (ROOT / test.split("::")[0]).is_file(), f"{mutant.name}: no {test}"


def test_names_are_unique():
    names = [m.name for m in MUTANTS]
    assert len(names) == len(set(names))
