"""The format's models (pydantic) are built only when a spec is loaded or the schema is asked
for: ``mechreport --version`` and a program that only imports the records do not pay for
them (issue 42, item 7). Checked by the modules a fresh interpreter has loaded, not by time."""
from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
HEAVY = ("pydantic", "mechreport.spec.schema", "mechreport.spec.loader")


def _loaded_after(code: str, heavy: tuple[str, ...] = HEAVY) -> list[str]:
    """The ``heavy`` modules loaded after running ``code`` in a fresh interpreter."""
    probe = (code + "\nimport sys\n"
             f"print(' '.join(m for m in {heavy!r} if m in sys.modules), file=sys.stderr)")
    out = subprocess.run([sys.executable, "-c", probe], cwd=ROOT, capture_output=True,
                         text=True, check=True, env={"PYTHONPATH": str(ROOT), "PATH": ""})
    return out.stderr.split()


def test_importing_the_records_builds_no_model():
    assert _loaded_after("import mechreport.spec; from mechreport.spec import Spec") == []


def _command(*argv: str) -> str:
    """Code running ``mechreport ARGV`` as the console script does."""
    return (f"import runpy, sys\nsys.argv = ['mechreport', *{argv!r}]\n"
            "try:\n    runpy.run_module('mechreport', run_name='__main__')\n"
            "except SystemExit:\n    pass")


def test_the_version_builds_no_model():
    assert _loaded_after(_command("--version")) == []


@pytest.mark.parametrize("argv", [("--version",), ("--help",), ("tolerance", "--help"),
                                  ("study", "--help"), ("optimize", "--help"),
                                  ("build", "--help")])
def test_the_command_line_help_loads_no_solver(argv):
    """The parsers offer the force methods' names without importing the methods (numpy)."""
    assert _loaded_after(_command(*argv), ("numpy", "mechreport.forces")) == []


def test_loading_a_spec_builds_them():
    code = "from mechreport.spec import load_spec\nload_spec('specs/four_bar.yaml')"
    assert _loaded_after(code) == list(HEAVY)
