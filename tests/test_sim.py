"""TR24-D5 over the simulated lossy channel: every command executed exactly once
and in order, every reply reaching the master, failure instead of a hang with a
retry limit, and the measured cost against the stop-and-wait formula."""
from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from codeword.sim import Link, Simulation, efficiency, reply_for

ROOT = Path(__file__).resolve().parent.parent
LOSS_RATES = (0.0, 0.1, 0.2, 0.3, 0.4, 0.5)
# Across the property runs below: 6 rates x 3 channel kinds x 2 seeds x 3000 commands
# = 108,000 commands, over 1 to 4 slaves.
CHANNELS = {
    "loss only": dict(),
    "duplicating": dict(duplicate=0.2, delay=(0, 8)),
    "duplicating, corrupting": dict(duplicate=0.1, corrupt=0.1, delay=(2, 6)),
}
COMMANDS = 3000


def check_exactly_once_in_order(sim: Simulation) -> None:
    for sid in sim.slave_ids:
        assert sim.executed[sid] == sim.issued[sid], f"slave {sid}: executed list differs from the commands sent"
    assert len(sim.outcomes) == sim.stats.commands
    for sid, command, outcome, reply in sim.outcomes:
        assert outcome == "delivered"
        assert reply == reply_for(command, sid)


@pytest.mark.parametrize("seed", (11, 12))
@pytest.mark.parametrize("channel", sorted(CHANNELS))
@pytest.mark.parametrize("loss", LOSS_RATES)
def test_every_command_runs_once_in_order_and_every_reply_arrives(loss, channel, seed):
    link = Link(p_fwd=loss, p_ack=loss, **CHANNELS[channel])
    slaves = 1 + (seed + int(loss * 10)) % 4
    sim = Simulation(seed, link, slaves=slaves, timeout=25)
    stats = sim.run(COMMANDS)
    assert stats.commands == COMMANDS and stats.delivered == COMMANDS and stats.failed == 0
    assert sim.idle() and not sim.queue
    check_exactly_once_in_order(sim)
    if loss:
        assert stats.lost > 0  # the channel did lose packets
    if "duplicate" in CHANNELS[channel]:
        assert stats.duplicated > 0


def test_asymmetric_loss_and_long_data():
    sim = Simulation(5, Link(p_fwd=0.5, p_ack=0.05, duplicate=0.1), slaves=4, data_length=59, timeout=25)
    sim.run(1000)
    check_exactly_once_in_order(sim)


@pytest.mark.parametrize("loss", (0.3, 0.5))
def test_retry_limit_reports_failure_instead_of_hanging(loss):
    """With a limit every command ends, delivered or failed, within (limit + 1)
    timeouts plus the last reply's delay; the limitation is only that after a
    failure the slave may take the next command for a duplicate (TR24-D4, D5)."""
    limit, timeout = 2, 25
    sim = Simulation(21, Link(p_fwd=loss, p_ack=loss, delay=(1, 5)), slaves=2, timeout=timeout, retry_limit=limit)
    stats = sim.run(2000)
    assert stats.delivered + stats.failed == stats.commands == 2000
    assert stats.failed > 0 and sim.idle()
    assert sim.now <= 2000 * ((limit + 1) * timeout + 5)
    after_failure = {sid: False for sid in sim.slave_ids}
    for sid in sim.slave_ids:
        runs = sim.executed[sid]
        assert len(runs) == len(set(runs)), "a command ran twice"
        issued = sim.issued[sid]
        positions = [issued.index(c) for c in runs]
        assert positions == sorted(positions), "commands ran out of order"
    for sid, command, outcome, reply in sim.outcomes:
        if outcome == "delivered" and not after_failure[sid]:
            assert reply == reply_for(command, sid)
            assert command in sim.executed[sid]
        after_failure[sid] = outcome == "failed"


def test_lossless_link_costs_one_packet_each_way():
    sim = Simulation(1, Link(), slaves=3)
    stats = sim.run(500)
    assert (stats.command_packets, stats.reply_packets) == (500, 500)


@pytest.mark.parametrize("p", (0.0, 0.1, 0.3, 0.5))
def test_transmissions_per_command_match_theory(p):
    measured, theory = efficiency(p, p, commands=20000)
    assert theory == pytest.approx(1 / (1 - p) ** 2)
    assert abs(measured - theory) / theory < 0.03, (measured, theory)


def test_a_seed_names_a_run():
    runs = [Simulation(9, Link(p_fwd=0.3, p_ack=0.3, duplicate=0.1), slaves=4, trace=True) for _ in range(2)]
    for sim in runs:
        sim.run(200)
    assert runs[0].trace == runs[1].trace
    other = Simulation(10, Link(p_fwd=0.3, p_ack=0.3, duplicate=0.1), slaves=4, trace=True)
    other.run(200)
    assert other.trace != runs[0].trace


@pytest.mark.parametrize("bad", (dict(p_fwd=0.6), dict(p_ack=-0.1), dict(delay=(5, 1)), dict(duplicate=1.0)))
def test_bad_channel_settings_are_refused(bad):
    with pytest.raises(ValueError):
        Simulation(1, Link(**bad))


def test_command_line():
    run = subprocess.run([sys.executable, "-m", "codeword.sim", "--seed", "4", "--loss", "0.2", "--slaves", "4",
                          "--commands", "300"], cwd=ROOT, capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stderr
    assert "delivered: 300" in run.stdout and "failed: 0" in run.stdout
    bad = subprocess.run([sys.executable, "-m", "codeword.sim", "--loss", "0.9"], cwd=ROOT,
                         capture_output=True, text=True, timeout=60)
    assert bad.returncode == 2 and "p_fwd" in bad.stderr and "Traceback" not in bad.stderr
    usage = subprocess.run([sys.executable, "-m", "codeword.sim", "--help"], cwd=ROOT, capture_output=True,
                           text=True, timeout=60)
    assert usage.returncode == 0 and "--loss" in usage.stdout
