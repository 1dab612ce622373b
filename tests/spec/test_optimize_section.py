"""The ``optimize:`` section (format 1.2): what it loads to, and how a mistake is told."""
from __future__ import annotations

import pytest

from mechreport.errors import SpecError
from mechreport.spec import parse_spec

from optimize_specs import four_bar

SECTION = """
optimize:
  vary:
    - {key: links.coupler.points.C.0, from: 150, to: 220}
    - {key: driver.rpm, from: 200, to: 400}
  minimize: cycle.torque.rms
  subject_to:
    - {quantity: cycle.transmission_angle.min, min: 0.7, unit: rad}
    - {quantity: joint.B.f_max, max: 500}
  budget: 300
  seed: 7
"""


def test_the_section_loads_with_its_bounds_in_si():
    opt = parse_spec(four_bar() + SECTION, "f.yaml").optimize
    assert [v.key for v in opt.vary] == ["links.coupler.points.C.0", "driver.rpm"]
    assert opt.vary[0].path == ("links", "coupler", "points", "C", 0)
    assert (opt.vary[1].start, opt.vary[1].stop) == (200.0, 400.0)   # as written
    assert opt.objective == "cycle.torque.rms" and not opt.maximize
    low = opt.bounds[0].low
    assert low == pytest.approx(0.7 * 57.29577951308232) and opt.bounds[0].unit == "rad"
    assert opt.bounds[1].high == 500.0 and opt.bounds[1].low is None
    assert (opt.budget, opt.seed) == (300, 7)


def test_defaults_and_maximize():
    text = four_bar() + """
optimize:
  vary: [{key: links.rocker.points.C.0, from: 100, to: 140}]
  maximize: cycle.transmission_angle.min
"""
    opt = parse_spec(text, "f.yaml").optimize
    assert opt.maximize and opt.objective == "cycle.transmission_angle.min"
    assert (opt.budget, opt.seed, opt.bounds) == (1000, 0, ())


@pytest.mark.parametrize("old, new, message", [
    ("  minimize: cycle.torque.rms\n", "  minimize: cycle.torque.rms\n  maximize: cycle.torque.max\n",
     "optimize: needs exactly one of 'minimize' and 'maximize'"),
    ("points.C.0, from: 150", "points.Q.0, from: 150",
     "optimize.vary[0].key: 'links.coupler.points.Q.0': links.coupler.points has no key 'Q'"),
    ("{key: driver.rpm, from: 200, to: 400}", "{key: links.coupler.points.C.0, from: 1, to: 2}",
     "is varied by optimize.vary[0] too"),
    ("joint.B.f_max, max: 500", "joint.Z.f_max, max: 500",
     "optimize.subject_to[1].quantity: 'joint.Z.f_max': no joint named 'Z'"),
    ("joint.B.f_max, max: 500", "joint.B.f_max", "optimize.subject_to[1]: needs 'min', 'max'"),
    ("unit: rad", "unit: N", "optimize.subject_to[0].unit: must be a unit of "
                             "cycle.transmission_angle.min (deg)"),
    ("budget: 300", "budget: 5", "optimize.budget: must be a whole number from 10"),
    ("from: 200, to: 400", "from: 200, to: 200", "equals 'from'"),
    ("{key: driver.rpm,", "{key: report.units.length,", "a study varies the mechanism"),
    ("{key: driver.rpm, from: 200, to: 400}",
     "{key: design.limits.transmission_angle, from: 20, to: 40}",
     "an optimisation varies the mechanism, not the limits it is judged by"),
    # a coarser or shorter sweep would pass by not looking at the worst angles
    ("{key: driver.rpm, from: 200, to: 400}", "{key: sweep.step, from: 1, to: 30}",
     "not the angles it is judged at"),
    ("{key: driver.rpm, from: 200, to: 400}", "{key: sweep.stop, from: 90, to: 360}",
     "not the angles it is judged at"),
])
def test_mistakes_are_told_with_their_key_path(old, new, message):
    text = four_bar(design=True) + SECTION
    assert old in text
    with pytest.raises(SpecError) as err:
        parse_spec(text.replace(old, new), "f.yaml")
    assert message in str(err.value)
