"""Properties every spec under specs/ must have over its whole sweep (new specs are picked up
by the glob in conftest.py):

- velocities and accelerations are the time derivatives of the solver's own positions
  (central finite differences at crank angle +- h, with d/dt = omega d/dphi and
  d2/dt2 = omega^2 d2/dphi2 + alpha d/dphi for the driver's omega and alpha);
- joint constraints hold: R joints keep their two points together, T joints keep the slider's
  point on the guide line and the slider parallel to the guide;
- nothing is NaN.
"""
from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from mechreport.kinematics import solve_kinematics
from mechreport.spec import GROUND

H1 = 1e-4   # deg: first differences (truncation ~h^2, rounding ~eps/h: both far below 1e-8)
H2 = 1e-2   # deg: second differences of positions (rounding ~eps/h^2 ~ 1e-8 relative)
SHIFTS = (H1, -H1, H2, -H2)


def _rows(kin, index):
    """``kin`` restricted to the rows ``index`` (same order)."""
    return replace(kin, angles=kin.angles[index], r=kin.r[index], theta=kin.theta[index],
                   v=kin.v[index], omega=kin.omega[index], a=kin.a[index],
                   alpha=kin.alpha[index])


class Sweeps:
    """The solved sweep and the same angles shifted by +-H1 and +-H2, row-aligned.

    Angles whose shifted neighbours are left out (next to a limit of motion or a singular
    position) are dropped from the comparison; at most a few may be."""

    def __init__(self, mech):
        self.mech = mech
        self.spec = mech.spec
        full = solve_kinematics(mech)
        base = full.angles
        keep = np.ones(len(base), bool)
        where = {}
        # a stroke's step [length unit] 10x the angle's [deg]: a 0.01 mm second difference
        # of a metre-sized boom is all rounding (eps / h^2)
        self.step = 1.0 if mech.spec.driver.kind == "R" else 10.0
        for h in SHIFTS:
            k = solve_kinematics(mech, base + h * self.step)
            pos = np.clip(np.searchsorted(k.angles, np.round(base + h * self.step, 9)), 0,
                          k.n - 1)
            keep &= np.abs(k.angles[pos] - (base + h * self.step)) < 1e-9
            where[h] = (k, pos)
        assert keep.sum() >= len(base) - 4, f"{(~keep).sum()} angles lost their neighbours"
        self.full = full
        self.kin = _rows(full, np.flatnonzero(keep))
        self.shifted = {h: _rows(k, pos[keep]) for h, (k, pos) in where.items()}
        for h, k in self.shifted.items():
            assert np.allclose(k.angles, self.kin.angles + h * self.step, atol=1e-9, rtol=0)
        self.w = self.spec.driver.omega
        self.al = self.spec.driver.alpha

    def points(self):
        """(link, point name) for every named point of every moving link."""
        return [(l.name, p) for l in self.spec.links for p in l.points]

    def length_scale(self) -> float:
        """Largest distance of any named point from the origin over the sweep [m]."""
        return max(float(np.max(np.hypot(*self.kin.named_point(p, l).r.T)))
                   for l, p in self.points())


_CACHE: dict = {}


@pytest.fixture
def sweeps(spec_path, mechanism) -> Sweeps:
    if spec_path not in _CACHE:
        _CACHE[spec_path] = Sweeps(mechanism)
    return _CACHE[spec_path]


def wrap(a: np.ndarray) -> np.ndarray:
    """Angle differences brought into (-pi, pi] (unwrapping across the +-pi seam)."""
    return np.angle(np.exp(1j * a))


def assert_close(got, want, tol, what):
    err = np.abs(np.asarray(got) - np.asarray(want))
    worst = np.unravel_index(np.argmax(err), err.shape) if err.size else None
    assert err.size == 0 or err.max() <= tol, (
        f"{what}: max error {err.max():.3e} > {tol:.1e} at index {worst}")


# -- derivatives -----------------------------------------------------------------------------

def test_point_velocities_are_derivatives_of_positions(sweeps):
    s = sweeps
    h = H1 * s.step * s.spec.driver.unit
    tol = 1e-7 * abs(s.w) * s.length_scale()
    for link, p in s.points():
        plus, minus = s.shifted[H1].named_point(p, link), s.shifted[-H1].named_point(p, link)
        fd = (plus.r - minus.r) / (2 * h)
        assert_close(s.kin.named_point(p, link).v, s.w * fd, tol, f"v of {p} on {link}")


def test_point_accelerations_are_derivatives_of_velocities(sweeps):
    s = sweeps
    h = H1 * s.step * s.spec.driver.unit
    tol = 1e-7 * s.w**2 * s.length_scale()
    for link, p in s.points():
        here = s.kin.named_point(p, link)
        plus, minus = s.shifted[H1].named_point(p, link), s.shifted[-H1].named_point(p, link)
        dv = (plus.v - minus.v) / (2 * h)
        # v = omega x'(phi) at a fixed omega, so omega dv/dphi = omega^2 x''; add alpha x'
        want = s.w * dv + (s.al / s.w) * here.v if s.w else dv
        assert_close(here.a, want, tol, f"a of {p} on {link} (from v)")


def test_point_accelerations_are_second_derivatives_of_positions(sweeps):
    s = sweeps
    h = H2 * s.step * s.spec.driver.unit
    tol = 1e-5 * s.w**2 * s.length_scale()
    for link, p in s.points():
        here = s.kin.named_point(p, link)
        rp, rm = s.shifted[H2].named_point(p, link).r, s.shifted[-H2].named_point(p, link).r
        d2 = (rp - 2 * here.r + rm) / h**2
        d1 = (rp - rm) / (2 * h)
        assert_close(here.a, s.w**2 * d2 + s.al * d1, tol, f"a of {p} on {link} (from r)")


def test_link_rates_are_derivatives_of_link_angles(sweeps):
    s = sweeps
    th0 = s.kin.theta
    h1, h2 = H1 * s.step * s.spec.driver.unit, H2 * s.step * s.spec.driver.unit
    d1 = wrap(s.shifted[H1].theta - s.shifted[-H1].theta) / (2 * h1)
    assert_close(s.kin.omega, s.w * d1, 1e-7 * abs(s.w), "omega from theta")
    dw = (s.shifted[H1].omega - s.shifted[-H1].omega) / (2 * h1)
    want = s.w * dw + (s.al / s.w) * s.kin.omega if s.w else dw
    assert_close(s.kin.alpha, want, 1e-7 * s.w**2, "alpha from omega")
    plus, minus = wrap(s.shifted[H2].theta - th0), wrap(s.shifted[-H2].theta - th0)
    d2 = (plus + minus) / h2**2
    d1b = (plus - minus) / (2 * h2)
    assert_close(s.kin.alpha, s.w**2 * d2 + s.al * d1b, 1e-5 * s.w**2, "alpha from theta")


def test_driver_state(sweeps):
    """The driven coordinate follows the sweep at the driver's rate: a crank's angle, the
    relative angle of an R joint between moving links, or a T joint's stroke."""
    s = sweeps
    d = s.spec.driver
    kin = s.kin
    value = kin.angles * d.unit
    if d.kind == "R":
        a, b = (s.spec.number(l) for l in d.links)
        k = b if d.links[0] == GROUND else a if d.crank else b
        base = 0 if d.crank else a
        sign = 1.0
        rel = wrap(sign * (kin.theta[:, k] - (kin.theta[:, base] if base else 0)) - value)
        assert_close(rel, 0, 1e-12, "driven angle")
        w = kin.omega[:, k] - (kin.omega[:, base] if base else 0)
        al = kin.alpha[:, k] - (kin.alpha[:, base] if base else 0)
        assert_close(w, s.w, 1e-12, "driven omega")
        assert_close(al, s.al, 1e-12, "driven alpha")
        if d.crank:
            pivot = kin.named_point(d.joint, d.link)
            assert_close(pivot.r, np.broadcast_to(s.spec.ground[d.joint], pivot.r.shape),
                         1e-12, "crank pivot")
            assert_close(pivot.v, 0, 1e-12, "crank pivot velocity")
        return
    joint = s.spec.joint(d.joint)
    g = s.spec.number(joint.guide)
    u = np.stack([np.cos(kin.theta[:, g]), np.sin(kin.theta[:, g])], axis=1) @ np.array(
        [[joint.line.direction[0], joint.line.direction[1]],
         [-joint.line.direction[1], joint.line.direction[0]]])
    through = kin.point(joint.guide, joint.line.through)
    slider = kin.named_point(joint.point, joint.slider)
    L = max(s.length_scale(), 1.0)
    assert_close(np.einsum("ni,ni->n", slider.r - through.r, u), value, 1e-9 * L, "stroke")


# -- joint constraints -----------------------------------------------------------------------

def test_revolute_joints_keep_their_points_together(sweeps):
    s, kin = sweeps, sweeps.full
    L = max(s.length_scale(), 1.0)
    for joint in s.spec.joints:
        if joint.type != "R":
            continue
        a, b = (kin.named_point(joint.point, link) for link in joint.links)
        assert_close(a.r, b.r, 1e-9 * L, f"R joint {joint.name}: position")
        assert_close(a.v, b.v, 1e-9 * abs(s.w) * L, f"R joint {joint.name}: velocity")
        assert_close(a.a, b.a, 1e-9 * s.w**2 * L, f"R joint {joint.name}: acceleration")
        if GROUND in joint.links:
            pin = a if joint.links[0] == GROUND else b
            assert_close(pin.r, np.broadcast_to(s.spec.ground[joint.point], pin.r.shape), 1e-12,
                         f"ground pin {joint.name}")


def test_prismatic_joints_keep_the_slider_on_the_line(sweeps):
    s, kin = sweeps, sweeps.full
    L = max(s.length_scale(), 1.0)
    for joint in s.spec.joints:
        if joint.type != "T":
            continue
        g, sl = s.spec.number(joint.guide), s.spec.number(joint.slider)
        slider_point = kin.named_point(joint.point, joint.slider).r
        through = kin.point(joint.guide, joint.line.through).r
        dx, dy = joint.line.direction
        th = kin.theta[:, g]
        d = np.stack([np.cos(th) * dx - np.sin(th) * dy, np.sin(th) * dx + np.cos(th) * dy], axis=1)
        e = slider_point - through
        off_line = e[:, 0] * d[:, 1] - e[:, 1] * d[:, 0]
        assert_close(off_line, 0, 1e-9 * L, f"T joint {joint.name}: point off the line")
        assert_close(wrap(kin.theta[:, sl] - th), 0, 1e-9, f"T joint {joint.name}: angle")
        assert_close(kin.omega[:, sl], kin.omega[:, g], 1e-9 * abs(s.w),
                     f"T joint {joint.name}: omega")
        assert_close(kin.alpha[:, sl], kin.alpha[:, g], 1e-9 * s.w**2,
                     f"T joint {joint.name}: alpha")


def test_ground_stays_put(sweeps):
    kin = sweeps.full
    for arr in (kin.r[:, 0], kin.theta[:, 0], kin.v[:, 0], kin.omega[:, 0], kin.a[:, 0],
                kin.alpha[:, 0]):
        assert np.all(arr == 0)


# -- coverage and NaN --------------------------------------------------------------------------

def test_no_nan_and_every_angle_accounted_for(sweeps):
    s = sweeps
    kin = s.full
    for name in ("r", "theta", "v", "omega", "a", "alpha"):
        arr = getattr(kin, name)
        assert arr.shape[:2] == (kin.n, len(s.spec.links) + 1), name
        assert np.all(np.isfinite(arr)), f"{name} has NaN or inf"
    for link, p in s.points():
        st = kin.named_point(p, link)
        assert np.all(np.isfinite(st.r)) and np.all(np.isfinite(st.v)) and np.all(np.isfinite(st.a))
    solved = set(np.round(kin.angles, 9))
    flagged = {round(f.angle, 9) for f in kin.flags}
    assert not solved & flagged
    assert solved | flagged == set(np.round(s.spec.analysed_angles(), 9))
    assert kin.n > 0.9 * len(s.spec.analysed_angles()), kin.flags
    for ref in s.spec.at:       # reference angles are analysed (unless flagged)
        assert kin.index_of(ref) is not None or round(ref, 9) in flagged


def test_explicit_angles_follow_the_sweep_branch(sweeps):
    # Solving a few angles on their own must give the same branch as the full sweep.
    s = sweeps
    pick = s.full.angles[:: max(1, s.full.n // 7)]
    for a in pick:
        one = solve_kinematics(s.mech, [a])
        k = s.full.index_of(a)
        assert one.angles.tolist() == [a]
        assert np.max(np.abs(one.r[0] - s.full.r[k])) < 1e-12, a
        assert np.max(np.abs(wrap(one.theta[0] - s.full.theta[k]))) < 1e-12, a


def test_every_spec_is_covered(spec_files, textbook_specs):
    # the glob in conftest.py feeds every test above; the shipped specs must be among them
    names = {p.name for p in spec_files}
    assert {p.name for p in textbook_specs.values()} <= names
    assert {"four_bar.yaml", "offset_slider_crank.yaml"} <= names
