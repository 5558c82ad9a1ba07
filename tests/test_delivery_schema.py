"""The `delivery` section of a schema: what it resolves to, and every rule the
resolver holds it to, each refused at the line to fix. The cases edit a copy of
tr24.yaml, whose section names the master and slave machines."""
from __future__ import annotations

from pathlib import Path

import pytest

from codeword.build import compile_schema
from codeword.diagnostics import SchemaError
from codeword.model import DeliveryNotes
from conftest import SCHEMAS, load_model

TR24 = (SCHEMAS / "tr24.yaml").read_text(encoding="utf-8")

# A second request event, which both of the master's states must handle.
SECOND_REQUEST = (
    ("      send: {request: command,", "      ping: {request: command, args: [receiver, data]}\n"
                                       "      send: {request: command,"),
    ("          timer: ignore\n", "          timer: ignore\n          ping: error\n"),
    ("          send: error ", "          ping: error\n          send: error "),
)
# A second receive event for the slave, ignored in both of its states.
SECOND_RECEIVE = (
    ("      receive: {message: command}\n", "      receive: {message: command}\n      hear: {message: reply}\n"),
    ("        doc: no command executed yet, no reply kept\n        on:\n",
     "        doc: no command executed yet, no reply kept\n        on:\n          hear: ignore\n"),
    ("        doc: a reply is kept; waiting for commands\n        on:\n",
     "        doc: a reply is kept; waiting for commands\n        on:\n          hear: ignore\n"),
)
PATIENCE = ("  own_id:\n", "  patience: {default: 5}\n  own_id:\n")  # a parameter no machine takes

# name: (edits, expected message, text of the line it is reported at)
CASES = {
    "unknown machine": ((("sender: master  ", "sender: boss  "),),
                        "delivery: unknown machine 'boss'", "sender: boss"),
    "one machine for both": ((("receiver: slave  ", "receiver: master  "),),
                             "delivery: the receiver is the sender, 'master'", "receiver: master"),
    "sender without a request": ((("sender: master  ", "sender: slave  "), ("receiver: slave  ", "receiver: master  ")),
                                 "sender 'slave' has no application request events", "sender: slave"),
    "sender without a timer": ((("sender: master  ", "sender: slave  "), ("receiver: slave  ", "receiver: master  ")),
                               "sender 'slave' has no timer event", "sender: slave"),
    "receiver without execute": ((("sender: master  ", "sender: slave  "),
                                  ("receiver: slave  ", "receiver: master  ")),
                                 "receiver 'master' has no `execute` action", "receiver: master"),
    "two requests": (SECOND_REQUEST, "sender 'master' has 2 (ping, send) application request events",
                     "sender: master"),
    "two receive events": (SECOND_RECEIVE, "receiver 'slave' has 2 receive events (receive, hear)",
                           "receiver: slave"),
    "request without its address": ((("args: [receiver, data]", "args: [data]"),),
                                    "request event 'send' of sender 'master' takes [data]; it needs two "
                                    "arguments", "args: [data]"),
    "unknown parameter": ((("address: own_id ", "address: device_id "),),
                          "delivery: unknown parameter 'device_id'", "address: device_id"),
    "address the receiver does not take": ((PATIENCE, ("address: own_id ", "address: patience ")),
                                           "receiver 'slave' does not take parameter 'patience'",
                                           "address: patience"),
    "timeout the sender does not take": ((PATIENCE, ("timeout: timeout ", "timeout: patience ")),
                                         "sender 'master' does not take parameter 'patience'", "timeout: patience"),
    "timeout no timer runs on": ((("timeout: timeout ", "timeout: retry_limit "),
                                  ("retry_limit: retry_limit ", "retry_limit: timeout ")),
                                 "sender 'master' starts no timer with parameter 'retry_limit'",
                                 "timeout: retry_limit"),
    "one parameter twice": ((("retry_limit: retry_limit ", "retry_limit: timeout "),),
                            "address, timeout and retry_limit name the same parameter twice", "delivery:"),
    "unknown note": ((("restart: TR24-D5}", "restart: TR24-D9}"),),
                     "delivery: unknown note 'TR24-D9'", "notes: {guarantee"),
    "missing key": ((("  retry_limit: retry_limit ", "  # no retry limit "),),
                    "'retry_limit' is a required property", "delivery:"),
}


def schema_with(tmp_path: Path, edits) -> Path:
    text = TR24
    for old, new in edits:
        assert text.count(old) == 1, old
        text = text.replace(old, new)
    path = tmp_path / "tr24.yaml"
    path.write_text(text, encoding="utf-8")
    return path


def test_the_section_resolves_to_names_the_targets_use():
    d = load_model("tr24").delivery
    assert (d.sender, d.receiver, d.address, d.timeout, d.retry_limit) == \
        ("master", "slave", "own_id", "timeout", "retry_limit")
    assert (d.request, d.address_arg, d.data_arg) == ("send", "receiver", "data")
    assert d.notes == DeliveryNotes(guarantee="TR24-D5", retry_limit="TR24-D4", restart="TR24-D5")
    assert load_model("mtv4").delivery is None


@pytest.mark.parametrize("name", sorted(CASES))
def test_a_broken_delivery_section_is_refused_at_its_line(tmp_path, name):
    edits, message, line_text = CASES[name]
    path = schema_with(tmp_path, edits)
    with pytest.raises(SchemaError) as err:
        compile_schema(path)
    lines = path.read_text(encoding="utf-8").splitlines()
    found = [d for d in err.value.diagnostics if message in d.message]
    assert found, [d.message for d in err.value.diagnostics]
    for diagnostic in found:
        assert diagnostic.loc.file == str(path) and diagnostic.hint
        assert line_text in lines[diagnostic.loc.line - 1], (diagnostic, lines[diagnostic.loc.line - 1])
