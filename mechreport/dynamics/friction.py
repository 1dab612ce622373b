"""Coulomb friction in the equation of motion.

With friction the torque the crank must receive is no longer affine in the state: each
joint's friction m_J opposes its relative motion with a magnitude that depends on the joint's
reaction, and the reactions depend on the speed, the acceleration and the frictions
themselves. The reference method's reactions are affine in all of these, so on the grid of
crank angles the equation keeps, for every reaction component u of a friction joint and for
the driver torque M,

    u = P0(phi) + P1(phi) omega + P2(phi) omega^2 + Pa(phi) alpha + sum_K G_K,u(phi) m_K,

the parts found by the same four rate states as J, B, C, D (Pa of M is J; P2 B, P1 C, P0 D)
and the responses G to a unit friction at each joint (one solve, one right-hand side per
joint). At a state (phi, omega) the equation of motion (J + If) alpha = Mm(omega) - M
eliminates alpha, which leaves the friction law m_J = -s_J mag_J(u(m)) (s_J the sign of the
joint's relative motion, fixed by phi for omega > 0): a small system solved by Newton's
method as :mod:`mechreport.forces.friction` solves it over a sweep. Where it has no
determined solution (the friction's loop gain 1 or more) the mechanism jams: an error.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from ..errors import AnalysisError
from ..forces.context import ForceContext, reaction_unknowns
from ..forces.friction import MAX_STEPS, TOL    # Newton's convergence, as the sweep's
from ..forces.friction_law import magnitude, relative_rate
from ..forces.newton_euler import build_steps as newton_euler_steps
from ..forces.sources import split_by_source
from ..kinematics import Kinematics, at_unit_rate, with_rates
from .motor import motor_function, motor_torque
from .pieces import DEGREE, GRID_STEP_DEG, periodic_pieces, values_at


@dataclass(frozen=True)
class FrictionTerms:
    """The friction parts of the equation of motion over the grid (see the module's text):
    ``pieces`` (N, channels, DEGREE + 1) their periodic splines over the grid (as the
    equation's J, C, D), by channel: for each friction joint, for each of its reaction
    components, P0, P1, P2, Pa and the responses G to every joint; then M's responses to
    every joint; then each joint's relative rate per unit crank speed; then each T joint's
    line direction (x, y). ``layout`` the channel ranges by name."""

    frictions: tuple
    joints: tuple
    pieces: np.ndarray
    layout: dict


def friction_terms(spec, kin: Kinematics, states, method_parts) -> FrictionTerms:
    """The friction parts over the grid kinematics ``kin`` (its angles), from
    ``method_parts(moving_kin)``: the reference method's unknowns split by source at the
    rate ``states`` [(omega, alpha)], each on kinematics carrying a unit friction."""
    frictions = spec.friction
    joints = tuple(spec.joint(fr.joint) for fr in frictions)
    own = [f"friction {fr.joint}" for fr in frictions]
    effort = spec.driver.quantity
    base, responses = [], None
    for omega, alpha in states:
        moving = with_rates(kin, np.full(kin.n, omega), np.full(kin.n, alpha))
        parts = method_parts(replace(moving, friction={fr.joint: np.ones(kin.n)
                                                       for fr in frictions}))
        base.append({u: sum(p[u] for src, p in parts.items() if src not in own)
                     for u in next(iter(parts.values()))})
        if responses is None:
            responses = [parts[name] for name in own]
    m1, m2, m3, m11 = base
    columns, layout = [], {}

    def add(name: str, arrays: list[np.ndarray]) -> None:
        layout[name] = (len(columns), len(columns) + len(arrays))
        columns.extend(arrays)
    for joint in joints:
        for u in reaction_unknowns(joint):
            p2 = (m3[u] - 2 * m2[u] + m1[u]) / 2
            p1 = (m2[u] - m1[u]) - 3 * p2
            add(u, [m1[u] - p1 - p2, p1, p2, m11[u] - m1[u]]
                + [g[u] for g in responses])
    add(effort, [g[effort] for g in responses])
    unit = at_unit_rate(kin)
    add("rates", [relative_rate(unit, j) for j in joints])
    ctx = ForceContext(kin)
    for joint in joints:
        if joint.type == "T":
            u = ctx.line_direction(joint)
            add(f"line {joint.name}", [u[:, 0], u[:, 1]])
    values = np.stack(columns, axis=1)
    if not np.all(np.isfinite(values)):
        raise AnalysisError(f"{spec.file}: the friction of the equation of motion is not "
                            "finite at every crank angle")
    return FrictionTerms(frictions, joints, periodic_pieces(np.radians(kin.angles), values),
                         layout)


def method_parts_of(ctx_kin: Kinematics) -> dict:
    """The Newton-Euler unknowns over ``ctx_kin`` split by source, each joint's friction
    apart (the reference method of :func:`friction_terms`)."""
    ctx = ForceContext(ctx_kin)
    return split_by_source(ctx, newton_euler_steps(ctx), friction_apart=True)


class _Lines:
    """What :func:`~mechreport.forces.friction_law.magnitude` asks of a context at the
    states being solved: each T joint's line direction (n, 2)."""

    def __init__(self, lines: dict):
        self.lines = lines

    def line_direction(self, joint):
        return self.lines[joint.name]


def friction_state(eom, phi: np.ndarray, omega: np.ndarray, file: str
                   ) -> tuple[np.ndarray, np.ndarray]:
    """(alpha (n,) [rad/s^2], the frictions m (n, J)) of the equation of motion ``eom``
    with its friction at the states (``phi`` [rad], ``omega`` [rad/s] > 0), by Newton's
    method on the friction law, batched over the states. Raises ``AnalysisError`` where
    the friction jams the mechanism (loop gain 1 or more) or Newton does not converge."""
    terms = eom.friction
    frictions, joints, layout = terms.frictions, terms.joints, terms.layout
    phi, omega = np.atleast_1d(np.asarray(phi, float)), np.atleast_1d(np.asarray(omega, float))
    n, J = len(phi), len(frictions)
    j, b, c, d = eom.at(phi).T
    vals = values_at(terms.pieces, phi)
    den = j + eom.flywheel
    free = (motor_torque(eom.motor, omega) - ((b * omega + c) * omega + d)) / den
    effort = next(span for name, span in layout.items() if name.startswith("driver."))
    gm = vals[:, effort[0]:effort[1]]                                        # (n, J)
    s = np.sign(vals[:, slice(*layout["rates"])])                            # (n, J)
    ctx = _Lines({jt.name: vals[:, slice(*layout[f"line {jt.name}"])]
                  for jt in joints if jt.type == "T"})
    base, resp = [], []
    for joint in joints:
        rows = [vals[:, slice(*layout[u])] for u in reaction_unknowns(joint)]   # (n, 4 + J)
        base.append([r[:, 0] + r[:, 1] * omega + r[:, 2] * omega ** 2 + r[:, 3] * free
                     for r in rows])
        resp.append([r[:, 4:] - (r[:, 3] / den)[:, None] * gm for r in rows])
    m = np.zeros((n, J))
    scale = None
    for _ in range(MAX_STEPS):
        mag, jac = _law(m, base, resp, frictions, joints, ctx)
        if scale is None:
            scale = np.maximum(np.max(np.abs(mag), axis=1), 1e-300)
        step = np.linalg.solve(np.eye(J) + s[:, :, None] * jac,
                               (m + s * mag)[:, :, None])[:, :, 0]
        m = m - step
        if np.all(np.abs(step) <= TOL * scale[:, None]):
            break
    mag, jac = _law(m, base, resp, frictions, joints, ctx)
    gain = np.max(np.abs(np.linalg.eigvals(s[:, :, None] * jac)), axis=1)
    ok = (gain < 1.0) & np.all(np.abs(m + s * mag) <= 1e3 * TOL * scale[:, None], axis=1)
    if not ok.all():
        k = int(np.flatnonzero(~ok)[0])
        raise AnalysisError(
            f"{file}: the friction jams the mechanism at crank angle "
            f"{math.degrees(phi[k]) % 360:.4g}° (speed {omega[k]:.6g} rad/s): its loop gain "
            f"{gain[k]:.4g} >= 1, the friction grows with the reaction it causes "
            "(self-locking); the motor cannot turn the crank on")
    return free - np.einsum("nj,nj->n", gm, m) / den, m


def friction_scalar(eom):
    """alpha(phi, omega) with friction for one state in plain floats: what the integrator
    calls about 2100 times a turn. The same equations as :func:`friction_state` (the tests
    compare them), where numpy's overhead on arrays of three or four numbers made each call
    about 3 ms (a 3-turn steady state of a four-bar with three rubbing pins in 11 s of CPU);
    here the channels are one matrix-vector product and the Newton steps plain arithmetic,
    warm-started from the previous call's frictions. A state where Newton's method does not
    converge raises ``AnalysisError``; the loop gain is checked on the sampled motion by
    :func:`friction_state`."""
    terms = eom.friction
    frictions, joints, layout = terms.frictions, terms.joints, terms.layout
    J = len(frictions)
    torque = motor_function(eom.motor)
    h = math.radians(GRID_STEP_DEG)
    pieces, core = terms.pieces, eom.coefficients
    n = len(pieces)
    period = n * h                          # one cycle [rad]
    powers = np.arange(DEGREE, -1, -1)
    effort = next(span for name, span in layout.items() if name.startswith("driver."))
    rates = layout["rates"]
    comps = [[layout[u] for u in reaction_unknowns(jt)] for jt in joints]
    lines = [layout.get(f"line {jt.name}") for jt in joints]
    laws = []
    for fr, jt in zip(frictions, joints):
        if jt.type == "T" and fr.length is not None:
            laws.append(("length", fr.mu, fr.length))
        else:
            laws.append(("norm", fr.journal_mu * fr.radius if jt.type == "R" else fr.mu, 0.0))
    fly = eom.flywheel
    state = {"m": [0.0] * J}

    def alpha(phi: float, omega: float) -> float:
        phi, omega = float(phi), float(omega)     # the integrator's numpy scalars: floats
        x = (phi % period) / h
        i = min(int(x), n - 1)
        tp = ((x - i) * h) ** powers
        j, b, c, d = (core[i] @ tp).tolist()
        v = (pieces[i] @ tp).tolist()
        den = j + fly
        free = (torque(omega) - ((b * omega + c) * omega + d)) / den
        gm = v[effort[0]:effort[1]]
        s = [(x > 0) - (x < 0) for x in v[rates[0]:rates[1]]]
        base, resp = [], []
        for span in comps:
            bk, rk = [], []
            for a, _ in span:
                pa = v[a + 3]
                bk.append(v[a] + v[a + 1] * omega + v[a + 2] * omega * omega + pa * free)
                rk.append([v[a + 4 + q] - pa * gm[q] / den for q in range(J)])
            base.append(bk)
            resp.append(rk)
        m = list(state["m"])
        scale = None
        for _ in range(MAX_STEPS):
            mag, jac = [], []
            for k in range(J):
                comp = [bk + sum(r[q] * m[q] for q in range(J))
                        for bk, r in zip(base[k], resp[k])]
                kind, mu, length = laws[k]
                if kind == "norm":
                    f = math.hypot(comp[0], comp[1])
                    ux, uy = (comp[0] / f, comp[1] / f) if f > 0 else (0.0, 0.0)
                    mag.append(mu * f)
                    dfx, dfy, dm = mu * ux, mu * uy, 0.0
                else:
                    lx, ly = v[lines[k][0]], v[lines[k][0] + 1]
                    nx, ny = -ly, lx
                    normal = comp[0] * nx + comp[1] * ny
                    lo, hi = normal / 2 - comp[2] / length, normal / 2 + comp[2] / length
                    slo, shi = (lo > 0) - (lo < 0), (hi > 0) - (hi < 0)
                    mag.append(mu * (abs(lo) + abs(hi)))
                    dn = mu * (slo + shi) / 2
                    dfx, dfy, dm = dn * nx, dn * ny, mu * (shi - slo) / length
                row = [dfx * resp[k][0][q] + dfy * resp[k][1][q]
                       + (dm * resp[k][2][q] if len(comp) > 2 else 0.0) for q in range(J)]
                jac.append(row)
            if scale is None:
                scale = max(max(abs(x) for x in mag), 1e-300)
            system = [[(1.0 if r == q else 0.0) + s[r] * jac[r][q] for q in range(J)]
                      for r in range(J)]
            step = _gauss(system, [m[r] + s[r] * mag[r] for r in range(J)])
            m = [m[r] - step[r] for r in range(J)]
            if all(abs(x) <= TOL * scale for x in step):
                break
        else:
            raise AnalysisError(
                f"{eom.file}: the friction has no solution at crank angle "
                f"{math.degrees(phi) % 360:.4g}° (speed {omega:.6g} rad/s): the friction "
                "grows with the reaction it causes (self-locking); the motor cannot turn the "
                "crank on")
        state["m"] = m
        return free - sum(g * mk for g, mk in zip(gm, m)) / den
    return alpha


def _gauss(a: list[list[float]], b: list[float]) -> list[float]:
    """The solution of the small system a x = b (Gaussian elimination, partial pivoting);
    NaN where it is singular (Newton then does not converge: reported)."""
    n = len(b)
    a = [row[:] + [b[i]] for i, row in enumerate(a)]
    for c in range(n):
        p = max(range(c, n), key=lambda r: abs(a[r][c]))
        if a[p][c] == 0.0:
            return [math.nan] * n
        a[c], a[p] = a[p], a[c]
        for r in range(c + 1, n):
            f = a[r][c] / a[c][c]
            for q in range(c, n + 1):
                a[r][q] -= f * a[c][q]
    x = [0.0] * n
    for r in range(n - 1, -1, -1):
        x[r] = (a[r][n] - sum(a[r][q] * x[q] for q in range(r + 1, n))) / a[r][r]
    return x


def _law(m, base, resp, frictions, joints, ctx):
    """Each joint's friction magnitude (n, J) at the frictions ``m`` (n, J) and its
    derivatives (n, J, J), from each joint's reaction components base + resp @ m."""
    n, J = m.shape
    mag = np.empty((n, J))
    jac = np.empty((n, J, J))
    for k, (fr, joint) in enumerate(zip(frictions, joints)):
        vals = [b + np.einsum("nj,nj->n", r, m) for b, r in zip(base[k], resp[k])]
        couple = vals[2] if len(vals) > 2 else None
        mag[:, k], dfx, dfy, dm = magnitude(fr, joint, ctx, vals[0], vals[1], couple)
        jac[:, k] = dfx[:, None] * resp[k][0] + dfy[:, None] * resp[k][1]
        if couple is not None:
            jac[:, k] += dm[:, None] * resp[k][2]
    return mag, jac


__all__ = ["FrictionTerms", "friction_scalar", "friction_state", "friction_terms",
           "method_parts_of"]
