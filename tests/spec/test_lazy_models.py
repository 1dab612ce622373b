"""The format's models (pydantic) are built only when a spec is loaded or the schema is asked
for: ``mechreport --version`` and a program that only imports the records do not pay for
them (issue 42, item 7). Checked by the modules a fresh interpreter has loaded, not by time."""
from __future__ import annotations

import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
HEAVY = ("pydantic", "mechreport.spec.schema", "mechreport.spec.loader")


def _loaded_after(code: str) -> list[str]:
    """The heavy modules loaded after running ``code`` in a fresh interpreter."""
    probe = (code + "\nimport sys\n"
             f"print(' '.join(m for m in {HEAVY!r} if m in sys.modules), file=sys.stderr)")
    out = subprocess.run([sys.executable, "-c", probe], cwd=ROOT, capture_output=True,
                         text=True, check=True, env={"PYTHONPATH": str(ROOT), "PATH": ""})
    return out.stderr.split()


def test_importing_the_records_builds_no_model():
    assert _loaded_after("import mechreport.spec; from mechreport.spec import Spec") == []


def test_the_version_builds_no_model():
    code = ("import runpy, sys\nsys.argv = ['mechreport', '--version']\n"
            "try:\n    runpy.run_module('mechreport', run_name='__main__')\n"
            "except SystemExit:\n    pass")
    assert _loaded_after(code) == []


def test_loading_a_spec_builds_them():
    code = "from mechreport.spec import load_spec\nload_spec('specs/four_bar.yaml')"
    assert _loaded_after(code) == list(HEAVY)
