"""Massless links and point masses (format 1.1): `mass: 0` alone is a massless link, a
two-force member when it carries no load; `inertia: 0` with a mass is a point mass."""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import mechreport
from mechreport.errors import SpecError
from mechreport.spec import parse_spec

ROOT = Path(__file__).resolve().parents[2]
TEXT = (ROOT / "specs" / "slider_crank.yaml").read_text(encoding="utf-8")
TEXT = TEXT[:TEXT.index("expect:")]
ROD = """  rod:
    points: {B: [0, 0], C: [1, 0]}
    mass: 1
    shape: {bar: {length: 1, height: 0.01, depth: 0.001}}"""


def _rod(body: str) -> str:
    assert ROD in TEXT
    return TEXT.replace(ROD, "  rod:\n    points: {B: [0, 0], C: [1, 0]}\n" + body)


def test_a_massless_rod_is_a_two_force_member_by_every_method():
    a = mechreport.analyse(_rod("    mass: 0"))
    assert a.passed
    theta = np.radians(a.kinematics.angle_deg("rod"))
    u = np.stack([np.cos(theta), np.sin(theta)], axis=1)          # the rod's line
    for name, res in a.forces.items():
        if not res.reactions:
            continue
        b, c = res.reactions["B"], res.reactions["C"]
        scale = np.max(np.abs([b.fx, b.fy]))
        across = b.fx * u[:, 1] - b.fy * u[:, 0]                 # force across the rod
        np.testing.assert_allclose(across, 0, atol=1e-9 * scale, err_msg=name)
        np.testing.assert_allclose([b.fx, b.fy], [c.fx, c.fy], atol=1e-9 * scale,
                                   err_msg=name)                 # the same force at both ends


@pytest.mark.parametrize("body, path, words", [
    ("    mass: 0\n    com: [0.5, 0]", "links.rod.mass", "massless: it has no com"),
    ("    mass: 0\n    shape: {bar: {length: 1, height: 0.01, depth: 0.001}}",
     "links.rod.mass", "no shape"),
    ("    com: [0.5, 0]\n    inertia: 0", "links.rod.inertia", "needs the link's 'mass'"),
    ("    mass: -1", "links.rod.mass", "positive"),
])
def test_what_a_massless_link_or_point_mass_may_not_have(body, path, words):
    with pytest.raises(SpecError) as info:
        parse_spec(_rod(body), "x.yaml")
    assert any(p.path == path and words in p.message for p in info.value.problems), \
        info.value.problems


def test_a_point_mass_has_no_rotary_inertia():
    spec = parse_spec(_rod("    mass: 1\n    com: [0.5, 0]\n    inertia: 0"), "x.yaml")
    assert spec.link("rod").inertia == 0.0 and spec.link("rod").mass == 1.0
    assert mechreport.analyse(spec).passed
