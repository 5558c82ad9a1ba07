"""The generated Python codecs, imported from generated/python."""

import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "generated" / "python"))

import car  # noqa: E402
import mtv4  # noqa: E402
import route  # noqa: E402
import tank  # noqa: E402
import tr24  # noqa: E402

__all__ = ["ROOT", "car", "mtv4", "route", "tank", "tr24"]
