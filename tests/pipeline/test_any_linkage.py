"""Any planar linkage: Assur groups of any class, a driver on any joint, springs and dampers.
Checked independently of the code's own numbers:

- a class III triad against a generic constraint solver written here (scipy's fsolve on the
  loop equations, per angle);
- the textbook slider-crank driven at its slider against the same motion driven at its crank:
  the same state gives the same reactions, and torque x omega = force x speed;
- a spring's power on its two ends equals -dU/dt of its energy U = k (L - L0)^2 / 2;
- the hydraulic boom's cylinder force against closed-form geometry and statics (slow lift).
Property tests (finite differences, constraints, method agreement, declaration order) run over
these specs too: they are in specs/ and tests/data.
"""
from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np
import pytest
from scipy.optimize import fsolve

from mechreport.pipeline.analysis import analyse
from mechreport.spec import load_spec, parse_spec

ROOT = Path(__file__).resolve().parents[2]
TRIAD = ROOT / "tests" / "data" / "class_iii_triad.yaml"


def test_triad_matches_a_generic_constraint_solver():
    a = analyse(TRIAD)
    spec, kin = a.spec, a.kinematics
    P, Q = np.array(spec.ground["P"]), np.array(spec.ground["Q"])
    tern = spec.link("tern").points

    def loops(x, B):
        t1, t2, t3, cx, cy, psi = x
        rot = lambda v: np.array([math.cos(psi) * v[0] - math.sin(psi) * v[1],
                                  math.sin(psi) * v[0] + math.cos(psi) * v[1]])
        c = np.array([cx, cy])
        e1 = B + 0.15 * np.array([math.cos(t1), math.sin(t1)]) - (c + rot(tern["T1"]))
        e2 = P + 0.15 * np.array([math.cos(t2), math.sin(t2)]) - (c + rot(tern["T2"]))
        e3 = Q + 0.15 * np.array([math.cos(t3), math.sin(t3)]) - (c + rot(tern["T3"]))
        return np.concatenate([e1, e2, e3])

    num = {l: spec.number(l) for l in ("b1", "b2", "b3", "tern")}
    for angle in (0, 52, 140, 266):
        k = kin.at(angle)
        B = kin.named_point("B", "crank").r[k]
        mine = np.array([kin.theta[k, num["b1"]], kin.theta[k, num["b2"]],
                         kin.theta[k, num["b3"]], *kin.r[k, num["tern"]],
                         kin.theta[k, num["tern"]]])
        start = mine + np.array([0.03, -0.03, 0.03, 0.002, -0.002, 0.03])
        theirs, info, ok, msg = fsolve(loops, start, args=(B,), full_output=True, xtol=1e-13)
        assert ok == 1, msg
        np.testing.assert_allclose(np.angle(np.exp(1j * (theirs[[0, 1, 2, 5]] - mine[[0, 1, 2, 5]]))),
                                   0, atol=1e-10)
        np.testing.assert_allclose(theirs[3:5], mine[3:5], atol=1e-11)


def _slider_driven(speed: float, stroke: float) -> str:
    text = (ROOT / "specs" / "slider_crank.yaml").read_text().split("expect:")[0]
    text = re.sub(r"driver: \{[^}]*\}", f"driver: {{joint: C_T, speed: {speed!r}}}", text)
    text = text.replace("sweep: {start: 0, stop: 360, step: 1}",
                        "sweep: {start: -1.9, stop: 1.9, step: 0.05}")
    text = text.replace("at: [45]", f"at: [{stroke!r}]")
    return text.replace("assembly: {C: [1.4, 0]}", "assembly: {B: [0.5, 0.87]}")


def test_slider_driven_equals_crank_driven_in_the_same_state():
    """x_C = 2 cos(phi): at phi = 60 deg (x = 1 m) a slider speed v means omega = v / x'(phi)
    and, for a steady slider (x'' = 0), alpha = -omega^2 x''(phi) / x'(phi) = -omega^2 cot(phi).
    Same positions, velocities and accelerations, so the same power goes in: M omega = F v
    (the reactions differ: the actuator pushes the slider, the motor turns the crank)."""
    v = 0.3
    phi = math.radians(60)
    omega = v / (-2 * math.sin(phi))
    alpha = -omega ** 2 / math.tan(phi)
    slider = analyse(parse_spec(_slider_driven(v, 1.0), "slider_driven.yaml"))
    text = (ROOT / "specs" / "slider_crank.yaml").read_text().split("expect:")[0]
    text = re.sub(r"driver: \{[^}]*\}", f"driver: {{joint: A, omega: {omega!r}, "
                                        f"alpha: {alpha!r}}}", text)
    crank = analyse(parse_spec(text.replace("at: [45]", "at: [60]"), "crank_driven.yaml"))
    ks, kc = slider.kinematics.at(1.0), crank.kinematics.at(60)
    np.testing.assert_allclose(slider.kinematics.a[ks], crank.kinematics.a[kc], atol=1e-12)
    for method in ("newton_euler", "dalembert", "dyad", "contour", "power"):
        force = slider.forces[method].driver_torque[ks]
        torque = crank.forces[method].driver_torque[kc]
        assert force * v == pytest.approx(torque * omega, rel=1e-10)
        assert slider.forces[method].driver_quantity == "driver.force"


def test_spring_power_is_minus_the_rate_of_its_energy():
    a = analyse(ROOT / "specs" / "spring_loaded_slider_crank.yaml")
    kin = a.kinematics
    spring = [ld for ld in a.loads if ld.load.kind == "spring"]
    assert {ld.link for ld in spring} == {"ground", "slider"}
    power = sum(np.einsum("ni,ni->n", ld.force, kin.named_point(ld.point, ld.link).v)
                for ld in spring)
    S, C = kin.named_point("S", "ground"), kin.named_point("C", "slider")
    d = C.r - S.r
    L = np.hypot(d[:, 0], d[:, 1])
    Ldot = np.einsum("ni,ni->n", d, C.v - S.v) / L
    k, L0 = 4000.0, 0.200
    np.testing.assert_allclose(power, -k * (L - L0) * Ldot, rtol=1e-12, atol=1e-12)
    # the power balance (which counts spring, damper and torsion spring power) agrees
    np.testing.assert_allclose(a.forces["power"].driver_torque,
                               a.forces["newton_euler"].driver_torque, rtol=0, atol=1e-9)


def test_hydraulic_boom_cylinder_force_from_statics():
    """Slow lift (50 mm/s): the cylinder force from closed-form geometry and statics. The
    moments of barrel and rod about P give the normal part of the pin force at R, the boom's
    moments about O its part along the cylinder, and the rod's forces along its line the
    actuator's push. Inertia, left out here, is below 1e-3 of the result."""
    a = analyse(ROOT / "specs" / "hydraulic_boom.yaml")
    spec, kin = a.spec, a.kinematics
    P = np.array([0.3, -0.5])
    cross = lambda p, q: p[0] * q[1] - p[1] * q[0]   # noqa: E731
    g = 9.81
    for stroke in (150.0, 300.0, 450.0):
        k = kin.at(stroke)
        s = stroke / 1000
        length = s + 0.8                                   # |PR| = stroke + rod length [m]
        c = (1.0 + P @ P - length ** 2) / 2.0              # P . (cos b, sin b) with OR = 1 m
        beta = math.atan2(P[1], P[0]) + math.acos(c / math.hypot(*P))   # the upper branch
        assert kin.theta[k, spec.number("boom")] == pytest.approx(beta, abs=1e-9)
        e = np.array([math.cos(beta), math.sin(beta)])
        R = 1.0 * e
        u = (R - P) / length
        n = np.array([-u[1], u[0]])
        W_b, W_r = np.array([0, -25 * g]), np.array([0, -10 * g])
        # barrel + rod about P: (R - P) x F + (c_b - P) x W_b + (c_r - P) x W_r = 0
        b = -(cross(0.45 * u, W_b) + cross((s + 0.4) * u, W_r)) / length
        # boom about O: R x (-F) + T x W_pay + C x W_boom = 0, F = a u + b n on the rod
        loads = cross(3.0 * e, np.array([0, -4905])) + cross(1.5 * e, np.array([0, -120 * g]))
        a_ = (loads - b * cross(R, n)) / cross(R, u)
        push = -(a_ + W_r @ u)                            # the rod along its line
        got = a.forces["newton_euler"].driver_torque[k]
        assert got == pytest.approx(push, rel=1e-3)


def test_groups_are_named_in_the_report_model():
    a = analyse(TRIAD)
    assert [b.kind for b in a.kinematics.branches] == ["triad (class III)"]
    assert a.kinematics.branches[0].rule.startswith("default: of the 2 assemblies found")


def test_springs_dampers_and_torsion_springs_are_drawn_as_elements():
    from mechreport.report.drawing import draw_scene
    from mechreport.report.scene import build_scene
    a = analyse(ROOT / "specs" / "spring_loaded_slider_crank.yaml")
    k = a.kinematics.index_of(30)
    names = {j.name: j.name for j in a.spec.joints}
    scene = build_scene(a, a.forces["newton_euler"], k, {j: "#000000" for j in names}, names)
    kinds = [e[0] for e in scene.elements]
    assert kinds == ["spring", "damper", "torsion_spring"]
    S = a.kinematics.named_point("S", "ground").r[k]
    assert scene.elements[0][1] == pytest.approx(tuple(S))
    draw_scene(scene)                   # zig-zag, dashpot beside it, spiral: draws


def test_report_power_of_a_t_driver_is_force_times_stroke_speed():
    """Mean input power = mean(force) x speed (50 mm/s), not force x a link's omega; the
    index gives peaks at strokes in mm."""
    from mechreport.report.model import build_model
    a = analyse(ROOT / "specs" / "hydraulic_boom.yaml")
    model = build_model(a)
    power = model.summary["mean_power"]
    power = power["value"] if isinstance(power, dict) else power
    force = a.forces["newton_euler"].driver_torque
    assert power == pytest.approx(float(np.mean(force)) * 0.05, rel=1e-12)
    assert model.index_row["peak"].endswith(" mm") and "°" not in model.index_row["bearing"]


def test_newton_group_error_estimate_does_not_depend_on_size():
    """The boom in mm and the same numbers in m (1000 times larger): same condition, same
    estimated error, same flags (angle rows and coordinates made dimensionless)."""
    text = (ROOT / "specs" / "hydraulic_boom.yaml").read_text()
    small = analyse(parse_spec(text, "mm.yaml"))
    large = analyse(parse_spec(text.replace("units: {length: mm, mass: kg}",
                                            "units: {length: m, mass: kg}"), "m.yaml"))
    np.testing.assert_allclose(large.kinematics.error, small.kinematics.error, rtol=1e-6)
    assert [f.angle for f in large.flags] == [f.angle for f in small.flags]


def test_frame_load_is_the_mechanism_momentum_balance(spec_path):
    """What the frame receives, from the reactions (post.frame_load), equals minus what it
    gives the mechanism, from the momentum balance alone: sum of weights and loads (a
    spring's frame end included) minus the sum of m a_C (force), and their moments minus
    those of m a_C and I alpha (moment about the frame load's point). Holds for cranks,
    drivers between links and linear actuators."""
    from mechreport.kinematics.frames import cross
    from mechreport.post import frame_load
    a = analyse(spec_path)
    kin, spec = a.kinematics, a.spec
    res = a.forces["newton_euler"]
    frame = frame_load(kin, res, a.loads)
    d = spec.driver
    pivot = (kin.named_point(d.joint, d.link).r if d.crank else np.zeros((kin.n, 2)))
    force = np.zeros((kin.n, 2))
    moment = np.zeros(kin.n)
    g = np.asarray(spec.gravity)
    for link in spec.links:
        c = kin.com(link.name)
        k = link.number
        net = link.mass * g - link.mass * c.a
        force += net
        moment += cross(c.r - pivot, net) - link.inertia * kin.alpha[:, k]
    for ld in a.loads:
        if ld.load.reacts_on == "ground":
            continue        # on a moving link, its reaction on the frame: they cancel
        # a load on a moving link reaches the frame through the joints; a spring's or
        # damper's frame end pushes the frame directly: either way it counts once
        if ld.force is not None:
            at = kin.named_point(ld.point, ld.link).r
            force += ld.force
            moment += cross(at - pivot, ld.force)
        else:
            moment += ld.moment
    scale = max(1.0, float(np.max(np.abs(force))))
    np.testing.assert_allclose(np.stack([frame.fx, frame.fy], axis=1), force, rtol=0,
                               atol=1e-9 * scale)
    mscale = max(1.0, float(np.max(np.abs(moment))))
    np.testing.assert_allclose(frame.m, moment, rtol=0, atol=1e-9 * mscale)


def test_newton_rows_solved_together_equal_each_row_alone(monkeypatch):
    """Damped Newton iterates only the rows not yet converged (a converged row is left as it
    is): the 96 starting poses of the triad's assembly, solved together, give bit for bit
    what each start gives alone, where it converges and where it does not."""
    from mechreport.kinematics import groups, solve_kinematics
    from mechreport.model import build_mechanism
    calls = []
    real = groups.newton

    def keep(*args, **kw):
        calls.append((args, kw))
        return real(*args, **kw)
    monkeypatch.setattr(groups, "newton", keep)
    solve_kinematics(build_mechanism(load_spec(TRIAD)))
    (spec, group, q0, known, idx, value, scale), _ = calls[0]      # the assembly's starts
    assert len(q0) == groups.STARTS
    q, ok = real(spec, group, q0, known, idx, value, scale, steps=30)
    assert 0 < ok.sum() < len(ok)              # some converge within 30 steps, some do not
    for k in range(len(q0)):
        qk, okk = real(spec, group, q0[k:k + 1], known, idx[k:k + 1], value, scale, steps=30)
        assert okk[0] == ok[k]
        np.testing.assert_array_equal(qk[0], q[k])


def test_fine_samples_solved_at_once_must_stay_on_the_followed_branch(monkeypatch):
    """A Newton group followed over more than COARSE samples solves the samples between the
    coarse ones at once, each from an interpolated guess. One of them converging elsewhere (an
    other assembly: here a solution moved by hand) is caught by the continuity check and
    followed again sample by sample: the result equals the undisturbed one."""
    import dataclasses
    from mechreport.kinematics import groups, solve_kinematics
    from mechreport.model import build_mechanism
    from mechreport.spec import Sweep
    spec = load_spec(ROOT / "tests" / "data" / "class_iii_triad.yaml")
    spec = dataclasses.replace(spec, sweep=Sweep(0.0, 360.0, 0.5))   # 720 samples: two levels
    mech = build_mechanism(spec)
    clean = solve_kinematics(mech)
    real = groups.newton
    moved = []

    def astray(spec_, group, q, known, idx, value, scale, **kw):
        sol, ok = real(spec_, group, q, known, idx, value, scale, **kw)
        if len(np.unique(idx)) > groups.CHUNK_MAX and not moved:   # the fine samples' batch
            sol = sol.copy()
            sol[len(idx) // 2, :2] += 0.3 * scale           # lands far from its neighbours
            moved.append(int(idx[len(idx) // 2]))
        return sol, ok

    monkeypatch.setattr(groups, "newton", astray)
    kin = solve_kinematics(mech)
    assert moved
    np.testing.assert_allclose(kin.r, clean.r, rtol=0, atol=1e-9)
    np.testing.assert_allclose(kin.theta, clean.theta, rtol=0, atol=1e-9)
