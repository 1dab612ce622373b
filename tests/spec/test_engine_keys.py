"""Format 1.2 engine keys in the loader: ``cycle`` (the loads' period, a whole multiple of
360 crank degrees) and the sweep it implies; every refusal names the file, line and key."""
from __future__ import annotations

import pytest

from mechreport.errors import SpecError
from mechreport.spec import parse_spec

FILE = "specs/engine.yaml"

BASE = """\
mechreport: 1.2
name: single cylinder
cycle: 720
ground: {A: [0, 0]}
links:
  crank: {points: {A: [0, 0], B: [0.05, 0]}, mass: 1, com: [0, 0], inertia: 0.001}
  rod: {points: {B: [0, 0], C: [0.2, 0]}, mass: 1, com: [0.05, 0], inertia: 0.001}
  piston: {points: {C: [0, 0]}, mass: 1, com: [0, 0], inertia: 0}
joints:
  A: {type: R, links: [ground, crank]}
  B: {type: R, links: [crank, rod]}
  C: {type: R, links: [rod, piston]}
  S: {type: T, links: [ground, piston], point: C, line: {through: A, direction: 0}}
driver: {joint: A, rpm: 1000}
assembly: {C: [0.25, 0]}
"""


def errors_of(text: str) -> str:
    with pytest.raises(SpecError) as exc:
        parse_spec(text, FILE)
    return str(exc.value)


def test_cycle_is_kept_and_the_default_sweep_is_one_cycle():
    spec = parse_spec(BASE, FILE)
    assert spec.cycle == 720.0
    assert (spec.sweep.start, spec.sweep.stop, spec.sweep.step) == (0.0, 720.0, 1.0)
    assert len(spec.sweep.angles()) == 720          # 720 itself repeats 0


def test_without_cycle_the_period_is_one_turn():
    spec = parse_spec(BASE.replace("cycle: 720\n", ""), FILE)
    assert spec.cycle == 360.0 and spec.sweep.stop == 360.0


def test_a_sweep_without_stop_runs_one_cycle():
    spec = parse_spec(BASE + "sweep: {step: 2}\n", FILE)
    assert spec.sweep.stop == 720.0 and len(spec.sweep.angles()) == 360


@pytest.mark.parametrize("value", ["700", "0", "-720", "true", "'720'", "720.5", "36360"])
def test_a_cycle_that_is_not_a_whole_multiple_of_a_turn_is_refused(value):
    message = errors_of(BASE.replace("cycle: 720", f"cycle: {value}"))
    assert f"{FILE}:3: cycle: must be a whole multiple of 360" in message


def test_a_whole_float_cycle_reads_as_its_number():
    assert parse_spec(BASE.replace("cycle: 720", "cycle: 1080.0"), FILE).cycle == 1080.0
