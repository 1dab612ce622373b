"""Kinematics pinned to the textbook (Marghitu, Dynamic Force Analysis, sections 4.6 and 4.7)
and to closed forms derived independently here.

Where the text is wrong (a known erratum of the chapter) the comment says so and the test uses the
correct value.
"""
from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from mechreport.kinematics import solve_kinematics
from mechreport.model import build_mechanism
from mechreport.spec import Sweep

S2 = math.sqrt(2.0)
EXACT = 1e-12      # closed forms against the solver
PRINTED = 1e-3     # three-decimal values printed by the text (truncated, not rounded: ERRATA)


# -- helpers -------------------------------------------------------------------------------

def perp(v):
    return np.array([-v[1], v[0]])


def cross(a, b) -> float:
    return float(a[0] * b[1] - a[1] * b[0])


def wrap_deg(angle: float) -> float:
    """Angle in (-180, 180] degrees."""
    a = math.fmod(angle, 360.0)
    a = a - 360.0 if a > 180.0 else a
    return a + 360.0 if a <= -180.0 else a


def rate_of_angle(d, dd, ddd):
    """Angle of a vector d(t) and its first two time derivatives, from d, d', d'':
    theta' = (d x d')/|d|^2, theta'' = (d x d'')/|d|^2 - 2 (d . d') theta'/|d|^2."""
    n2 = float(d @ d)
    w = cross(d, dd) / n2
    return math.atan2(d[1], d[0]), w, cross(d, ddd) / n2 - 2.0 * float(d @ dd) * w / n2


def tool_value(spec, kin, quantity: str, angle: float) -> float:
    """The solver's value of a kinematic ``expect`` quantity (point.* or link.*)."""
    k = kin.index_of(angle)
    assert k is not None, f"{angle} deg was left out: {kin.flags}"
    kind, name, attr = quantity.split(".")
    if kind == "point":
        p = kin.named_point(name)
        return {"x": p.r[k, 0], "y": p.r[k, 1], "vx": p.v[k, 0], "vy": p.v[k, 1],
                "ax": p.a[k, 0], "ay": p.a[k, 1]}[attr]
    j = spec.number(name)
    return {"angle": wrap_deg(math.degrees(kin.theta[k, j])), "omega": kin.omega[k, j],
            "alpha": kin.alpha[k, j]}[attr]


# -- 4.6 slider-crank at phi = 45 deg ------------------------------------------------------

@pytest.fixture(scope="module")
def kin46(textbook_specs, mechanisms):
    mech = mechanisms(textbook_specs["4.6"])
    return mech.spec, solve_kinematics(mech, [44.0, 45.0, 46.0])


def test_4_6_positions_at_45_deg(kin46):
    spec, kin = kin46
    k = kin.at(45)
    B, C = kin.named_point("B"), kin.named_point("C")
    assert B.r[k] == pytest.approx([S2 / 2, S2 / 2], abs=EXACT)     # r_B = sqrt2/2 (i + j)
    assert C.r[k] == pytest.approx([S2, 0.0], abs=EXACT)            # r_C = sqrt2 i
    assert math.degrees(kin.theta[k, spec.number("rod")]) == pytest.approx(-45.0, abs=1e-10)
    assert kin.theta[k, spec.number("slider")] == pytest.approx(0.0, abs=EXACT)


def test_4_6_velocities_at_45_deg(kin46):
    spec, kin = kin46
    k = kin.at(45)
    assert kin.named_point("B").v[k] == pytest.approx([-S2 / 2, S2 / 2], abs=EXACT)
    assert kin.named_point("C").v[k] == pytest.approx([-S2, 0.0], abs=EXACT)   # v_C = -sqrt2 i
    assert kin.omega[k, spec.number("crank")] == pytest.approx(1.0, abs=EXACT)  # 30/pi rpm
    assert kin.omega[k, spec.number("rod")] == pytest.approx(-1.0, abs=EXACT)   # omega2 = -1
    assert kin.omega[k, spec.number("slider")] == pytest.approx(0.0, abs=EXACT)


def test_4_6_accelerations_at_45_deg(kin46):
    spec, kin = kin46
    k = kin.at(45)
    assert kin.named_point("B").a[k] == pytest.approx([-S2 / 2, -S2 / 2], abs=EXACT)
    assert kin.named_point("C").a[k] == pytest.approx([-S2, 0.0], abs=EXACT)   # a_C = -sqrt2 i
    assert kin.alpha[k, spec.number("crank")] == pytest.approx(0.0, abs=EXACT)
    assert kin.alpha[k, spec.number("rod")] == pytest.approx(0.0, abs=EXACT)    # alpha2 = 0


def test_4_6_centres_of_mass_at_45_deg(kin46):
    _, kin = kin46
    k = kin.at(45)
    assert kin.com("crank").r[k] == pytest.approx([S2 / 4, S2 / 4], abs=EXACT)
    assert kin.com("rod").r[k] == pytest.approx([3 * S2 / 4, S2 / 4], abs=EXACT)
    assert kin.com("slider").r[k] == pytest.approx([S2, 0.0], abs=EXACT)
    assert kin.com("crank").a[k] == pytest.approx([-S2 / 4, -S2 / 4], abs=EXACT)
    assert kin.com("rod").a[k] == pytest.approx([-3 * S2 / 4, -S2 / 4], abs=EXACT)
    assert kin.com("slider").a[k] == pytest.approx([-S2, 0.0], abs=EXACT)


# -- 4.6 slider-crank over the whole sweep: singular at 90 and 270 deg ----------------------

def test_4_6_sweep_flags_exactly_90_and_270_deg(textbook_specs, mechanisms):
    mech = mechanisms(textbook_specs["4.6"])
    kin = solve_kinematics(mech)
    # AB = BC: at 90 and 270 deg the slider sits on A and the rod lies along the crank, where
    # the velocity equations are singular (ERRATA, 4.6). Nothing else is left out.
    assert [f.angle for f in kin.flags] == [90.0, 270.0]
    assert all("singular" in f.reason for f in kin.flags)
    expected = [a for a in range(360) if a not in (90, 270)]
    assert kin.angles.tolist() == expected


def test_4_6_sweep_slider_continues_smoothly_through_the_singular_angles(textbook_specs,
                                                                         mechanisms):
    # The branch picked at 45 deg has the rod as the crank's mirror image (rod angle -phi), so
    # x_C = 2 cos(phi) all the way round: through 90 and 270 deg the slider passes A and goes
    # on to negative x instead of folding back (the other root, x_C = 0 for 90 < phi < 270).
    mech = mechanisms(textbook_specs["4.6"])
    kin = solve_kinematics(mech)
    phi = np.radians(kin.angles)
    C = kin.named_point("C")
    assert np.max(np.abs(C.r[:, 0] - 2 * np.cos(phi))) < 1e-12
    assert np.max(np.abs(C.r[:, 1])) < 1e-12
    assert np.max(np.abs(C.v[:, 0] + 2 * np.sin(phi))) < 1e-9        # omega = 1 rad/s
    assert np.max(np.abs(C.a[:, 0] + 2 * np.cos(phi))) < 1e-9
    rod = mech.spec.number("rod")
    assert np.max(np.abs(np.angle(np.exp(1j * (kin.theta[:, rod] + phi))))) < 1e-12
    assert np.max(np.abs(kin.omega[:, rod] + 1.0)) < 1e-9
    # angles asked for on their own follow the same branch (not the hint at their own angle)
    alone = solve_kinematics(mech, [120.0])
    assert alone.named_point("C").r[0] == pytest.approx([-1.0, 0.0], abs=1e-12)
    # near the singular angles, too
    near = solve_kinematics(mech, [89.5, 90.5, 269.5, 270.5])
    assert near.angles.tolist() == [89.5, 90.5, 269.5, 270.5]
    assert near.named_point("C").r[:, 0] == pytest.approx(2 * np.cos(np.radians(near.angles)),
                                                          abs=1e-12)
    # closer than that, accelerations are not trustworthy to 1e-6: flagged, not reported
    closer = solve_kinematics(mech, [89.99, 90.01, 269.99, 270.01])
    assert closer.n == 0
    assert {f.kind for f in closer.flags} == {"near-singular"}


@pytest.mark.parametrize("step", range(2, 13))
def test_4_6_coarser_sweeps_continue_through_the_touch_points(step, textbook_specs, mechanisms):
    # The same continuation with coarser sweeps, whether or not 90 and 270 lie on the grid
    # (steps of 7 and 8 used to flip twice in a row and fold the slider back onto A).
    spec = mechanisms(textbook_specs["4.6"]).spec
    coarse = replace(spec, sweep=Sweep(0.0, 360.0, float(step)), expect=())
    kin = solve_kinematics(build_mechanism(coarse))
    on_grid = [a for a in (90, 270) if a % step == 0]
    assert [f.angle for f in kin.flags] == on_grid
    x = kin.named_point("C").r[:, 0]
    assert np.max(np.abs(x - 2 * np.cos(np.radians(kin.angles)))) < 1e-12


# -- 4.7 R-RTR-RTR at phi = 30 deg ---------------------------------------------------------

def closed_form_4_7(phi_deg: float, n_rpm: float = 50.0):
    """Section 4.7 kinematics derived from scratch: A origin, C = (0, AC), E = (0, -AE);
    link 3 passes through B (slider 2) and pivots at C, with D on the far side of C from B;
    link 5 passes through D (slider 4) and pivots at E."""
    AB, AC, AE, CD, DF, EG = 0.14, 0.06, 0.25, 0.15, 0.4, 0.5
    w1 = n_rpm * math.pi / 30
    phi = math.radians(phi_deg)
    rC, rE = np.array([0.0, AC]), np.array([0.0, -AE])
    rB = AB * np.array([math.cos(phi), math.sin(phi)])
    vB, aB = w1 * perp(rB), -w1**2 * rB
    th3, w3, al3 = rate_of_angle(rB - rC, vB, aB)              # link 3 is along C -> B
    u3 = np.array([math.cos(th3), math.sin(th3)])
    rD = rC - CD * u3
    vD = -CD * w3 * perp(u3)
    aD = -CD * (al3 * perp(u3) - w3**2 * u3)
    rF = rD + DF * u3
    aF = (DF - CD) * (al3 * perp(u3) - w3**2 * u3)
    th5, w5, al5 = rate_of_angle(rD - rE, vD, aD)              # link 5 is along E -> D
    u5 = np.array([math.cos(th5), math.sin(th5)])
    rG = rE + EG * u5
    vG = EG * w5 * perp(u5)
    aG = EG * (al5 * perp(u5) - w5**2 * u5)
    return dict(rB=rB, rD=rD, rF=rF, rG=rG, vB=vB, vD=vD, vG=vG, aB=aB, aD=aD, aF=aF, aG=aG,
                phi3=math.degrees(th3), w3=w3, al3=al3, phi5=math.degrees(th5), w5=w5, al5=al5)


@pytest.fixture(scope="module")
def kin47(textbook_specs, mechanisms):
    mech = mechanisms(textbook_specs["4.7"])
    kin = solve_kinematics(mech, [29.0, 30.0, 31.0])
    return mech.spec, kin, kin.at(30)


def test_4_7_positions_at_30_deg(kin47):
    spec, kin, k = kin47
    # textbook: r_B = 0.121 i + 0.070 j, r_D = -0.149 i + 0.047 j, r_F = 0.249 i + 0.080 j,
    # r_G = -0.224 i + 0.196 j (truncated to three decimals: G is 0.19682)
    assert kin.named_point("B").r[k] == pytest.approx([0.121, 0.070], abs=PRINTED)
    assert kin.named_point("D").r[k] == pytest.approx([-0.149, 0.047], abs=PRINTED)
    assert kin.named_point("F").r[k] == pytest.approx([0.249, 0.080], abs=PRINTED)
    assert kin.named_point("G").r[k] == pytest.approx([-0.224, 0.196], abs=PRINTED)
    ref = closed_form_4_7(30)
    for p in "BDFG":
        assert kin.named_point(p).r[k] == pytest.approx(ref["r" + p], abs=EXACT), p
    # D is on both link 3 and slider 4, B on link 1 and slider 2: the same point
    assert kin.named_point("D", "slider4").r[k] == pytest.approx(ref["rD"], abs=EXACT)
    assert kin.named_point("B", "slider2").r[k] == pytest.approx(ref["rB"], abs=EXACT)


def test_4_7_link_angles_at_30_deg(kin47):
    spec, kin, k = kin47
    ref = closed_form_4_7(30)
    deg = np.degrees(kin.theta[k])
    # phi2 = phi3 = 4.715 deg
    assert deg[spec.number("slider2")] == pytest.approx(4.715, abs=PRINTED)
    assert deg[spec.number("link3")] == pytest.approx(4.715, abs=PRINTED)
    # phi4 = phi5: the text prints 16.666 deg, a typo for 116.666 deg (ERRATA): G = E + EG
    # (cos phi5, sin phi5) must come out at -0.224 i + 0.196 j, which needs 116.666 deg.
    assert deg[spec.number("slider4")] == pytest.approx(116.666, abs=PRINTED)
    assert deg[spec.number("link5")] == pytest.approx(116.666, abs=PRINTED)
    g = np.array([0.0, -0.25]) + 0.5 * np.array([math.cos(math.radians(116.666)),
                                                  math.sin(math.radians(116.666))])
    assert g == pytest.approx([-0.224, 0.196], abs=PRINTED)
    g_typo = np.array([0.0, -0.25]) + 0.5 * np.array([math.cos(math.radians(16.666)),
                                                       math.sin(math.radians(16.666))])
    assert abs(g_typo[0] - (-0.224)) > 0.1        # the printed 16.666 cannot be right
    assert deg[spec.number("link3")] == pytest.approx(ref["phi3"], abs=1e-10)
    assert deg[spec.number("link5")] == pytest.approx(ref["phi5"], abs=1e-10)


def test_4_7_angular_velocities_and_accelerations_at_30_deg(kin47):
    spec, kin, k = kin47
    ref = closed_form_4_7(30)
    n = spec.number
    assert kin.omega[k, n("link1")] == pytest.approx(50 * math.pi / 30, abs=EXACT)
    assert kin.alpha[k, n("link1")] == pytest.approx(0.0, abs=EXACT)           # alpha1 = 0
    assert kin.omega[k, n("link5")] == pytest.approx(0.917, abs=PRINTED)       # omega5
    assert kin.alpha[k, n("link3")] == pytest.approx(14.568, abs=PRINTED)      # alpha3
    assert kin.alpha[k, n("link5")] == pytest.approx(-5.771, abs=PRINTED)      # alpha5
    # sliders turn with their guides: omega2 = omega3, alpha2 = alpha3, omega4 = omega5, ...
    for slider, guide in (("slider2", "link3"), ("slider4", "link5")):
        assert kin.omega[k, n(slider)] == pytest.approx(kin.omega[k, n(guide)], abs=EXACT)
        assert kin.alpha[k, n(slider)] == pytest.approx(kin.alpha[k, n(guide)], abs=EXACT)
    assert kin.omega[k, n("link3")] == pytest.approx(ref["w3"], abs=EXACT)
    assert kin.alpha[k, n("link3")] == pytest.approx(ref["al3"], abs=1e-10)
    assert kin.omega[k, n("link5")] == pytest.approx(ref["w5"], abs=EXACT)
    assert kin.alpha[k, n("link5")] == pytest.approx(ref["al5"], abs=1e-10)


def test_4_7_point_accelerations_at_30_deg(kin47):
    spec, kin, k = kin47
    # textbook (truncated): a_B = -3.323 i - 1.919 j (-3.32396 exactly: ERRATA),
    # a_D = 4.617 i - 1.811 j, a_F = -7.695 i + 3.019 j, a_G = 2.767 i + 0.919 j
    assert kin.named_point("B").a[k] == pytest.approx([-3.323, -1.919], abs=PRINTED)
    assert kin.named_point("D").a[k] == pytest.approx([4.617, -1.811], abs=PRINTED)
    assert kin.named_point("F").a[k] == pytest.approx([-7.695, 3.019], abs=PRINTED)
    assert kin.named_point("G").a[k] == pytest.approx([2.767, 0.919], abs=PRINTED)
    ref = closed_form_4_7(30)
    for p in "BDFG":
        assert kin.named_point(p).a[k] == pytest.approx(ref["a" + p], abs=1e-10), p
    for p in "BDG":
        assert kin.named_point(p).v[k] == pytest.approx(ref["v" + p], abs=EXACT), p


def test_4_7_centres_of_mass_at_30_deg(kin47):
    spec, kin, k = kin47
    # r_C1 = 0.060 i + 0.035 j, r_C3 = 0.049 i + 0.064 j, r_C5 = -0.112 i - 0.026 j;
    # a_C1 = -1.661 i - 0.959 j, a_C3 = -1.539 i + 0.603 j, a_C5 = 1.383 i + 0.459 j
    assert kin.com("link1").r[k] == pytest.approx([0.060, 0.035], abs=PRINTED)
    assert kin.com("link3").r[k] == pytest.approx([0.049, 0.064], abs=PRINTED)
    assert kin.com("link5").r[k] == pytest.approx([-0.112, -0.026], abs=PRINTED)
    assert kin.com("link1").a[k] == pytest.approx([-1.661, -0.959], abs=PRINTED)
    assert kin.com("link3").a[k] == pytest.approx([-1.539, 0.603], abs=PRINTED)
    assert kin.com("link5").a[k] == pytest.approx([1.383, 0.459], abs=PRINTED)
    assert kin.com("slider2").a[k] == pytest.approx([-3.323, -1.919], abs=PRINTED)
    assert kin.com("slider4").a[k] == pytest.approx([4.617, -1.811], abs=PRINTED)


def test_4_7_sweep_follows_the_assembly_branch(textbook_specs, mechanisms):
    # The listing's atan puts links 3 and 5 on the wrong side for 90 < phi < 270 (ERRATA);
    # the solver follows the branch of the reference angle: D stays on the far side of C from
    # B and G on the side of D, all the way round, and nothing is flagged.
    mech = mechanisms(textbook_specs["4.7"])
    kin = solve_kinematics(mech)
    assert kin.flags == ()
    assert kin.angles.tolist() == list(range(360))
    for k in range(0, 360, 7):
        ref = closed_form_4_7(float(kin.angles[k]))
        for p in "BDFG":
            assert kin.named_point(p).r[k] == pytest.approx(ref["r" + p], abs=1e-12), (k, p)
        assert kin.named_point("G").a[k] == pytest.approx(ref["aG"], abs=1e-9), k


# -- the new specs: closed forms derived by hand -------------------------------------------

def four_bar_closed_form(phi_deg, w1, AB=0.05, BC=0.18, DC=0.12, D=(0.2, 0.0),
                         E_local=(0.09, 0.03)):
    """specs/four_bar.yaml: C from the circles |C - B| = BC, |C - D| = DC (the open branch,
    C to the left of B -> D); rates from the loop v_B + omega2 k x BC = omega3 k x DC and its
    derivative, each a 2x2 linear system."""
    phi = math.radians(phi_deg)
    D = np.asarray(D)
    B = AB * np.array([math.cos(phi), math.sin(phi)])
    vB, aB = w1 * perp(B), -w1**2 * B
    d = D - B
    dist = math.hypot(*d)
    a = (BC**2 - DC**2 + dist**2) / (2 * dist)
    e = d / dist
    C = B + a * e + math.sqrt(BC**2 - a**2) * perp(e)
    bc, dc = C - B, C - D
    M = np.column_stack([perp(bc), -perp(dc)])
    w2, w3 = np.linalg.solve(M, -vB)
    al2, al3 = np.linalg.solve(M, -aB + w2**2 * bc - w3**2 * dc)
    th2 = math.atan2(bc[1], bc[0])
    rot = np.array([[math.cos(th2), -math.sin(th2)], [math.sin(th2), math.cos(th2)]])
    e_rel = rot @ np.asarray(E_local)
    E = B + e_rel
    out = {"point.C.x": C[0], "point.C.y": C[1], "link.coupler.angle": math.degrees(th2),
           "link.rocker.angle": math.degrees(math.atan2(dc[1], dc[0])),
           "link.coupler.omega": w2, "link.rocker.omega": w3,
           "link.coupler.alpha": al2, "link.rocker.alpha": al3}
    vC, aC = vB + w2 * perp(bc), aB + al2 * perp(bc) - w2**2 * bc
    vE, aE = vB + w2 * perp(e_rel), aB + al2 * perp(e_rel) - w2**2 * e_rel
    for name, p, v, acc in (("C", C, vC, aC), ("E", E, vE, aE)):
        out.update({f"point.{name}.x": p[0], f"point.{name}.y": p[1],
                    f"point.{name}.vx": v[0], f"point.{name}.vy": v[1],
                    f"point.{name}.ax": acc[0], f"point.{name}.ay": acc[1]})
    return out


def offset_slider_crank_closed_form(phi_deg, w1, r=0.025, l=0.095, e=0.010):
    """specs/offset_slider_crank.yaml: vertical guide x = e, piston above the crank:
    y_C = y_B + s with s = sqrt(l^2 - (e - x_B)^2), differentiated twice by hand."""
    phi = math.radians(phi_deg)
    xB, yB = r * math.cos(phi), r * math.sin(phi)
    vBx, vBy = -w1 * yB, w1 * xB
    aBx, aBy = -w1**2 * xB, -w1**2 * yB
    s = math.sqrt(l**2 - (e - xB) ** 2)
    sd = (e - xB) * vBx / s
    sdd = (-vBx**2 + (e - xB) * aBx - sd**2) / s
    yC, vC, aC = yB + s, vBy + sd, aBy + sdd
    th, w, al = rate_of_angle(np.array([e - xB, s]), np.array([-vBx, sd]), np.array([-aBx, sdd]))
    return {"point.C.x": e, "point.C.y": yC, "point.C.vx": 0.0, "point.C.vy": vC,
            "point.C.ax": 0.0, "point.C.ay": aC, "link.rod.angle": math.degrees(th),
            "link.rod.omega": w, "link.rod.alpha": al}


CLOSED_FORMS = {"four_bar": four_bar_closed_form,
                "offset_slider_crank": offset_slider_crank_closed_form}


@pytest.mark.parametrize("name", sorted(CLOSED_FORMS))
def test_new_spec_expectations_match_closed_forms(name, repo_root, mechanisms):
    mech = mechanisms(repo_root / "specs" / f"{name}.yaml")
    spec = mech.spec
    kin = solve_kinematics(mech)
    kinematic = [e for e in spec.expect if e.quantity.split(".")[0] in ("point", "link")]
    assert len(kinematic) >= 5
    for e in kinematic:
        hand = CLOSED_FORMS[name](e.angle, spec.driver.omega)[e.quantity]
        assert abs(hand - e.value) <= e.tol, (e.angle, e.quantity, hand, e.value)
        assert abs(tool_value(spec, kin, e.quantity, e.angle) - e.value) <= e.tol, e


@pytest.mark.parametrize("name", sorted(CLOSED_FORMS))
def test_new_spec_full_sweep_matches_closed_form_without_flags(name, repo_root, mechanisms):
    mech = mechanisms(repo_root / "specs" / f"{name}.yaml")
    spec = mech.spec
    kin = solve_kinematics(mech)
    assert kin.flags == ()
    assert kin.angles.tolist() == list(range(360))
    for k in range(0, 360, 5):
        hand = CLOSED_FORMS[name](float(kin.angles[k]), spec.driver.omega)
        for quantity, value in hand.items():
            got = tool_value(spec, kin, quantity, float(kin.angles[k]))
            scale = max(1.0, abs(value))
            assert abs(got - value) <= 1e-9 * scale, (kin.angles[k], quantity, got, value)


def test_offset_slider_crank_dead_centres_as_described():
    # description: TDC at about 85.2 deg (crank and rod in line, |AC| = l + r) and BDC at
    # about 261.8 deg (crank folded back under the rod, |AC| = l - r, crank opposite to C)
    r, l, e = 0.025, 0.095, 0.010
    tdc = math.degrees(math.atan2(math.sqrt((l + r) ** 2 - e**2), e))
    bdc = math.degrees(math.atan2(math.sqrt((l - r) ** 2 - e**2), e)) + 180.0
    assert round(tdc, 1) == 85.2 and round(bdc, 1) == 261.8
    assert round(360 + tdc - bdc, 1) == 183.4                 # compression stroke, degrees
    for dead, sign in ((tdc, 1), (bdc, -1)):
        y = [offset_slider_crank_closed_form(a, 1.0)["point.C.y"]
             for a in (dead - 0.5, dead, dead + 0.5)]
        assert sign * (y[1] - y[0]) > 0 and sign * (y[1] - y[2]) > 0
        v = offset_slider_crank_closed_form(dead, 1.0)["point.C.vy"]
        assert v == pytest.approx(0, abs=1e-12)


def test_four_bar_is_a_grashof_crank_rocker_with_good_transmission():
    a, b, c, d = 0.05, 0.18, 0.12, 0.2     # crank, coupler, rocker, frame
    s, l_ = min(a, b, c, d), max(a, b, c, d)
    assert s == a and s + l_ < sum((a, b, c, d)) - s - l_
    # transmission angle: cos mu = (b^2 + c^2 - BD^2) / (2 b c), extremes at phi = 0 and 180
    mu = [math.degrees(math.acos((b * b + c * c - (d - a * math.cos(math.radians(p))) ** 2
                                  - (a * math.sin(math.radians(p))) ** 2) / (2 * b * c)))
          for p in range(360)]
    assert 55 < min(mu) < 57 and 110 < max(mu) < 112      # "between about 56 and 111 degrees"
