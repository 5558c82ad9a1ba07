"""The fuzzer's check that a generated module defines nothing it does not use
(fuzz/schema/unused.py): what it reports, what it lets pass, and the committed modules."""
from __future__ import annotations

import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
from fuzz.schema.unused import unused_names  # noqa: E402

SOURCE = '''
import re
import struct
from typing import Any, Iterator, Optional
from binascii import crc_hqx as _crc_hqx


def _used(x: Any) -> Optional[int]:
    return struct.calcsize(x)


def _only_itself(n: int) -> int:
    return _only_itself(n - 1) if n else 0


def _called_by_unused() -> int:
    return 1


def _unused() -> int:
    return _called_by_unused()


def public() -> Optional[int]:
    return _used("<H")
'''


def test_it_names_each_unused_import_and_private_function():
    assert unused_names(SOURCE) == ["import re", "from typing import Iterator",
                                    "from binascii import crc_hqx", "def _only_itself", "def _unused"]


def test_a_name_read_anywhere_is_a_use():
    assert unused_names("import os\nfrom typing import Any\nX: Any = os.sep\n") == []


def test_no_committed_module_defines_what_it_does_not_use():
    modules = sorted((ROOT / "generated").rglob("*.py"))
    assert len(modules) >= 10
    assert {str(p.relative_to(ROOT)): unused_names(p.read_text(encoding="utf-8")) for p in modules
            if unused_names(p.read_text(encoding="utf-8"))} == {}
