"""Kinematics of many variants of one mechanism at once (a design study's batch).

The variants' numbers are stacked with the angles (:mod:`mechreport.spec.stack`): rows are
variants x angles, and the closed-form poses, the velocity and acceleration systems and their
condition numbers are computed for every row in one pass, exactly as for one spec. What
follows one variant's sweep (choosing its branch at the first reference angle, following it,
its range of motion) runs per variant on its own rows, through the same functions as a
single analysis.

A variant whose sweep is not clean (an angle that cannot close, is unreachable, singular or
near-singular) is marked, not analysed here: the caller analyses it alone, so its flags and
reasons are exactly those of a single analysis.
"""
from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from ..model import Mechanism
from ..spec import GROUND, Spec
from ..spec.stack import stack_specs
from . import TRUST_RTOL, _rates, driver_pose, kinematic_error
from .constraints import joint_residual
from .frames import LinkFrames
from .path import sweep_path
from .position import dyad_candidates, signature, track_branches
from .result import Kinematics, Motion, motion_of


@dataclass(frozen=True)
class StackedKinematics:
    """``kin``: every variant's kinematics, rows variant-major (``per`` rows each) over the
    stacked spec; ``clean`` (V,) the variants whose every angle was solved and trusted;
    ``motions`` each variant's range of motion; ``branches`` each variant's assembly branch
    choices (one per two-branch dyad, as ``Kinematics.branches``)."""

    kin: Kinematics
    per: int
    clean: np.ndarray
    motions: tuple[Motion | None, ...]
    branches: tuple[tuple, ...] = ()

    def rows(self, v: int) -> slice:
        return slice(v * self.per, (v + 1) * self.per)


def stackable(mech: Mechanism) -> bool:
    """Closed forms only: the driver's link and dyads (Newton groups follow each variant's
    continuation alone)."""
    return all(g.dyad is not None or (g.driver is not None and len(g.links) == 1)
               for g in mech.groups)


def solve_stacked(mech: Mechanism, specs: list[Spec]) -> StackedKinematics | None:
    """Kinematics of ``specs`` (variants of ``mech.spec`` that differ in numbers only), or
    None when they cannot be stacked (see :func:`mechreport.spec.stack.stack_specs`)."""
    first = specs[0]
    if not stackable(mech) or len({np.sign(s.driver.omega) for s in specs}) != 1:
        return None
    phi = first.analysed_angles()
    path = sweep_path(first, phi, first.at[0])
    n_path, per, V = len(path.angles), len(phi), len(specs)
    on_path = stack_specs(specs, n_path)
    analysed = on_path if n_path == per else stack_specs(specs, per)
    if on_path is None or analysed is None:
        return None
    unit = first.driver.unit
    mech = mech.with_spec(on_path)      # the groups' joints (their lines) are the stacked ones
    value = np.tile(path.angles * unit, V)
    r = {GROUND: np.zeros((V * n_path, 2))}
    th = {GROUND: np.zeros(V * n_path)}
    clean = np.ones(V, bool)
    runs = [list(path.runs) for _ in range(V)]
    choices: list[list] = [[] for _ in range(V)]
    own = [mech.with_spec(s) for s in specs]     # each variant's joints, for its bookkeeping
    for g, group in enumerate(mech.groups):
        if group.dyad is None:
            chosen = driver_pose(on_path, value)
        else:
            cands = dyad_candidates(on_path, group.dyad, {k: (r[k], th[k]) for k in r})
            sigs = [signature(on_path, group.dyad.links, c) for c in cands]
            chosen = {l: (np.full((V * n_path, 2), np.nan), np.full(V * n_path, np.nan))
                      for l in group.links}
            for v in range(V):
                cut = slice(v * n_path, (v + 1) * n_path)
                mine = [{l: (c[l][0][cut], c[l][1][cut]) for l in c} for c in cands]
                if not all(np.all(np.isfinite(c[l][0][path.ref])) for c in mine for l in c):
                    clean[v] = False          # cannot assemble: analysed alone, for its reason
                    continue
                poses, choice, runs[v] = track_branches(specs[v], own[v].groups[g].dyad, mine,
                                                        path, runs[v], [s[cut] for s in sigs])
                choices[v].append(choice)
                if not choice.closes:
                    clean[v] = False         # analysed alone: its review says why it has none
                for l, (rr, tt) in poses.items():
                    chosen[l][0][cut], chosen[l][1][cut] = rr, tt
        for link, (rr, tt) in chosen.items():
            r[link], th[link] = rr, tt
    motions = tuple(motion_of(path, runs[v], specs[v].driver.omega, first.axis_unit)
                    if clean[v] else None for v in range(V))
    idx = (np.arange(V)[:, None] * n_path + path.analysed[None, :]).ravel()
    r = {k: x[idx] for k, x in r.items()}
    th = {k: x[idx] for k, x in th.items()}
    flat = mech.with_spec(analysed)
    problems: dict[int, tuple[str, str]] = {}
    v_, w_, acc, al, conds = _rates(flat, np.tile(phi * unit, V), r, th, problems)
    error = kinematic_error([c for _, c in conds], V * per)
    bad = ~np.isfinite(r[first.links[-1].name][:, 0]) | (error > TRUST_RTOL)
    bad |= ~_closed(flat, r, th)
    bad[list(problems)] = True
    clean &= ~bad.reshape(V, per).any(axis=1)
    order = [GROUND] + [l.name for l in first.links]

    def by_link(d):
        return np.stack([d[k] for k in order], axis=1)

    kin = Kinematics(flat, np.tile(phi, V), by_link(r), by_link(th), by_link(v_), by_link(w_),
                     by_link(acc), by_link(al), (), (), None, error)
    return StackedKinematics(kin, per, clean, motions, tuple(map(tuple, choices)))


def _closed(mech: Mechanism, r: dict, th: dict) -> np.ndarray:
    """Rows (n,) where every joint closes (gaps within 1e-9 of the mechanism's extent, angles
    within 1e-9 rad): a check that the stacked poses are each variant's own."""
    with np.errstate(invalid="ignore"):
        scale = 1e-3 + np.max(np.stack([np.abs(x).max(axis=1) for x in r.values()]), axis=0)
        ok = np.ones(len(scale), bool)
        frames = LinkFrames(r, th)
        for joint in mech.spec.joints:
            gap = joint_residual(mech.spec, joint, frames)
            if joint.type == "R":
                ok &= np.hypot(gap[:, 0], gap[:, 1]) <= 1e-9 * scale
            else:
                ok &= (np.abs(gap[:, 0]) <= 1e-9) & (np.abs(gap[:, 1]) <= 1e-9 * scale)
    return ok


def variant_kinematics(stacked: StackedKinematics, v: int, mech: Mechanism) -> Kinematics:
    """Variant ``v``'s own kinematics (its rows, its spec in ``mech``)."""
    kin = replace(stacked.kin.take(stacked.rows(v), ()), mechanism=mech,
                  motion=stacked.motions[v],
                  branches=stacked.branches[v] if stacked.branches else ())
    kin.carry_points(stacked.kin, stacked.rows(v))
    return kin
