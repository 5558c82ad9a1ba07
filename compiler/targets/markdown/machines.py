"""State machines and rules in words: Mermaid stateDiagram-v2 source, the
transition table, and the conditions of message, sequence and guard rules."""
from __future__ import annotations

from typing import Any

from ...model import Condition, Machine, Protocol, Sequence, SequenceItem
from .text import DecisionLinker, anchor, cell, code, en, number, originals
from ..escape import mermaid_text


def _value(value: Any) -> str:
    if value is None:
        return "absent"
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        return value
    return number(value)


def condition(c: Condition) -> str:
    """`seq = expected`, `h2_time absent`, `retries < retry_limit` …"""
    op, path, value = c.op, c.path, c.value
    if op == "eq":
        return f"{path} absent" if value is None else f"{path} = {_value(value)}"
    if op == "ne":
        return f"{path} present" if value is None else f"{path} ≠ {_value(value)}"
    if op == "in":
        return f"{path} ∈ {{{', '.join(_value(v) for v in value)}}}"
    if op == "range":
        return f"{path} in {_value(value[0])} … {_value(value[1])}"
    symbols = {"eq_var": "=", "ne_var": "≠", "eq_param": "=", "ne_param": "≠", "lt_param": "<",
               "le_param": "≤", "gt_param": ">", "ge_param": "≥", "lt_var": "<", "gt_var": ">"}
    if op in symbols:
        kind = "variable" if op.endswith("_var") else "parameter"
        return f"{path} {symbols[op]} {kind} {value}"
    return f"{path} {op} {_value(value)}"


def conditions(cs: tuple[Condition, ...]) -> str:
    return " and ".join(condition(c) for c in cs)


def _mermaid_id(name: str) -> str:
    return "".join(ch if ch.isalnum() or ch == "_" else "_" for ch in name)


def machine_view(p: Protocol, m: Machine, linker: DecisionLinker) -> dict:
    """Diagram edges carry the event and a row number; the table spells out guard and actions."""
    rows, edges = [], []
    for state in m.states:
        for handler in state.handlers:
            if handler.kind != "transitions":
                rows.append({"n": "", "state": state.name, "event": handler.event, "guard": "",
                             "to": "—", "actions": "ignored" if handler.kind == "ignore" else "error"})
                continue
            for t in handler.transitions:
                n = len([r for r in rows if r["n"]]) + 1
                guard = conditions(t.guard) if t.guard else ("otherwise" if len(handler.transitions) > 1 else "")
                rows.append({"n": str(n), "state": state.name, "event": handler.event, "guard": cell(guard),
                             "to": t.to, "actions": ", ".join(t.actions) or "—"})
                label = f"{handler.event} ({n})"
                edges.append((_mermaid_id(state.name), _mermaid_id(t.to), label))
    lines = ["stateDiagram-v2", f"    [*] --> {_mermaid_id(m.initial)}"]
    for state in m.states:
        if state.doc:
            lines.append(f"    {_mermaid_id(state.name)}: {state.name} — {mermaid_text(en(state.doc))}")
    for a, b, label in edges:
        lines.append(f"    {a} --> {b}: {label}")
    for final in m.final:
        lines.append(f"    {_mermaid_id(final)} --> [*]")
    events = [{"name": e.name, "doc": cell(en(e.doc)) if e.doc else
               (f"a received [{e.message}](#{anchor('msg', e.message)})" if e.message else ""),
               "timer": e.timer} for e in m.events]
    return {
        "name": m.name, "anchor": anchor("machine", m.name), "role": m.role,
        "doc": linker.link(cell(en(m.doc))), "originals": [(l, cell(t)) for l, t in originals(m.doc)],
        "mermaid": "\n".join(lines), "rows": rows, "initial": m.initial, "final": list(m.final),
        "states": [{"name": s.name, "doc": cell(en(s.doc))} for s in m.states],
        "variables": [{"name": v.name, "bits": v.bits, "initial": v.initial} for v in m.variables],
        "parameters": list(m.parameters), "events": events,
    }


def _grammar(items: tuple[SequenceItem, ...], indent: str = "") -> list[dict]:
    out = []
    for item in items:
        if item.count:
            times = f"exactly `{item.count}` times"
        elif item.repeat:
            times = "zero or more times"
        else:
            times = "once"
        target = f"[{item.message}](#{anchor('msg', item.message)})" if item.message else "a group:"
        out.append({"name": indent + code(item.name), "what": target, "times": times,
                    "doc": cell(en(item.doc)) if item.doc else ""})
        if item.items:
            out.extend(_grammar(item.items, indent + "&nbsp;&nbsp;&nbsp;&nbsp;"))
    return out


def sequence_rule_text(rule) -> str:
    path = code(rule.path)
    if rule.kind == "consecutive":
        return f"{path} counts {rule.start}, {rule.start + 1}, {rule.start + 2}, … in order"
    if rule.kind == "equal":
        return f"every {path} equals {code(rule.to)} of its group"
    if rule.kind == "member":
        return f"{path} occurs among {code(rule.of)}"
    if rule.kind == "unique":
        return f"no two {path} share ({', '.join(rule.key)})"
    return f"{path}: {rule.kind}"


def sequence_view(s: Sequence, linker: DecisionLinker) -> dict:
    return {"name": s.name, "anchor": anchor("seq", s.name), "doc": linker.link(cell(en(s.doc))),
            "originals": [(l, cell(t)) for l, t in originals(s.doc)], "grammar": _grammar(s.items),
            "rules": [{"id": linker.ref(r.id), "text": sequence_rule_text(r),
                       "message": cell(en(r.message)) if r.message else ""} for r in s.rules]}
