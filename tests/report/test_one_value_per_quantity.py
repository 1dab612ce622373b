"""One quantity, one value, in every output (issue 30, items 1 and 2): summary.json's
design.cycle and its quantities agree, round-off is 0 everywhere, and a counterweight that
gains nothing is not recommended."""
from __future__ import annotations

from pathlib import Path

import pytest

import mechreport
from mechreport.report.model import build_model

ROOT = Path(__file__).resolve().parents[2]
SPECS = sorted((ROOT / "specs").glob("*.yaml")) + sorted((ROOT / "tests" / "data").glob("*.yaml"))


@pytest.mark.parametrize("path", SPECS, ids=lambda p: p.stem)
def test_cycle_quantities_have_one_value_in_summary_json(path):
    summary = build_model(mechreport.analyse(path)).summary
    cycle = (summary["design"].get("cycle") or {})
    for name, entry in cycle.items():
        assert summary["quantities"][name]["value"] == entry["value"], name


def test_a_counterweight_that_gains_nothing_is_not_recommended():
    m = build_model(mechreport.analyse(ROOT / "specs" / "r_rtr_rtr.yaml"))
    text = m.design.counterweight
    assert text.startswith("No counterweight is recommended") and "brings" not in text
    assert "e-1" not in text                    # the angle's round-off is 0, not 8e-13
    assert m.summary["design"]["cycle"]["balance.counterweight.angle"]["value"] == 0.0


def test_a_counterweight_that_helps_is_recommended_with_its_gain():
    m = build_model(mechreport.analyse(ROOT / "specs" / "slider_crank.yaml"))
    assert m.design.counterweight.startswith("A point counterweight")
    assert "(-48.6 %)" in m.design.counterweight
