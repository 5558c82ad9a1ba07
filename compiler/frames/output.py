"""Rows written as an aligned table, JSON lines or CSV."""
from __future__ import annotations

import csv
import json
from typing import TextIO

from .rows import Row

FORMATS = ("table", "json", "csv")


def write(rows: list[Row], fmt: str, out: TextIO) -> None:
    if fmt == "json":
        for row in rows:
            out.write(json.dumps(row.as_json(), ensure_ascii=False) + "\n")
    elif fmt == "csv":
        writer = csv.writer(out, lineterminator="\n")
        writer.writerow(["offset", "frame", "message", "field", "value", "error"])
        for row in rows:  # text from the wire is escaped as the table shows it: no control character reaches a terminal
            if row.error is not None:
                writer.writerow([row.offset, _visible(row.frame), "", "", "", _visible(row.error)])
            for name, _, value in row.values:
                shown = json.dumps(value, ensure_ascii=False) if isinstance(value, (list, dict)) else value
                writer.writerow([row.offset, _visible(row.frame), row.message, name,
                                 _visible(shown) if isinstance(shown, str) else shown, ""])
    else:
        out.write(table(rows))


def table(rows: list[Row]) -> str:
    """Offset, frame and message columns aligned; values follow the message."""
    if not rows:
        return ""
    cells = [(str(r.offset), _visible(r.frame), r.message or "error") for r in rows]
    widths = [max(len(c[i]) for c in cells + [("offset", "frame", "message")]) for i in range(3)]
    head = f"{'offset':>{widths[0]}}  {'frame':<{widths[1]}}  message\n"
    lines = [head]
    for (offset, frame, name), row in zip(cells, rows):
        rest = row.error if row.error is not None else " ".join(f"{n}={s}" for n, s, _ in row.values)
        lines.append(f"{offset:>{widths[0]}}  {frame:<{widths[1]}}  {name:<{widths[2]}}  {rest}".rstrip() + "\n")
    return "".join(lines)


def _visible(frame: str) -> str:
    """A text line with its terminator and control characters written as escapes."""
    return frame.encode("unicode_escape").decode("ascii") if not frame.isprintable() else frame
