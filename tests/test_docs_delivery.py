"""The tr24 page's delivery section: the measured cost against the stop-and-wait
formula, and the guarantee with the limits PROTOCOLS.md gives it (TR24-D4, D5)."""
from __future__ import annotations

import re
import subprocess
import sys

import pytest

from codeword.build import compile_schema, render_protocol
from conftest import PROTOCOLS, ROOT

DOCS = ROOT / "generated" / "docs"


def section(page: str) -> str:
    start = page.index('<a id="delivery"></a>')
    return page[start:page.index('<a id="spec-notes"></a>', start)]


def table_rows(text: str) -> list[tuple[float, float, float]]:
    """(p, measured, theory) from the cost table."""
    rows = re.findall(r"^\| (0\.\d) \| (\d+\.\d{3}) \| (\d+\.\d{3}) \| \d+\.\d% \|$", text, re.M)
    return [(float(p), float(m), float(t)) for p, m, t in rows]


def test_cost_table_matches_the_formula_within_3_percent():
    rows = table_rows(section((DOCS / "tr24.md").read_text(encoding="utf-8")))
    assert [p for p, _, _ in rows] == [0.0, 0.1, 0.3, 0.5]
    # theory by hand: 1/(1-p)^2 = 1, 1/0.81, 1/0.49, 1/0.25
    assert [t for _, _, t in rows] == [1.000, 1.235, 2.041, 4.000]
    for p, measured, theory in rows:
        assert abs(measured - theory) / theory < 0.03, (p, measured, theory)
    assert rows[0][1] == 1.000  # no loss: one transmission each


def test_cost_table_is_what_the_simulator_prints():
    """The command the page names reproduces its table."""
    page = section((DOCS / "tr24.md").read_text(encoding="utf-8"))
    command = re.search(r"`python -m codeword\.sim ([^`]*--efficiency[^`]*)`", page).group(1).split()
    assert command[:2] == ["--schema", "tr24"]  # the page's own protocol, in any project
    run = subprocess.run([sys.executable, "-m", "codeword.sim", *command], cwd=ROOT, capture_output=True,
                         text=True, timeout=120)
    assert run.returncode == 0, run.stderr
    printed = [(float(p), float(m), float(t)) for p, m, t in
               re.findall(r"^\| (0\.\d) \| (\d+\.\d{3}) \| (\d+\.\d{3}) \|", run.stdout, re.M)]
    assert printed == table_rows(page)


def test_guarantee_and_its_limits_cite_the_decisions():
    text = section((DOCS / "tr24.md").read_text(encoding="utf-8"))
    assert "exactly once and in order" in text and "every reply reaches the master" in text
    assert "**Retry limit** ([TR24-D4](#note-tr24-d4))" in text
    assert "**Restart** ([TR24-D5](#note-tr24-d5))" in text
    assert "generated/promela/tr24.pml" in text
    assert "-DMASTER_RESTART" in text and "-DRETRY_LIMIT=2" in text  # the variants tests/test_spin.py runs
    assert (ROOT / "generated" / "promela" / "tr24.pml").is_file()


def test_contents_link_the_section():
    page = (DOCS / "tr24.md").read_text(encoding="utf-8")
    assert "[Delivery guarantee](#delivery)" in page


@pytest.mark.parametrize("protocol", [p for p in PROTOCOLS if p != "tr24"])
def test_protocols_without_delivery_machines_have_no_section(protocol):
    page = (DOCS / f"{protocol}.md").read_text(encoding="utf-8")
    assert 'id="delivery"' not in page and "#delivery" not in page


def test_machines_without_a_delivery_section_have_no_section(tmp_path):
    """The section comes from the schema's `delivery` section, not from the machines."""
    text = (ROOT / "schemas" / "tr24.yaml").read_text(encoding="utf-8")
    schema = tmp_path / "tr24.yaml"
    schema.write_text(text[:text.index("\ndelivery:")], encoding="utf-8")
    page = render_protocol(compile_schema(schema))["docs/tr24.md"]
    assert "## State machines" in page and 'id="delivery"' not in page and "#delivery" not in page


def test_the_section_names_the_declared_machines(tmp_path):
    """Prose and SPIN flags follow the `delivery` section's machine and parameter names."""
    text = (ROOT / "schemas" / "tr24.yaml").read_text(encoding="utf-8")
    head, delivery = text.split("\ndelivery:")
    renames = (("\n  master:\n", "\n  sender:\n"), ("\n  slave:\n", "\n  receiver:\n"),
               ("retry_limit", "attempts"))
    for old, new in renames:
        assert old in head, old
        head = head.replace(old, new)
    delivery = delivery.replace("sender: master", "sender: sender").replace("receiver: slave", "receiver: receiver")
    text = head + "\ndelivery:" + delivery.replace("retry_limit: retry_limit", "retry_limit: attempts")
    schema = tmp_path / "tr24.yaml"
    schema.write_text(text, encoding="utf-8")
    page = section(render_protocol(compile_schema(schema))["docs/tr24.md"])
    assert "every reply reaches the sender" in page and "one to four receivers" in page
    assert "-DSENDER_RESTART" in page and "-DATTEMPTS=2" in page and "with `attempts` above 0" in page
    assert "master" not in page and "slave" not in page
