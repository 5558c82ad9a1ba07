"""`codeword diff` output: plain text for a terminal, Markdown for a changelog."""
from __future__ import annotations

from .compare import BREAKING, COMPATIBLE, DOCS, Change, Diff

BIT_NOTE = "(bit positions count from the first bit of the frame, 0 = the most significant bit sent first)"
HEADINGS = {BREAKING: "Wire-breaking", COMPATIBLE: "Compatible", DOCS: "Docs only"}


def _line(c: Change, code: str = "") -> str:
    subject = f"{code}{c.subject}{code}"
    where = f" in {', '.join(c.messages)}" if c.messages else ""
    return f"{subject}{where}: {c.what}"


def _version(p) -> str:
    return f"{p.name} {p.version}" if p.version else p.name


def fingerprint_line(d: Diff) -> str:
    if d.old_fingerprint == d.new_fingerprint:
        return f"fingerprint {d.old_fingerprint} (unchanged: same wire format)"
    return f"fingerprint {d.old_fingerprint} → {d.new_fingerprint} (changed)"


def as_text(d: Diff, old_name: str, new_name: str) -> str:
    lines = [f"{_version(d.old)} ({old_name}) → {_version(d.new)} ({new_name})", fingerprint_line(d)]
    if not d.changes:
        lines.append("no changes")
    for kind in (BREAKING, COMPATIBLE, DOCS):
        changes = d.of_kind(kind)
        if changes:
            lines.append(f"{HEADINGS[kind].lower()} ({len(changes)}):")
            lines.extend(f"  {_line(c)}" for c in changes)
    lines.append("result: WIRE-BREAKING" if d.breaking else "result: wire-compatible")
    if any("bit" in c.what for c in d.changes):
        lines.append(BIT_NOTE)
    return "\n".join(lines) + "\n"


def as_markdown(d: Diff, old_name: str, new_name: str) -> str:
    title = f"{d.new.name} {d.new.version}" if d.new.version else d.new.name
    since = f"{d.old.version}" if d.old.version else f"`{old_name}`"
    verdict = "**Breaks the wire format.**" if d.breaking else "Wire-compatible."
    fp = (f"Fingerprint `{d.old_fingerprint}` → `{d.new_fingerprint}`."
          if d.old_fingerprint != d.new_fingerprint else f"Fingerprint `{d.new_fingerprint}` (unchanged).")
    out = [f"## {title}", "", f"Changes since {since}. {verdict} {fp}", ""]
    if not d.changes:
        out += ["No changes.", ""]
    for kind in (BREAKING, COMPATIBLE, DOCS):
        changes = d.of_kind(kind)
        if changes:
            out += [f"### {HEADINGS[kind]}", ""]
            out += [f"- {_line(c, '`')}" for c in changes]
            out.append("")
    if any("bit" in c.what for c in d.changes):
        out += [BIT_NOTE, ""]
    return "\n".join(out)
