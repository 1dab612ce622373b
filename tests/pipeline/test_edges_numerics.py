"""Numbers that must never pass silently (issue 9, items 1 and 3-7): non-finite results,
contour equations chosen from where probes fall, near-singular positions, a branch jump next
to a touch point, motion the mechanism cannot reach, and an undecidable first reference angle.

Reference values come from closed forms of the textbook geometry (section 4.6: AB = BC = 1 m,
omega = 1 rad/s, g = 10, 100 N on the slider against its motion): on the branch the text takes,
x_C = 2 cos(phi), the rod angle is -phi, and the power balance gives the driver torque
M = 6 sin(phi) cos(phi) + 10 cos(phi) + 200 |sin(phi)| [N m] (3 + 105 sqrt2 at 45 deg)."""
from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pytest

from mechreport.pipeline.analysis import analyse
from mechreport.checks import agreement
from mechreport.errors import AnalysisError, AssemblyError, MechreportError
from mechreport.forces import solve_forces
from mechreport.kinematics import solve_kinematics
from mechreport.model import build_mechanism
from mechreport.spec import parse_spec

ROOT = Path(__file__).resolve().parents[2]
SLIDER_CRANK = (ROOT / "specs" / "slider_crank.yaml").read_text()
PARALLELOGRAM = (ROOT / "tests" / "data" / "edge" / "parallelogram_four_bar.yaml").read_text()


def textbook_torque(phi_deg):
    p = np.radians(phi_deg)
    return 6 * np.sin(p) * np.cos(p) + 10 * np.cos(p) + 200 * np.abs(np.sin(p))


def slider_crank(at: str = "[45]", extra: str = "", expect: bool = False):
    text = SLIDER_CRANK.replace("at: [45]", f"at: {at}")
    if not expect:
        text = text.split("expect:")[0]
    return parse_spec(text + extra, "slider_crank.yaml")


# 1. non-finite results ---------------------------------------------------------------------

@pytest.mark.filterwarnings("ignore:overflow:RuntimeWarning",
                            "ignore:invalid value:RuntimeWarning")
def test_non_finite_result_is_an_error_naming_quantity_and_angle():
    # the loader refuses such a mass; a Spec built in Python must still never pass
    spec = slider_crank()
    heavy = dataclasses.replace(spec.link("rod"), mass=1e308)
    spec = dataclasses.replace(spec, links=tuple(heavy if l.name == "rod" else l
                                                  for l in spec.links))
    with pytest.raises(AnalysisError, match=r"not a finite number at \d+ deg"):
        analyse(spec)


def test_non_finite_result_or_pose_is_named_by_the_final_check():
    """The last check before any report (analysis._require_finite) looks at every
    kinematic quantity and every result at once, and names the first one that is not
    finite, with its method and angle."""
    from mechreport.pipeline.analysis import _require_finite, solve_trusted
    from mechreport.kinematics import solve_kinematics
    from mechreport.model import build_mechanism
    kin, _, forces = solve_trusted(solve_kinematics(build_mechanism(slider_crank())))
    _require_finite(kin, forces)
    bad = forces["dyad"].reactions["B"].fy.copy()
    bad[4] = np.nan
    broken = {**forces, "dyad": dataclasses.replace(
        forces["dyad"], reactions={**forces["dyad"].reactions, "B": dataclasses.replace(
            forces["dyad"].reactions["B"], fy=bad)})}
    with pytest.raises(AnalysisError, match=rf"joint\.B\.fy \(dyad\) is not a finite number "
                                            rf"at {kin.angles[4]:g} deg"):
        _require_finite(kin, broken)
    omega = kin.omega.copy()
    omega[7, 2] = np.inf
    with pytest.raises(AnalysisError, match=rf"kinematics omega of link \w+ is not a finite "
                                            rf"number at {kin.angles[7]:g} deg"):
        _require_finite(dataclasses.replace(kin, omega=omega), forces)


@pytest.mark.filterwarnings("ignore:overflow:RuntimeWarning",
                            "ignore:invalid value:RuntimeWarning")
def test_non_finite_gravity_is_an_error_not_a_pass():
    spec = dataclasses.replace(slider_crank(), gravity=(1e308, -1e308))
    with pytest.raises(AnalysisError, match=r"not finite numbers at \d+ deg"):
        analyse(spec)


def test_agreement_of_nan_values_is_infinitely_bad_not_zero():
    kin = solve_kinematics(build_mechanism(slider_crank()))
    forces = solve_forces(kin, ["newton_euler", "dyad"])
    nan = dataclasses.replace(forces["dyad"], driver_torque=np.full(kin.n, np.nan))
    worst = agreement({"newton_euler": forces["newton_euler"], "dyad": nan})[0]
    assert worst.quantity == "driver.torque" and worst.relative == np.inf


# 3. contour equation choice ------------------------------------------------------------------

def test_contour_equations_do_not_depend_on_where_probes_fall():
    """A fine sweep across the slot's parallel position (180 deg) was rejected outright."""
    text = (ROOT / "tests" / "data" / "slotted_crank_slider.yaml").read_text()
    text = text.replace("sweep: {start: 30, stop: 150, step: 2}",
                        "sweep: {start: 170, stop: 190, step: 0.01}")
    a = analyse(parse_spec(text, "slotted.yaml"))
    swept = a.angles[a.angles >= 170]              # besides the reference angle, 60 deg
    assert a.passed and swept.min() == pytest.approx(170) and len(a.forces) == 5
    # the slider runs off to infinity at 180 deg: nothing beyond is reachable from 60 deg
    assert swept.max() < 180 and len(swept) >= 980
    assert any(f.kind == "unreachable" and f.angle > 180 for f in a.flags)


def test_slot_parallel_to_guide_is_a_clear_error_not_a_linalg_traceback():
    text = (ROOT / "specs" / "scotch_yoke.yaml").read_text()
    text = text.replace("line: {through: S, direction: 90}", "line: {through: S, direction: 0}")
    with pytest.raises(MechreportError, match="cannot close at the first reference angle"):
        analyse(parse_spec(text.split("expect:")[0], "yoke.yaml"))


def test_sweep_singular_everywhere_is_a_clear_error():
    spec = slider_crank(at="[90]", extra="")
    spec = dataclasses.replace(spec, sweep=dataclasses.replace(spec.sweep, start=90, stop=90.5))
    with pytest.raises(AnalysisError, match="no angle of the sweep can be analysed: .*singular"):
        analyse(spec)


def test_a_sweep_shorter_than_round_off_keeps_its_angle():
    """Sweep(0, 1e-10) counted as 'zero whole turns' and lost its only angle (IndexError)."""
    spec = slider_crank(at="[0]")
    spec = dataclasses.replace(spec, sweep=dataclasses.replace(spec.sweep, start=0, stop=1e-10))
    assert list(spec.sweep.angles()) == [0.0]
    assert list(analyse(spec).angles) == [0.0]


# 4. near-singular positions ------------------------------------------------------------------

@pytest.mark.parametrize("offset", [1e-1, 1e-2, 1e-3, 1e-4, 1e-5, 1e-6])
@pytest.mark.parametrize("side", [1, -1])
def test_4_6_near_90_deg_every_value_is_flagged_or_trustworthy_to_1e_6(offset, side):
    phi = 90 + side * offset
    a = analyse(slider_crank(at=f"[45, {phi!r}]"))
    k = a.kinematics.index_of(phi)
    if k is None:
        (flag,) = [f for f in a.flags if abs(f.angle - phi) < 1e-9]
        assert flag.kind == "near-singular" and "near-singular" in flag.reason
    else:
        for res in a.forces.values():
            assert res.driver_torque[k] == pytest.approx(textbook_torque(phi), rel=1e-6)
    assert (k is None) == (offset <= 0.1)   # flagged within about 0.1 deg, not further out


@pytest.mark.parametrize("offset", [1, 1e-1, 1e-2, 1e-3, 1e-4, 1e-5])
@pytest.mark.parametrize("base", [0, 180])
def test_parallelogram_change_points_flagged_or_trustworthy_to_1e_6(offset, base):
    """Parallelogram four-bar: torque = g cos(phi) (0.2 m1 + 0.4 m2 + 0.2 m3) = 20 cos(phi)
    N m; near 0 and 180 deg both branches meet (7.5e-2 error at 1e-3 deg, unflagged, before)."""
    for phi in (base + offset, base - offset):
        a = analyse(parse_spec(PARALLELOGRAM.replace("at: [30]", f"at: [30, {phi % 360!r}]"),
                               "parallelogram.yaml"))
        k = a.kinematics.index_of(phi % 360)
        if k is None:
            assert any(f.kind == "near-singular" for f in a.flags
                       if abs(f.angle - phi % 360) < 1e-9)
            continue
        for res in a.forces.values():
            assert res.driver_torque[k] == pytest.approx(20 * np.cos(np.radians(phi)),
                                                         rel=1e-6, abs=1e-9)


# 5. branch jump ---------------------------------------------------------------------------

def test_a_sample_next_to_a_touch_point_does_not_switch_the_branch():
    """`at: [45, 90.0000001]` made 91..359 deg follow the slider-on-the-pivot branch."""
    a = analyse(slider_crank(at="[45, 90.0000001]", expect=True))
    assert a.passed
    on = a.angles[a.angles > 90.5]
    for res in a.forces.values():
        got = res.driver_torque[np.isin(a.angles, on)]
        np.testing.assert_allclose(got, textbook_torque(on), rtol=1e-9)
    assert a.forces["newton_euler"].driver_torque[a.kinematics.at(120)] == \
        pytest.approx(165.607, abs=1e-3)


# 6. unreachable motion ----------------------------------------------------------------------

def test_rod_shorter_than_crank_reports_only_the_reachable_range():
    """Rod 0.8 m < crank 1 m: the rod reaches the guide only while sin(phi) <= 0.8, so from
    the assembly at 0 deg the crank swings between -53.13 and 53.13 deg and locks there."""
    text = SLIDER_CRANK.split("expect:")[0]
    text = text.replace("points: {B: [0, 0], C: [1, 0]}", "points: {B: [0, 0], C: [0.8, 0]}")
    text = text.replace("assembly: {C: [1.4, 0]}", "assembly: {C: [1.2, 0]}")
    a = analyse(parse_spec(text.replace("at: [45]", "at: [0]"), "short_rod.yaml"))
    lock = np.degrees(np.arcsin(0.8))
    reached = np.where(a.angles > 180, a.angles - 360, a.angles)
    assert np.all(np.abs(reached) < lock)
    assert len(a.angles) == 2 * int(lock) + 1
    motion = a.kinematics.motion
    assert not motion.full and "cannot make a full turn" in motion.describe()
    assert motion.locks == ((53.0, 54.0), (-54.0, -53.0))
    beyond = [f for f in a.flags if f.kind == "unreachable"]
    assert len(beyond) == 360 - len(a.angles)
    assert "the mechanism locks between 53 and 54 deg" in \
        next(f.reason for f in beyond if f.angle == 60)
    assert "between 306 and 307 deg" in next(f.reason for f in beyond if f.angle == 300)


def test_double_rocker_beyond_its_lock_is_not_reported():
    """A non-Grashof four-bar: the crank rocks; angles past the lock, even where the linkage
    could close on the far side, are motion the mechanism cannot reach from its assembly."""
    text = (ROOT / "specs" / "four_bar.yaml").read_text().split("expect:")[0]
    text = text.replace("points: {A: [0, 0], B: [50, 0]}", "points: {A: [0, 0], B: [150, 0]}")
    text = text.replace("shape: {bar: {length: 50, height: 20, depth: 10}}",
                        "shape: {bar: {length: 150, height: 20, depth: 10}}")
    text = text.replace("at: [30, 210]", "at: [60]").replace("assembly: {C: [196, 120]}",
                                                             "assembly: {C: [250, 100]}")
    a = analyse(parse_spec(text, "double_rocker.yaml"))
    motion = a.kinematics.motion
    assert not motion.full and len(motion.locks) == 2
    for angle in a.angles:
        assert motion.contains(angle)
    unreached = [f.angle for f in a.flags if f.kind == "unreachable"]
    assert unreached and not any(motion.contains(x) for x in unreached)


# 7. singular first reference angle -----------------------------------------------------------

def test_first_reference_angle_at_a_touch_point_says_no_hint_can_decide():
    kin = solve_kinematics(build_mechanism(slider_crank(at="[90]")))
    (choice,) = kin.branches
    assert choice.rule.startswith("undecided: no hint can decide at 90 deg")
    assert "C is at" in choice.rule   # and says where the branch it took leads


def test_assembly_error_still_raised_when_the_reference_angle_cannot_close():
    text = SLIDER_CRANK.split("expect:")[0]
    text = text.replace("points: {B: [0, 0], C: [1, 0]}", "points: {B: [0, 0], C: [0.5, 0]}")
    with pytest.raises(AssemblyError, match="cannot close at the first reference angle 45"):
        analyse(parse_spec(text, "x.yaml"))


def test_a_sweep_with_nothing_trustworthy_left_fails_although_an_at_angle_survives():
    """At rest, 200 angles within 0.05 deg of the textbook slider-crank's singular 90 deg are
    all near-singular; the reference angle 45 deg, outside the sweep, once survived alone and
    the spec passed. A sweep with nothing trustworthy left is an error, by either check."""
    from mechreport.pipeline.streamed import check_sweep
    text = SLIDER_CRANK.split("expect:")[0]
    text = text.replace("sweep: {start: 0, stop: 360, step: 1}",
                        "sweep: {start: 89.95, stop: 90.05, step: 0.0005}")
    text = text.replace("rpm: 9.549296585513721", "rpm: 0")
    assert "89.95" in text and "rpm: 0" in text
    spec = parse_spec(text, "slider_crank.yaml")
    with pytest.raises(AnalysisError, match="no angle of the sweep can be analysed: near-sing"):
        analyse(spec)
    with pytest.raises(AnalysisError, match="no angle of the sweep can be analysed"):
        check_sweep(spec, chunk=40)
    wider = parse_spec(text.replace("stop: 90.05", "stop: 90.5"), "slider_crank.yaml")
    assert len(analyse(wider).angles) > 1        # angles beyond 0.1 deg are trustworthy
