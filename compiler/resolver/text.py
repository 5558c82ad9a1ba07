"""Schema prose (a string, or a mapping of language codes with `en`) as a model Text."""
from __future__ import annotations

from typing import Any, Optional

from ..model import Text


def text(value: Any) -> Optional[Text]:
    if value is None:
        return None
    if isinstance(value, str):
        return Text(value)
    return Text(value["en"], tuple(sorted((k, v) for k, v in value.items() if k != "en")))
