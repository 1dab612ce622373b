"""Stage 3: kinematics over the crank sweep, vectorised over the angle axis.

Positions come dyad by dyad in closed form (``position``); velocities and accelerations solve,
dyad by dyad, the differentiated joint constraints (``constraints``) as batched 6x6 systems.
Angles where a dyad cannot close, or whose velocity equations are singular (condition number
of the equilibrated 6x6 system above ``SINGULAR_COND``, see ``linalg``), are flagged and left
out.
"""
from __future__ import annotations

import numpy as np

from ..errors import AssemblyError
from ..linalg import SINGULAR_COND, batched_solve, batched_solve_cond
from ..model import Mechanism
from ..spec import GROUND
from .constraints import joint_blocks
from .frames import perp, rotate
from .path import SweepPath, sweep_path
from .position import BranchChoice, dyad_candidates, track_branches
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
    r = {k: x[idx] for k, x in r.items()}
    th = {k: x[idx] for k, x in th.items()}
    problems: dict[int, tuple[str, str]] = {}   # angle index -> (kind, why it is left out)
    for k in np.flatnonzero(~np.isfinite(r[spec.links[-1].name][:, 0])):
        problems[int(k)] = _unreached(motion, float(phi_deg[k]), mech, r, int(k))
    v, w, acc, al, conds = _rates(mech, np.radians(phi_deg), r, th, problems)
    error = kinematic_error(conds, len(phi_deg))
    for k in np.flatnonzero(error > TRUST_RTOL):
        worst = max(range(len(conds)), key=lambda d: conds[d][k])
        problems.setdefault(int(k), (
            "near-singular",
            f"near-singular: dyad {mech.dyads[worst].label} (condition {conds[worst][k]:.1e}); "
            f"results would not be trustworthy to {TRUST_RTOL:g}"))
    keep = np.ones(len(phi_deg), bool)
    keep[list(problems)] = False
    order = [GROUND] + [l.name for l in spec.links]

    def stack(d):
        return np.stack([d[k] for k in order], axis=1)[keep]

    flags = tuple(Flag(float(phi_deg[k]), why, kind) for k, (kind, why) in sorted(problems.items()))
    return Kinematics(mech, phi_deg[keep], stack(r), stack(th), stack(v), stack(w), stack(acc),
                      stack(al), flags, tuple(branches), motion, error[keep])


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
                               f"{lock[0]:g} and {lock[1]:g} deg")
    bad = next((d for d in mech.dyads if not np.isfinite(r[d.links[0]][k, 0])), None)
    label = bad.label if bad is not None else "?"
    return "cannot close", f"dyad {label} cannot close"


def _positions(mech: Mechanism, path: SweepPath):
    """Link-frame origins r (N, 2) and angles theta (N,) by link name over ``path.angles``,
    dyad by dyad, each branch chosen at the first reference angle and followed along the
    path's runs; NaN where not reached. Also the branch choices and the range of motion."""
    spec = mech.spec
    phi_deg = path.angles
    n, phi = len(phi_deg), np.radians(phi_deg)
    ref_angle = spec.at[0]
    crank = spec.link(spec.driver.link)
    pivot = np.asarray(spec.ground[spec.driver.joint])
    r = {GROUND: np.zeros((n, 2)), crank.name: pivot - rotate(crank.points[spec.driver.joint],
                                                                phi)}
    th = {GROUND: np.zeros(n), crank.name: phi}
    branches: list[BranchChoice] = []
    runs = list(path.runs)
    for dyad in mech.dyads:
        cands = dyad_candidates(spec, dyad, {k: (r[k], th[k]) for k in r})
        if not all(np.all(np.isfinite(c[link][0][path.ref])) for c in cands
                   for link in dyad.links):
            raise AssemblyError(
                f"{spec.file}: the dyad {dyad.label} ({', '.join(dyad.links)}) cannot close at "
                f"the first reference angle {ref_angle:g} deg; check link lengths and `at`")
        chosen, choice, runs = track_branches(spec, dyad, cands, path, runs)
        branches.append(choice)
        for link, (rr, tt) in chosen.items():
            r[link], th[link] = rr, tt
    return r, th, branches, motion_of(path, runs, spec.driver.omega)


def _rates(mech: Mechanism, phi: np.ndarray, r: dict, th: dict,
           problems: dict[int, tuple[str, str]]):
    """Velocities and accelerations (origins and angular) by link name, dyad by dyad: each
    dyad's 6x6 system J qdot = -J_known qdot_known, then J qddot = gamma - J_known qddot_known."""
    spec = mech.spec
    n = len(phi)
    crank = spec.link(spec.driver.link)
    crank_s = rotate(crank.points[spec.driver.joint], phi)
    w_d, a_d = spec.driver.omega, spec.driver.alpha
    zeros2 = np.zeros((n, 2))
    v = {GROUND: zeros2, crank.name: -w_d * perp(crank_s)}
    w = {GROUND: np.zeros(n), crank.name: np.full(n, w_d)}
    acc = {GROUND: zeros2, crank.name: -a_d * perp(crank_s) + w_d**2 * crank_s}
    al = {GROUND: np.zeros(n), crank.name: np.full(n, a_d)}
    finite = np.all(np.isfinite(np.stack([r[k][:, 0] for k in r])), axis=0)
    safe_th = {k: np.where(finite, t, 0.0) for k, t in th.items()}
    safe_r = {k: np.where(finite[:, None], x, 0.0) for k, x in r.items()}
    conds = []
    for dyad in mech.dyads:
        i, j = dyad.links
        A = np.zeros((n, 6, 6))
        b_v, b_a = np.zeros((n, 6)), np.zeros((n, 6))
        known_blocks = []
        for row, joint in enumerate((*dyad.outer, dyad.inner)):
            rows = slice(2 * row, 2 * row + 2)
            blocks, _ = joint_blocks(spec, joint, safe_r, safe_th)
            for link, blk in blocks.items():
                if link in (i, j):
                    col = 0 if link == i else 3
                    A[:, rows, col:col + 3] = blk
                else:
                    known_blocks.append((rows, link, blk))
                    qd = np.concatenate([v[link], w[link][:, None]], axis=1)
                    b_v[:, rows] -= np.einsum("nij,nj->ni", blk, qd)
        x, cond = batched_solve_cond(A, b_v)
        sing = ~(cond < SINGULAR_COND)
        conds.append(np.where(finite, cond, np.inf))
        for k in np.flatnonzero(sing & finite):
            problems.setdefault(int(k), ("singular",
                                         f"dyad {dyad.label}: velocity equations singular"))
        x = np.where(sing[:, None], 0.0, x)
        v[i], w[i], v[j], w[j] = x[:, 0:2], x[:, 2], x[:, 3:5], x[:, 5]
        for row, joint in enumerate((*dyad.outer, dyad.inner)):
            b_a[:, 2 * row:2 * row + 2] += joint_blocks(spec, joint, safe_r, safe_th, v, w)[1]
        for rows, link, blk in known_blocks:
            qdd = np.concatenate([acc[link], al[link][:, None]], axis=1)
            b_a[:, rows] -= np.einsum("nij,nj->ni", blk, qdd)
        x, _ = batched_solve(A, b_a)
        x = np.where(sing[:, None], 0.0, x)
        acc[i], al[i], acc[j], al[j] = x[:, 0:2], x[:, 2], x[:, 3:5], x[:, 5]
    return v, w, acc, al, conds


__all__ = ["solve_kinematics", "Kinematics", "PointState", "Flag", "BranchChoice", "Motion",
           "SINGULAR_COND", "TRUST_RTOL", "EPS"]
