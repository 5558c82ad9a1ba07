"""Rows written as an aligned table, JSON lines or CSV."""
from __future__ import annotations

import csv
import json
from typing import TextIO

from .rows import Row

FORMATS = ("table", "json", "csv")


def _place(rows: list[Row]) -> tuple[str, list]:
    """The first column: each frame's offset in the stream, or, for frames read with
    their own times (a CAN log), those times."""
    if rows and all(r.offset is None and r.time is not None for r in rows):
        return "time", [r.time for r in rows]
    return "offset", [r.offset for r in rows]


def write(rows: list[Row], fmt: str, out: TextIO) -> None:
    if fmt == "json":
        for row in rows:
            out.write(json.dumps(row.as_json(), ensure_ascii=False) + "\n")
    elif fmt == "csv":
        writer = csv.writer(out, lineterminator="\n")
        label, places = _place(rows)
        writer.writerow([label, "frame", "message", "field", "value", "error"])
        for row, place in zip(rows, places):  # text from the wire is escaped as the table shows it: no control character reaches a terminal
            if row.error is not None:
                writer.writerow([place, _visible(row.frame), "", "", "", _visible(row.error)])
            for name, _, value in row.values:
                shown = json.dumps(value, ensure_ascii=False) if isinstance(value, (list, dict)) else value
                writer.writerow([place, _visible(row.frame), row.message, name,
                                 _visible(shown) if isinstance(shown, str) else shown, ""])
    else:
        out.write(table(rows))


def table(rows: list[Row]) -> str:
    """Offset (or time), frame and message columns aligned; values follow the message."""
    if not rows:
        return ""
    label, places = _place(rows)
    cells = [(str(place), _visible(r.frame), r.message or "error") for r, place in zip(rows, places)]
    widths = [max(len(c[i]) for c in cells + [(label, "frame", "message")]) for i in range(3)]
    head = f"{label:>{widths[0]}}  {'frame':<{widths[1]}}  message\n"
    lines = [head]
    for (offset, frame, name), row in zip(cells, rows):
        rest = row.error if row.error is not None else " ".join(f"{n}={s}" for n, s, _ in row.values)
        lines.append(f"{offset:>{widths[0]}}  {frame:<{widths[1]}}  {name:<{widths[2]}}  {rest}".rstrip() + "\n")
    return "".join(lines)


def _visible(frame: str) -> str:
    """A text line with its terminator and control characters written as escapes."""
    return frame.encode("unicode_escape").decode("ascii") if not frame.isprintable() else frame
