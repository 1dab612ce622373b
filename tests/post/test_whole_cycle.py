"""Cycle quantities over a whole cycle longer than a turn (format 1.2 ``cycle: 720``): a
mechanism whose loads repeat every turn has the same cycle quantities over its 720-degree
cycle as over one turn (the mean, RMS and cube-mean over two equal turns are those of one;
the energy integral's step is the cycle's over its angles; a bearing's life counts the
cycle's two revolutions), and a one-turn sweep of a 720-degree cycle has none."""
from __future__ import annotations

import pytest

import mechreport
from mechreport.errors import SpecError
from mechreport.spec import parse_spec

ENGINE = """\
mechreport: 1.2
name: slider-crank over a long cycle
cycle: CYCLE
ground: {O: [0, 0]}
units: {length: mm, mass: kg}
links:
  crank: {points: {O: [0, 0], B: [43, 0]}, mass: 3, com: [5, 0], inertia: 0.012}
  rod: {points: {B: [0, 0], C: [145, 0]}, mass: 0.55, com: [40, 0], inertia: 1.7e-3}
  piston: {points: {C: [0, 0]}, mass: 0.45, com: [0, 0], inertia: 0}
joints:
  O: {type: R, links: [ground, crank]}
  B: {type: R, links: [crank, rod]}
  C: {type: R, links: [rod, piston]}
  bore: {type: T, links: [ground, piston], point: C, line: {through: O, direction: 0}}
driver: {joint: O, rpm: 3000}
sweep: {start: 0, stop: STOP, step: 2}
assembly: {C: [188, 0]}
loads:
  - {type: force, link: piston, point: C, direction: [-1, 0], profile: [[0, 0], [90, 800], [180, 0]]}
design:
  speed_fluctuation: 0.02
  bearings: {O: {rating: 20000}}
"""


def _values(cycle: int, profile: str | None = None) -> dict:
    text = ENGINE.replace("CYCLE", str(cycle)).replace("STOP", str(cycle))
    if profile is not None:
        text = text.replace("[[0, 0], [90, 800], [180, 0]]", profile)
    return mechreport.analyse(text).review.values


def test_loads_that_repeat_every_turn_give_the_same_cycle_quantities_over_two_turns():
    one, two = _values(360), _values(720, "[[0, 0], [90, 800], [180, 0], [360, 0], "
                                          "[450, 800], [540, 0]]")
    assert set(one) == set(two)
    for name, value in one.items():
        assert two[name] == pytest.approx(value, rel=1e-9, abs=1e-9), name
    assert two["joint.O.life_h"] > 0 and two["cycle.energy_fluctuation"] > 0


def test_a_load_every_other_turn_is_averaged_over_the_cycle():
    one, two = _values(360), _values(720)        # the same profile, now once in two turns
    assert two["cycle.torque.mean"] == pytest.approx(one["cycle.torque.mean"] / 2, rel=1e-6,
                                                     abs=1e-9)


def test_a_one_turn_sweep_of_a_720_cycle_has_no_cycle_quantities():
    text = ENGINE.replace("CYCLE", "720").replace("STOP", "360")
    with pytest.raises(SpecError) as exc:
        parse_spec(text, "engine.yaml")
    assert "one whole cycle of 720 crank degrees" in str(exc.value)
