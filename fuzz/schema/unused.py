"""What a generated Python module defines and never uses: private module-level functions
and imported names. Strict type checkers report each (pyright: reportUnusedFunction,
reportUnusedImport), so the generator writes only what the module's code calls."""
from __future__ import annotations

import ast
from collections import Counter


def unused_names(source: str) -> list[str]:
    """The private top-level functions and imported names of `source` that no code reads,
    one line each (`def _x`, `import re`, `from typing import Iterator`)."""
    tree = ast.parse(source)
    reads = Counter(_reads(tree))
    found = []
    for node in tree.body:
        if isinstance(node, ast.FunctionDef) and node.name.startswith("_"):
            if reads[node.name] == sum(1 for _ in _reads(node) if _ == node.name):  # its own calls only
                found.append(f"def {node.name}")
        elif isinstance(node, ast.Import):
            found += [f"import {a.name}" for a in node.names if not reads[(a.asname or a.name).split(".")[0]]]
        elif isinstance(node, ast.ImportFrom) and node.module != "__future__":
            found += [f"from {node.module} import {a.name}" for a in node.names if not reads[a.asname or a.name]]
    return found


def _reads(tree: ast.AST):
    """Every name read under `tree`: a name loaded, or the root of an attribute (`re` in
    `re.compile`)."""
    for node in ast.walk(tree):
        if isinstance(node, ast.Name) and not isinstance(node.ctx, ast.Store):
            yield node.id
