"""Sections at the ends of the accepted range: a thin wall on a huge tube once cancelled
to a zero second moment of area and ended `check` in a ZeroDivisionError (issue "trust
round three", point 8). The tube's area and inertia are computed in factored form."""
from __future__ import annotations

import math
from pathlib import Path

import pytest

import mechreport
from mechreport.spec import parse_spec

ROOT = Path(__file__).resolve().parents[2]
STRENGTH = (ROOT / "specs" / "crank_press_strength.yaml").read_text()


@pytest.mark.parametrize("d, t", [(1e15, 1e-5), (60, 4), (1e-3, 4e-4)])
def test_a_tube_section_keeps_its_area_and_inertia_however_thin_its_wall(d, t):
    text = STRENGTH.replace("section: {rect: {width: 12, height: 20}}",
                            f"section: {{tube: {{d: {d}, t: {t}}}}}")
    spec = parse_spec(text, "tube.yaml")
    sec = spec.link("rod").strength.section
    D, T = d * 1e-3, t * 1e-3                          # mm -> m
    area = math.pi * T * (D - T)
    assert sec.area == pytest.approx(area, rel=1e-12) and sec.area > 0
    mean_r2 = (D**2 + (D - 2 * T)**2) / 16           # I = A (d^2 + di^2) / 16
    assert sec.inertia == pytest.approx(area * mean_r2, rel=1e-12) and sec.inertia > 0
    if d == 60:                                      # the textbook form, where it is exact
        assert sec.inertia == pytest.approx(math.pi * (D**4 - (D - 2 * T)**4) / 64, rel=1e-12)
    a = mechreport.analyse(spec)                     # no ZeroDivisionError in the review
    assert a.strength is not None
