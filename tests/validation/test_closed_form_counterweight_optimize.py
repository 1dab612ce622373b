"""The design review's own best counterweight (a closed form: the point mass x radius and
angle on the crank minimising the RMS inertial shaking force, docs/spec.md) reproduced by
``mechreport optimize`` moving the crank's centre of mass: m (com - com0) is the
counterweight's m r at its angle."""
from __future__ import annotations

import math

import mechreport
from mechreport.study.optimize import optimize

from optimize_specs import four_bar

MASS = 0.4          # kg, the crank's (400 g)
CRANK = """    points: {A: [0, 0], B: [50, 0]}
    mass: 400
    com: [25, 0]
    inertia: 2.0e-4"""


def test_counterweight_closed_form_by_optimisation():
    text = four_bar(step=8).replace("""    points: {A: [0, 0], B: [50, 0]}
    density: 7850                 # kg/m^3 (always SI)
    shape: {bar: {length: 50, height: 20, depth: 10}}""", CRANK)
    review = mechreport.analyse(text).review.values
    mr, angle = review["balance.counterweight.mr"], review["balance.counterweight.angle"]
    spec = text + """
optimize:
  vary:
    - {key: links.crank.com.0, from: -40, to: 40}
    - {key: links.crank.com.1, from: -20, to: 20}
  minimize: cycle.inertia_shaking.force_rms
  budget: 300
  seed: 1
"""
    r = optimize(spec)
    assert r.feasible and r.polished
    dx = (r.values["links.crank.com.0"] - 25) / 1000        # m
    dy = r.values["links.crank.com.1"] / 1000
    assert math.isclose(MASS * math.hypot(dx, dy), mr, rel_tol=1e-4)
    assert math.isclose(math.degrees(math.atan2(dy, dx)), angle, rel_tol=1e-4)
    assert math.isclose(r.objective, review["balance.inertia_shaking.force_rms"], rel_tol=1e-6)
