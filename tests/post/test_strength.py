"""Strength of the links (mechreport.post.strength) against closed forms: a beam at rest under
its weight, a uniformly rotating bar, the diagrams' ends against the joint reactions, the cut
seen from either side, Euler's and Johnson's column loads, and the modified Goodman line
against a worked example."""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from mechreport.errors import SpecError
from mechreport.pipeline.analysis import analyse
from mechreport.post.strength import (critical_load, goodman, internal_forces, link_members,
                                      point_actions, sides)
from mechreport.spec import Material, Section, parse_spec

STEEL = "materials:\n  steel: {E: 210e9, yield: 355e6, ultimate: 510e6, endurance: 240e6}\n"


def slider_crank(omega: float = 1.0, gravity: str = "[0, -10]", rod_mass: str = "1",
                 slider_mass: str = "1", load: bool = True, crank_mass: str = "1",
                 sweep: str = "{start: 0, stop: 360, step: 15}", extra: str = "") -> str:
    """Textbook 4.6's slider-crank (AB = BC = 1 m) with a section on the crank and the
    rod; bars whose inertia is that of their uniform members."""
    bar = "shape: {bar: {length: 1, height: 0.01, depth: 0.001}}"
    section = "section: {rect: {width: 0.001, height: 0.01}}\n    material: steel"

    def link(name, points, mass, shape=bar, sec=section):
        if mass == "0":
            return f"  {name}:\n    points: {points}\n    mass: 0\n    {sec}\n"
        return f"  {name}:\n    points: {points}\n    mass: {mass}\n    {shape}\n    {sec}\n"
    return (f"mechreport: 1.1\nname: test\ngravity: {gravity}\n" + STEEL
            + "ground: {A: [0, 0], O: [0, 0]}\nlinks:\n"
            + link("crank", "{A: [0, 0], B: [1, 0]}", crank_mass)
            + link("rod", "{B: [0, 0], C: [1, 0]}", rod_mass)
            + (f"  slider:\n    points: {{C: [0, 0]}}\n    mass: {slider_mass}\n"
               + ("" if slider_mass == "0" else
                  "    shape: {block: {width: 0.01, height: 0.01, depth: 0.001}}\n"))
            + "joints:\n  A: {type: R, links: [ground, crank]}\n"
              "  B: {type: R, links: [crank, rod]}\n  C: {type: R, links: [rod, slider]}\n"
              "  C_T: {type: T, links: [ground, slider], point: C, line: {through: O, "
              "direction: 0}}\n"
            + f"driver: {{joint: A, omega: {omega}}}\nsweep: {sweep}\nat: [45]\n"
              "assembly: {C: [1.4, 0]}\n"
            + ("loads:\n  - {type: force, link: slider, point: C, value: [100, 0], "
               "oppose: velocity}\n" if load else "")
            + extra)


def row(a, angle: float) -> int:
    return int(np.flatnonzero(np.isclose(a.angles, angle))[0])


def test_a_link_at_rest_under_gravity_is_a_beam_on_two_pins():
    """At rest, the rod carries its weight w = m g / L between its pins: M(s) = w cos(theta)
    s (L - s) / 2 and V = -dM/ds = -w cos(theta) (L - 2 s) / 2, whatever the slider and
    crank carry (they load the rod only at its ends)."""
    a = analyse(slider_crank(omega=0, load=False, sweep="{start: 20, stop: 70, step: 25}"))
    m = a.strength.members["rod"]
    d = m.diagram
    s, L = d.s, m.length
    w = 1 * 10 / L
    for k in range(a.n):
        c = math.cos(a.kinematics.theta[k, 2])
        np.testing.assert_allclose(d.M[k], w * c * s * (L - s) / 2, atol=1e-9)
        np.testing.assert_allclose(d.V[k], -w * c * (L - 2 * s) / 2, atol=1e-9)


def test_a_uniformly_rotating_bar_pinned_at_one_end_carries_its_centrifugal_force():
    """The crank alone has mass (the rod and the slider are massless, no gravity, no load):
    N(s) = m omega^2 (L^2 - s^2) / (2 L), no shear and no bending at constant speed."""
    omega = 3.0
    a = analyse(slider_crank(omega=omega, gravity="[0, 0]", rod_mass="0", slider_mass="0",
                             load=False, crank_mass="2"))
    d = a.strength.members["crank"].diagram
    L, s = 1.0, d.s
    np.testing.assert_allclose(d.N, np.broadcast_to(2 * omega ** 2 * (L ** 2 - s ** 2)
                                                    / (2 * L), d.N.shape), atol=1e-9)
    np.testing.assert_allclose(d.V, 0, atol=1e-9)
    np.testing.assert_allclose(d.M, 0, atol=1e-9)
    assert a.strength.members["crank"].buckling_safety is None     # never in compression
    assert "member.crank.buckling_safety" not in a.strength.values


def _frame(a, link):
    th = a.kinematics.theta[:, a.spec.number(link)]
    e = np.stack([np.cos(th), np.sin(th)], axis=1)
    return e, np.stack([-e[:, 1], e[:, 0]], axis=1)


def test_the_ends_of_each_diagram_are_the_joint_reactions_in_the_member_frame():
    """Rod B -> C: at B (s = 0) the rod's inside pushes back what the crank exerts, N e + V n
    = -F_B (joint B: crank on rod); at C (s = L), N e + V n = what the slider exerts on the
    rod, -F_C (joint C: rod on slider). M vanishes at both pins.
    The crank carries the motor torque M to its pin as bending: at A, M(0) is the moment
    about A of everything beyond the cut, which balances M: M(0) = -M."""
    a = analyse(slider_crank())
    res = a.forces[a.strength.method]
    e, n = _frame(a, "rod")
    d = a.strength.members["rod"].diagram
    FB = np.stack([res.reactions["B"].fx, res.reactions["B"].fy], axis=1)
    FC = np.stack([res.reactions["C"].fx, res.reactions["C"].fy], axis=1)
    np.testing.assert_allclose(d.N[:, 0], -np.sum(FB * e, axis=1), atol=1e-9)
    np.testing.assert_allclose(d.V[:, 0], -np.sum(FB * n, axis=1), atol=1e-9)
    np.testing.assert_allclose(d.N[:, -1], -np.sum(FC * e, axis=1), atol=1e-9)
    np.testing.assert_allclose(d.V[:, -1], -np.sum(FC * n, axis=1), atol=1e-9)
    np.testing.assert_allclose(d.M[:, [0, -1]], 0, atol=1e-9)
    crank = a.strength.members["crank"].diagram
    np.testing.assert_allclose(crank.M[:, 0], -res.driver_torque, atol=1e-9)
    # at the crank pin B, what the rod exerts on the crank: -F_B
    e, n = _frame(a, "crank")
    np.testing.assert_allclose(crank.N[:, -1], np.sum(-FB * e, axis=1), atol=1e-9)
    np.testing.assert_allclose(crank.V[:, -1], np.sum(-FB * n, axis=1), atol=1e-9)


def test_the_internal_forces_from_either_side_of_a_cut_agree():
    a = analyse(slider_crank(omega=2.5))
    ctx = a._context
    res = a.forces[a.strength.method]
    for name in ("crank", "rod"):
        link = a.spec.link(name)
        members = link_members(ctx, link)
        acts = point_actions(ctx, res, name, [(m.rP, m.e, m.L) for m in members])
        k = link.number
        g = np.asarray(a.spec.gravity)
        args = (members, acts, link.mass / members[0].L,
                link.strength.section.inertia / link.strength.section.area, g,
                a.kinematics.omega[:, k], a.kinematics.alpha[:, k], 0,
                np.array([0.13, 0.5, 0.77]), sides(link.strength.members))
        right, left = internal_forces(*args), internal_forces(*args, from_end=False)
        for x, y in ((right.N, left.N), (right.V, left.V), (right.M, left.M)):
            np.testing.assert_allclose(x, y, atol=1e-9 * max(1.0, np.abs(x).max()))


def test_stress_and_safety_factors_follow_from_the_diagrams():
    a = analyse(slider_crank(omega=2.0))
    m = a.strength.members["rod"]
    sec = m.section
    d = m.diagram
    stress = np.abs(d.N) / sec.area + np.abs(d.M) * sec.c / sec.inertia
    assert m.stress_max == pytest.approx(stress.max(), rel=1e-12)
    assert m.static_safety == pytest.approx(355e6 / stress.max(), rel=1e-12)
    assert a.strength.values["member.rod.stress_max"] == m.stress_max


def test_euler_load_of_a_pinned_column():
    """P_cr = pi^2 E I / L^2 (pinned-pinned) above the transition slenderness; Johnson's
    parabola below it, which meets Euler's curve at the transition (sigma = S_y / 2)."""
    mat = Material("steel", 210e9, 355e6, 240e6, 510e6)
    w, h = 0.012, 0.025
    sec = Section("rect", w * h, w * h ** 3 / 12, h / 2, h * w ** 3 / 12)
    r = math.sqrt(sec.inertia_min / sec.area)          # = w / sqrt(12)
    transition = math.pi * math.sqrt(2 * 210e9 / 355e6)
    L = 1.5 * transition * r
    p, slender, rule = critical_load(sec, mat, L)
    assert rule == "Euler" and slender == pytest.approx(L / r)
    assert p == pytest.approx(math.pi ** 2 * 210e9 * h * w ** 3 / 12 / L ** 2, rel=1e-12)
    p, _, rule = critical_load(sec, mat, 0.5 * transition * r)
    assert rule == "Johnson"
    sigma = 355e6 - (355e6 * 0.5 * transition / (2 * math.pi)) ** 2 / 210e9
    assert p == pytest.approx(sec.area * sigma, rel=1e-12)
    below, _, _ = critical_load(sec, mat, transition * r * (1 - 1e-9))
    assert below / sec.area == pytest.approx(355e6 / 2, rel=1e-6)


def test_goodman_against_a_worked_example():
    """Modified Goodman, sigma_a / S_e + sigma_m / S_ut = 1 / n (Shigley's Mechanical
    Engineering Design, eq. 6-46). Worked example of the fatigue life calculator at
    engineering-calculators.pages.dev/fatigue-life-calculator (per Shigley): sigma_a = 200
    MPa, sigma_m = 100 MPa, S_ut = 700 MPa (S_e' = 350 MPa), Marin factors giving
    S_e = 224.6 MPa: n = 0.97 ("UNSAFE")."""
    n = goodman(200e6, 100e6, 224.6e6, 700e6)
    assert float(n) == pytest.approx(0.97, abs=0.005)
    assert float(n) == pytest.approx(1 / (200 / 224.6 + 100 / 700), rel=1e-12)
    # a compressive mean stress does not shorten the life: n = S_e / sigma_a
    assert float(goodman(100e6, -50e6, 224.6e6, 700e6)) == pytest.approx(2.246)
    assert math.isinf(float(goodman(0.0, -5e6, 224.6e6, 700e6)))


def test_a_link_whose_com_is_off_its_members_says_so():
    text = slider_crank().replace(
        "    mass: 1\n    shape: {bar: {length: 1, height: 0.01, depth: 0.001}}\n"
        "    section: {rect: {width: 0.001, height: 0.01}}\n    material: steel\n"
        "  slider", "    mass: 1\n    com: [0.3, 0]\n    inertia: 0.1\n"
        "    section: {rect: {width: 0.001, height: 0.01}}\n    material: steel\n  slider")
    a = analyse(text)
    note = a.strength.members["rod"].note
    assert "centre of mass is 0.2 m from its members' middle" in note
    assert "inertia is 0.1 kg·m²" in note
    assert a.strength.members["crank"].note == ""


def test_member_quantities_exist_for_any_sweep_with_verdicts_and_expect():
    text = slider_crank(sweep="{start: 10, stop: 80, step: 10}", extra=(
        "design: {limits: {static_safety: 1e-6, buckling_safety: 1e-9}}\n"
        "expect:\n  - {quantity: member.rod.stress_max, value: 1, unit: MPa, tol: 1e9}\n"))
    a = analyse(text)
    assert a.review is None                       # not a whole turn: no cycle quantities
    assert all(e.ok for e in a.expectations)
    assert [v.item for v in a.verdicts] == ["limits.static_safety", "limits.buckling_safety"]
    assert all(v.passed for v in a.verdicts)


def spec_problems(text: str) -> list[str]:
    with pytest.raises(SpecError) as info:
        parse_spec(text, "x.yaml")
    return [f"{p.path}: {p.message}" for p in info.value.problems]


def test_strength_keys_are_checked_with_their_key_paths():
    text = slider_crank().replace("section: {rect: {width: 0.001, height: 0.01}}\n    "
                                  "material: steel\n  rod",
                                  "section: {tube: {d: 0.01, t: 0.006}}\n    material: "
                                  "stainless\n  rod", 1)
    got = spec_problems(text)
    assert any(m.startswith("links.crank.section.tube.t: a wall of 0.006") for m in got)
    assert any(m.startswith("links.crank.material: no material named 'stainless'")
               for m in got)
    got = spec_problems(slider_crank().replace("height: 0.01}}\n    material: steel\n  rod",
                                               "height: 0}}\n    material: steel\n  rod", 1))
    assert any(m.startswith("links.crank.section.rect.height: must be a positive number")
               for m in got)
    got = spec_problems(slider_crank().replace(
        "material: steel\n  rod", "material: steel\n    members: [[A, A]]\n  rod", 1))
    assert any("links.crank.members[0]: member [A, A] of link 'crank' has zero length" in m
               for m in got)
    got = spec_problems(slider_crank(extra="expect:\n  - {quantity: member.rod.stress, "
                                           "value: 1}\n  - {angle: 3, quantity: "
                                           "member.rod.stress_max, value: 1}\n"))
    assert any("'member.rod.stress': a member has stress_max" in m for m in got)
    assert any("expect[1].angle: 'member.rod.stress_max' is a cycle quantity" in m
               for m in got)


FOUR_BAR = (Path(__file__).resolve().parents[2] / "specs" / "four_bar.yaml").read_text()


def four_bar(members: str) -> str:
    """specs/four_bar.yaml with a massless coupler (so that its reactions balance its
    members' loads exactly) made of ``members``, carrying the process load at E."""
    text = FOUR_BAR.split("expect:")[0].replace("mechreport: 1\n", "mechreport: 1.1\n")
    text = text.replace("sweep: {start: 0, stop: 360, step: 1}",
                        "sweep: {start: 0, stop: 360, step: 20}")
    old = text[text.index("  coupler:"):text.index("  rocker:")]
    return text.replace(old, "  coupler:\n    points: {B: [0, 0], C: [180, 0], E: [90, 30]}\n"
                        "    mass: 0\n    section: {tube: {d: 12, t: 2}}\n"
                        "    material: {E: 70e9, yield: 270e6, ultimate: 310e6, "
                        f"endurance: 95e6}}\n    members: {members}\n")


@pytest.mark.parametrize("members", ["[[B, E], [E, C]]", "[[E, B], [C, E]]"])
def test_a_link_of_several_members_is_cut_as_a_tree(members):
    a = analyse(four_bar(members))
    names = sorted(a.strength.members)
    pairs = [tuple(p.strip() for p in pq.split(",")) for pq in members[2:-2].split("], [")]
    assert names == sorted(f"coupler.{p}_{q}" for p, q in pairs)
    assert all(f"member.{n}.stress_max" in a.strength.values for n in names)
    ctx, link = a._context, a.spec.link("coupler")
    res = a.forces[a.strength.method]
    members_ = link_members(ctx, link)
    acts = point_actions(ctx, res, "coupler", [(m.rP, m.e, m.L) for m in members_])
    g = np.asarray(a.spec.gravity)
    zero = np.zeros(a.n)
    for i, m in enumerate(members_):
        s = m.L * np.array([0.21, 0.5, 0.83])
        args = (members_, acts, 0.0, 1.0, g, zero, zero, i, s, sides(link.strength.members))
        right, left = internal_forces(*args), internal_forces(*args, from_end=False)
        for x, y in ((right.N, left.N), (right.V, left.V), (right.M, left.M)):
            np.testing.assert_allclose(x, y, atol=1e-9 * max(1.0, np.abs(x).max()))
    # at B, the member from B carries what the crank exerts on the coupler (joint B)
    which = next(i for i, (p, q) in enumerate(link.strength.members) if "B" in (p, q))
    p, q = link.strength.members[which]
    d = a.strength.members[f"coupler.{p}_{q}"].diagram
    FB = np.stack([res.reactions["B"].fx, res.reactions["B"].fy], axis=1)
    e = members_[which].e
    end = 0 if p == "B" else -1
    sign = -1.0 if p == "B" else 1.0      # at P: minus the load there; at Q: the load there
    np.testing.assert_allclose(d.N[:, end], sign * np.sum(FB * e, axis=1), atol=1e-9)


def test_members_that_close_a_loop_or_fall_apart_are_refused():
    got = spec_problems(four_bar("[[B, E], [E, C], [C, B]]"))
    assert any("links.coupler.members: the members close a loop" in m for m in got)
    got = spec_problems(four_bar("[[B, E]]").replace("points: {B: [0, 0], C: [180, 0], "
                                                     "E: [90, 30]}", "points: {B: [0, 0], "
                                                     "C: [180, 0], E: [90, 30], F: [0, 9]}")
                        .replace("members: [[B, E]]", "members: [[B, E], [C, F]]"))
    assert any("must join into one piece" in m for m in got)
    # a link with one joint point has no default member: list them
    text = slider_crank().replace("    mass: 1\n    shape: {block:", "    mass: 1\n    section: "
                                  "{round: {d: 0.01}}\n    material: steel\n    shape: {block:")
    got = spec_problems(text)
    assert any("links.slider.section: link 'slider' has 1 joint points (C): list its "
               "straight members" in m for m in got)


def test_a_buckling_limit_with_no_member_in_compression_passes_and_says_why():
    """The spinning crank of a massless rod and slider is only ever in tension."""
    a = analyse(slider_crank(omega=3.0, gravity="[0, 0]", rod_mass="0", slider_mass="0",
                             load=False, crank_mass="2",
                             extra="design: {limits: {buckling_safety: 3}}\n"))
    (v,) = a.verdicts
    assert v.passed and v.value is None and v.why == "no member is in compression"
    assert v.describe() == "limits.buckling_safety: passes: no member is in compression"


def test_strength_limits_fail_where_no_method_solved_the_reactions():
    a = analyse(slider_crank(extra="design: {limits: {static_safety: 1e-9}}\n"),
                methods=["power"])
    assert a.strength is None
    (v,) = a.verdicts
    assert not v.passed and "need the joint reactions" in v.why


def test_section_sizes_are_in_the_length_unit_and_area_inertia_c_give_the_same_stress():
    """The press (mm): the rod's 12 x 20 rectangle written as {area: 240, inertia: 8000,
    c: 10} (mm², mm⁴, mm) gives the same stresses; its buckling then uses the in-plane
    inertia, the only one given, I = 8000 mm⁴: L / r = 400 / sqrt(8000 / 240) = 69.3, below
    the transition pi sqrt(2 E / S_y) = 92.0, so Johnson's A (S_y - (S_y L / (2 pi r))^2 /
    E)."""
    text = (Path(__file__).resolve().parents[2] / "specs" / "crank_press_strength.yaml"
            ).read_text().replace("sweep: {start: 0, stop: 360, step: 1}",
                                  "sweep: {start: 0, stop: 360, step: 5}")
    rect = analyse(text).strength.members["rod"]
    given = analyse(text.replace("section: {rect: {width: 12, height: 20}}",
                                 "section: {area: 240, inertia: 8000, c: 10}"))
    rod = given.strength.members["rod"]
    assert rod.section.area == pytest.approx(240e-6) and rod.section.c == pytest.approx(0.01)
    assert rod.stress_max == pytest.approx(rect.stress_max, rel=1e-12)
    assert rod.fatigue_safety == pytest.approx(rect.fatigue_safety, rel=1e-12)
    slender = 400 / math.sqrt(8000 / 240)
    assert rod.buckling_rule == "Johnson" and rod.slenderness == pytest.approx(slender)
    assert rod.critical_load == pytest.approx(
        240e-6 * (490e6 - (490e6 * slender / (2 * math.pi)) ** 2 / 210e9), rel=1e-12)
