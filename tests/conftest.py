"""Shared fixtures: the repository root, the spec files under specs/, loaded mechanisms.

Any test that takes a ``spec_path`` argument runs once per ``specs/*.yaml`` file and per test
mechanism in ``tests/data/*.yaml`` (collected with globs, so new specs are picked up without
touching the tests).
"""
from __future__ import annotations

import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:  # make `mechreport` importable however pytest is started
    sys.path.insert(0, str(ROOT))
if str(ROOT / "tests") not in sys.path:  # tests/helpers.py, shared by tests in every folder
    sys.path.insert(0, str(ROOT / "tests"))

SPEC_DIR = ROOT / "specs"
SPEC_FILES = sorted(SPEC_DIR.glob("*.yaml"))
DATA_SPEC_FILES = sorted((ROOT / "tests" / "data").glob("*.yaml"))


#: shipped specs whose whole-cycle analyses and dynamics are the costliest (720 angles, a
#: mean-speed simulation): the property tests run over every spec parametrise them in the slow
#: tier (``make test`` runs it), so that ``pytest -m "not slow"`` stays under a minute; the
#: tests written for them (tests/validation, the engine and flywheel tests) are not
#: parametrised by name and stay in the fast tier
HEAVY_SPECS = ("single_cylinder_engine", "inline_four_engine", "punching_press", "four_bar_motor")


def pytest_collection_modifyitems(config, items) -> None:
    for item in items:
        callspec = getattr(item, "callspec", None)
        if callspec is not None and any(name in callspec.id.split("-")
                                        for name in HEAVY_SPECS):
            item.add_marker(pytest.mark.slow)


def pytest_generate_tests(metafunc: pytest.Metafunc) -> None:
    if "spec_path" in metafunc.fixturenames:
        paths = SPEC_FILES + DATA_SPEC_FILES
        metafunc.parametrize("spec_path", paths, ids=[p.stem for p in paths])


@pytest.fixture(scope="session")
def repo_root() -> Path:
    """The project root (the folder holding specs/, tests/, mechreport/)."""
    return ROOT


@pytest.fixture(scope="session")
def spec_files() -> list[Path]:
    """Every spec file under specs/, sorted."""
    assert SPEC_FILES, f"no spec files found under {SPEC_DIR}"
    return list(SPEC_FILES)


@pytest.fixture(scope="session")
def mechanisms():
    """Loader cache: ``mechanisms(path)`` returns the built Mechanism of a spec file, loading
    each file once per test session."""
    from mechreport.model import build_mechanism
    from mechreport.spec import load_spec

    cache: dict[Path, object] = {}

    def get(path: Path):
        path = Path(path)
        if path not in cache:
            cache[path] = build_mechanism(load_spec(path))
        return cache[path]

    return get


@pytest.fixture
def mechanism(spec_path: Path, mechanisms):
    """The built Mechanism of the current ``spec_path``."""
    return mechanisms(spec_path)


@pytest.fixture(scope="session")
def textbook_specs() -> dict[str, Path]:
    """The two specs that reproduce the textbook's worked examples (sections 4.6 and 4.7)."""
    return {"4.6": SPEC_DIR / "slider_crank.yaml", "4.7": SPEC_DIR / "r_rtr_rtr.yaml"}
