"""TR24-D5 over the simulated lossy channel: every command executed exactly once
and in order, every reply reaching the master, failure instead of a hang with a
retry limit, and the measured cost against the stop-and-wait formula; and the
same guarantee for a copy of the schema whose machines, parameters and events
have other names, which the simulator finds through the `delivery` section."""
from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import pytest

from codeword.check.run import load_codec
from codeword.sim import Link, Simulation, efficiency, reply_for
from conftest import load_generated, load_model, simulation

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
    for rid in sim.receiver_ids:
        assert sim.executed[rid] == sim.issued[rid], f"slave {rid}: executed list differs from the commands sent"
    assert len(sim.outcomes) == sim.stats.commands
    for rid, command, outcome, reply in sim.outcomes:
        assert outcome == "delivered"
        assert reply == reply_for(command, rid)


@pytest.mark.parametrize("seed", (11, 12))
@pytest.mark.parametrize("channel", sorted(CHANNELS))
@pytest.mark.parametrize("loss", LOSS_RATES)
def test_every_command_runs_once_in_order_and_every_reply_arrives(loss, channel, seed):
    link = Link(p_fwd=loss, p_ack=loss, **CHANNELS[channel])
    slaves = 1 + (seed + int(loss * 10)) % 4
    sim = simulation("tr24", seed, link, receivers=slaves, timeout=25)
    stats = sim.run(COMMANDS)
    assert stats.commands == COMMANDS and stats.delivered == COMMANDS and stats.failed == 0
    assert sim.idle() and not sim.queue
    check_exactly_once_in_order(sim)
    if loss:
        assert stats.lost > 0  # the channel did lose packets
    if "duplicate" in CHANNELS[channel]:
        assert stats.duplicated > 0


def test_asymmetric_loss_and_long_data():
    sim = simulation("tr24", 5, Link(p_fwd=0.5, p_ack=0.05, duplicate=0.1), receivers=4,
                     parameters={"data_length": 59}, timeout=25)
    assert all(len(c) == 59 for c in sim.issued[3] + sim.executed[3])
    sim.run(1000)
    check_exactly_once_in_order(sim)


@pytest.mark.parametrize("loss", (0.3, 0.5))
def test_retry_limit_reports_failure_instead_of_hanging(loss):
    """With a limit every command ends, delivered or failed, within (limit + 1)
    timeouts plus the last reply's delay; the limitation is only that after a
    failure the slave may take the next command for a duplicate (TR24-D4, D5)."""
    limit, timeout = 2, 25
    sim = simulation("tr24", 21, Link(p_fwd=loss, p_ack=loss, delay=(1, 5)), receivers=2, timeout=timeout,
                     retry_limit=limit)
    stats = sim.run(2000)
    assert stats.delivered + stats.failed == stats.commands == 2000
    assert stats.failed > 0 and sim.idle()
    assert sim.now <= 2000 * ((limit + 1) * timeout + 5)
    after_failure = {rid: False for rid in sim.receiver_ids}
    for rid in sim.receiver_ids:
        runs = sim.executed[rid]
        assert len(runs) == len(set(runs)), "a command ran twice"
        issued = sim.issued[rid]
        positions = [issued.index(c) for c in runs]
        assert positions == sorted(positions), "commands ran out of order"
    for rid, command, outcome, reply in sim.outcomes:
        if outcome == "delivered" and not after_failure[rid]:
            assert reply == reply_for(command, rid)
            assert command in sim.executed[rid]
        after_failure[rid] = outcome == "failed"


def test_lossless_link_costs_one_packet_each_way():
    sim = simulation("tr24", 1, Link(), receivers=3)
    stats = sim.run(500)
    assert (stats.command_packets, stats.reply_packets) == (500, 500)


@pytest.mark.parametrize("p", (0.0, 0.1, 0.3, 0.5))
def test_transmissions_per_command_match_theory(p):
    measured, theory = efficiency(load_model("tr24"), load_generated("tr24"), p, p, commands=20000)
    assert theory == pytest.approx(1 / (1 - p) ** 2)
    assert abs(measured - theory) / theory < 0.03, (measured, theory)


def test_a_seed_names_a_run():
    runs = [simulation("tr24", 9, Link(p_fwd=0.3, p_ack=0.3, duplicate=0.1), receivers=4, trace=True)
            for _ in range(2)]
    for sim in runs:
        sim.run(200)
    assert runs[0].trace == runs[1].trace
    other = simulation("tr24", 10, Link(p_fwd=0.3, p_ack=0.3, duplicate=0.1), receivers=4, trace=True)
    other.run(200)
    assert other.trace != runs[0].trace


@pytest.mark.parametrize("bad", (dict(p_fwd=0.6), dict(p_ack=-0.1), dict(delay=(5, 1)), dict(duplicate=1.0)))
def test_bad_channel_settings_are_refused(bad):
    with pytest.raises(ValueError):
        simulation("tr24", 1, Link(**bad))


def test_command_line():
    run = subprocess.run([sys.executable, "-m", "codeword.sim", "--seed", "4", "--loss", "0.2", "--receivers", "4",
                          "--commands", "300"], cwd=ROOT, capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stderr
    assert "delivered: 300" in run.stdout and "failed: 0" in run.stdout
    bad = subprocess.run([sys.executable, "-m", "codeword.sim", "--loss", "0.9"], cwd=ROOT,
                         capture_output=True, text=True, timeout=60)
    assert bad.returncode == 2 and "p_fwd" in bad.stderr and "Traceback" not in bad.stderr
    usage = subprocess.run([sys.executable, "-m", "codeword.sim", "--help"], cwd=ROOT, capture_output=True,
                           text=True, timeout=60)
    assert usage.returncode == 0 and "--loss" in usage.stdout


def test_unknown_or_missing_parameters_are_refused():
    with pytest.raises(ValueError, match="unknown parameter 'size'"):
        simulation("tr24", 1, Link(), parameters={"size": 3})
    bad = subprocess.run([sys.executable, "-m", "codeword.sim", "--param", "data_length=60"], cwd=ROOT,
                         capture_output=True, text=True, timeout=60)
    assert bad.returncode == 2 and "data_length" in bad.stderr and "Traceback" not in bad.stderr


def test_a_schema_without_delivery_cannot_be_simulated():
    with pytest.raises(ValueError, match="no `delivery` section"):
        Simulation(load_model("mtv4"), load_generated("mtv4"), 1, Link())
    run = subprocess.run([sys.executable, "-m", "codeword.sim", "--schema", "mtv4"], cwd=ROOT,
                         capture_output=True, text=True, timeout=60)
    assert run.returncode == 2 and "delivery" in run.stderr


# -- the same machines under other names ------------------------------------------


def renamed_schema(folder: Path) -> Path:
    """tr24.yaml with every name the simulator relies on changed: protocol,
    machines, events, the address, timeout, retry-limit and data-length
    parameters; the `delivery` section names the new ones."""
    text = (ROOT / "schemas" / "tr24.yaml").read_text(encoding="utf-8")
    text = text[:text.index("\ndelivery:")]  # written anew below
    for old, new in (("protocol: tr24", "protocol: relay"), ("\n  master:\n", "\n  sender:\n"),
                     ("\n  slave:\n", "\n  receiver:\n")):
        assert text.count(old) == 1, old
        text = text.replace(old, new)
    for old, new in ((r"\bown_id\b", "address"), (r"\bdata_length\b", "size"), (r"\btimeout\b", "patience"),
                     (r"\bretry_limit\b", "attempts"), (r"\bsend:", "post:"), (r"\breceive:", "hear:"),
                     (r"(?m)^(\s+)timer:", r"\1alarm:")):
        text, n = re.subn(old, new, text)
        assert n, old
    text += """
delivery:
  sender: sender
  receiver: receiver
  address: address
  timeout: patience
  retry_limit: attempts
  notes: {guarantee: TR24-D5, retry_limit: TR24-D4, restart: TR24-D5}
"""
    path = folder / "relay.yaml"
    path.write_text(text, encoding="utf-8")
    return path


def test_renamed_machines_deliver_every_command_once_in_order(tmp_path):
    protocol, codec = load_codec(renamed_schema(tmp_path))
    assert not hasattr(codec, "MasterMachine") and hasattr(codec.SenderMachine, "post")
    assert hasattr(codec.ReceiverMachine, "hear") and not hasattr(codec.ReceiverMachine, "receive")
    commands, size = 1500, 5
    link = Link(p_fwd=0.3, p_ack=0.3, duplicate=0.2, corrupt=0.05, delay=(0, 8))
    sim = Simulation(protocol, codec, 3, link, receivers=3, timeout=25, parameters={"size": size})
    stats = sim.run(commands)
    assert stats.lost > 0 and stats.duplicated > 0  # the link was lossy
    assert stats.delivered == commands and stats.failed == 0 and sim.idle()
    # Each command carries its number in its first four bytes: every number runs
    # exactly once, each receiver runs its own in increasing order, and each
    # reply is the command's bytes plus the receiver's address.
    numbers = []
    for rid, ran in sim.executed.items():
        assert all(len(c) == size for c in ran)
        mine = [int.from_bytes(c[:4], "big") for c in ran]
        assert mine == sorted(mine), f"receiver {rid} ran commands out of order"
        numbers += mine
    assert sorted(numbers) == list(range(commands))
    for rid, command, outcome, reply in sim.outcomes:
        assert outcome == "delivered" and reply == bytes((b + rid) % 256 for b in command)


def test_command_line_simulates_a_named_schema_file(tmp_path):
    schema = renamed_schema(tmp_path)
    run = subprocess.run([sys.executable, "-m", "codeword.sim", "--schema", str(schema), "--receivers", "2",
                          "--loss", "0.3", "--commands", "200", "--param", "size=9"], cwd=ROOT,
                         capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stderr
    assert "delivered: 200" in run.stdout and "failed: 0" in run.stdout


# -- device addresses, timeout and retry limit inside the schema's ranges -----------


def narrowed_schema(folder: Path, own_id: str, timeout: str = "", retry_limit: str = "[0, 255]") -> Path:
    """tr24.yaml with other ranges for the address, timeout and retry-limit parameters."""
    text = (ROOT / "schemas" / "tr24.yaml").read_text(encoding="utf-8")
    for old, new in (("  own_id:\n    range: [0, 255]", f"  own_id:\n    range: {own_id}"),
                     ("  timeout:\n    default: 100", f"  timeout:\n    default: 100{timeout}"),
                     ("    default: 0\n    range: [0, 255]", f"    default: 0\n    range: {retry_limit}")):
        assert text.count(old) == 1, old
        text = text.replace(old, new)
    if retry_limit.startswith("[1"):
        text = text.replace("    default: 0\n    range: [1", "    default: 1\n    range: [1")
    if timeout:
        text = text.replace("    default: 100\n", "    default: 2\n")
    path = folder / "tr24.yaml"
    path.write_text(text, encoding="utf-8")
    return path


def test_devices_take_addresses_the_address_range_admits(tmp_path):
    """An ID range of 7..9 holds none of the default addresses (1, 3..6): the
    simulator's devices are 7, 8 and 9, and a fourth receiver does not exist."""
    protocol, codec = load_codec(narrowed_schema(tmp_path, "[7, 9]"))
    assert protocol.delivery.addresses == (7, 8, 9)
    sim = Simulation(protocol, codec, 5, Link(p_fwd=0.2, p_ack=0.2), receivers=2)
    stats = sim.run(300)
    assert stats.delivered == 300 and sim.receiver_ids == (8, 9)
    check_exactly_once_in_order(sim)
    with pytest.raises(ValueError, match=r"receivers must be in 1\.\.2"):
        Simulation(protocol, codec, 5, Link(), receivers=3)


def test_the_default_addresses_stay_where_the_range_admits_them():
    assert load_model("tr24").delivery.addresses == (1, 3, 4, 5, 6)


def test_measurement_takes_timeout_and_retry_limit_from_their_ranges(tmp_path):
    """A timeout of at most 3 ticks (the measurement would use 10) and a retry limit
    of at least 1 (it would use 0, no limit): the measurement runs inside both,
    with packets fast enough that no round trip outlasts the timeout."""
    protocol, codec = load_codec(narrowed_schema(tmp_path, "[0, 255]", timeout="\n    range: [1, 3]",
                                                 retry_limit="[1, 5]"))
    measured, theory = efficiency(protocol, codec, 0.0, 0.0, commands=200)
    assert (measured, theory) == (1.0, 1.0)  # no loss, no early resend: one transmission each
    measured, theory = efficiency(protocol, codec, 0.3, 0.3, commands=2000)
    assert measured > 1.0 and theory == pytest.approx(1 / 0.49)
