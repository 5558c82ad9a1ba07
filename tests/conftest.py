"""Shared fixtures: the committed generated modules and the resolved models."""
from __future__ import annotations

import importlib.util
import os
import sys
import tempfile
from functools import lru_cache
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
SCHEMAS = ROOT / "schemas"
GENERATED = ROOT / "generated" / "python"
DATA = Path(__file__).resolve().parent / "data"
PROTOCOLS = ("route", "car", "tank", "mtv4", "tr24")

sys.path.insert(0, str(ROOT))


def imported_codeword() -> Path:
    """The folder the `codeword` package is imported from."""
    import codeword
    return Path(codeword.__file__).resolve().parent


def pytest_sessionstart(session) -> None:
    """The tests test this checkout: an editable install of another clone (or a released
    codeword) would be tested in its place, and pass or fail for the wrong code."""
    found = imported_codeword()
    if found != ROOT / "compiler":
        raise pytest.UsageError(f"`import codeword` finds {found}, not this checkout's {ROOT / 'compiler'}; "
                                f"run `pip install -e .` in {ROOT} (with the Python that runs the tests)")


def needs(what: str, install: str) -> None:
    """A test whose tool is missing skips on a developer's machine and fails in CI (CI set,
    as .ci/run sets it), where scripts/install-toolchains and scripts/setup install it."""
    if os.environ.get("CI"):
        pytest.fail(f"{what} is missing; {install}")
    pytest.skip(f"{what} is not installed ({install})")

# the build cache (compiler/cache.py) of this run, apart from the user's; builds in subprocesses inherit it
_CACHE = tempfile.TemporaryDirectory(prefix="codeword-test-cache-")
os.environ["CODEWORD_CACHE"] = _CACHE.name


def load_generated(name: str):
    """Import generated/python/<name>.py as a stand-alone module (no `compiler` import)."""
    key = f"generated_{name}"
    if key in sys.modules:
        return sys.modules[key]
    spec = importlib.util.spec_from_file_location(key, GENERATED / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    sys.modules[key] = module
    spec.loader.exec_module(module)
    return module


@lru_cache(maxsize=None)
def load_model(name: str):
    from codeword.build import compile_schema
    return compile_schema(SCHEMAS / f"{name}.yaml")


def simulation(name: str, seed: int, link, **options):
    """The lossy-link simulator over a committed protocol's delivery machines."""
    from codeword.sim import Simulation
    return Simulation(load_model(name), load_generated(name), seed, link, **options)


@pytest.fixture(scope="session")
def route():
    return load_generated("route")


@pytest.fixture(scope="session")
def car():
    return load_generated("car")


@pytest.fixture(scope="session")
def tank():
    return load_generated("tank")


@pytest.fixture(scope="session")
def mtv4():
    return load_generated("mtv4")


@pytest.fixture(scope="session")
def tr24():
    return load_generated("tr24")
