"""`codeword diff`: what a schema change does to the wire."""
from .compare import BREAKING, COMPATIBLE, DOCS, Change, Diff, compare

__all__ = ["BREAKING", "COMPATIBLE", "DOCS", "Change", "Diff", "compare"]
