"""Stage 3: kinematics over the crank sweep, vectorised over the angle axis.

Positions come dyad by dyad in closed form (``position``); velocities and accelerations solve,
dyad by dyad, the differentiated joint constraints (``constraints``) as batched 6x6 systems.
Angles where a dyad cannot close, or whose velocity equations are singular (condition number
of the equilibrated 6x6 system above ``SINGULAR_COND``, see ``linalg``), are flagged and left
out.
"""
from __future__ import annotations

import sys
from dataclasses import replace

import numpy as np

from ..errors import AssemblyError
from ..linalg import SINGULAR_COND, Equilibrated
from ..model import Mechanism
from ..spec import GROUND
from .dyadsolve import DyadSystem
from .frames import LinkFrames, Trig, perp, rotate
from .constraints import mechanism_size
from .groups import RateEquations, row_scale, solve_newton_group
from .path import SweepPath, sweep_path
from .position import BranchChoice, dyad_candidates, signature, track_branches
from .result import Flag, Kinematics, Motion, PointState, motion_of

TRUST_RTOL = 1e-6   # every reported value must be trustworthy to this relative accuracy
EPS = float(np.finfo(float).eps)


def solve_kinematics(mech: Mechanism, angles: np.ndarray | None = None) -> Kinematics:
    """Solve positions, velocities, accelerations at ``angles`` [deg] (default: the spec's
    analysed angles). Raises ``AssemblyError`` if the first reference angle cannot close.

    Explicit ``angles`` are solved together with the spec's analysed angles, so that the
    assembly branch chosen at the first reference angle is followed to them; the result holds
    the requested angles only, in the order given."""
    if angles is None:
        return _solve(mech, mech.spec.analysed_angles())
    wanted = np.round(np.atleast_1d(np.asarray(angles, float)), 9)
    grid = np.unique(np.concatenate([mech.spec.analysed_angles(), wanted]))
    return _select(_solve(mech, grid), wanted)


def _select(kin: Kinematics, wanted: np.ndarray) -> Kinematics:
    """The rows of ``kin`` at the ``wanted`` angles (those left out stay in ``flags``)."""
    have = kin.angles
    pos = np.clip(np.searchsorted(have, wanted), 0, max(len(have) - 1, 0))
    hit = np.abs(have[pos] - wanted) < 1e-9 if len(have) else np.zeros(len(wanted), bool)
    flags = tuple(f for f in kin.flags if np.any(np.abs(wanted - f.angle) < 1e-9))
    return kin.take(pos[hit], flags)


def _solve(mech: Mechanism, phi_deg: np.ndarray) -> Kinematics:
    spec = mech.spec
    path = sweep_path(spec, phi_deg, spec.at[0])
    r, th, branches, motion = _positions(mech, path)
    idx = path.analysed
    if len(idx) < len(path.angles):     # else every solved angle is analysed, in order
        r = {k: x[idx] for k, x in r.items()}
        th = {k: x[idx] for k, x in th.items()}
    return finish(mech, phi_deg, r, th, branches, motion)


def finish(mech: Mechanism, phi_deg: np.ndarray, r: dict, th: dict, branches, motion: Motion
           ) -> Kinematics:
    """The kinematics at the analysed angles ``phi_deg`` (n,) [deg] from the poses there
    (origins r (n, 2) [m] and angles theta (n,) [rad] by link name, NaN where not reached):
    velocities, accelerations, their estimated error and the angles left out (unreachable,
    cannot close, singular, near-singular), with the sweep's ``branches`` and ``motion``."""
    spec = mech.spec
    problems: dict[int, tuple[str, str]] = {}   # angle index -> (kind, why it is left out)
    for k in np.flatnonzero(~np.isfinite(r[spec.links[-1].name][:, 0])):
        problems[int(k)] = _unreached(motion, float(phi_deg[k]), mech, r, int(k))
    v, w, acc, al, conds = _rates_chunked(mech, phi_deg * spec.driver.unit, r, th, problems)
    error = kinematic_error([c for _, c in conds], len(phi_deg))
    for k in np.flatnonzero(error > TRUST_RTOL):
        name, worst = max(conds, key=lambda c: c[1][k])
        problems.setdefault(int(k), (
            "near-singular",
            f"near-singular: {name} (condition {worst[k]:.1e}); results would not be "
            f"trustworthy to {TRUST_RTOL:g}"))
    keep = np.ones(len(phi_deg), bool)
    keep[list(problems)] = False
    order = [GROUND] + [l.name for l in spec.links]

    def by_link(d):
        out = np.stack([d[k] for k in order], axis=1)
        return out if not problems else out[keep]

    # many angles share a reason (those beyond one lock): one string for all of them
    flags = tuple(Flag(float(phi_deg[k]), sys.intern(why), kind)
                  for k, (kind, why) in sorted(problems.items()))
    return Kinematics(mech, phi_deg[keep], by_link(r), by_link(th), by_link(v), by_link(w),
                      by_link(acc), by_link(al), flags, tuple(branches), motion, error[keep])


def at_unit_rate(kin: Kinematics) -> Kinematics:
    """``kin`` with the driver moving at unit rate (1 rad/s, or 1 m/s for a T driver) and no
    acceleration: its velocities are the velocity coefficients d(x)/d(driven coordinate),
    the same at any speed (the virtual-work check at zero speed uses them; a driver at rest
    gives zero velocities). Positions and flags as ``kin``'s; accelerations zero."""
    v, w, _, _ = _unit_rates(kin)
    return replace(kin, v=v, omega=w, a=np.zeros_like(kin.a), alpha=np.zeros_like(kin.alpha))


def with_rates(kin: Kinematics, omega: np.ndarray, alpha: np.ndarray) -> Kinematics:
    """``kin`` with the driver at its own rate at each angle: ``omega`` (n,) [rad/s] and
    ``alpha`` (n,) [rad/s^2] (machine dynamics: the crank's true motion). A one-degree-of-
    freedom mechanism's velocities are its velocity coefficients k times omega, and its
    accelerations k alpha + k' omega^2 (k' the accelerations at unit rate and no angular
    acceleration): both from one solve at unit rate. Positions and flags as ``kin``'s."""
    k, kw, ka, kal = _unit_rates(kin)
    omega = np.asarray(omega, float)
    alpha = np.asarray(alpha, float)
    return replace(kin, v=k * omega[:, None, None], omega=kw * omega[:, None],
                   a=k * alpha[:, None, None] + ka * (omega ** 2)[:, None, None],
                   alpha=kw * alpha[:, None] + kal * (omega ** 2)[:, None],
                   rates=omega.copy())


def _unit_rates(kin: Kinematics) -> tuple[np.ndarray, ...]:
    """The velocities (n, L+1, 2), angular velocities (n, L+1), accelerations and angular
    accelerations of ``kin``'s poses with the driver at unit rate and no acceleration (the
    velocity coefficients and their derivatives), by link number."""
    mech = kin.mechanism
    spec = mech.spec
    unit = mech.with_spec(replace(spec, driver=replace(spec.driver, omega=1.0, alpha=0.0)))
    order = [GROUND] + [link.name for link in spec.links]
    r = {name: kin.r[:, i] for i, name in enumerate(order)}
    th = {name: kin.theta[:, i] for i, name in enumerate(order)}
    rates = _rates_chunked(unit, kin.angles * spec.driver.unit, r, th, {})[:4]
    return tuple(np.stack([d[name] for name in order], axis=1) for d in rates)


def kinematic_error(conds: list[np.ndarray], n: int) -> np.ndarray:
    """Estimated relative error (n,) of the accelerations, from each dyad's equilibrated
    velocity-system condition number c_d (n,): eps c_max^2 prod(c_d).

    Near a singular position a closed-form pose is accurate to eps c, velocities (one solve
    with that pose) to eps c^2 and accelerations to eps c^3 (measured: the textbook
    slider-crank near 90 deg and a parallelogram four-bar near 180 deg follow
    err = k eps c^3 with k = 1e-4 and 0.02); well-conditioned dyads of a chain multiply it."""
    if not conds:
        return np.full(n, EPS)
    c = np.stack(conds)
    with np.errstate(over="ignore", invalid="ignore"):
        est = EPS * np.max(c, axis=0) ** 2 * np.prod(c, axis=0)
    return np.where(np.isfinite(est), est, np.inf)


def _unreached(motion: Motion, angle: float, mech: Mechanism, r: dict,
               k: int) -> tuple[str, str]:
    """Why analysed angle ``angle`` has no pose: beyond a lock, or a dyad that cannot close
    between two reachable neighbours."""
    lock = motion.nearest_lock(angle)
    if lock is not None and not motion.contains(angle):
        return "unreachable", (f"not reachable from the assembly: the mechanism locks between "
                               f"{lock[0]:g} and {lock[1]:g} {motion.unit}")
    bad = next((g for g in mech.groups if not np.isfinite(r[g.links[-1]][k, 0])), None)
    label = f"{bad.kind} {bad.label}" if bad is not None else "the mechanism"
    return "cannot close", f"{label} cannot close"


def _positions(mech: Mechanism, path: SweepPath):
    """Link-frame origins r (N, 2) and angles theta (N,) by link name over ``path.angles``,
    group by group: the driver's link in closed form, dyads in closed form with their branch
    chosen at the first reference angle and followed along the path's runs, other groups by
    Newton-Raphson continued along the same runs; NaN where not reached. Also the branch
    choices and the range of motion."""
    spec = mech.spec
    value = path.angles * spec.driver.unit          # the driven coordinate [rad or m]
    n = len(value)
    r = {GROUND: np.zeros((n, 2))}
    th = {GROUND: np.zeros(n)}
    branches: list[BranchChoice] = []
    runs = list(path.runs)
    scale = _newton_scale(mech)
    for group in mech.groups:
        known = {k: (r[k], th[k]) for k in r}
        if group.driver is not None and len(group.links) == 1:
            chosen = driver_pose(spec, value)
        elif group.dyad is not None:
            dyad = group.dyad
            trig = Trig()      # the candidates' cos and sin, for their signatures too
            cands = dyad_candidates(spec, dyad, known, trig)
            require_closes_at_ref(spec, dyad, cands, path.ref)
            sig = [signature(spec, dyad.links, c, trig) for c in cands]
            chosen, choice, runs = track_branches(spec, dyad, cands, path, runs, sig)
            branches.append(choice)
        else:
            chosen, choice, runs = solve_newton_group(spec, group, known, path, runs, value,
                                                      scale)
            branches.append(choice)
        for link, (rr, tt) in chosen.items():
            r[link], th[link] = rr, tt
    return r, th, branches, motion_of(path, runs, spec.driver.omega, spec.axis_unit)


def require_closes_at_ref(spec, dyad, cands: list, ref: int) -> None:
    """Raise ``AssemblyError`` unless every candidate pose of ``dyad`` is solved at index
    ``ref`` (the first reference angle)."""
    if not all(np.all(np.isfinite(c[link][0][ref])) for c in cands for link in dyad.links):
        raise AssemblyError(
            f"{spec.file}: the dyad {dyad.label} ({', '.join(dyad.links)}) cannot close at "
            f"the first reference angle {spec.at[0]:g} {spec.axis_unit}; check link lengths "
            "and `at`")


def driver_rates(spec, value: np.ndarray):
    """Velocity, angular velocity, acceleration and angular acceleration of the driver's link
    on ground, (n, 2), (n,), (n, 2), (n,), differentiating :func:`driver_pose`: a crank turned
    to ``value`` [rad] at omega and alpha, or a slider (or guide) pushed along its line."""
    d = spec.driver
    n = len(value)
    omega, alpha = np.broadcast_to(d.omega, (n,)), np.broadcast_to(d.alpha, (n,))
    if d.kind == "R":
        s = rotate(spec.link(d.link).points[spec.joint(d.joint).point], value)  # r = pivot - s
        ds = perp(s)
        return (-omega[:, None] * ds, omega.copy(),
                -alpha[:, None] * ds + (omega ** 2)[:, None] * s, alpha.copy())
    joint = spec.joint(d.joint)
    u = np.broadcast_to(np.asarray(joint.line.direction, float), (n, 2))
    sign = 1.0 if joint.guide == GROUND else -1.0   # the slider moves, or the guide is pushed
    zero = np.zeros(n)
    return sign * omega[:, None] * u, zero, sign * alpha[:, None] * u, zero.copy()


def _newton_scale(mech: Mechanism) -> float:
    """The length that makes Newton groups' systems dimensionless (1 without them; dyads
    and the driver's link keep their own form)."""
    newton = any(g.dyad is None and len(g.links) > 1 for g in mech.groups)
    return mechanism_size(mech.spec) if newton else 1.0


def driver_pose(spec, value: np.ndarray) -> dict:
    """Pose of a driver link on ground, in closed form from the driven coordinate ``value``
    (n,) [rad or m]: a crank turned to ``value``, or a slider pushed ``value`` along its line
    (or a guide pushed so that its line carries the ground's point at that stroke)."""
    d = spec.driver
    joint = spec.joint(d.joint)
    n = len(value)
    link = spec.link(d.link)
    if d.kind == "R":
        pivot = np.asarray(spec.ground[joint.point])
        return {d.link: (pivot - rotate(link.points[joint.point], value), value)}
    u = np.asarray(joint.line.direction)
    zero = np.zeros(n)
    if joint.guide == GROUND:      # the slider moves along a line fixed to the frame
        at = np.asarray(joint.line.through) + value[:, None] * u
        return {d.link: (at - np.asarray(link.points[joint.point]), zero)}
    point = np.asarray(spec.ground[joint.point])     # the frame carries the slider's point
    through = np.asarray(joint.line.through)
    return {d.link: (point - through - value[:, None] * u, zero)}


CHUNK = 8192   # angles whose velocity and acceleration systems are solved together


def _rates_chunked(mech: Mechanism, value: np.ndarray, r: dict, th: dict,
                   problems: dict[int, tuple[str, str]]):
    """:func:`_rates` over chunks of at most ``CHUNK`` angles (bounded working memory)."""
    n = len(value)
    if n <= CHUNK:
        return _rates(mech, value, r, th, problems)
    parts = []
    for a in range(0, n, CHUNK):
        cut = slice(a, a + CHUNK)
        found: dict[int, tuple[str, str]] = {}
        parts.append(_rates(mech, value[cut], {k: x[cut] for k, x in r.items()},
                            {k: x[cut] for k, x in th.items()}, found))
        for k, why in found.items():
            problems.setdefault(a + k, why)
    joined = [{k: np.concatenate([p[i][k] for p in parts]) for k in parts[0][i]}
              for i in range(4)]
    conds = [(name, np.concatenate([p[4][g][1] for p in parts]))
             for g, (name, _) in enumerate(parts[0][4])]
    return (*joined, conds)


def _rates(mech: Mechanism, value: np.ndarray, r: dict, th: dict,
           problems: dict[int, tuple[str, str]]):
    """Velocities and accelerations (origins and angular) by link name, group by group: each
    group's system J qdot = -J_known qdot_known (+ the driver's rate on its row), then
    J qddot = gamma - J_known qddot_known (+ the driver's acceleration). Also each group's
    condition numbers with its label (the driver's closed-form link has none)."""
    spec = mech.spec
    n = len(value)
    zeros2 = np.zeros((n, 2))
    v, w, acc, al = {GROUND: zeros2}, {GROUND: np.zeros(n)}, {GROUND: zeros2}, {GROUND: np.zeros(n)}
    finite = np.all(np.isfinite(np.stack([r[k][:, 0] for k in r])), axis=0)
    if finite.all():
        frames = LinkFrames(r, th)
    else:   # poses not reached: any finite stand-in (their rates are not reported)
        frames = LinkFrames({k: np.where(finite[:, None], x, 0.0) for k, x in r.items()},
                            {k: np.where(finite, t, 0.0) for k, t in th.items()})
    conds: list[tuple[str, np.ndarray]] = []
    size = _newton_scale(mech)
    systems = _rate_systems(spec, mech.groups, frames, size)
    for group in mech.groups:
        if group.driver is not None and len(group.links) == 1:
            # the driver's link on ground, in closed form (its system is never singular)
            link = group.links[0]
            v[link], w[link], acc[link], al[link] = driver_rates(spec, value)
            continue
        label = f"{group.kind} {group.label}"
        cond = _group_rates(spec, group, *systems[id(group)], (v, w), (acc, al))
        conds.append((label, np.where(finite, cond, np.inf)))
        for k in np.flatnonzero(~(cond < SINGULAR_COND) & finite):
            problems.setdefault(int(k), ("singular", f"{label}: velocity equations singular"))
    return v, w, acc, al, conds


def _rate_systems(spec, groups, frames: LinkFrames, size: float) -> dict[int, tuple]:
    """(equations, system, rs, cs) for each group but the driver's crank, by ``id`` of the
    group: a dyad's solved through its structure (:class:`DyadSystem`, in its own form: rs
    and cs None), every dyad's prepared together (:meth:`DyadSystem.joined`: one pass of
    numpy calls for all of them, the same numbers); a Newton group's by
    :func:`_newton_system`."""
    out = {}
    dyads = []
    for group in groups:
        if group.driver is not None and len(group.links) == 1:
            continue
        eqs = RateEquations(spec, group, frames)
        if group.dyad is not None:
            dyads.append((group, eqs))
        else:
            out[id(group)] = (eqs, *_newton_system(spec, group, eqs, size))
    for (group, eqs), system in zip(dyads, DyadSystem.joined([eqs for _, eqs in dyads])):
        out[id(group)] = (eqs, system, None, None)
    return out


def _group_rates(spec, group, eqs: RateEquations, system, rs, cs, vel: tuple[dict, dict],
                 accel: tuple[dict, dict]) -> np.ndarray:
    """Solve one group's velocities and accelerations into ``vel`` (v (n, 2) [m/s], omega
    (n,) [rad/s] by link) and ``accel`` ([m/s^2], [rad/s^2]), zero where its velocity system
    is singular, with its equations ``eqs`` and their ``system`` and scales ``rs``, ``cs``
    (:func:`_rate_systems`); returns its condition numbers (n,)."""
    b_v = eqs.known_part(*vel)
    np.negative(b_v, out=b_v)
    if eqs.drow is not None:
        b_v[eqs.drow] += spec.driver.omega
    x, cond = system.solve_cond(_scaled(b_v, rs).T)
    x = _scaled(x, cs)
    sing = ~(cond < SINGULAR_COND)
    x[sing] = 0.0
    for i, link in enumerate(group.links):
        vel[0][link], vel[1][link] = x[:, 3 * i:3 * i + 2], x[:, 3 * i + 2]
    b_a = eqs.gamma(*vel)
    b_a -= eqs.known_part(*accel)
    if eqs.drow is not None:
        b_a[eqs.drow] += spec.driver.alpha
    x = _scaled(system.solve(_scaled(b_a, rs).T), cs)
    x[sing] = 0.0
    for i, link in enumerate(group.links):
        accel[0][link], accel[1][link] = x[:, 3 * i:3 * i + 2], x[:, 3 * i + 2]
    return cond


def _scaled(x: np.ndarray, factors: np.ndarray | None) -> np.ndarray:
    """``x`` times ``factors`` (broadcast), or ``x`` itself without them."""
    return x if factors is None else x * factors


def _newton_system(spec, group, eqs: RateEquations, size: float):
    """A Newton group's velocity matrices (3k, 3k, n) equilibrated once, for both solves, and
    the row and column factors (rs (3k, 1), cs (3k,)) its right-hand sides and solutions
    take: made dimensionless (angle rows as lengths, x and y columns times the mechanism's
    size ``size``), the same solution, a condition number independent of the mechanism's
    size. (A dyad's stays in its own form, its error estimate calibrated in it.)"""
    rs = row_scale(spec, group, size)
    cs = np.tile([size, size, 1.0], len(group.links))
    A = eqs.matrix() * rs[:, None, None] * cs[:, None]   # dimensionless: x = cs * (solution)
    return Equilibrated(A), rs[:, None], cs


__all__ = ["solve_kinematics", "at_unit_rate", "with_rates", "Kinematics", "PointState", "Flag", "BranchChoice", "Motion",
           "SINGULAR_COND", "TRUST_RTOL", "EPS"]
