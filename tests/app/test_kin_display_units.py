"""What a person reads is in the spec's display units (issue 30, item 4): `kin` of a spec
written in mm prints mm, as its report does; results.csv stays SI."""
from __future__ import annotations

from pathlib import Path

from mechreport.app.cli import main

ROOT = Path(__file__).resolve().parents[2]


def test_kin_of_a_mm_spec_prints_mm(capsys):
    assert main(["kin", str(ROOT / "specs" / "offset_slider_crank.yaml")]) == 0
    out = capsys.readouterr().out
    assert "x [mm]" in out and "vx [mm/s]" in out and "x [m]" not in out
    row = next(l for l in out.splitlines() if l.startswith("B (crank)"))
    x = float(row.split()[2])
    assert 5 < abs(x) < 30                      # the 25 mm crank pin, in mm (not 0.0125)


def test_kin_of_a_metre_spec_prints_metres(capsys):
    assert main(["kin", str(ROOT / "specs" / "slider_crank.yaml")]) == 0
    assert "x [m]" in capsys.readouterr().out
