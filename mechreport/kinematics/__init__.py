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
from ..linalg import SINGULAR_COND, batched_solve
from ..model import Mechanism
from ..spec import GROUND
from .constraints import joint_blocks
from .frames import perp, rotate
from .position import BranchChoice, dyad_candidates, track_branches
from .result import Flag, Kinematics, PointState


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
    phi = np.radians(phi_deg)
    problems: dict[int, str] = {}   # angle index -> why it is left out
    r, th, branches = _positions(mech, phi_deg, problems)
    v, w, acc, al = _rates(mech, phi, r, th, problems)
    keep = np.ones(len(phi), bool)
    keep[list(problems)] = False
    order = [GROUND] + [l.name for l in spec.links]

    def stack(d):
        return np.stack([d[k] for k in order], axis=1)[keep]

    flags = tuple(Flag(float(phi_deg[k]), why) for k, why in sorted(problems.items()))
    return Kinematics(mech, phi_deg[keep], stack(r), stack(th), stack(v), stack(w), stack(acc),
                      stack(al), flags, tuple(branches))


def _positions(mech: Mechanism, phi_deg: np.ndarray, problems: dict[int, str]):
    """Link-frame origins r (n, 2) and angles theta (n,) by link name, dyad by dyad, with the
    branch of each chosen at the first reference angle and followed through the sweep."""
    spec = mech.spec
    n, phi = len(phi_deg), np.radians(phi_deg)
    ref_angle = spec.at[0]
    ref = int(np.argmin(np.abs(phi_deg - ref_angle)))
    crank = spec.link(spec.driver.link)
    pivot = np.asarray(spec.ground[spec.driver.joint])
    r = {GROUND: np.zeros((n, 2)), crank.name: pivot - rotate(crank.points[spec.driver.joint],
                                                                phi)}
    th = {GROUND: np.zeros(n), crank.name: phi}
    branches: list[BranchChoice] = []
    for dyad in mech.dyads:
        cands = dyad_candidates(spec, dyad, {k: (r[k], th[k]) for k in r})
        if not np.all(np.isfinite(cands[0][dyad.links[0]][0][ref])):
            raise AssemblyError(
                f"{spec.file}: the dyad {dyad.label} ({', '.join(dyad.links)}) cannot close at "
                f"the first reference angle {ref_angle:g} deg; check link lengths and `at`")
        chosen, choice = track_branches(spec, dyad, cands, phi_deg, ref)
        branches.append(choice)
        for link, (rr, tt) in chosen.items():
            r[link], th[link] = rr, tt
        for k in np.flatnonzero(~np.isfinite(chosen[dyad.links[0]][0][:, 0])):
            problems.setdefault(int(k), f"dyad {dyad.label} cannot close")
    return r, th, branches


def _rates(mech: Mechanism, phi: np.ndarray, r: dict, th: dict, problems: dict[int, str]):
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
        x, sing = batched_solve(A, b_v)
        for k in np.flatnonzero(sing & finite):
            problems.setdefault(int(k), f"dyad {dyad.label}: velocity equations singular")
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
    return v, w, acc, al


__all__ = ["solve_kinematics", "Kinematics", "PointState", "Flag", "BranchChoice",
           "SINGULAR_COND"]
