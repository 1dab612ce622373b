"""Stage 3: kinematics over the crank sweep, vectorised over the angle axis.

Positions come dyad by dyad in closed form (``position``); velocities and accelerations solve,
dyad by dyad, the differentiated joint constraints (``constraints``) as batched 6x6 systems.
Angles where a dyad cannot close, or whose velocity equations are singular (condition number
of the equilibrated 6x6 system above ``SINGULAR_COND``, see ``linalg``), are flagged and left
out.
"""
from __future__ import annotations

from dataclasses import replace

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
    rows = pos[hit]
    flags = tuple(f for f in kin.flags if np.any(np.abs(wanted - f.angle) < 1e-9))
    return replace(kin, angles=have[rows], r=kin.r[rows], theta=kin.theta[rows], v=kin.v[rows],
                   omega=kin.omega[rows], a=kin.a[rows], alpha=kin.alpha[rows], flags=flags)


def _solve(mech: Mechanism, phi_deg: np.ndarray) -> Kinematics:
    spec = mech.spec
    n = len(phi_deg)
    phi = np.radians(phi_deg)
    ref_angle = spec.at[0]
    ref = int(np.argmin(np.abs(phi_deg - ref_angle)))

    crank = spec.link(spec.driver.link)
    pivot = np.asarray(spec.ground[spec.driver.joint])
    p_loc = crank.points[spec.driver.joint]
    zeros2 = np.zeros((n, 2))
    r = {GROUND: zeros2, crank.name: pivot - rotate(p_loc, phi)}
    th = {GROUND: np.zeros(n), crank.name: phi}
    problems: dict[int, str] = {}

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
        bad = ~np.isfinite(chosen[dyad.links[0]][0][:, 0])
        for k in np.flatnonzero(bad):
            problems.setdefault(int(k), f"dyad {dyad.label} cannot close")

    # velocities and accelerations, dyad by dyad
    crank_s = rotate(p_loc, phi)
    w_d, a_d = spec.driver.omega, spec.driver.alpha
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
        b_v = np.zeros((n, 6))
        rows = []
        for row, joint in enumerate((*dyad.outer, dyad.inner)):
            blocks, _ = joint_blocks(spec, joint, safe_r, safe_th)
            rows.append((row, joint, blocks))
            for link, blk in blocks.items():
                if link in (i, j):
                    col = 0 if link == i else 3
                    A[:, 2 * row:2 * row + 2, col:col + 3] = blk
                else:
                    qd = np.concatenate([v[link], w[link][:, None]], axis=1)
                    b_v[:, 2 * row:2 * row + 2] -= np.einsum("nij,nj->ni", blk, qd)
        x, sing = batched_solve(A, b_v)
        for k in np.flatnonzero(sing & finite):
            problems.setdefault(int(k), f"dyad {dyad.label}: velocity equations singular")
        x = np.where(sing[:, None], 0.0, x)
        v[i], w[i] = x[:, 0:2], x[:, 2]
        v[j], w[j] = x[:, 3:5], x[:, 5]
        b_a = np.zeros((n, 6))
        for row, joint, blocks in rows:
            _, gamma = joint_blocks(spec, joint, safe_r, safe_th, v, w)
            b_a[:, 2 * row:2 * row + 2] += gamma
            for link, blk in blocks.items():
                if link not in (i, j):
                    qdd = np.concatenate([acc[link], al[link][:, None]], axis=1)
                    b_a[:, 2 * row:2 * row + 2] -= np.einsum("nij,nj->ni", blk, qdd)
        x, _ = batched_solve(A, b_a)
        x = np.where(sing[:, None], 0.0, x)
        acc[i], al[i] = x[:, 0:2], x[:, 2]
        acc[j], al[j] = x[:, 3:5], x[:, 5]

    keep = np.ones(n, bool)
    keep[list(problems)] = False
    order = [GROUND] + [l.name for l in spec.links]

    def stack(d, vec):
        arr = np.stack([d[k] for k in order], axis=1)
        return arr[keep]

    flags = tuple(Flag(float(phi_deg[k]), why) for k, why in sorted(problems.items()))
    theta = stack(th, False)
    return Kinematics(mech, phi_deg[keep], stack(r, True), theta, stack(v, True), stack(w, False),
                      stack(acc, True), stack(al, False), flags, tuple(branches))


__all__ = ["solve_kinematics", "Kinematics", "PointState", "Flag", "BranchChoice",
           "SINGULAR_COND"]
