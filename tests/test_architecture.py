"""The compiler's structure: no import cycles among its modules (an import made only
for type checkers aside), and a package per target with one entry point."""
from __future__ import annotations

import ast
import importlib
from pathlib import Path

from conftest import ROOT

COMPILER = ROOT / "compiler"


def module_names() -> dict[str, Path]:
    out = {}
    for path in COMPILER.rglob("*.py"):
        parts = list(path.relative_to(COMPILER).with_suffix("").parts)
        if parts[-1] == "__init__":
            parts = parts[:-1]
        out[".".join(parts)] = path
    return out


def runtime_imports(module: str, path: Path, modules: dict[str, Path]) -> set[str]:
    """Modules of the compiler that `module` imports, at module level or in a function,
    leaving out `if TYPE_CHECKING:` blocks."""
    package = module.split(".") if path.name == "__init__.py" else module.split(".")[:-1]
    tree = ast.parse(path.read_text(encoding="utf-8"))
    type_only = {id(n) for block in ast.walk(tree) if isinstance(block, ast.If)
                 and getattr(block.test, "id", None) == "TYPE_CHECKING" for n in ast.walk(block)}
    found = set()
    for node in ast.walk(tree):
        if not isinstance(node, ast.ImportFrom) or not node.level or id(node) in type_only:
            continue
        base = package[:len(package) - node.level + 1] if node.level > 1 else package
        target = ".".join([*base, *([node.module] if node.module else [])])
        for alias in node.names:
            full = f"{target}.{alias.name}" if target else alias.name
            found.add(full if full in modules else target)
    return {m for m in found if m in modules and m != module}


def cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    out: list[list[str]] = []

    def visit(v: str) -> None:
        index[v] = low[v] = len(index)
        stack.append(v)
        for w in graph[v]:
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                component.append(w)
                if w == v:
                    break
            if len(component) > 1:
                out.append(sorted(component))

    for v in graph:
        if v not in index:
            visit(v)
    return out


def test_no_import_cycles_among_compiler_modules():
    modules = module_names()
    graph = {m: runtime_imports(m, p, modules) for m, p in modules.items()}
    assert cycles(graph) == []


def test_the_cycle_finder_finds_a_cycle():
    assert cycles({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) == [["a", "b", "c"]]


def test_each_target_is_a_package_with_a_render_function():
    for target in ("python", "c", "markdown", "promela"):
        package = importlib.import_module(f"codeword.targets.{target}")
        assert Path(package.__file__).name == "__init__.py"
        assert callable(package.render), target


def test_templates_lay_out_and_do_no_arithmetic():
    """Numbers in generated code come from the views: a template expression adds,
    subtracts, multiplies or shifts nothing."""
    import re
    expression = re.compile(r"{{(.*?)}}|{%(.*?)%}", re.S)
    string = re.compile(r"'[^']*'|\"[^\"]*\"")
    arithmetic = re.compile(r"\s[-+*/%]\s|\*\*|<<|>>")
    found = []
    for path in sorted((ROOT / "templates").rglob("*.j2")):
        for m in expression.finditer(path.read_text(encoding="utf-8")):
            code = string.sub("''", m.group(1) or m.group(2))
            if arithmetic.search(code):
                found.append(f"{path.relative_to(ROOT)}: {m.group(0)[:80]}")
    assert found == []


def test_every_package_of_the_compiler_is_installed():
    """pyproject.toml lists the packages a (non-editable) install copies: a package left out
    works in a checkout and is missing from an installed codeword."""
    import tomllib
    listed = set(tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["tool"]["setuptools"]["packages"])
    found = {".".join(("codeword",) + init.parent.relative_to(COMPILER).parts)
             for init in COMPILER.rglob("__init__.py") if "__pycache__" not in init.parts}
    assert found - listed == set()
