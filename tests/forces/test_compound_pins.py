"""Pins joining several links (format 1.1): `{type: R, links: [a, b, c]}` is one pin; its
force on each link (`joint.C.on.<link>`) sums to zero over the links and equals what the same
mechanism gives written with coincident two-link joints, by every method."""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import mechreport
from mechreport.errors import SpecError
from mechreport.spec import parse_spec

ROOT = Path(__file__).resolve().parents[2]
PIN = (ROOT / "tests" / "data" / "compound_pin_six_bar.yaml").read_text(encoding="utf-8")
LINKS = ("coupler", "rocker", "rod")


def _twin(second_pair: tuple[str, str]) -> str:
    """The six-bar written with two coincident two-link joints at C: C (coupler, rocker)
    and C2 joining ``second_pair`` (the rod to the coupler, or to the rocker)."""
    text = PIN.replace("C: {type: R, links: [coupler, rocker, rod]}",
                       "C: {type: R, links: [coupler, rocker]}\n"
                       f"  C2: {{type: R, links: [{second_pair[0]}, {second_pair[1]}]}}")
    point = {"coupler": "C2: [180, 0]", "rocker": "C2: [120, 0]"}[second_pair[0]]
    own = {"coupler": "{B: [0, 0], C: [180, 0]}", "rocker": "{D: [0, 0], C: [120, 0]}"}
    text = text.replace(own[second_pair[0]], own[second_pair[0]][:-1] + f", {point}}}")
    return text.replace("{C: [0, 0], E: [200, 0]}", "{C2: [0, 0], E: [200, 0]}")


@pytest.fixture(scope="module")
def pinned():
    return mechreport.analyse(PIN)


def test_the_pins_forces_on_its_links_sum_to_zero(pinned):
    assert pinned.passed
    for name, res in pinned.forces.items():
        if not res.reactions:
            continue
        assert [k for k in res.reactions if k.startswith("C.")] == \
            [f"C.on.{x}" for x in LINKS], name
        for axis in ("fx", "fy"):
            total = sum(getattr(res.reactions[f"C.on.{x}"], axis) for x in LINKS)
            scale = max(np.max(np.abs(getattr(res.reactions[f"C.on.{x}"], axis)))
                        for x in LINKS)
            np.testing.assert_allclose(total, 0, atol=1e-12 * scale, err_msg=name)


@pytest.mark.parametrize("pair", [("coupler", "rod"), ("rocker", "rod")])
def test_a_pin_equals_coincident_two_link_joints(pinned, pair):
    twin = mechreport.analyse(_twin(pair))
    np.testing.assert_array_equal(twin.angles, pinned.angles)
    for name, res in pinned.forces.items():
        other = twin.forces[name]
        scale = np.max(np.abs(res.driver_torque))
        np.testing.assert_allclose(res.driver_torque, other.driver_torque, rtol=0,
                                   atol=1e-9 * scale, err_msg=name)
        if not res.reactions:
            continue
        c, c2 = other.reactions["C"], other.reactions["C2"]
        # the force on each link at C, from the twin's two joints (first link on second)
        on = {"rocker": (c.fx, c.fy) if pair[0] == "coupler" else (c.fx - c2.fx, c.fy - c2.fy),
              "rod": (c2.fx, c2.fy),
              "coupler": (-c.fx - (c2.fx if pair[0] == "coupler" else 0),
                          -c.fy - (c2.fy if pair[0] == "coupler" else 0))}
        for link in LINKS:
            r = res.reactions[f"C.on.{link}"]
            big = np.max(np.abs(np.concatenate(on[link])))
            np.testing.assert_allclose([r.fx, r.fy], on[link], rtol=0, atol=1e-9 * big,
                                       err_msg=f"{name}: C.on.{link}")
        for joint in ("A", "B", "D", "E", "S"):
            np.testing.assert_allclose(res.reactions[joint].f, other.reactions[joint].f,
                                       rtol=1e-9, atol=1e-9 * scale, err_msg=joint)


def test_expect_reads_a_pins_force_on_each_link_and_a_joints_on_either_link(pinned):
    res = pinned.forces["dyad"]
    k = int(np.flatnonzero(pinned.angles == 30)[0])
    lines = [f"  - {{angle: 30, quantity: joint.C.on.{x}.fx, value: "
             f"{float(res.reactions[f'C.on.{x}'].fx[k])!r}, tol: 1e-9}}" for x in LINKS]
    lines += [f"  - {{angle: 30, quantity: joint.B.on.coupler.fy, value: "
              f"{float(res.reactions['B'].fy[k])!r}, tol: 1e-9}}",
              f"  - {{angle: 30, quantity: joint.B.on.crank.fy, value: "
              f"{-float(res.reactions['B'].fy[k])!r}, tol: 1e-9}}",
              f"  - {{angle: 30, quantity: joint.C.on.coupler.f, value: "
              f"{float(res.reactions['C.on.coupler'].f[k])!r}, tol: 1e-9}}"]
    checked = mechreport.analyse(PIN + "expect:\n" + "\n".join(lines) + "\n")
    assert checked.passed
    assert len(checked.expectations) == 4 * len(lines)      # by each force method


def test_results_list_the_pins_force_on_every_link(pinned):
    names = [c.name for c in pinned.columns()]
    for x in LINKS:
        assert f"dyad.joint.C.on.{x}.fx [N]" in names
    assert "dyad.joint.C.fx [N]" not in names


@pytest.mark.parametrize("edit, path, words", [
    (("quantity: ", "quantity: joint.C.fx"), "expect[0].quantity",
     "joint.C.on.coupler.fx, joint.C.on.rocker.fx, joint.C.on.rod.fx"),
    (("quantity: ", "quantity: joint.C.on.crank.fx"), "expect[0].quantity",
     "joins coupler, rocker, rod, not 'crank'"),
    (("quantity: ", "quantity: joint.C.on.rod.moment"), "expect[0].quantity", "fx, fy, f"),
    (("[coupler, rocker, rod]", "[coupler, rocker, coupler]"), "joints.C.links",
     "lists coupler twice"),
    (("[coupler, rocker, rod]", "[coupler, rocker, rods]"), "joints.C.links[2]",
     "unknown link 'rods'"),
    (("loads:\n", "loads:\n  - {type: torsion_spring, joint: C, stiffness: 2, free_angle: 0}\n"),
     "loads[0].joint", "name one of 'C.on.rocker' (coupler and rocker), 'C.on.rod'"),
    (("expect:\n", "design: {bearings: {C: {rating: 5000}}}\nexpect:\n"),
     "design.bearings.C", "a bearing sits between two of them; name one of 'C.on.rocker'"),
])
def test_mistakes_with_a_pin_are_reported_where_they_are(edit, path, words):
    text = PIN + "expect:\n  - {angle: 30, quantity: driver.torque, value: 1}\n"
    old, new = edit
    assert old in text, "the edit finds nothing to change"
    text = text.replace(old, new, 1) if old != "quantity: " else \
        text.replace("quantity: driver.torque", new)
    with pytest.raises(SpecError) as info:
        parse_spec(text, "pin.yaml")
    found = [p for p in info.value.problems if p.path == path]
    assert found and words in found[0].message, info.value.problems


COAXIAL = """\
mechreport: 1.1
name: a lever on the crank's pivot
units: {length: mm, mass: kg}
ground: {A: [0, 0], D: [200, 0]}
links:
  crank:   {points: {A: [0, 0], B: [50, 0]}, mass: 0.4, com: [25, 0], inertia: 1.0e-4}
  coupler: {points: {B: [0, 0], C: [180, 0]}, mass: 1.2, com: [90, 0], inertia: 3.0e-3}
  rocker:  {points: {D: [0, 0], C: [120, 0], E: [60, 0]}, mass: 0.8, com: [60, 0],
            inertia: 1.0e-3}
  link5:   {points: {E: [0, 0], F: [150, 0]}, mass: 0.3, com: [75, 0], inertia: 6.0e-4}
  lever:   {points: {A: [0, 0], F: [100, 0]}, mass: 0.5, com: [50, 0], inertia: 5.0e-4}
joints:
  A: {type: R, links: [ground, crank, lever]}
  B: {type: R, links: [crank, coupler]}
  C: {type: R, links: [coupler, rocker]}
  D: {type: R, links: [ground, rocker]}
  E: {type: R, links: [rocker, link5]}
  F: {type: R, links: [link5, lever]}
driver: {joint: A, rpm: 120}
sweep: {start: 0, stop: 360, step: 10}
assembly: {C: [196, 120], F: [60, 80]}
"""


def test_a_pin_on_the_frame_may_drive_its_first_two_links():
    """Two links pivoted on one ground pin, the first of them driven: the driver turns the
    crank (the pin's second link) against the frame (its first), as the twin with two ground
    pins at one place does."""
    pinned = mechreport.analyse(COAXIAL)
    twin = mechreport.analyse(COAXIAL.replace(
        "A: {type: R, links: [ground, crank, lever]}",
        "A: {type: R, links: [ground, crank]}\n  A2: {type: R, links: [ground, lever]}")
        .replace("ground: {A: [0, 0], D: [200, 0]}", "ground: {A: [0, 0], A2: [0, 0], "
                 "D: [200, 0]}").replace("{A: [0, 0], F: [100, 0]}", "{A2: [0, 0], F: [100, 0]}"))
    assert pinned.passed and twin.passed
    assert pinned.spec.driver.link == "crank"
    for name, res in pinned.forces.items():
        other = twin.forces[name]
        scale = np.max(np.abs(res.driver_torque))
        np.testing.assert_allclose(res.driver_torque, other.driver_torque, atol=1e-9 * scale)
        if res.reactions:
            np.testing.assert_allclose(res.reactions["A.on.lever"].fx,
                                       other.reactions["A2"].fx, atol=1e-9 * scale)
            np.testing.assert_allclose(res.reactions["A.on.ground"].fy,
                                       -other.reactions["A"].fy - other.reactions["A2"].fy,
                                       atol=1e-9 * scale)


def test_a_torsion_spring_and_a_bearing_sit_at_one_link_of_a_pin():
    """`C.on.rod` names the pin's joint between its hub (the coupler) and the rod: a torsion
    spring there acts between those two links, a bearing there carries the pin's force on the
    rod."""
    text = PIN.replace("loads:\n", "loads:\n  - {type: torsion_spring, joint: C.on.rod, "
                                    "stiffness: 2, free_angle: 0, name: spring}\n")
    text += "design: {bearings: {C.on.rod: {rating: 5000}}}\n"
    spec = parse_spec(text, "pin.yaml")
    spring = next(ld for ld in spec.loads if ld.label == "spring")
    assert spring.joint == "C.on.rod" and spring.link == "rod"
    assert set(spec.design.bearings) == {"C.on.rod"}
