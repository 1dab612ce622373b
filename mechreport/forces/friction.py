"""Coulomb friction in the joints (format 1.1 ``friction:``).

Joint J's friction is one known action on each of its two links, written ``m_J`` for what
acts on its second link (minus that on its first):

- an R joint: a couple opposing the second link's rotation relative to the first, of
  magnitude mu r |F| (r the journal radius, F the joint's reaction);
- a T joint: a force along the line at the slider's point, opposing the slider's motion
  relative to the guide, of magnitude mu |N|; with the slider's ``length`` L the normal force
  N and the couple M are carried by its two ends, N1,2 = N/2 -/+ M/L, and the magnitude is
  mu (|N1| + |N2|) (a slider can jam: the drawer effect).

Every method's equations are linear in every known action, so its reactions are affine in
the friction values: F(m) = F0 + sum_J m_J G_J, with F0 the frictionless solution and G_J
the response to a unit friction at J (one solve with one right-hand side per joint, see
:func:`~mechreport.forces.sources.split_by_source`). The friction values solve the small
nonlinear system m_J = -s_J mag_J(F(m)) at each angle (s_J the sign of J's relative motion),
by Newton's method from the frictionless m = 0, batched over the angles. The solution is
unique where the friction's loop gain (the spectral radius of d(-s mag)/dm) is below 1; at
or above 1 the friction feeds itself without bound: the joint is self-locking, and the angle
is left out.
"""
from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from ..kinematics import Flag, Kinematics
from ..spec import Friction, Joint
from .newton_euler import build_steps as newton_euler_steps
from .context import ForceContext, reaction_unknowns
from .friction_law import RATE_ZERO, magnitude, relative_rate, senses
from .sources import split_by_source

TOL = 1e-13          # Newton's convergence: the last step, relative to the friction's scale
MAX_STEPS = 50


@dataclass(frozen=True)
class FrictionSolution:
    """Each friction joint's signed value on its second link (``values``, (n,) [N m or N])
    over the angles of the kinematics it was solved on; ``left_out`` by angle index: why that
    angle has no determined solution (the direction undetermined, self-locking, no
    convergence); ``reversed`` (n,) where friction alone reverses the sign of the driver's
    effort; ``frictionless`` (n,) the effort without friction; ``steps`` Newton's steps;
    ``stopped`` the indices of ``left_out`` where a joint's relative motion stops."""

    values: dict[str, np.ndarray]
    left_out: dict[int, str]
    reversed: np.ndarray
    frictionless: np.ndarray
    steps: int
    stopped: frozenset[int] = frozenset()


def unit_friction(kin: Kinematics, frictions: tuple[Friction, ...]) -> Kinematics:
    """``kin`` carrying a unit friction value at every friction joint (the responses
    G_J are the parts of the unknowns due to each)."""
    return replace(kin, friction={fr.joint: np.ones(kin.n) for fr in frictions})


def solve_friction(kin: Kinematics, parts: dict[str, dict[str, np.ndarray]],
                   ctx: ForceContext) -> FrictionSolution:
    """The friction values over ``kin`` from one method's unknowns split by source,
    ``parts`` (:func:`~mechreport.forces.sources.split_by_source` of its steps over ``ctx``,
    a context whose kinematics carry unit friction, with each joint's friction its own
    source ``friction J``)."""
    spec = kin.mechanism.spec
    frictions = spec.friction
    n, J = kin.n, len(frictions)
    joints = [spec.joint(fr.joint) for fr in frictions]
    own = {f"friction {fr.joint}" for fr in frictions}
    base = {u: sum(p[u] for src, p in parts.items() if src not in own)
            for u in next(iter(parts.values()))}
    response = [parts[f"friction {fr.joint}"] for fr in frictions]
    s, stopped = senses(kin, frictions)
    m = np.zeros((n, J))
    names = [reaction_unknowns(j) for j in joints]
    scale = np.ones(J)
    steps = 0
    for steps in range(1, MAX_STEPS + 1):
        mag, jac = _law(m, base, response, names, frictions, joints, ctx)
        if steps == 1:          # the frictionless magnitudes set each joint's scale
            scale = np.maximum(np.max(np.abs(mag), axis=0, initial=0.0), 1e-300)
        residual = m + s * mag
        system = np.eye(J) + s[:, :, None] * jac
        with np.errstate(all="ignore"):
            step = _solve(system, residual)
        m = m - step
        if np.all(np.abs(step) <= TOL * scale):
            break
    mag, jac = _law(m, base, response, names, frictions, joints, ctx)
    converged = np.all(np.abs(m + s * mag) <= 1e3 * TOL * scale, axis=1)
    gain = _spectral_radius(s[:, :, None] * jac)
    effort = spec.driver.quantity
    frictionless = base[effort]
    with_friction = frictionless + sum(m[:, k] * response[k][effort] for k in range(J))
    flip = (np.sign(with_friction) * np.sign(frictionless) < 0)
    left_out = _left_out(kin, joints, stopped, converged, gain)
    return FrictionSolution({fr.joint: m[:, k] + 0.0 for k, fr in enumerate(frictions)},
                            left_out, flip, frictionless, steps,
                            frozenset(int(k) for k in np.flatnonzero(stopped.any(axis=1))))


def with_friction(kin: Kinematics) -> tuple[Kinematics, FrictionSolution]:
    """``kin`` carrying the friction every method then includes (``Kinematics.friction``),
    found from the Newton-Euler equations' responses, with the angles that have no
    determined friction left out and flagged, and those where friction alone reverses the
    driver's effort (``reversed_by_friction``: the loads cannot drive the mechanism back
    there, a note says so), and the driver's effort without friction (``frictionless``)."""
    unit = ForceContext(unit_friction(kin, kin.mechanism.spec.friction))
    parts = split_by_source(unit, newton_euler_steps(unit), friction_apart=True)
    solution = solve_friction(kin, parts, unit)
    keep = np.ones(kin.n, bool)
    keep[list(solution.left_out)] = False
    flags = tuple(sorted(kin.flags + tuple(
        Flag(float(kin.angles[k]), why, "friction direction" if k in solution.stopped
             else "friction") for k, why in solution.left_out.items()),
        key=lambda f: f.angle))
    reversed_at = tuple(float(x) for x in kin.angles[solution.reversed & keep])
    out = replace(kin, friction=solution.values, reversed_by_friction=reversed_at,
                  frictionless=solution.frictionless)
    return (out if keep.all() else out.take(keep, flags)), solution


def _law(m, base, response, names, frictions, joints, ctx):
    """Each joint's friction magnitude (n, J) at the friction values ``m`` (n, J) and its
    derivatives with respect to every value, (n, J, J)."""
    n, J = m.shape
    mag = np.empty((n, J))
    jac = np.empty((n, J, J))
    for j, (fr, joint, unknowns) in enumerate(zip(frictions, joints, names)):
        vals = [base[u] + sum(m[:, k] * response[k][u] for k in range(J)) for u in unknowns]
        couple = vals[2] if len(vals) > 2 else None
        mag[:, j], dfx, dfy, dm = magnitude(fr, joint, ctx, vals[0], vals[1], couple)
        for k in range(J):
            jac[:, j, k] = dfx * response[k][unknowns[0]] + dfy * response[k][unknowns[1]]
            if couple is not None:
                jac[:, j, k] += dm * response[k][unknowns[2]]
    return mag, jac


def _solve(system: np.ndarray, rhs: np.ndarray) -> np.ndarray:
    """``system`` (n, J, J) x = ``rhs`` (n, J); NaN where a system is singular."""
    out = np.full_like(rhs, np.nan)
    det = np.linalg.det(system)
    ok = np.isfinite(det) & (np.abs(det) > 1e-300)
    if ok.any():
        out[ok] = np.linalg.solve(system[ok], rhs[ok][:, :, None])[:, :, 0]
    return out


def _spectral_radius(a: np.ndarray) -> np.ndarray:
    """max |eigenvalue| of each (J, J) matrix of ``a`` (n, J, J); inf where not finite."""
    out = np.full(a.shape[0], np.inf)
    ok = np.all(np.isfinite(a), axis=(1, 2))
    if ok.any():
        out[ok] = np.max(np.abs(np.linalg.eigvals(a[ok])), axis=1)
    return out


def _left_out(kin: Kinematics, joints: list[Joint], stopped: np.ndarray,
              converged: np.ndarray, gain: np.ndarray) -> dict[int, str]:
    """Why each angle without a determined friction is left out, by angle index."""
    out: dict[int, str] = {}
    for k in np.flatnonzero(stopped.any(axis=1)):
        names = ", ".join(j.written for j, hit in zip(joints, stopped[k]) if hit)
        out[int(k)] = (f"friction direction undetermined: the relative motion in joint "
                       f"{names} stops here")
    for k in np.flatnonzero(~(gain < 1.0)):
        out.setdefault(int(k), f"self-locking: friction's loop gain {gain[k]:.4g} >= 1 (the "
                               "friction force grows with the reaction it causes: no "
                               "determined solution)")
    for k in np.flatnonzero(~converged):
        out.setdefault(int(k), "self-locking: the friction iteration has no solution here")
    return out


__all__ = ["FrictionSolution", "RATE_ZERO", "magnitude", "relative_rate", "senses",
           "solve_friction", "unit_friction", "with_friction"]
