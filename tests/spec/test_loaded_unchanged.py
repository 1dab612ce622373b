"""Every shipped spec loads to the same frozen dataclasses, bit for bit, as it did before the
format was declared once (issue 42): ``data/loaded_reprs.json`` holds ``repr(load_spec(path))``
of every spec under specs/ and tests/data/, made by the loader of revision cd65f79. A float's
repr is the shortest text that reads back to the same bits, so equal reprs mean equal specs.

To remake the reference (only when a change of the loaded values is intended), run from the
repository root::

    python -c "import json; from pathlib import Path; from mechreport.spec import load_spec; \
print(json.dumps({str(p): repr(load_spec(p)) for p in sorted([*Path('specs').rglob('*.yaml'), \
*Path('tests/data').rglob('*.yaml')])}, indent=0, sort_keys=True))" \
> tests/spec/data/loaded_reprs.json
"""
from __future__ import annotations

import json
from pathlib import Path

import pytest

from mechreport.spec import load_spec

ROOT = Path(__file__).resolve().parents[2]
REFERENCE = json.loads((Path(__file__).parent / "data" / "loaded_reprs.json")
                       .read_text(encoding="utf-8"))
SHIPPED = sorted(str(p.relative_to(ROOT)) for p in
                 [*(ROOT / "specs").rglob("*.yaml"), *(ROOT / "tests" / "data").rglob("*.yaml")])


def test_the_reference_covers_every_shipped_spec():
    assert sorted(REFERENCE) == SHIPPED


@pytest.mark.parametrize("path", SHIPPED)
def test_a_shipped_spec_loads_as_before(path, monkeypatch):
    monkeypatch.chdir(ROOT)               # the reference names files relative to the root
    assert repr(load_spec(path)) == REFERENCE[path]
