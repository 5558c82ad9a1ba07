"""TR24-D5 model-checked: SPIN explores every interleaving of the generated
Promela model of the tr24 machines over a channel that loses and duplicates
packets without reordering them.

The model's own checks (generated/promela/tr24.pml): the slave executes
command numbers 1, 2, 3, … each once and in order; the master delivers only
the reply to the outstanding command, once. Expected outcomes come from
PROTOCOLS.md: no error for the declared machines; a counterexample when the
master may restart (TR24-D5) or gives up after a retry limit (TR24-D4).
"""
from __future__ import annotations

import re
import shutil
import subprocess
from pathlib import Path

import pytest

from codeword.build import compile_schema
from codeword.diagnostics import SchemaError
from codeword.targets import promela
from conftest import ROOT, SCHEMAS

MODEL = ROOT / "generated" / "promela" / "tr24.pml"


def verify(model_text: str, work: Path, *defines: str) -> tuple[str, str]:
    """(pan's report, the replayed trail's printed lines or "") for the model with -D`defines`."""
    for tool in ("spin", "gcc"):
        assert shutil.which(tool), f"{tool} is not installed (.ci/run installs it)"
    work.mkdir(parents=True, exist_ok=True)
    (work / "model.pml").write_text(model_text, encoding="utf-8")
    flags = [f"-D{d}" for d in defines]
    run = lambda *cmd: subprocess.run(cmd, cwd=work, capture_output=True, text=True, timeout=120)  # noqa: E731
    generated = run("spin", *flags, "-a", "model.pml")
    assert generated.returncode == 0, generated.stdout + generated.stderr
    # breadth-first: a counterexample is a shortest one, so its trail reads easily;
    # the state space is small, so an unoptimised verifier compiles faster than it pays off
    built = run("gcc", "-O0", "-DSAFETY", "-DBFS", "-o", "pan", "pan.c")
    assert built.returncode == 0, built.stderr
    report = run("./pan").stdout
    trail = ""
    if (work / "model.pml.trail").exists():
        trail = run("spin", *flags, "-t", "model.pml").stdout
    return report, trail


def errors(report: str) -> int:
    found = re.search(r"errors: (\d+)", report)
    assert found, report
    return int(found.group(1))


def printed(trail: str) -> list[str]:
    """The application's lines of a replayed trail: send, execute, deliver, fail, restart."""
    keep = ("send command", "execute command", "deliver reply", "failed", "restarts")
    return [line.split(" (")[0].strip() for line in trail.splitlines() if any(k in line for k in keep)]


def replies_to_other_commands(lines: list[str]) -> list[tuple[int, int]]:
    """(reply, command) for every reply delivered to a command it does not answer."""
    out = []
    for line in lines:
        found = re.fullmatch(r"deliver reply (\d+) for command (\d+)", line)
        if found and found.group(1) != found.group(2):
            out.append((int(found.group(1)), int(found.group(2))))
    return out


def test_declared_machines_execute_every_command_once_in_order(tmp_path):
    report, trail = verify(MODEL.read_text(encoding="utf-8"), tmp_path)
    assert "Full statespace search" in report
    assert "max search depth too small" not in report
    assert errors(report) == 0, report
    assert trail == ""


def test_master_restart_makes_the_slave_drop_a_command_as_a_duplicate(tmp_path):
    """TR24-D5: a master that restarts while idle sends with seq 0 again; a slave
    expecting 1 takes the command for a duplicate, does not run it, and sends the
    kept reply to the previous command (TR24-D2), which the master delivers."""
    report, trail = verify(MODEL.read_text(encoding="utf-8"), tmp_path, "MASTER_RESTART")
    assert errors(report) > 0, report
    lines = printed(trail)
    assert "master restarts" in lines, trail
    wrong = replies_to_other_commands(lines[lines.index("master restarts"):])
    assert wrong, lines
    reply, command = wrong[0]
    assert f"execute command {reply}" in lines  # the previous command ran …
    assert f"execute command {command}" not in lines  # … the new one was skipped


def test_retry_limit_failure_can_make_the_next_command_a_duplicate(tmp_path):
    """TR24-D4: after a failure seq is kept; if the failed command did run and only
    its replies were lost, the next command looks like its duplicate."""
    report, trail = verify(MODEL.read_text(encoding="utf-8"), tmp_path, "RETRY_LIMIT=2")
    assert errors(report) > 0, report
    lines = printed(trail)
    failed = [line for line in lines if line.endswith("failed")]
    assert failed, lines
    failed_number = int(failed[0].split()[1])
    assert f"execute command {failed_number}" in lines
    assert replies_to_other_commands(lines) == [(failed_number, failed_number % 4 + 1)]


def test_the_checks_catch_a_slave_that_executes_duplicates(tmp_path):
    """The model's checks can fail: a slave that runs a duplicate command again
    instead of resending its kept reply is caught."""
    text = (SCHEMAS / "tr24.yaml").read_text(encoding="utf-8")
    broken = text.replace("actions: [resend_cached]", "actions: [execute, cache_reply, send_reply]")
    assert broken != text
    schema = tmp_path / "tr24.yaml"
    schema.write_text(broken, encoding="utf-8")
    model = promela.render(compile_schema(schema))["promela/tr24.pml"]
    report, trail = verify(model, tmp_path / "spin")
    assert errors(report) > 0, report
    executed = [line.split()[2] for line in printed(trail) if line.startswith("execute command")]
    assert len(executed) != len(set(executed)), trail  # one command ran twice


def test_schemas_without_machines_have_no_model():
    assert promela.render(compile_schema(SCHEMAS / "route.yaml")) == {}


def test_a_machine_keeping_two_messages_is_reported_not_crashed(tmp_path):
    text = (SCHEMAS / "tr24.yaml").read_text(encoding="utf-8")
    broken = text.replace("keep: reply\n        fields: {seq: {packet: seq}, sender: {param: own_id}, "
                          "receiver: {packet: sender}, data: {const: 0}}",
                          "keep: command\n        fields: {seq: {packet: seq}, sender: {param: own_id}, "
                          "receiver: {packet: sender}, data: {const: 0}}")
    assert broken != text
    schema = tmp_path / "tr24.yaml"
    schema.write_text(broken, encoding="utf-8")
    with pytest.raises(SchemaError) as caught:
        promela.render(compile_schema(schema))
    assert "one kept message" in str(caught.value.diagnostics[0])


def test_an_application_event_without_values_is_modelled(tmp_path):
    """A master event the application raises with no request message (`poke`, ignored
    in every state) is one the model's application may raise wherever it is taken,
    not a packet to receive: the model builds and SPIN verifies it with no error."""
    lines = []
    master = False
    for line in (SCHEMAS / "tr24.yaml").read_text(encoding="utf-8").split("\n"):
        lines.append(line)
        master = line.startswith("  master:") or (master and not line.startswith("  slave:"))
        if master and line.strip().startswith("send: {request: command"):
            lines.append("      poke: {doc: the application asks for nothing}")
        if master and line.strip() == "on:":
            lines.append(" " * (len(line) - len(line.lstrip()) + 2) + "poke: ignore")
    schema = tmp_path / "tr24.yaml"
    schema.write_text("\n".join(lines), encoding="utf-8")
    model = promela.render(compile_schema(schema))["promela/tr24.pml"]
    assert "poke" in model
    report, _ = verify(model, tmp_path / "spin")
    assert errors(report) == 0, report
