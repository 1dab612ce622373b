"""Quantities that are zero by construction are judged as zero, never as a disagreement.

Rebuilt from the descriptions of two published examples that `check` once failed although
both answers were reproduced (issue "trust round three", point 6):

- a balanced rotor: a steel bar turning at constant speed about a pin, no gravity, no load.
  The driver torque is exactly zero; the pin carries the centripetal force m omega^2 L / 2.
- a toggle clamp held at rest by its plunger (a slider driver): the handle's hand force is
  carried by the two-force link to the plunger; the guide's couple on the plunger is zero.

and a third case, a mechanism whose every moment is zero (two blocks joined by a massless rod
on one inclined guide, pushed back along the guide). The methods give 0 and 1e-14 N·m for such a quantity; the
agreement check scales a moment by the analysis's forces times the mechanism's size, so
round-off next to the real loads is round-off (mechreport/checks/agreement.py).
"""
from __future__ import annotations

import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import mechreport

ROTOR = """\
mechreport: 1
name: Spinning steel bar
gravity: [0, 0]
ground: {A: [0, 0]}
links:
  bar:
    points: {A: [0, 0], B: [0.5, 0]}
    density: 7850
    shape: {bar: {length: 0.5, height: 0.04, depth: 0.025}}
joints:
  A: {type: R, links: [ground, bar]}
driver: {joint: A, omega: 44.721359549995796}
sweep: {start: 0, stop: 360, step: 1}
at: [0]
"""

CLAMP = """\
mechreport: 1.1
name: Toggle clamp held by its plunger
units: {length: mm, mass: kg}
gravity: [0, 0]
ground:
  A: [0, 0]
links:
  handle:  {points: {A: [0, 0], B: [100, 0], H: [350, 0]}, mass: 0}
  link:    {points: {B: [0, 0], C: [150, 0]}, mass: 0}
  plunger: {points: {C: [0, 0]}, mass: 0}
joints:
  A: {type: R, links: [ground, handle]}
  B: {type: R, links: [handle, link]}
  C: {type: R, links: [link, plunger]}
  D_T: {type: T, links: [ground, plunger], point: C, line: {through: A, direction: 15}}
driver: {joint: D_T, speed: 0}
sweep: {start: 100, stop: 240, step: 5}
at: [200]
assembly: {B: [50, 90]}
loads:
  - {type: force, link: handle, point: H, value: [0, -100], name: hand}
"""

TRAIN = """\
mechreport: 1.1
name: Two blocks joined by a rod along an inclined guide
gravity: [0, 0]
ground: {O: [0, 0]}
links:
  lead:
    points: {P: [0, 0]}
    mass: 2
    shape: {block: {width: 0.1, height: 0.05, depth: 0.05}}
  rod: {points: {P: [0, 0], Q: [0.2, 0]}, mass: 0}
  trail:
    points: {Q: [0, 0]}
    mass: 3
    shape: {block: {width: 0.1, height: 0.05, depth: 0.05}}
joints:
  P_T: {type: T, links: [ground, lead], point: P, line: {through: O, direction: 30}}
  P: {type: R, links: [lead, rod]}
  Q: {type: R, links: [rod, trail]}
  Q_T: {type: T, links: [ground, trail], point: Q, line: {through: O, direction: 30}}
driver: {joint: P_T, speed: 0.5, accel: 3}
sweep: {start: 0, stop: 0.3, step: 0.01}
at: [0.1]
assembly: {Q: [0.3, 0.17]}
loads:
  - {type: force, link: trail, point: Q, value: [-86.60254037844386, -50], name: push back}
"""


def _analysed(tmp_path: Path, text: str, name: str):
    path = tmp_path / f"{name}.yaml"
    path.write_text(text)
    return path, mechreport.analyse(path)


def test_balanced_rotor_zero_driver_torque_is_not_a_disagreement(tmp_path):
    path, a = _analysed(tmp_path, ROTOR, "rotor")
    m = 7850 * 0.5 * 0.04 * 0.025                 # 3.925 kg
    for name, res in a.forces.items():
        values = res.values()
        if "joint.A.fx" in values:                 # the pin carries m omega^2 L / 2
            f = np.hypot(values["joint.A.fx"], values["joint.A.fy"])
            np.testing.assert_allclose(f, m * 2000.0 * 0.25, rtol=1e-12)
            assert f[0] == pytest.approx(1962.5, rel=1e-12)
        assert np.max(np.abs(values["driver.torque"])) < 1e-9, name
    assert a.passed, [(g.quantity, g.relative) for g in a.agreement[:3]]
    assert a.agreement[0].relative < 1e-9


def _clamp_force(stroke_mm: float) -> float:
    """The guide's push on the plunger along its line [N], by statics of the two-force link
    (independent of mechreport): moments about A on the handle, then the plunger."""
    d = np.array([math.cos(math.radians(15)), math.sin(math.radians(15))])
    C = stroke_mm * d
    # B on the circles |B| = 100 and |B - C| = 150, on the side of the assembly hint (+y)
    L = np.linalg.norm(C)
    along = (100**2 - 150**2 + L**2) / (2 * L)
    h = math.sqrt(100**2 - along**2)
    u = C / L
    n = np.array([-u[1], u[0]])
    B = along * u + h * n
    if B @ np.array([50.0, 90.0]) < 0:          # pragma: no cover - the hint's branch
        B = along * u - h * n
    H = 3.5 * B
    e = (B - C) / np.linalg.norm(B - C)          # the link's force on the handle: t e, at B
    hand = np.array([0.0, -100.0])
    t = -(H[0] * hand[1] - H[1] * hand[0]) / (B[0] * e[1] - B[1] * e[0])
    return float(t * (e @ d))                   # the link pushes the plunger with -t e


def test_toggle_clamp_at_rest_zero_guide_couple_is_not_a_disagreement(tmp_path):
    path, a = _analysed(tmp_path, CLAMP, "clamp")
    strokes = a.angles
    want = np.array([_clamp_force(s * 1000) for s in strokes]) \
        if strokes.max() < 1 else np.array([_clamp_force(s) for s in strokes])
    for name, res in a.forces.items():
        values = res.values()
        np.testing.assert_allclose(values["driver.force"], want, rtol=1e-9, err_msg=name)
        if "joint.D_T.moment" in values:
            assert np.max(np.abs(values["joint.D_T.moment"])) < 1e-9
    assert a.passed, [(g.quantity, g.relative) for g in a.agreement[:3]]
    run = subprocess.run([sys.executable, "-m", "mechreport", "check", str(path)],
                         capture_output=True, text=True)
    assert run.returncode == 0, run.stdout + run.stderr
    assert run.stdout.startswith("PASS")


def test_mechanism_whose_every_moment_is_zero_passes(tmp_path):
    path, a = _analysed(tmp_path, TRAIN, "train")
    for res in a.forces.values():
        for q, v in res.values().items():
            if q.endswith("moment"):
                assert np.max(np.abs(v)) < 1e-9
    assert a.passed, [(g.quantity, g.relative) for g in a.agreement[:3]]


def test_a_real_disagreement_in_a_small_moment_still_fails():
    """The floor is a thousandth of the load scale: a moment that is a real part of the
    loads (here 1 % of the force times the size) and differs by 1 % between two methods is
    still a disagreement."""
    from mechreport.checks.agreement import Spread, finish

    parts = {"joint.A.fx": Spread(0.0, ("a", "b"), 0.0, 1000.0, 2),
             "driver.torque": Spread(0.1, ("a", "b"), 10.0, 5.0, 2)}
    worst = finish(parts, size=0.5)[0]
    assert worst.quantity == "driver.torque"
    assert worst.relative == pytest.approx(0.1 / 5.0)
    tiny = {**parts, "driver.torque": Spread(1e-13, ("a", "b"), 10.0, 1e-13, 2)}
    assert finish(tiny, size=0.5)[0].relative < 1e-12


def test_a_real_torque_lost_in_huge_inertia_forces_is_still_a_disagreement():
    """The other side of the load scale: a 1e20 kg crank under 1e-20 gravity turns a piston
    whose load needs about 13 N·m; the crank's 1e19 N inertia forces swamp that torque in
    rounding (the methods give 5 to 95 N·m). The piston's load requires a resolvable share
    of the torque, so the torque is no round-off: the check fails, in memory and streamed."""
    from mechreport.forces.power import resolvable_effort
    from mechreport.pipeline.streamed import check_sweep
    from mechreport.spec import parse_spec
    root = Path(__file__).resolve().parents[2]
    text = (root / "specs" / "offset_slider_crank.yaml").read_text(encoding="utf-8")
    text = text[:text.index("study:")]
    heavy = text.replace("    mass: 600                     # g, web and counterweight",
                         "    mass: 1e20").replace("gravity: [0, -9.81]", "gravity: [0, -1e-20]")
    assert heavy.count("1e20") == 1 and "-1e-20" in heavy
    a = mechreport.analyse(heavy)
    assert not a.passed and a.worst.quantity == "driver.torque"
    assert not check_sweep(parse_spec(heavy, "heavy.yaml"), chunk=100).passed
    assert resolvable_effort(a._context) > 1.0


def test_a_balanced_rotor_has_no_resolvable_effort(tmp_path):
    from mechreport.forces.power import resolvable_effort
    _, a = _analysed(tmp_path, ROTOR, "rotor")
    assert resolvable_effort(a._context) == 0.0
