"""The friction circle (format 1.2 ``model: circle``): a journal that rubs along a line takes
the couple r sin(phi) |F|, phi = atan mu the friction angle, so r mu / sqrt(1 + mu^2) |F|
(statics texts' friction circle; 0.5 % below mu r |F| at mu = 0.1), by every method; the
default ``model: couple`` keeps mu r |F|."""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

import mechreport
from mechreport.errors import SpecError
from mechreport.spec import parse_spec

from test_friction import FLYWHEEL, G  # noqa: E402 - the wheel on a journal, written once

ROOT = Path(__file__).resolve().parents[2]


@pytest.mark.parametrize("mu", [0.1, 0.2, 0.6])
def test_a_journal_on_the_friction_circle_takes_r_mu_over_root_1_plus_mu2_of_its_load(mu):
    text = FLYWHEEL.replace("RPM", "300").replace(
        "A: {mu: 0.05, radius: 0.02}", f"A: {{mu: {mu}, radius: 0.02, model: circle}}")
    a = mechreport.analyse(text)
    assert a.passed
    expected = 0.02 * mu / math.sqrt(1 + mu * mu) * 20 * G
    for name, res in a.forces.items():
        np.testing.assert_allclose(res.driver_torque, expected, rtol=1e-12, err_msg=name)
        if res.reactions:
            np.testing.assert_allclose(res.reactions["A"].friction, -expected, rtol=1e-12)
    couple = mechreport.analyse(text.replace(", model: circle", ", model: couple"))
    for res in couple.forces.values():
        np.testing.assert_allclose(res.driver_torque, mu * 0.02 * 20 * G, rtol=1e-12)


def test_every_method_agrees_on_a_linkage_with_friction_circles():
    plain = (ROOT / "specs" / "offset_slider_crank.yaml").read_text(encoding="utf-8")
    rubbed = plain.replace("\nloads:", "\nfriction:\n  A: {mu: 0.2, radius: 12, model: circle}\n"
                           "  B: {mu: 0.2, radius: 10, model: circle}\nloads:", 1)
    a = mechreport.analyse(rubbed)
    couple = mechreport.analyse(rubbed.replace("model: circle", "model: couple"))
    ref = a.forces["newton_euler"].driver_torque
    scale = np.max(np.abs(ref))
    for name, res in a.forces.items():
        np.testing.assert_allclose(res.driver_torque, ref, rtol=0, atol=1e-9 * scale,
                                   err_msg=name)
    assert a.worst.relative < 1e-9
    # the circle's couples are smaller: less torque lost than with mu r |F|
    assert not np.allclose(ref, couple.forces["newton_euler"].driver_torque)
    friction_circle = a.forces["newton_euler"].reactions["A"].friction
    f = a.forces["newton_euler"].reactions["A"].f
    np.testing.assert_allclose(np.abs(friction_circle), 0.012 * 0.2 / math.sqrt(1.04) * f,
                               rtol=1e-9)


def test_the_friction_model_is_one_of_couple_or_circle():
    text = FLYWHEEL.replace("RPM", "300").replace("radius: 0.02}", "radius: 0.02, model: ring}")
    with pytest.raises(SpecError, match="couple, circle"):
        parse_spec(text, "f.yaml")


def test_the_sheet_works_the_friction_circle_s_couple():
    from mechreport.report.sheet import build_sheet, render_markdown
    text = FLYWHEEL.replace("RPM", "300").replace(
        "A: {mu: 0.05, radius: 0.02}", "A: {mu: 0.2, radius: 0.02, model: circle}")
    md = render_markdown(build_sheet(mechreport.analyse(text)))
    assert r"r\,\sin(\arctan\mu)" in md
    assert "0.196116" in md                   # sin(atan 0.2) = 0.2 / sqrt(1.04)
