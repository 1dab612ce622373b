"""Spec loader errors: every message names the file, the line, the key path and what was
expected, and every problem of a file is reported at once.

Each case edits one thing in ``BASE`` (the textbook 4.6 slider-crank, written out here so the
line numbers do not move when the shipped specs change). Expected line numbers come from
``line_of``, which searches the edited text itself, independently of the loader.
"""
from __future__ import annotations

import math
import re
import subprocess
import sys
from dataclasses import fields, is_dataclass

import pytest

from mechreport.errors import AssemblyError, SpecError
from mechreport.kinematics import solve_kinematics
from mechreport.model import build_mechanism
from mechreport.spec import load_spec, parse_spec

FILE = "specs/x.yaml"

BASE = """\
mechreport: 1
name: slider-crank
units: {length: m, mass: kg}
gravity: [0, -10]
ground:
  A: [0, 0]
  O: [0, 0]
links:
  crank:
    points: {A: [0, 0], B: [1, 0]}
    mass: 1
    shape: {bar: {length: 1, height: 0.01, depth: 0.001}}
  rod:
    points: {B: [0, 0], C: [1, 0]}
    mass: 2
    shape: {bar: {length: 1, height: 0.01, depth: 0.001}}
  slider:
    points: {C: [0, 0]}
    mass: 3
    shape: {block: {width: 0.01, height: 0.01, depth: 0.001}}
joints:
  A: {type: R, links: [ground, crank]}
  B: {type: R, links: [crank, rod]}
  C: {type: R, links: [rod, slider]}
  C_T: {type: T, links: [ground, slider], point: C, line: {through: O, direction: 0}}
driver: {joint: A, omega: 1}
sweep: {start: 0, stop: 360, step: 1}
at: [45]
assembly: {C: [1.4, 0]}
loads:
  - {type: force, link: slider, point: C, value: [100, 0], oppose: velocity}
expect:
  - {angle: 45, quantity: point.C.x, value: 1.4142136}
  - {angle: 45, quantity: link.rod.omega, value: -1}
"""


# -- helpers -------------------------------------------------------------------------------

def edit(text: str, old: str, new: str) -> str:
    """Replace ``old`` (which must occur exactly once) by ``new``."""
    assert text.count(old) == 1, f"{old!r} occurs {text.count(old)} times"
    return text.replace(old, new)


def line_of(text: str, needle: str, occurrence: int = 1) -> int:
    """1-based number of the line holding the ``occurrence``-th line that contains ``needle``."""
    hits = [k for k, line in enumerate(text.splitlines(), start=1) if needle in line]
    assert len(hits) >= occurrence, f"{needle!r} found on {len(hits)} line(s)"
    return hits[occurrence - 1]


def problems(text: str):
    with pytest.raises(SpecError) as info:
        parse_spec(text, FILE)
    return info.value.problems


def only_problem(text: str):
    """The single problem of ``text`` (fails if there are none, or follow-on noise)."""
    found = problems(text)
    assert len(found) == 1, "expected exactly one problem, got:\n" + "\n".join(map(str, found))
    return found[0]


def assert_problem(problem, line: int | None, path: str, *parts: str) -> None:
    assert problem.file == FILE
    assert problem.line == line, str(problem)
    assert problem.path == path, str(problem)
    for part in parts:
        assert part in problem.message, f"{part!r} not in {str(problem)!r}"


# -- the base is valid ---------------------------------------------------------------------

def test_base_spec_is_valid():
    spec = parse_spec(BASE, FILE)
    assert [l.name for l in spec.links] == ["crank", "rod", "slider"]
    assert [l.number for l in spec.links] == [1, 2, 3]
    assert [l.mass for l in spec.links] == [1.0, 2.0, 3.0]
    assert spec.driver.link == "crank" and spec.driver.omega == 1.0


def test_shipped_slider_crank_loads(repo_root):
    spec = load_spec(repo_root / "specs" / "slider_crank.yaml")
    assert spec.driver.omega == pytest.approx(1.0, abs=1e-12)   # 30/pi rpm


# -- YAML syntax ---------------------------------------------------------------------------

def test_malformed_yaml_mapping_value():
    text = edit(BASE, "    mass: 2\n", "    mass: 2: kg\n")
    p = only_problem(text)
    assert_problem(p, line_of(text, "mass: 2: kg"), "", "malformed YAML",
                   "mapping values are not allowed here")
    assert str(p).startswith(f"{FILE}:{line_of(text, 'mass: 2: kg')}: malformed YAML")


def test_malformed_yaml_tab():
    text = edit(BASE, "    mass: 2\n", "\tmass: 2\n")
    p = only_problem(text)
    assert_problem(p, line_of(text, "\tmass: 2"), "", "malformed YAML", "'\\t'")


def test_empty_file():
    p = only_problem("")
    assert p.line is None and "the file is empty" in p.message
    assert str(p) == f"{FILE}: the file is empty; a spec starts with 'mechreport: 1'"


def test_top_level_not_a_mapping():
    p = only_problem("- a\n- b\n")
    assert_problem(p, 1, "", "must be a mapping of keys")


# -- unknown keys --------------------------------------------------------------------------

@pytest.mark.parametrize("old, new, path, suggestion", [
    ("gravity: [0, -10]", "gravty: [0, -10]", "gravty", "gravity"),
    ("step: 1}", "steps: 1}", "sweep.steps", "step"),
    ("    mass: 2\n", "    mass: 2\n    intertia: 0.1\n", "links.rod.intertia", "inertia"),
    ("{type: force, link: slider", "{type: force, lnk: slider, link: slider",
     "loads[0].lnk", "link"),
    ("value: -1}", "value: -1, tl: 0.1}", "expect[1].tl", "tol"),
])
def test_unknown_key_did_you_mean(old, new, path, suggestion):
    text = edit(BASE, old, new)
    p = only_problem(text)
    key = path.rsplit(".", 1)[-1]
    assert_problem(p, line_of(text, key), path, f"unknown key; did you mean '{suggestion}'?")


def test_unknown_key_without_close_match_lists_allowed_keys():
    text = edit(BASE, "    mass: 2\n", "    mass: 2\n    colour: red\n")
    p = only_problem(text)
    assert_problem(p, line_of(text, "colour"), "links.rod.colour",
                   "unknown key; allowed: points, mass, density, com, inertia, shape")


def test_typo_in_required_key_reports_both_the_typo_and_the_missing_key():
    text = edit(BASE, "    mass: 2\n", "    mas: 2\n")
    found = problems(text)
    assert [str(p) for p in found] == [
        f"{FILE}:{line_of(text, '  rod:')}: links.rod: link 'rod' needs 'mass', or 'density' "
        "with a 'shape'",
        f"{FILE}:{line_of(text, 'mas: 2')}: links.rod.mas: unknown key; did you mean 'mass'?",
    ]


# -- missing required keys -----------------------------------------------------------------

def test_missing_name():
    text = edit(BASE, "name: slider-crank\n", "")
    p = only_problem(text)
    assert str(p) == f"{FILE}:1: missing required key 'name'"


def test_missing_driver():
    text = edit(BASE, "driver: {joint: A, omega: 1}\n", "")
    p = only_problem(text)
    assert_problem(p, 1, "", "missing required key 'driver'")


def test_missing_link_points():
    text = edit(BASE, "    points: {C: [0, 0]}\n", "")
    p = only_problem(text)   # no follow-on noise about joints C and C_T or the load on C
    assert_problem(p, line_of(text, "  slider:"), "links.slider", "missing required key 'points'")


def test_missing_joint_type():
    text = edit(BASE, "B: {type: R, links: [crank, rod]}", "B: {links: [crank, rod]}")
    p = only_problem(text)   # and not "missing 'point'/'line'" as if it were a T joint
    assert_problem(p, line_of(text, "B: {links"), "joints.B",
                   "missing required key 'type' (R or T)")


def test_missing_t_joint_line():
    text = edit(BASE, ", line: {through: O, direction: 0}}", "}")
    p = only_problem(text)
    assert_problem(p, line_of(text, "C_T:"), "joints.C_T", "missing required key 'line'")


def test_missing_driver_speed():
    text = edit(BASE, "driver: {joint: A, omega: 1}", "driver: {joint: A}")
    p = only_problem(text)
    assert_problem(p, line_of(text, "driver:"), "driver", "give exactly one of 'rpm' or 'omega'")


# -- wrong types and values ----------------------------------------------------------------

def test_mass_not_a_number():
    text = edit(BASE, "    mass: 2\n", "    mass: heavy\n")
    p = only_problem(text)   # rod stays a known link: no "unknown link 'rod'" follow-ons
    assert str(p) == (f"{FILE}:{line_of(text, 'mass: heavy')}: links.rod.mass: "
                      "must be a positive number, got 'heavy'")


@pytest.mark.parametrize("old, new, needle, path, expected", [
    ("points: {A: [0, 0], B: [1, 0]}", "points: {A: [0, 0], B: [1, 0, 0]}", "[1, 0, 0]",
     "links.crank.points.B", "must be a pair [x, y] or {r: R, angle: A}, got [1, 0, 0]"),
    ("points: {A: [0, 0], B: [1, 0]}", "points: {A: [0, 0], B: [one, 0]}", "[one, 0]",
     "links.crank.points.B[0]", "must be a number, got 'one'"),
    ("gravity: [0, -10]", "gravity: down", "gravity:", "gravity",
     "must be a pair [gx, gy] in m/s^2, got 'down'"),
    ("driver: {joint: A, omega: 1}", "driver: {joint: A, omega: fast}", "driver:",
     "driver.omega", "must be a number, got 'fast'"),
    ("length: m,", "length: inch,", "units:", "units.length",
     "must be one of m, cm, mm, in, ft, got 'inch'"),
    ("mechreport: 1", "mechreport: 2", "mechreport:", "mechreport",
     "format version must be 1, got 2"),
    ("at: [45]", "at: 45", "at:", "at", "must be a list of crank angles in degrees, got 45"),
    ("value: [100, 0], oppose: velocity", "value: [100, 0], oppose: always", "always",
     "loads[0].oppose", "must be one of velocity, got 'always'"),
    ("direction: 0}", "direction: [0, 0]}", "C_T:", "joints.C_T.line.direction",
     "must not be the zero vector"),
    ("links: [crank, rod]", "links: [crank]", "[crank]", "joints.B.links",
     "must be two link names [first, second], got ['crank']"),
])
def test_wrong_type(old, new, needle, path, expected):
    text = edit(BASE, old, new)
    p = only_problem(text)
    assert_problem(p, line_of(text, needle), path, expected)


def test_a_reference_angle_given_twice_is_refused_where_it_repeats():
    """Issue 40: two equal `at` angles made two reference sections, figures and DXF layers of
    one name (the build failed on the DXF); an angle closer than the report shows is not the
    same angle and is kept."""
    text = edit(BASE, "at: [45]", "at: [30, 45, 45.0]")
    assert_problem(only_problem(text), line_of(text, "at:"), "at[2]",
                   "45.0 is given twice (also at[1]); give each reference angle once")
    assert parse_spec(edit(BASE, "at: [45]", "at: [45, 45.00001]"), FILE).at == (45, 45.00001)


@pytest.mark.parametrize("speed", ["omega: 0", "rpm: 0", "omega: 0, alpha: 3"])
def test_a_driver_at_rest_is_a_static_analysis_or_a_start(speed):
    """Format 1.1: zero speed is allowed (it was an error in format 1)."""
    text = edit(BASE, "driver: {joint: A, omega: 1}", f"driver: {{joint: A, {speed}}}")
    spec = parse_spec(text, FILE)
    assert spec.driver.at_rest and spec.driver.omega == 0.0


def test_negative_speed_means_clockwise():
    spec = parse_spec(edit(BASE, "omega: 1}", "rpm: -60}"), FILE)
    assert spec.driver.omega == pytest.approx(-2 * math.pi, rel=1e-14)


def test_sheet_must_be_boolean():
    text = BASE + "sheet: maybe\n"
    p = only_problem(text)
    assert_problem(p, line_of(text, "sheet:"), "sheet", "must be true or false, got 'maybe'")


@pytest.mark.parametrize("old, new, needle, path, shown", [
    ("    mass: 2\n", "    mass: -2\n", "mass: -2", "links.rod.mass", "-2"),
    ("    mass: 2\n", "    density: -7850\n", "density:", "links.rod.density", "-7850"),
    ("    mass: 2\n", "    mass: 2\n    inertia: -1\n", "inertia:", "links.rod.inertia", "-1"),
    ("{bar: {length: 1, height: 0.01, depth: 0.001}}\n  rod:",
     "{bar: {length: 0, height: 0.01, depth: 0.001}}\n  rod:", "length: 0",
     "links.crank.shape.bar.length", "0"),
    ("{block: {width: 0.01,", "{block: {width: -0.01,", "width: -0.01",
     "links.slider.shape.block.width", "-0.01"),
    ("height: 0.01, depth: 0.001}}\n  slider:", "height: 0.01, depth: 0}}\n  slider:",
     "depth: 0}", "links.rod.shape.bar.depth", "0"),
    ("step: 1}", "step: 0}", "step: 0", "sweep.step", "0"),
])
def test_non_positive_quantities(old, new, needle, path, shown):
    text = edit(BASE, old, new)
    p = only_problem(text)
    assert_problem(p, line_of(text, needle), path)
    assert p.message == f"must be a positive number, got {shown}"


def test_sweep_stop_before_start():
    text = edit(BASE, "sweep: {start: 0, stop: 360, step: 1}", "sweep: {start: 90, stop: 10}")
    p = only_problem(text)
    assert_problem(p, line_of(text, "sweep:"), "sweep.stop", "must be greater than start (90)")


def test_profile_angles_must_increase():
    text = edit(BASE, "value: [100, 0], oppose: velocity",
                "direction: [1, 0], profile: [[10, 1], [5, 2]]")
    p = only_problem(text)
    assert_problem(p, line_of(text, "profile:"), "loads[0].profile",
                   "angles must be strictly increasing")


def test_force_profile_needs_direction():
    text = edit(BASE, "value: [100, 0], oppose: velocity", "profile: [[0, 1], [180, 2]]")
    p = only_problem(text)
    assert_problem(p, line_of(text, "profile:"), "loads[0]", "needs a 'direction'")


# -- names that refer to nothing -----------------------------------------------------------

def test_unknown_link_in_joint():
    text = edit(BASE, "links: [crank, rod]", "links: [crank, rood]")
    p = only_problem(text)
    assert str(p) == (f"{FILE}:{line_of(text, 'rood')}: joints.B.links[1]: unknown link 'rood' "
                      "(links: ground, crank, rod, slider)")


def test_unknown_link_in_load():
    text = edit(BASE, "link: slider, point: C", "link: piston, point: C")
    p = only_problem(text)
    assert_problem(p, line_of(text, "piston"), "loads[0].link",
                   "unknown link 'piston' (loads act on moving links: crank, rod, slider)")


@pytest.mark.parametrize("old, new, path, expected", [
    ("link: slider, point: C", "link: slider, point: Q", "loads[0].point",
     "'Q' is not a point of link 'slider'"),
    ("point: C, line:", "point: Q, line:", "joints.C_T.point",
     "'Q' is not a point of the slider 'slider'"),
    ("through: O,", "through: Q,", "joints.C_T.line.through",
     "'Q' is not a point of the guide 'ground'"),
    ("assembly: {C: [1.4, 0]}", "assembly: {Q: [1.4, 0]}", "assembly.Q",
     "'Q' is not a point of any moving link"),
])
def test_unknown_point_name(old, new, path, expected):
    text = edit(BASE, old, new)
    p = only_problem(text)
    assert_problem(p, line_of(text, "Q"), path, expected)


def test_driver_joint_unknown():
    text = edit(BASE, "driver: {joint: A,", "driver: {joint: Z,")
    p = only_problem(text)
    assert_problem(p, line_of(text, "driver:"), "driver.joint",
                   "unknown joint 'Z' (joints: A, B, C, C_T)")


@pytest.mark.parametrize("link, where, index", [
    ("rod", "link 'rod' points", 1),
    ("crank", "link 'crank' points", 0),
])
def test_r_joint_point_missing_on_one_link(link, where, index):
    old = {"rod": "points: {B: [0, 0], C: [1, 0]}", "crank": "points: {A: [0, 0], B: [1, 0]}"}
    new = {"rod": "points: {B1: [0, 0], C: [1, 0]}", "crank": "points: {A: [0, 0], B1: [1, 0]}"}
    text = edit(BASE, old[link], new[link])
    p = only_problem(text)
    assert_problem(p, line_of(text, "B: {type: R"), f"joints.B.links[{index}]",
                   f"R joint 'B' needs a point named 'B' in {where}")


def test_r_joint_point_missing_on_ground():
    text = edit(BASE, "  A: [0, 0]\n", "  A0: [0, 0]\n")
    p = only_problem(text)
    assert_problem(p, line_of(text, "A: {type: R"), "joints.A.links[0]",
                   "R joint 'A' needs a point named 'A' in ground points")


# -- duplicate names -----------------------------------------------------------------------

def test_duplicate_ground_point():
    text = edit(BASE, "  O: [0, 0]\n", "  O: [0, 0]\n  A: [5, 0]\n")
    p = only_problem(text)
    assert str(p) == f"{FILE}:{line_of(text, 'A: [5, 0]')}: ground.A: duplicate key"


def test_duplicate_link_name():
    text = edit(BASE, "joints:\n", "  rod:\n    points: {B: [0, 0]}\n    mass: 1\njoints:\n")
    p = only_problem(text)
    assert_problem(p, line_of(text, "  rod:", occurrence=2), "links.rod", "duplicate key")


def test_duplicate_joint_name():
    text = edit(BASE, "driver:", "  B: {type: R, links: [rod, slider]}\ndriver:")
    p = only_problem(text)
    assert_problem(p, line_of(text, "B: {type: R", occurrence=2), "joints.B", "duplicate key")


def test_duplicate_point_in_flow_mapping():
    text = edit(BASE, "points: {C: [0, 0]}", "points: {C: [0, 0], C: [0, 1]}")
    p = only_problem(text)
    assert_problem(p, line_of(text, "C: [0, 1]"), "links.slider.points.C", "duplicate key")


# -- structure: driver, mobility, connectivity ---------------------------------------------

def test_driver_may_be_any_joint():
    """Any joint may drive (format additions): an R joint between moving links drives their
    relative angle; a T joint its stroke, with speed and accel in the length unit."""
    spec = parse_spec(edit(BASE, "driver: {joint: A,", "driver: {joint: B,"), FILE)
    assert (spec.driver.kind, spec.driver.links, spec.driver.link) == ("R", ("crank", "rod"),
                                                                        "rod")
    assert spec.driver.quantity == "driver.torque" and not spec.driver.crank
    text = re.sub(r"driver: \{joint: A, [^}]*\}", "driver: {joint: C_T, speed: 0.5, accel: 0.1}",
                  BASE)
    text = text.split("expect:")[0]
    spec = parse_spec(text, FILE)
    assert (spec.driver.kind, spec.driver.omega, spec.driver.alpha) == ("T", 0.5, 0.1)
    assert spec.driver.quantity == "driver.force" and not spec.sweep.wraps


def test_t_driver_takes_speed_not_rpm():
    text = edit(BASE, "driver: {joint: A,", "driver: {joint: C_T,")
    p = only_problem(text)
    assert_problem(p, line_of(text, "driver:"), "driver.omega",
                   "a T driver drives its stroke: give 'speed'")


def test_mobility_too_high():
    text = edit(BASE, "  C_T: {type: T, links: [ground, slider], point: C, "
                      "line: {through: O, direction: 0}}\n", "")
    p = only_problem(text)
    assert str(p) == (f"{FILE}:{line_of(text, 'joints:')}: joints: the mechanism has mobility 3 "
                      "(Gruebler: 3 x 3 moving links - 2 x 3 joints); a single driver needs "
                      "mobility 1")


def test_mobility_too_low():
    text = edit(BASE, "  O: [0, 0]\n", "  O: [0, 0]\n  D: [1, 1]\n")
    text = edit(text, "points: {B: [0, 0], C: [1, 0]}", "points: {B: [0, 0], C: [1, 0], D: [0, 1]}")
    text = edit(text, "driver:", "  D: {type: R, links: [ground, rod]}\ndriver:")
    p = only_problem(text)
    assert_problem(p, line_of(text, "joints:"), "joints", "mobility -1",
                   "3 x 3 moving links - 2 x 5 joints")


def test_link_not_connected():
    # Two extra links pinned to each other three times: mobility stays 3*5 - 2*7 = 1, so the
    # only problem is that they are not connected to the rest.
    text = edit(BASE, "joints:\n", (
        "  p:\n    points: {P1: [0, 0], P2: [1, 0], P3: [0, 1]}\n    mass: 1\n"
        "    com: [0, 0]\n    inertia: 1\n"
        "  q:\n    points: {P1: [0, 0], P2: [1, 0], P3: [0, 1]}\n    mass: 1\n"
        "    com: [0, 0]\n    inertia: 1\n"
        "joints:\n"))
    text = edit(text, "driver:", "  P1: {type: R, links: [p, q]}\n  P2: {type: R, links: [p, q]}\n"
                                 "  P3: {type: R, links: [p, q]}\ndriver:")
    p = only_problem(text)
    assert str(p) == (f"{FILE}:{line_of(text, '  p:')}: links.p: not connected to the rest of "
                      "the mechanism: p, q")


# -- expectations --------------------------------------------------------------------------

@pytest.mark.parametrize("quantity, expected", [
    ("point.Z.x", "'point.Z.x': no moving link has a point named 'Z'"),
    ("point.C.speed", "'point.C.speed': a point has x, y, vx, vy, ax, ay"),
    ("link.rood.omega", "'link.rood.omega': no link named 'rood' (links: crank, rod, slider)"),
    ("link.rod.speed", "'link.rod.speed': a link has angle, omega, alpha"),
    ("joint.Z.fx", "'joint.Z.fx': no joint named 'Z' (joints: A, B, C, C_T)"),
    ("joint.A.moment", "'joint.A.moment': a R joint has fx, fy, f"),
    ("rod.omega", "'rod.omega' names nothing: expected driver.torque"),
    ("driver.power", "'driver.power' names nothing"),
])
def test_expect_quantity_names_nothing(quantity, expected):
    text = edit(BASE, "quantity: link.rod.omega", f"quantity: {quantity}")
    p = only_problem(text)
    assert_problem(p, line_of(text, quantity), "expect[1].quantity", expected)


def test_expect_quantities_that_exist_are_accepted():
    text = edit(BASE, "quantity: link.rod.omega, value: -1}",
                "quantity: joint.C_T.moment, value: 0, tol: 1e-9}")
    spec = parse_spec(text, FILE)
    assert [e.quantity for e in spec.expect] == ["point.C.x", "joint.C_T.moment"]
    assert spec.expect[0].tol == pytest.approx(1e-4 * 1.4142136)   # default 1e-4 max(1, |v|)
    assert spec.expect[1].tol == 1e-9
    assert spec.expect[1].line == line_of(text, "joint.C_T.moment")


# -- mass properties -----------------------------------------------------------------------

def test_com_off_centroid_without_inertia():
    text = edit(BASE, "    mass: 3\n", "    mass: 3\n    com: [0.002, 0]\n")
    p = only_problem(text)
    assert str(p) == (f"{FILE}:{line_of(text, 'com: [0.002, 0]')}: links.slider.com: is off the "
                      "shape's centroid [0.0, 0.0]: give 'inertia' too (a shape's inertia is "
                      "about its own centroid)")


def test_com_off_centroid_with_inertia_is_accepted():
    text = edit(BASE, "    mass: 3\n", "    mass: 3\n    com: [0.002, 0]\n    inertia: 0.5\n")
    slider = parse_spec(text, FILE).link("slider")
    assert slider.com == (0.002, 0.0) and slider.inertia == 0.5


def test_com_on_centroid_keeps_shape_inertia():
    text = edit(BASE, "    mass: 2\n", "    mass: 2\n    com: [0.5, 0]\n")
    rod = parse_spec(text, FILE).link("rod")
    assert rod.inertia == pytest.approx(2 * (1 + 0.01**2) / 12, rel=1e-14)


def test_link_with_no_mass_and_no_density():
    text = edit(BASE, "    mass: 3\n", "")
    p = only_problem(text)   # and no "unknown link 'slider'" in joints or loads
    assert str(p) == (f"{FILE}:{line_of(text, '  slider:')}: links.slider: link 'slider' needs "
                      "'mass', or 'density' with a 'shape'")


SLIDER_MASS_SHAPE = "    mass: 3\n    shape: {block: {width: 0.01, height: 0.01, depth: 0.001}}\n"


def test_link_with_density_but_no_shape():
    text = edit(BASE, SLIDER_MASS_SHAPE,
                "    density: 7850\n")
    p = only_problem(text)
    assert_problem(p, line_of(text, "  slider:"), "links.slider",
                   "link 'slider' needs 'mass', or 'density' with a 'shape'")


def test_link_with_no_shape_needs_com_and_inertia():
    text = edit(BASE, SLIDER_MASS_SHAPE,
                "    mass: 3\n    inertia: 1e-6\n")
    p = only_problem(text)
    assert_problem(p, line_of(text, "  slider:"), "links.slider",
                   "link 'slider' needs 'com' (centre of mass) or a 'shape'")
    text = edit(BASE, SLIDER_MASS_SHAPE,
                "    mass: 3\n    com: [0, 0]\n")
    p = only_problem(text)
    assert_problem(p, line_of(text, "  slider:"), "links.slider",
                   "link 'slider' needs 'inertia' or a 'shape'")


def test_density_and_shape_give_mass_and_inertia():
    text = edit(BASE, "    mass: 2\n", "    density: 8000\n")
    rod = parse_spec(text, FILE).link("rod")
    m = 8000 * 1 * 0.01 * 0.001
    assert rod.mass == pytest.approx(m, rel=1e-14)
    assert rod.com == (0.5, 0.0)
    assert rod.inertia == pytest.approx(m * (1 + 0.01**2) / 12, rel=1e-14)


# -- units, numbers, all problems at once --------------------------------------------------

UNITS_M_KG = """\
mechreport: 1
name: units
units: {length: m, mass: kg}
ground:
  A: [0, 0]
links:
  crank:
    points: {A: [0, 0], B: [0.05, 0]}
    density: 7850
    shape: {bar: {length: 0.05, height: 0.02, depth: 0.01}}
  rod:
    points: {B: [0, 0], C: [0.2, 0]}
    mass: 0.25
    com: [0.08, 0.004]
    inertia: 8.5e-4
    shape: {bar: {length: 0.2, height: 0.015, depth: 0.008}}
  slider:
    points: {C: [0, 0]}
    mass: 0.4
    shape: {block: {width: 0.03, height: 0.02, depth: 0.02}}
joints:
  A: {type: R, links: [ground, crank]}
  B: {type: R, links: [crank, rod]}
  C: {type: R, links: [rod, slider]}
  C_T: {type: T, links: [ground, slider], point: C,
        line: {through: [0, 0.01], direction: 0}}
driver: {joint: A, rpm: 600}
assembly: {C: [0.24, 0.01]}
loads:
  - {type: force, link: slider, point: C, value: [-50, 0]}
  - {type: moment, link: rod, value: 1.5}
"""


def _scaled_text(factor_len: float, factor_mass: float, units: str) -> str:
    """UNITS_M_KG rewritten in other units by hand (every length and mass literal)."""
    def L(x: float) -> str:
        return repr(round(x * factor_len, 9))

    def M(x: float) -> str:
        return repr(round(x * factor_mass, 9))

    return f"""\
mechreport: 1
name: units
units: {units}
ground:
  A: [0, 0]
links:
  crank:
    points: {{A: [0, 0], B: [{L(0.05)}, 0]}}
    density: 7850
    shape: {{bar: {{length: {L(0.05)}, height: {L(0.02)}, depth: {L(0.01)}}}}}
  rod:
    points: {{B: [0, 0], C: [{L(0.2)}, 0]}}
    mass: {M(0.25)}
    com: [{L(0.08)}, {L(0.004)}]
    inertia: 8.5e-4
    shape: {{bar: {{length: {L(0.2)}, height: {L(0.015)}, depth: {L(0.008)}}}}}
  slider:
    points: {{C: [0, 0]}}
    mass: {M(0.4)}
    shape: {{block: {{width: {L(0.03)}, height: {L(0.02)}, depth: {L(0.02)}}}}}
joints:
  A: {{type: R, links: [ground, crank]}}
  B: {{type: R, links: [crank, rod]}}
  C: {{type: R, links: [rod, slider]}}
  C_T: {{type: T, links: [ground, slider], point: C,
        line: {{through: [0, {L(0.01)}], direction: 0}}}}
driver: {{joint: A, rpm: 600}}
assembly: {{C: [{L(0.24)}, {L(0.01)}]}}
loads:
  - {{type: force, link: slider, point: C, value: [-50, 0]}}
  - {{type: moment, link: rod, value: 1.5}}
"""


def assert_same_si(a, b, path="spec"):
    """Recursive comparison of loaded specs: floats to 1e-12 relative, the rest exactly."""
    if is_dataclass(a):
        assert type(a) is type(b), path
        for f in fields(a):
            if f.name in ("units", "file"):
                continue
            assert_same_si(getattr(a, f.name), getattr(b, f.name), f"{path}.{f.name}")
    elif isinstance(a, dict):
        assert a.keys() == b.keys(), path
        for k in a:
            assert_same_si(a[k], b[k], f"{path}[{k!r}]")
    elif isinstance(a, (list, tuple)):
        assert len(a) == len(b), path
        for k, (x, y) in enumerate(zip(a, b)):
            assert_same_si(x, y, f"{path}[{k}]")
    elif isinstance(a, float) or isinstance(b, float):
        assert math.isclose(a, b, rel_tol=1e-12, abs_tol=1e-15), f"{path}: {a} != {b}"
    else:
        assert a == b, f"{path}: {a!r} != {b!r}"


@pytest.mark.parametrize("factor_len, factor_mass, units, names", [
    (1000, 1000, "{length: mm, mass: g}", {"length": "mm", "mass": "g"}),
    (100, 1, "{length: cm, mass: kg}", {"length": "cm", "mass": "kg"}),
    (1000, 1, "{length: mm}", {"length": "mm", "mass": "kg"}),
])
def test_units_give_the_same_si_spec(factor_len, factor_mass, units, names):
    si = parse_spec(UNITS_M_KG, FILE)
    other = parse_spec(_scaled_text(factor_len, factor_mass, units), FILE)
    assert_same_si(si, other)
    # spot checks against hand-computed SI values
    crank, rod = other.link("crank"), other.link("rod")
    assert crank.points["B"] == pytest.approx((0.05, 0.0), rel=1e-12)
    assert crank.mass == pytest.approx(7850 * 0.05 * 0.02 * 0.01, rel=1e-12)   # 0.0785 kg
    assert rod.mass == pytest.approx(0.25, rel=1e-12)
    assert rod.inertia == 8.5e-4                       # inertia is always SI, never scaled
    assert other.joint("C_T").line.through == pytest.approx((0.0, 0.01), rel=1e-12)
    assert other.assembly["C"] == pytest.approx((0.24, 0.01), rel=1e-12)
    assert other.loads[0].value == (-50.0, 0.0)        # forces are always SI
    assert other.units == names


def test_numbers_written_like_1e_minus_3_are_accepted():
    # YAML 1.1 reads 1e-3 (no dot) as a string; the loader must still take it as a number.
    text = edit(BASE, "height: 0.01, depth: 0.001}}\n  slider:",
                "height: 1e-2, depth: 1e-3}}\n  slider:")
    text = edit(text, "    mass: 2\n", "    mass: 2e0\n    inertia: 5E-1\n    com: [5e-1, 0]\n")
    text = edit(text, "driver: {joint: A, omega: 1}", "driver: {joint: A, omega: 1e0}")
    text = edit(text, "value: -1}", "value: -1, tol: 1e-6}")
    text = edit(text, "assembly: {C: [1.4, 0]}", "assembly: {C: [14e-1, 0]}")
    spec = parse_spec(text, FILE)
    rod = spec.link("rod")
    assert rod.shape.height == 0.01 and rod.shape.depth == 0.001
    assert rod.mass == 2.0 and rod.inertia == 0.5 and rod.com == (0.5, 0.0)
    assert spec.driver.omega == 1.0
    assert spec.expect[1].tol == 1e-6
    assert spec.assembly["C"] == (1.4, 0.0)


def test_all_problems_of_a_file_are_reported_together():
    text = edit(BASE, "    mass: 2\n", "    mass: heavy\n")
    text = edit(text, "link: slider, point: C", "link: slider, point: Q")
    with pytest.raises(SpecError) as info:
        parse_spec(text, FILE)
    found = info.value.problems
    assert [(p.line, p.path) for p in found] == [
        (line_of(text, "mass: heavy"), "links.rod.mass"),
        (line_of(text, "point: Q"), "loads[0].point"),
    ]
    assert str(info.value).splitlines() == [str(p) for p in found]


def test_load_spec_names_the_file_and_missing_file(tmp_path):
    path = tmp_path / "bad.yaml"
    path.write_text(edit(BASE, "    mass: 2\n", "    mass: heavy\n"), encoding="utf-8")
    with pytest.raises(SpecError) as info:
        load_spec(path)
    assert str(info.value).startswith(f"{path}:{line_of(BASE, 'mass: 2')}: links.rod.mass:")
    with pytest.raises(SpecError) as info:
        load_spec(tmp_path / "missing.yaml")
    assert "cannot read file" in str(info.value)


# -- structures the model does not support, assembly failures ------------------------------

TRIAD = """\
mechreport: 1
name: class III group
ground:
  A: [0, 0]
  P: [0.3, 0]
  Q: [0.15, -0.25]
links:
  crank:
    points: {A: [0, 0], B: [0.05, 0]}
    mass: 1
    com: [0.025, 0]
    inertia: 1e-4
  b1:
    points: {B: [0, 0], T1: [0.15, 0]}
    mass: 1
    com: [0.075, 0]
    inertia: 1e-4
  b2:
    points: {P: [0, 0], T2: [0.15, 0]}
    mass: 1
    com: [0.075, 0]
    inertia: 1e-4
  b3:
    points: {Q: [0, 0], T3: [0.15, 0]}
    mass: 1
    com: [0.075, 0]
    inertia: 1e-4
  tern:
    points: {T1: [0, 0], T2: [0.1, 0], T3: [0.05, -0.08]}
    mass: 1
    com: [0.05, -0.03]
    inertia: 1e-4
joints:
  A: {type: R, links: [ground, crank]}
  B: {type: R, links: [crank, b1]}
  T1: {type: R, links: [b1, tern]}
  P: {type: R, links: [ground, b2]}
  T2: {type: R, links: [b2, tern]}
  Q: {type: R, links: [ground, b3]}
  T3: {type: R, links: [b3, tern]}
driver: {joint: A, rpm: 60}
"""

# Stephenson III six-bar: ternary links T1 (pivoted on ground at G) and T2 (pinned to the
# crank at B) joined by two binary links; neither ternary link is split off by a dyad.
STEPHENSON_III = """\
mechreport: 1
name: Stephenson III six-bar
ground:
  A: [0, 0]
  G: [0.3, 0]
links:
  crank:
    points: {A: [0, 0], B: [0.05, 0]}
    mass: 1
    com: [0.025, 0]
    inertia: 1e-4
  T2:
    points: {B: [0, 0], J: [0.2, 0.05], K: [0.2, -0.05]}
    mass: 1
    com: [0.13, 0]
    inertia: 1e-4
  c1:
    points: {J: [0, 0], L: [0.1, 0]}
    mass: 1
    com: [0.05, 0]
    inertia: 1e-4
  c2:
    points: {K: [0, 0], M: [0.1, 0]}
    mass: 1
    com: [0.05, 0]
    inertia: 1e-4
  T1:
    points: {G: [0, 0], L: [0.05, 0.1], M: [0.05, -0.1]}
    mass: 1
    com: [0.03, 0]
    inertia: 1e-4
joints:
  A: {type: R, links: [ground, crank]}
  B: {type: R, links: [crank, T2]}
  J: {type: R, links: [T2, c1]}
  L: {type: R, links: [c1, T1]}
  K: {type: R, links: [T2, c2]}
  M: {type: R, links: [c2, T1]}
  G: {type: R, links: [ground, T1]}
driver: {joint: A, rpm: 60}
"""


@pytest.mark.parametrize("text, groups", [
    (TRIAD, [("driver", ("crank",)), ("triad (class III)", ("b1", "b2", "b3", "tern"))]),
    (STEPHENSON_III, [("driver", ("crank",)), ("class IV group", ("T2", "c1", "c2", "T1"))]),
], ids=["class-III-triad", "stephenson-III"])
def test_structures_without_dyads_split_into_larger_assur_groups(text, groups):
    spec = parse_spec(text, FILE)          # passes Gruebler: 3 x 5 - 2 x 7 = 1, connected
    mech = build_mechanism(spec)
    assert [(g.class_name, g.links) for g in mech.groups] == groups


def test_reference_angle_that_cannot_close_raises_assembly_error():
    # rod 0.5 m cannot reach the x-axis when the 1 m crank points straight up
    text = edit(BASE, "points: {B: [0, 0], C: [1, 0]}", "points: {B: [0, 0], C: [0.5, 0]}")
    text = edit(text, "at: [45]", "at: [90]")
    text = edit(text, "assembly: {C: [1.4, 0]}\n", "")
    text = edit(text, "  - {angle: 45, quantity: point.C.x, value: 1.4142136}\n", "")
    mech = build_mechanism(parse_spec(text, FILE))
    with pytest.raises(AssemblyError) as info:
        solve_kinematics(mech)
    assert str(info.value) == (f"{FILE}: the dyad B C C_T (rod, slider) cannot close at the "
                               "first reference angle 90 deg; check link lengths and `at`")
    # with a reference angle where it closes (|sin phi| <= 0.5), the other angles are flagged:
    # 30 deg is the lock itself (velocities unbounded), 40 deg lies beyond it
    mech = build_mechanism(parse_spec(edit(text, "at: [90]", "at: [0]"), FILE))
    kin = solve_kinematics(mech, [0, 10, 20, 30, 40])
    assert list(kin.angles) == [0, 10, 20]
    assert [(f.angle, f.kind) for f in kin.flags] == [(30, "near-singular"), (40, "unreachable")]
    assert kin.flags[1].reason == ("not reachable from the assembly: the mechanism locks "
                                   "between 30 and 31 deg")


# -- the command line ----------------------------------------------------------------------

def _cli(repo_root, *args):
    return subprocess.run([sys.executable, "-m", "mechreport.app.cli", *args], cwd=repo_root,
                          capture_output=True, text=True, timeout=60)


def test_cli_validate_bad_spec(tmp_path, repo_root):
    bad = tmp_path / "bad.yaml"
    text = edit(BASE, "    mass: 2\n", "    mass: heavy\n")
    bad.write_text(text, encoding="utf-8")
    run = _cli(repo_root, "validate", str(bad))
    assert run.returncode == 1
    assert run.stdout == ""
    assert run.stderr == (f"{bad}:{line_of(text, 'mass: heavy')}: links.rod.mass: must be a "
                          "positive number, got 'heavy'\n")


@pytest.mark.parametrize("text, fragment", [
    (edit(BASE, "    mass: 2\n", "    mass: 2: kg\n"), "malformed YAML"),
    (edit(BASE, "driver: {joint: A,", "driver: {joint: C_T,"), "a T driver drives its stroke"),
    (edit(edit(BASE, "C: [1, 0]}\n    mass: 2", "C: [0.5, 0]}\n    mass: 2"), "at: [45]",
          "at: [90]"), "cannot close at the first reference angle 90 deg"),
], ids=["malformed-yaml", "t-driver-with-rpm", "cannot-close"])
def test_cli_validate_reports_errors_without_traceback(tmp_path, repo_root, text, fragment):
    bad = tmp_path / "bad.yaml"
    bad.write_text(text, encoding="utf-8")
    good = repo_root / "specs" / "slider_crank.yaml"
    run = _cli(repo_root, "validate", str(good), str(bad))
    assert run.returncode == 1
    assert fragment in run.stderr
    assert "Traceback" not in run.stderr + run.stdout
    assert f"{good}: OK" in run.stdout        # other files are still validated


def test_cli_validate_missing_file(tmp_path, repo_root):
    run = _cli(repo_root, "validate", str(tmp_path / "nope.yaml"))
    assert run.returncode == 1
    assert "cannot read file" in run.stderr and "Traceback" not in run.stderr


def test_cli_validate_good_specs(repo_root):
    run = _cli(repo_root, "validate", "specs")
    assert run.returncode == 0, run.stderr
    assert run.stderr == ""
    assert "slider_crank.yaml: OK" in run.stdout


def test_a_force_load_whose_point_key_is_misspelt_is_reported_not_an_internal_error():
    """The loader read loads[i]["point"] before asking whether the models had refused the
    load (KeyError: 'point', reported as an internal error)."""
    text = edit(BASE, "point: C, value: [100, 0]", "pint: C, value: [100, 0]")
    messages = [f"{p.path}: {p.message}" for p in problems(text)]
    assert not any("internal" in m for m in messages), messages
    assert any("missing required key 'point'" in m for m in messages), messages
    assert any(m.startswith("loads[0].pint: unknown key") for m in messages), messages
