"""The generated Python codecs, imported from generated/python in pure Python (the
compiled accelerators `codeword accelerate` builds are measured apart, by
bench/accelerated.py)."""

import os
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "generated" / "python"))

os.environ["CODEWORD_PURE_PYTHON"] = "1"
import car  # noqa: E402
import mtv4  # noqa: E402
import route  # noqa: E402
import tank  # noqa: E402
import tr24  # noqa: E402
del os.environ["CODEWORD_PURE_PYTHON"]

__all__ = ["ROOT", "car", "mtv4", "route", "tank", "tr24"]
