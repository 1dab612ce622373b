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


PRESSURE = """\
loads:
  - type: pressure
    link: piston
    point: C
    bore: 86
    direction: [-2, 0]
    unit: bar
    ambient: 1
    profile: [[0, 1], [180, 1], [360, 60], [380, 45], [540, 3], [720, 1]]
    shift: 90
"""
MM = BASE.replace("ground: {A: [0, 0]}", "units: {length: mm, mass: kg}\nground: {A: [0, 0]}")


def test_a_pressure_load_is_a_force_of_p_minus_ambient_times_the_area():
    spec = parse_spec(MM + PRESSURE, FILE)
    (load,) = spec.loads
    area = 3.141592653589793 * 0.086 ** 2 / 4
    assert load.kind == "force" and load.reacts_on == "ground" and load.shift == 90.0
    assert load.direction == (-1.0, 0.0)                  # normalised
    assert load.pressure.unit == "bar" and abs(load.pressure.area / area - 1) < 1e-12
    forces = dict(load.profile)
    assert abs(forces[360.0] - 59e5 * area) < 1e-9 * 59e5 * area     # (60 - 1) bar x A
    assert forces[0.0] == 0.0 and forces[720.0] == 0.0


def test_a_pressure_load_by_area_in_psi():
    text = MM + PRESSURE.replace("bore: 86", "area: 5000").replace("unit: bar", "unit: psi")
    load = parse_spec(text, FILE).loads[0]
    assert abs(load.pressure.area - 5000e-6) < 1e-18
    assert abs(dict(load.profile)[360.0] / (59 * 6894.757293168361 * 5e-3) - 1) < 1e-12


def line_of(text: str, fragment: str) -> int:
    """The 1-based line of the first line of ``text`` holding ``fragment``."""
    return next(i for i, ln in enumerate(text.splitlines(), 1) if fragment in ln)


@pytest.mark.parametrize("edit, line, where, says", [
    (("bore: 86", "bore: 86\n    area: 5000"), "area:", "loads[0].area",
     "give exactly one of 'bore'"),
    (("    bore: 86\n", ""), "- type: pressure", "loads[0].bore", "give exactly one of 'bore'"),
    (("direction: [-2, 0]", "direction: [0, 0]"), "direction: [0", "loads[0].direction",
     "not zero"),
    (("unit: bar", "unit: atm"), "unit: atm", "loads[0].unit", "must be one of Pa, kPa, bar, MPa, psi"),
    (("bore: 86", "bore: -86"), "bore:", "loads[0].bore", "positive"),
    (("shift: 90", "shift: x"), "shift:", "loads[0].shift", "must be a number"),
    (("point: C", "point: Q"), "point: Q", "loads[0].point", "'Q' is not a point of link 'piston'"),
    (("[720, 1]]", "[720, 2]]"), "profile:", "loads[0].profile[5]", "must repeat the point at 0"),
    (("[720, 1]]", "[730, 1]]"), "profile:", "loads[0].profile[5][0]", "beyond the cycle, 720"),
    (("    ambient: 1\n", "    ambient: 1\n    reacts_on: piston\n"),
     "reacts_on:",
     "loads[0].reacts_on", "must be one of ground"),
])
def test_pressure_load_errors_are_located(edit, line, where, says):
    text = MM + PRESSURE.replace(*edit)
    message = errors_of(text)
    assert f"{FILE}:{line_of(text, line)}: {where}: " in message and says in message, message


def test_a_profile_over_one_turn_cannot_run_past_360_without_a_cycle():
    text = MM.replace("cycle: 720\n", "") + PRESSURE.replace("shift: 90", "shift: 0")
    message = errors_of(text)
    assert "loads[0].profile[3][0]: lies beyond the cycle, 360 crank degrees" in message


def test_shift_on_force_and_moment_profiles():
    text = BASE + ("loads:\n"
                   "  - {type: force, link: piston, point: C, direction: [1, 0], "
                   "profile: [[0, 1], [360, 2]], shift: 180}\n"
                   "  - {type: moment, link: rod, profile: [[0, 1], [720, 1]], shift: -30}\n")
    spec = parse_spec(text, FILE)
    assert [ld.shift for ld in spec.loads] == [180.0, -30.0]
    assert [ld.reacts_on for ld in spec.loads] == [None, None]
