"""The error of a schema shape the C target cannot express."""
from __future__ import annotations


class CTargetError(ValueError):
    """A schema feature the C target cannot express yet; loc is where the schema asks for it."""

    def __init__(self, message: str, loc=None):
        super().__init__(message)
        self.loc = loc
