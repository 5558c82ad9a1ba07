"""Schemas with delivery machines, in the style of tr24: a master that sends a command
and resends it on its timer until the reply comes, a slave that executes each command
and answers it; and the check that every target's machines run one exchange alike.

The generator draws every name from the fuzzer's name pool, so the generated code
meets names of every kind; lengths are fixed or a link parameter, with or without a
sequence bit, with or without a retry limit and a `delivery` section."""
from __future__ import annotations

import random
import re
import shutil
import subprocess
import tempfile
from pathlib import Path

import yaml

MACHINE_SHARE = 0.15  # of the seeds, when the feature is on

# the parameter values the exchange uses where a parameter has no default: in every
# range the generator draws, and the one address every device and argument gets
ADDRESS = 3


def machine_schema(g) -> dict:
    """A whole schema document with a master and a slave machine; `g` is the Generator."""
    rng = g.rng
    name = g.name
    seq_bit = rng.random() < 0.6
    retry = rng.random() < 0.7
    master_role, slave_role, down, up = name(), name(), name(), name()
    length_param = name() if rng.random() < 0.6 else None
    length = rng.randint(1, 6)
    timeout, retry_limit, address = name(), name() if retry else None, name()
    parameters: dict = {}
    if length_param:
        parameters[length_param] = {"default": length, "range": [1, rng.choice([length, 16, 59])]}
    if "delivery_ranges" in g.on:
        parameters.update(narrow_ranges(random.Random(f"delivery ranges {g.seed}"), timeout, retry_limit, address))
    else:
        parameters[timeout] = {"default": rng.choice([5, 10, 100]), "range": [1, 1000]}
        if retry_limit:
            parameters[retry_limit] = {"default": rng.randint(0, 3), "range": [0, 255]}
        parameters[address] = {"range": [0, 255]}  # no default: set per device

    seq, sender, receiver, kind = (name() if seq_bit else None), name(), name(), name()
    layout = envelope(g, seq, sender, receiver, kind)
    command, reply, data, answer = name(), name(), name(), name()
    size = {"length": length_param} if length_param else {"length": length}
    extra = name() if rng.random() < 0.4 else None  # a number the application also gives
    command_fields = [{"name": data, "type": "bytes", **size}]
    if extra:
        command_fields.insert(rng.randint(0, 1), {"name": extra, "type": f"u{rng.choice([4, 8])}"})
        if command_fields[0]["type"] == "u4":  # a number of 4 bits stays inside its byte
            command_fields.insert(1, {"name": name(), "type": "u4", "reserved": True})
        elif command_fields[-1]["type"] == "u4":
            command_fields.append({"name": name(), "type": "u4", "reserved": True})
    bits = int(next(f for f in layout if f.get("dispatch"))["type"][1:])
    ids = rng.sample(range(1 << bits), 2)
    doc: dict = {
        "codeword": 1, "protocol": f"fz{g.seed}", "title": f"fuzz schema {g.seed}", "source": "fuzz/schema",
        "notes": [{"id": n, "text": t} for n, t in (("FZ-1", "each command is executed once"),
                                                   ("FZ-2", "the master gives up at the retry limit"),
                                                   ("FZ-3", "a restarted master may lose one command"))],
        "roles": {master_role: {"doc": "sends commands"}, slave_role: {"doc": "executes commands"}},
        "directions": {down: {"from": master_role, "to": slave_role},
                       up: {"from": slave_role, "to": master_role}},
        "parameters": parameters,
        "framing": {"kind": "bytes", "byte_order": rng.choice(["big", "little"]), "layout": layout},
        "messages": {
            command: {"id": ids[0], "direction": down, "answered_by": [reply], "fields": command_fields},
            reply: {"id": ids[1], "direction": up, "fields": [{"name": answer, "type": "bytes", **size}]},
        },
    }
    lengths = [length_param] if length_param else []
    master_name, slave_name = name(), name()
    doc["machines"] = {
        master_name: master(g, master_role, lengths + [timeout] + ([retry_limit] if retry else []) + [address],
                            command, reply, seq, sender, receiver, data, answer, extra, timeout, retry_limit, address),
        slave_name: slave(g, slave_role, lengths + [address], command, reply, seq, sender, receiver, data, answer,
                          address),
    }
    if retry and not extra:  # the simulator's pair: one request of an address and data
        doc["delivery"] = {"sender": master_name, "receiver": slave_name, "address": address, "timeout": timeout,
                           "retry_limit": retry_limit,
                           "notes": {"guarantee": "FZ-1", "retry_limit": "FZ-2", "restart": "FZ-3"}}
    return doc


def narrow_ranges(rng: random.Random, timeout: str, retry_limit: str | None, address: str) -> dict:
    """Parameter ranges that leave out what the simulator would pick by itself: a
    timeout that may be shorter than its round trip, a retry limit that may not be
    0 (no limit), and device addresses from 0, 2 or 3 up; each range still holds
    ADDRESS and two addresses at least."""
    high = rng.choice([2, 3, 6, 9, 1000])
    out = {timeout: {"default": rng.randint(1, min(high, 100)), "range": [1, high]}}
    if retry_limit:
        low, high = rng.choice([0, 1, 2]), rng.choice([3, 255])
        out[retry_limit] = {"default": rng.randint(low, 3), "range": [low, high]}
    out[address] = {"range": [rng.choice([0, 2, 3]), rng.choice([4, 5, 8, 255])]}
    return out


def envelope(g, seq, sender, receiver, kind) -> list[dict]:
    """An optional sync byte, a byte of the dispatch bits, the sequence bit and reserved
    bits (or a whole dispatch byte), the sender and receiver bytes, the payload and an
    optional end marker."""
    rng = g.rng
    layout: list[dict] = []
    if rng.random() < 0.6:
        layout.append({"name": g.name(), "type": "u8", "const": rng.choice([0x02, 0x55, 0xA5, 0x7E])})
    width = rng.choice([1, 2, 3, 8])
    service = [{"name": kind, "type": f"u{width}", "dispatch": True}]
    if seq:
        service.append({"name": seq, "type": "u1"})
    if width < 8:
        rng.shuffle(service)
        spare = 8 - width - (1 if seq else 0)
        service.insert(rng.randint(0, len(service)), {"name": g.name(), "type": f"u{spare}", "reserved": True})
    elif seq:  # the sequence bit in a byte of its own
        service[1:] = [{"name": g.name(), "type": "u7", "reserved": True}, service[1]]
    layout += service
    ends = [{"name": sender, "type": "u8"}, {"name": receiver, "type": "u8"}]
    rng.shuffle(ends)
    layout += ends + [{"payload": True}]
    if rng.random() < 0.5:
        layout.append({"name": g.name(), "type": "u8", "const": rng.choice([0x03, 0x0A, 0xAA])})
    return layout


def master(g, role, parameters, command, reply, seq, sender, receiver, data, answer, extra, timeout,
           retry_limit, address) -> dict:
    """Sends a command, resends it on the timer up to the retry limit, delivers the reply."""
    name = g.name
    peer, retries = name(), name()
    send, receive, timer = name(), name(), name()
    idle, waiting = name(), name()
    a = {k: name() for k in ("set_peer", "keep", "transmit", "start", "stop", "flip", "count", "reset", "deliver",
                             "fail")}
    variables: dict = {peer: {"type": "u8", "initial": 0}}
    if seq:
        variables[name()] = {"type": "u1", "initial": 0}
    seq_var = next((v for v in variables if v != peer), None)
    if retry_limit:
        variables[retries] = {"type": "u8", "initial": 0}
    fields: dict = {sender: {"param": address}, receiver: {"request": receiver}, data: {"request": data}}
    if seq:
        fields[seq] = {"var": seq_var}
    if extra:
        fields[extra] = {"request": extra}
    args = [receiver, data] + ([extra] if extra else [])
    g.rng.shuffle(args) if extra else None
    actions: dict = {
        a["set_peer"]: {"set": peer, "value": {"request": receiver}},
        a["keep"]: {"keep": command, "fields": fields},
        a["transmit"]: {"transmit": "kept"},
        a["start"]: {"start_timer": timeout},
        a["stop"]: {"stop_timer": True},
        a["deliver"]: {"deliver": answer},
    }
    if seq:
        actions[a["flip"]] = {"flip": seq_var}
    if retry_limit:
        actions[a["count"]] = {"increment": retries}
        actions[a["reset"]] = {"set": retries, "value": {"const": 0}}
        actions[a["fail"]] = {"fail": "no reply within the retry limit"}
    guard: dict = {receiver: {"eq_param": address}, sender: {"eq_var": peer}}
    if seq:
        guard[seq] = {"eq_var": seq_var}
    done = [a["stop"]] + ([a["flip"]] if seq else []) + ([a["reset"]] if retry_limit else []) + [a["deliver"]]
    resend = [a["transmit"], a["start"]]
    if retry_limit:
        timer_rows: list = [{"guard": {retry_limit: 0}, "to": waiting, "actions": resend},
                            {"guard": {retries: {"lt_param": retry_limit}}, "to": waiting,
                             "actions": [a["count"]] + resend},
                            {"to": idle, "actions": [a["reset"], a["fail"]]}]
    else:
        timer_rows = [{"to": waiting, "actions": resend}]
    return {
        "role": role, "parameters": parameters, "variables": variables,
        "events": {send: {"request": command, "args": args}, receive: {"message": reply}, timer: {"timer": True}},
        "actions": actions, "initial": idle,
        "states": {
            idle: {"on": {send: {"to": waiting, "actions": [a["set_peer"], a["keep"], a["transmit"], a["start"]]},
                          receive: "ignore", timer: "ignore"}},
            waiting: {"on": {send: "error",
                             receive: [{"guard": guard, "to": idle, "actions": done}, {"to": waiting}],
                             timer: timer_rows}},
        },
    }


def slave(g, role, parameters, command, reply, seq, sender, receiver, data, answer, address) -> dict:
    """Executes a command for its address and answers it; with a sequence bit, a duplicate
    gets the kept reply again (a blank one before any command)."""
    name = g.name
    receive, fresh, listening, expected = name(), name(), name(), name()
    a = {k: name() for k in ("execute", "cache", "blank", "send", "flip")}
    fields: dict = {sender: {"param": address}, receiver: {"packet": sender}, answer: {"result": data}}
    blank = dict(fields, **{answer: {"const": 0}})
    if seq:
        fields[seq] = blank[seq] = {"packet": seq}
    actions: dict = {a["execute"]: {"execute": data}, a["cache"]: {"keep": reply, "fields": fields},
                     a["send"]: {"transmit": "kept"}}
    run = [a["execute"], a["cache"], a["send"]]
    mine = {receiver: {"eq_param": address}}
    if not seq:
        return {"role": role, "parameters": parameters, "events": {receive: {"message": command}},
                "actions": actions, "initial": fresh,
                "states": {fresh: {"on": {receive: [{"guard": mine, "to": fresh, "actions": run}, {"to": fresh}]}}}}
    actions[a["blank"]] = {"keep": reply, "fields": blank}
    actions[a["flip"]] = {"flip": expected}
    new = dict(mine, **{seq: {"eq_var": expected}})
    again = dict(mine, **{seq: {"ne_var": expected}})
    return {
        "role": role, "parameters": parameters, "variables": {expected: {"type": "u1", "initial": 0}},
        "events": {receive: {"message": command}}, "actions": actions, "initial": fresh,
        "states": {
            fresh: {"on": {receive: [{"guard": new, "to": listening, "actions": run + [a["flip"]]},
                                     {"guard": again, "to": fresh, "actions": [a["blank"], a["send"]]},
                                     {"to": fresh}]}},
            listening: {"on": {receive: [{"guard": new, "to": listening, "actions": run + [a["flip"]]},
                                         {"guard": again, "to": listening, "actions": [a["send"]]},
                                         {"to": listening}]}},
        },
    }


# -- the check ---------------------------------------------------------------------------------
def machine_checks(protocol, module, out: Path, where: Path, strict: list[str]) -> str:
    """'' when the machines run one exchange as expected in Python and in C (the C file,
    which calls every machine function, compiled with `strict`), byte for byte alike,
    and the Promela model passes spin's syntax check; else what went wrong."""
    if not protocol.machines:
        return ""
    plan = Exchange(protocol)
    try:
        python = plan.python(module)
    except Exception as e:  # noqa: BLE001 - whatever the generated code raises is the finding
        return f"python machines: {type(e).__name__}: {e}"
    problem = plan.expect(python, module)
    if problem:
        return "python machines: " + problem
    c = plan.c(out / "c", where, strict)
    if c.startswith("!"):
        return "C machines: " + c[1:]
    if c != python:
        first = next(i for i, (a, b) in enumerate(zip(python.splitlines() + [""], c.splitlines() + [""])) if a != b)
        return f"C machines disagree at step {first}: python {python.splitlines()[first:first + 1]}, " \
               f"C {c.splitlines()[first:first + 1]}"
    return promela_check(out / "promela" / f"{protocol.name}.pml", where)


def promela_check(model: Path, where: Path) -> str:
    if not model.exists():
        return f"no Promela model {model.name}"
    spin = shutil.which("spin")
    if spin is None:
        return ""
    folder = where / "spin"
    folder.mkdir(exist_ok=True)
    ran = subprocess.run([spin, "-a", str(model)], cwd=folder, capture_output=True, text=True, timeout=60)
    if ran.returncode != 0:
        return "spin -a: " + " | ".join((ran.stdout + ran.stderr).splitlines()[:2])
    return ""


def _hex(data) -> str:
    return bytes(data).hex() or "-"


class Exchange:
    """A command from the sender to the receiver, resent once on the timer, executed and
    answered; the reply delivered; the timer then silent; both machines reset."""

    def __init__(self, p):
        self.p = p
        self.sender = next(m for m in p.machines if any(e.request for e in m.events))
        self.receiver = next(m for m in p.machines if m is not self.sender)
        self.request = next(e for e in self.sender.events if e.request)
        self.timer = next((e for e in self.sender.events if e.timer), None)
        defaults = {x.name: x.default for x in p.parameters}
        self.values = {n: ADDRESS if defaults.get(n) is None else int(defaults[n])
                       for m in p.machines for n in m.parameters}
        message = p.message(self.request.request)
        self.args = {}
        for arg in self.request.args:
            f = next(x for x in message.members if x.name == arg)
            size = self.values[f.length_param] if f.length_param else f.length
            self.args[arg] = bytes((0x41 + 7 * i) & 0xFF for i in range(size)) if f.kind == "bytes" else ADDRESS
        self.data = next(v for v in self.args.values() if isinstance(v, bytes))
        self.timeout = self.values.get(next((a.target for a in self.sender.actions if a.kind == "start_timer"), ""), 0)
        self.receive_at = self.timeout + 1 if self.timer else 1

    def steps(self):
        """(label, machine, event, time)"""
        out = [("send", self.sender, self.request, 0)]
        if self.timer:
            out.append(("resend", self.sender, self.timer, self.timeout))
        out += [("execute", self.receiver, next(e for e in self.receiver.events if e.message), self.receive_at),
                ("deliver", self.sender, next(e for e in self.sender.events if e.message), self.receive_at + 1)]
        if self.timer:
            out.append(("quiet", self.sender, self.timer, 10 ** 6))
        return out

    @staticmethod
    def line(label, rc, sent, delivered, executed, failed, dropped) -> str:
        return f"{label} rc={rc} sent={_hex(sent)} delivered={_hex(delivered)} executed={_hex(executed)} " \
               f"failed={failed or '-'} dropped={int(bool(dropped))}"

    # -- Python ------------------------------------------------------------------------------
    def python(self, module) -> str:
        from codeword.targets.python.machines import EXECUTE_ARGUMENT, class_name, method_name
        objects = {}
        for m in self.p.machines:
            kwargs = {n: self.values[n] for n in m.parameters}
            if any(a.kind == "execute" for a in m.actions):
                kwargs[EXECUTE_ARGUMENT] = lambda data: bytes((b + ADDRESS) & 0xFF for b in data)
            objects[m.name] = getattr(module, class_name(m))(**kwargs)
        lines, packet = [], b""
        for label, m, event, now in self.steps():
            fn = getattr(objects[m.name], method_name(event))
            try:
                if event.request:
                    out = fn(now, **self.args)
                elif event.message:
                    out = fn(now, packet)
                else:
                    out = fn(now)
                rc = 0
            except module.MachineError:
                lines.append(self.line(label, -1, b"", b"", b"", "", False))
                continue
            if len(out.sent) > 1 or len(out.delivered) > 1 or len(out.executed) > 1:
                raise AssertionError(f"{label}: more than one output of a kind: {out!r}")
            packet = out.sent[0] if out.sent else packet
            lines.append(self.line(label, rc, out.sent[0] if out.sent else b"", (out.delivered or [b""])[0],
                                   (out.executed or [b""])[0], (out.failed or [""])[0], out.dropped))
        for o in objects.values():
            o.reset()
        return "\n".join(lines) + "\n"

    def expect(self, text: str, module) -> str:
        """The exchange did what the schema says: the command carries the data (the codec
        decodes it so), is resent unchanged, executed once and its reply delivered."""
        got = {line.split()[0]: dict(kv.split("=", 1) for kv in line.split()[1:]) for line in text.splitlines()}
        reply = bytes((b + ADDRESS) & 0xFF for b in self.data).hex()
        sent = got["send"]["sent"]
        if got["send"]["rc"] != "0" or sent == "-":
            return f"the request sent nothing: {got['send']}"
        try:
            decoded = module.decode(bytes.fromhex(sent))
        except module.CodecError as e:
            return f"the codec does not decode the machine's command {sent}: {e}"
        for arg, value in self.args.items():
            if getattr(decoded, arg) != value:
                return f"command {sent} decodes {arg}={getattr(decoded, arg)!r}, not {value!r}"
        if self.timer and got["resend"]["sent"] != sent:
            return f"the timer resent {got['resend']['sent']}, not {sent}"
        if got["execute"]["executed"] != self.data.hex() or got["execute"]["sent"] == "-":
            return f"the receiver did not execute and answer {self.data.hex()}: {got['execute']}"
        if got["deliver"]["delivered"] != reply:
            return f"the reply {got['execute']['sent']} delivered {got['deliver']['delivered']}, not {reply}"
        if self.timer and got["quiet"]["sent"] != "-":
            return f"the timer resent after the reply: {got['quiet']}"
        return ""

    # -- C -----------------------------------------------------------------------------------
    def c(self, include: Path, where: Path, strict: list[str]) -> str:
        """The C driver's output, or '!' and why it did not compile or run."""
        gcc = shutil.which("gcc")
        if gcc is None:
            return "!gcc is not installed"
        src, exe = where / "machines.c", where / "machines"
        src.write_text(self.c_source(), encoding="utf-8")
        built = subprocess.run([gcc, *strict, "-I", str(include), str(src), "-o", str(exe)], capture_output=True,
                               text=True, timeout=300)
        if built.returncode != 0:
            first = next((x for x in built.stderr.splitlines() if "error" in x), built.stderr[:300])
            return "!does not compile: " + first.replace(str(where) + "/", "")
        ran = subprocess.run([str(exe)], capture_output=True, text=True, timeout=60)
        if ran.returncode != 0:
            return f"!driver exit {ran.returncode}: " + " | ".join((ran.stdout + ran.stderr).splitlines()[:3])
        return ran.stdout

    def c_source(self) -> str:
        p, px = self.p, self.p.name.lower()
        message = p.message(self.request.request)
        lines = [f'#include "{p.name}.h"', "#include <stdio.h>", "",
                 "static void put_hex(const char *key, const uint8_t *b, unsigned n)", "{",
                 '    printf(" %s=", key);', '    if (n == 0u) printf("-");',
                 '    for (unsigned i = 0u; i < n; i++) printf("%02x", b[i]);', "}", "",
                 f"static void show(const char *label, int rc, const {px}_machine_out_t *o)", "{",
                 '    printf("%s rc=%d", label, rc);', '    put_hex("sent", o->sent, o->sent_len);',
                 '    put_hex("delivered", o->delivered, o->delivered_len);',
                 '    put_hex("executed", o->executed, o->executed_len);',
                 '    printf(" failed=%s dropped=%d\\n", o->failed != NULL ? o->failed : "-", o->dropped ? 1 : 0);',
                 "}", "",
                 "static void answer(void *ctx, const uint8_t *command, uint8_t len, uint8_t *result)", "{",
                 "    (void)ctx;",
                 f"    for (uint8_t i = 0u; i < len; i++) result[i] = (uint8_t)(command[i] + {ADDRESS}u);", "}", "",
                 "int main(void)", "{", f"    {px}_machine_out_t o;", f"    static uint8_t packet[{px.upper()}_MACHINE_MAX_PACKET];",
                 "    uint8_t packet_len = 0u;"]
        for arg, value in self.args.items():
            if isinstance(value, bytes):
                lines.append(f"    static const uint8_t arg_{arg}[] = {{{', '.join(str(b) for b in value)}}};")
        for m in p.machines:
            lines.append(f"    {px}_{m.name}_t {m.name};")
            values = [f"{self.values[n]}u" for n in m.parameters]
            if any(a.kind == "execute" for a in m.actions):
                values += ["answer", "NULL"]
            lines.append(f"    if ({px}_{m.name}_init(&{m.name}{''.join(', ' + v for v in values)}) != 0) return 2;")
        for label, m, event, now in self.steps():
            fn = f"{px}_{m.name}_{'tick' if event.timer else event.name}"
            args = [f"&{m.name}", f"{now}u"]
            if event.request:
                for arg in self.request.args:
                    value = self.args[arg]
                    f = next(x for x in message.members if x.name == arg)
                    args += [f"arg_{arg}", f"{len(value)}u"] if isinstance(value, bytes) else \
                        [f"({'uint8_t' if f.bits <= 8 else 'uint16_t' if f.bits <= 16 else 'uint32_t'}){value}u"]
            elif event.message:
                args += ["packet", "packet_len"]
            lines.append(f"    {{ int rc = {fn}({', '.join(args)}, &o); show(\"{label}\", rc, &o);")
            lines.append("      if (o.sent_len) { for (unsigned i = 0u; i < o.sent_len; i++) packet[i] = o.sent[i];"
                         " packet_len = o.sent_len; } }")
        for m in p.machines:
            lines.append(f"    {px}_{m.name}_reset(&{m.name});")
        lines += ["    return 0;", "}", ""]
        return "\n".join(lines)


# -- names that meet the generated machine code -------------------------------------------------
# names the generated functions, methods and structs use beside the schema's
ARGUMENT_NAMES = ("m", "now", "out", "self", "state", "values", "packet", "len")
FIELD_NAMES = ("b", "n", "packet", "len", "values", "state")
PARAMETER_NAMES = ("m", "b", "n", "now", "out", "execute", "execute_ctx", "packet", "len", "state", "kept")
VARIABLE_NAMES = ("state", "kept", "kept_len", "deadline", "timer_on", "execute", "execute_ctx")
EVENT_NAMES = ("tick", "reset", "init", "state", "kept", "deadline")


def machine_renames(doc: dict) -> list[tuple[str, str, str]]:
    """(name, new name, what) for each rename that makes a machine name meet another name
    the generated code uses; [] for a schema without machines."""
    machines = doc.get("machines")
    if not isinstance(machines, dict) or len(machines) != 2:
        return []
    sender = next((m for m in machines.values() if any("request" in e for e in m["events"].values())), None)
    if sender is None:
        return []
    request = next(e for e in sender["events"].values() if "request" in e)
    fields = {f["name"]: f for body in doc["messages"].values() for f in body["fields"]}
    fields.update({f["name"]: f for f in doc["framing"]["layout"] if "name" in f})
    members = [n for n, f in fields.items() if not {"const", "reserved", "dispatch"} & set(f)]
    data = next(a for a in request["args"] if fields[a]["type"] == "bytes")
    numbers = [a for a in request["args"] if fields[a]["type"] != "bytes"]
    params = list(doc["parameters"])
    out = [(a, f"{data}_len", f"argument {a} named like the length of {data}") for a in numbers]
    out += [(a, x, f"argument {a} named {x}") for a in numbers for x in ARGUMENT_NAMES]
    out += [(f, x, f"field {f} named {x}") for f in members for x in FIELD_NAMES]
    out += [(f, p, f"field {f} named like the parameter {p}") for f in members for p in params]
    out += [(p, x, f"parameter {p} named {x}") for p in params for x in PARAMETER_NAMES]
    for machine in machines.values():
        variables = list(machine.get("variables", {}))
        out += [(v, x, f"variable {v} named {x}") for v in variables for x in VARIABLE_NAMES + tuple(params)]
        out += [(e, x, f"event {e} named {x}") for e in machine["events"] for x in EVENT_NAMES]
    out += [(m, x, f"machine {m} named like the message {x}") for m in machines for x in doc["messages"]]
    return out


def rename(text: str, old: str, new: str) -> str:
    return re.sub(rf"(?<![A-Za-z0-9_]){re.escape(old)}(?![A-Za-z0-9_])", new, text)


def check_machine_collision(seed: int, doc: dict, build_text) -> str:
    """'' when a schema whose machine name meets a generated one is refused on a line with
    that name (and a hint), or builds to machines that compile and run the exchange."""
    choices = machine_renames(doc)
    if not choices:
        return ""
    old, new, what = random.Random(f"machine names {seed}").choice(choices)
    text = rename(yaml.safe_dump(doc, sort_keys=False, allow_unicode=True), old, new)
    lines = [i for i, line in enumerate(text.splitlines(), 1) if re.search(rf"(?<![A-Za-z0-9_]){new}(?![A-Za-z0-9_])", line)]
    where = f"machine names {seed} ({what})"
    with tempfile.TemporaryDirectory(prefix=f"mnames{seed}-") as tmp:
        folder = Path(tmp)
        path = folder / f"fz{seed}.yaml"
        path.write_text(text, encoding="utf-8")
        result, crashed = build_text(text, seed, where)
        if crashed:
            return crashed
        if result.errors:
            if not any(d.loc.line in lines and d.hint.strip() for d in result.errors):
                return f"{where}: refused elsewhere: {str(result.errors[0]).splitlines()[0]}"
            return ""
        from codeword.build import build, compile_schema
        build([path], folder / "out", root=folder)
        try:
            module = _import(folder / "out" / "python" / f"fz{seed}.py")
        except Exception as e:  # noqa: BLE001 - a module that does not import is the finding
            return f"{where}: built; the Python module does not import: {type(e).__name__}: {e}"
        from .check import STRICT
        problem = machine_checks(compile_schema(path), module, folder / "out", folder, STRICT)
        return f"{where}: built; {problem}" if problem else ""


def _import(path: Path):
    from .check import _load  # check imports this module: its loader is taken when first used
    return _load(path)
