"""Equations of an Assur group over its links' frame coordinates q = (x, y, theta) per link,
batched over angles: residuals and Jacobians (Newton-Raphson for groups without a closed form),
and the rate systems J qdot = -J_known qdot_known and J qddot = gamma - J_known qddot_known of
every group (dyads and the driver's own included).

Columns follow ``group.links`` (3 per link); rows follow ``group.joints`` (2 per joint; the
driver joint adds the row of its prescribed coordinate, see ``constraints.driver_row``).

Groups with no closed form are assembled at the first reference angle by damped Newton from
many starting poses (the assembly hints choose among the distinct solutions; without hints, the
one whose joint points lie highest), then continued along the path's runs: chunks of angles at
once, each guessed by extrapolating the last three solved poses along the travel and corrected
by Newton; the chunk grows while it converges and shrinks when it does not. A run stops where
Newton cannot follow the motion even one sample ahead: the group locks there.
"""
from __future__ import annotations

from functools import cached_property

import numpy as np

from ..errors import AssemblyError
from ..linalg import batched_solve_cond
from ..model import Group
from ..spec import GROUND, Spec
from .constraints import driver_row, geometry, joint_residual, wrap_angle
from .frames import LinkFrames, rotate
from .path import SweepPath
from .position import BranchChoice, Poses, first_false, point_global, signature

STARTS = 96          # starting poses for the assembly at the first reference angle
NEWTON_STEPS = 40    # iterations per solve at most
CHUNK_MAX = 64       # angles per continuation chunk at most
COARSE = 360         # samples of a run followed one chunk after another; the rest at once


def row_scale(spec: Spec, group: Group, scale: float) -> np.ndarray:
    """(3k,) factors that turn the group's angle rows (a slider's relative angle, an R
    driver's angle) into lengths, times the mechanism's size ``scale`` [m]: then every row is a
    length, the condition number does not change with the mechanism's size, and one length
    tolerance serves every row."""
    out = []
    for joint in group.joints:
        out += [scale, 1.0] if joint.type == "T" else [1.0, 1.0]
        if joint.name == group.driver:
            out.append(scale if spec.driver.kind == "R" else 1.0)
    return np.asarray(out)


def equations(spec: Spec, group: Group, r: dict, th: dict, value=None, scale: float = 1.0):
    """Residual F (n, 3k) and Jacobian J (n, 3k, 3k) of the group at poses ``r``, ``th``
    (dicts over every link, (n, 2) and (n,)); ``value`` (n,) the driven coordinate [rad or m]
    when the group holds the driver. Angle rows are multiplied by ``scale`` (``row_scale``).
    The Jacobian is the velocity matrix (:meth:`RateEquations.matrix`)."""
    eqs = RateEquations(spec, group, LinkFrames(r, th))
    F = np.zeros((eqs.frames.n, eqs.m))
    for rows, joint, geo in zip(eqs.rows, group.joints, eqs.geometry):
        F[:, rows] = joint_residual(spec, joint, eqs.frames, geo)
    if eqs.drow is not None:
        gap = eqs.driver_value - value
        F[:, eqs.drow] = wrap_angle(gap) if spec.driver.kind == "R" else gap
    rs = row_scale(spec, group, scale)
    return F * rs, eqs.matrix().transpose(2, 0, 1) * rs[:, None]


class RateEquations:
    """A group's velocity and acceleration equations at the poses ``frames``, angle-last:
    A qdot = -J_known qdot_known and A qddot = gamma - J_known qddot_known (the driver's
    rate and acceleration go on row ``drow``, None without the driver joint).

    Rows follow ``group.joints`` (2 per joint, 3 for the driver joint), columns
    ``group.links`` (x, y, theta each). ``rows``: each joint's rows; ``known``: [(rows, link,
    (r, 3, n))] the Jacobian blocks of links solved before (ground's, whose rates are zero,
    left out), built when first asked for; ``driver_value`` (n,) the driven coordinate at the
    poses. Each joint's geometry is computed once, for the blocks and for gamma."""

    def __init__(self, spec: Spec, group: Group, frames: LinkFrames):
        self.spec, self.group, self.frames = spec, group, frames
        self.m = 3 * len(group.links)
        self.geometry = [geometry(spec, joint, frames) for joint in group.joints]
        self.rows: list[slice] = []
        self.drow = self._driver = self.driver_value = None
        row = 0
        for joint, geo in zip(group.joints, self.geometry):
            self.rows.append(slice(row, row + 2))
            row += 2
            if joint.name == group.driver:
                self.drow = row
                self._driver_geo = geo
                self.driver_value, self._driver, _ = driver_row(spec, frames, geo=geo)
                row += 1

    @cached_property
    def known(self) -> list:
        """[(rows, link, (r, 3, n))]: see the class docstring."""
        out = []
        links = self.group.links
        for rows, joint, geo in zip(self.rows, self.group.joints, self.geometry):
            blocks = {l: np.zeros((2, 3, self.frames.n)) for l in joint.links
                      if l not in links and l != GROUND}
            geo.write_blocks(blocks)
            out += [(rows, l, blk) for l, blk in blocks.items()]
            if joint.name == self.group.driver:
                out += [(slice(self.drow, self.drow + 1), l, blk[None])
                        for l, blk in self._driver.items() if l not in links and l != GROUND]
        return out

    def matrix(self) -> np.ndarray:
        """The velocity matrix A (3k, 3k, n)."""
        col = {l: 3 * i for i, l in enumerate(self.group.links)}
        A = np.zeros((self.m, self.m, self.frames.n))
        for rows, joint, geo in zip(self.rows, self.group.joints, self.geometry):
            geo.write_blocks({l: A[rows, col[l]:col[l] + 3] for l in joint.links if l in col})
        for link, blk in (self._driver or {}).items():
            if link in col:
                A[self.drow, col[link]:col[link] + 3] = blk
        return A

    def known_part(self, lin: dict, ang: dict) -> np.ndarray:
        """J_known qdot_known (or qddot) (3k, n) from the known links' rates ``lin`` (n, 2)
        [m/s or m/s^2] and ``ang`` (n,) [rad/s or rad/s^2]."""
        out = np.zeros((self.m, self.frames.n))
        for rows, link, blk in self.known:
            q = lin[link]
            out[rows] += blk[:, 0] * q[:, 0] + blk[:, 1] * q[:, 1] + blk[:, 2] * ang[link]
        return out

    def gamma(self, v: dict, w: dict) -> np.ndarray:
        """The part of each constraint's second time derivative not in J qddot (3k, n), from
        the velocities ``v`` (n, 2) [m/s], ``w`` (n,) [rad/s] of every link (the group's own
        included)."""
        out = np.empty((self.m, self.frames.n))
        for rows, geo in zip(self.rows, self.geometry):
            out[rows] = geo.gamma(v, w)
        if self.drow is not None:
            out[self.drow] = driver_row(self.spec, self.frames, v, w, self._driver_geo)[2]
        return out


# ------------------------------------------------------------------------ Newton groups

def _as_poses(group: Group, q: np.ndarray) -> Poses:
    """The group's links' poses {link: (r (m, 2), theta (m,))} from coordinates q (m, 3k)."""
    return {l: (q[:, 3 * i:3 * i + 2], q[:, 3 * i + 2]) for i, l in enumerate(group.links)}


def _poses(group: Group, q: np.ndarray, known: Poses, idx: np.ndarray) -> tuple[dict, dict]:
    """Pose dicts at angle indices ``idx``: known links from ``known``, group links from q."""
    r = {l: known[l][0][idx] for l in known}
    th = {l: known[l][1][idx] for l in known}
    for l, (rr, tt) in _as_poses(group, q).items():
        r[l], th[l] = rr, tt
    return r, th


def newton(spec: Spec, group: Group, q: np.ndarray, known: Poses, idx: np.ndarray,
           value: np.ndarray | None, scale: float, steps: int = NEWTON_STEPS,
           patience: int | None = None):
    """Damped Newton-Raphson from ``q`` (m, 3k) at angle indices ``idx`` (m,); returns the
    solution and where it converged (m,) bool: every residual (lengths [m], angles [rad])
    below 1e-13 of ``scale`` (the mechanism's size); converged rows are then polished by one
    more step. Each iteration evaluates only the rows not converged yet (the rows are
    independent: a row's result is the one it gets alone). With ``patience``, it gives up
    once no further row has converged for that many iterations (for many starting poses,
    some of which never converge)."""
    q = q.copy()
    tol = 1e-13 * scale      # lengths [m]; angle rows [rad] are held to the same number
    done = np.zeros(len(q), bool)
    active = np.arange(len(q))  # the rows not converged yet: a converged row stays as it is
    best, since = 0, 0
    for _ in range(steps):
        F, J = _equations_at(spec, group, q[active], known, idx[active], value, scale)
        moving = ~(np.max(np.abs(F), axis=1) <= tol)      # (NaN: not converged)
        done[active[~moving]] = True
        if done.all():
            break
        count = int(done.sum())
        best, since = (count, 0) if count > best else (best, since + 1)
        if patience is not None and best and since >= patience:
            break
        active = active[moving]
        q[active] += _damped_step(J[moving], F[moving], q.shape[1], scale)
    if done.any():           # quadratic convergence: one more step reaches round-off
        F, J = _equations_at(spec, group, q[done], known, idx[done], value, scale)
        q[done] += _damped_step(J, F, q.shape[1], scale)
    return q, done


def _equations_at(spec: Spec, group: Group, q: np.ndarray, known: Poses, idx: np.ndarray,
                  value, scale: float):
    r, th = _poses(group, q, known, idx)
    return equations(spec, group, r, th, None if value is None else value[idx], scale)


def _damped_step(J: np.ndarray, F: np.ndarray, width: int, scale: float) -> np.ndarray:
    """The Newton step -J^-1 F, shortened so that no link moves by more than the mechanism's
    size or turns by more than 1 rad (zero where J is singular)."""
    try:                 # Newton needs no condition estimate: the plain LU solve
        step = np.linalg.solve(J, -F[..., None])[..., 0]
    except np.linalg.LinAlgError:    # an exactly singular pose: the careful solver
        step, _ = batched_solve_cond(J, -F)
    step = np.where(np.isfinite(step), step, 0.0)
    big = np.max(np.abs(step) / np.where(np.arange(width) % 3 == 2, 1.0, scale), axis=1)
    return step * np.minimum(1.0, 1.0 / np.maximum(big, 1e-300))[:, None]


def assemble(spec: Spec, group: Group, known: Poses, path: SweepPath, value, scale: float,
             rng_seed: int = 20261122):
    """Every distinct assembly of the group at the first reference angle, by damped Newton
    from ``STARTS`` starting poses: (solutions (s, 3k), the chosen one's index, the rule)."""
    rng = np.random.default_rng(rng_seed)
    ref = path.ref
    k = len(group.links)
    idx = np.full(STARTS, ref)
    centre = _anchor_centre(spec, group, known, ref)
    q0 = np.zeros((STARTS, 3 * k))
    for i, link in enumerate(group.links):
        theta = rng.uniform(-np.pi, np.pi, STARTS)
        anchor = _anchor(spec, group, link, known, ref)
        local = np.asarray(anchor[1] if anchor else (0.0, 0.0))
        where = anchor[0] if anchor else centre + rng.normal(0, scale / 3, (STARTS, 2))
        q0[:, 3 * i:3 * i + 2] = where - rotate(local, theta)
        q0[:, 3 * i + 2] = theta
    q, ok = newton(spec, group, q0, known, idx, value, scale, steps=80, patience=8)
    if not ok.any():
        raise AssemblyError(
            f"{spec.file}: the {group.class_name} {group.label} ({', '.join(group.links)}) "
            f"cannot be assembled at the first reference angle {path.angles[ref]:g}; check "
            "link lengths, `at` and the assembly hints")
    sols, sig = _distinct(spec, group, q[ok], scale)
    hints = {p: v for p, v in spec.assembly.items() if spec.point_owner(p) in group.links}
    if hints:
        err = np.zeros(len(sols))
        for p, target in hints.items():
            link = spec.point_owner(p)
            i = group.links.index(link)
            pos = sols[:, 3 * i:3 * i + 2] + rotate(spec.link(link).points[p], sols[:, 3 * i + 2])
            err += np.sum((pos - np.asarray(target)) ** 2, axis=1)
        pick = int(np.argmin(err))
        rule = f"hint: {', '.join(hints)} (of {len(sols)} assemblies found)"
    else:
        pick = int(np.argmax(sig[:, 1::2].sum(axis=1)))
        rule = (f"default: of the {len(sols)} assemblies found, the one whose points lie "
                "highest (largest sum of y)")
    return sols, pick, rule


def _anchor(spec: Spec, group: Group, link: str, known: Poses, ref: int):
    """(global point (2,), local point) of a pin joining ``link`` to a known link, if any."""
    for j in group.joints:
        if j.type == "R" and link in j.links:
            other = j.links[1] if j.links[0] == link else j.links[0]
            if other in known:
                at = point_global({other: (known[other][0][ref:ref + 1],
                                           known[other][1][ref:ref + 1])}, other,
                                  spec.points_of(other)[j.point])
                return at[0], spec.link(link).points[j.point]
    return None


def _anchor_centre(spec: Spec, group: Group, known: Poses, ref: int) -> np.ndarray:
    pts = [a[0] for l in group.links if (a := _anchor(spec, group, l, known, ref))]
    return np.mean(pts, axis=0) if pts else np.zeros(2)


def _distinct(spec: Spec, group: Group, sols: np.ndarray, scale: float):
    """The distinct poses among ``sols`` (s, 3k), in a stable order whatever the starts found,
    and their signatures (global positions of every named point, see ``signature``)."""
    every = signature(spec, group.links, _as_poses(group, sols))
    keep: list[int] = []
    for k, sig in enumerate(every):
        if all(np.max(np.abs(sig - every[t])) > 1e-6 * scale for t in keep):
            keep.append(k)
    order = np.lexsort(every[keep].T[::-1])
    return sols[keep][order], every[keep][order]


def continue_group(spec: Spec, group: Group, q_ref: np.ndarray, known: Poses, path: SweepPath,
                   runs: list[np.ndarray], value, scale: float):
    """The group's poses q (N, 3k) over ``path.angles`` followed from ``q_ref`` at the first
    reference angle along each run (NaN where not reached), and the runs cut where it locks.

    Long runs go in two levels: a coarse subset of the run (at most ``COARSE`` samples) is
    followed first; every sample between solved coarse ones is then solved at once from the
    interpolated poses; near a lock, and wherever that fails, the run is followed sample by
    sample."""
    N = len(path.angles)
    q = np.full((N, q_ref.size), np.nan)
    q[path.ref] = q_ref
    reached = np.zeros(N, bool)
    reached[path.ref] = True
    cut = []
    for run, travel in zip(runs, path.travel):
        pos = 1
        stride = max(1, len(run) // COARSE)
        if stride > 1:
            sub = np.arange(0, len(run), stride)
            got = _follow(spec, group, q, reached, run[sub], travel[sub], 1, known, value, scale)
            last = int(sub[got - 1])
            fine = np.setdiff1d(np.arange(1, last + 1), sub)
            fine = fine[~reached[run[fine]]]
            if fine.size:
                solved = sub[:got]
                guess = np.stack([np.interp(travel[fine], travel[solved], q[run[solved], c])
                                  for c in range(q.shape[1])], axis=1)
                sol, ok = newton(spec, group, guess, known, run[fine], value, scale)
                ok &= _continues(sol, guess, q[run[solved]], travel[solved], travel[fine],
                                 scale)
                q[run[fine[ok]]] = sol[ok]
                reached[run[fine[ok]]] = True
                pos = int(fine[~ok][0]) if (~ok).any() else last + 1
            else:
                pos = last + 1
        pos = _follow(spec, group, q, reached, run, travel, pos, known, value, scale)
        cut.append(run[:pos])
    off, lo, hi, w = path.off_grid_neighbours()
    if off.size:
        ok_n = reached[lo] & reached[hi]
        if ok_n.any():
            guess = (1 - w[ok_n])[:, None] * q[lo[ok_n]] + w[ok_n][:, None] * q[hi[ok_n]]
            sol, ok = newton(spec, group, guess, known, off[ok_n], value, scale)
            q[off[ok_n][ok]] = sol[ok]
    return q, cut


def _continues(sol: np.ndarray, guess: np.ndarray, q_coarse: np.ndarray, t_coarse: np.ndarray,
               t_fine: np.ndarray, scale: float) -> np.ndarray:
    """Which fine samples (F,) solved at once stayed on the followed branch: each must land
    within half a coarse step of the pose interpolated between its coarse neighbours (a
    Newton solve from that guess may converge to another assembly). The others are then
    followed sample by sample."""
    def size(dq):   # dimensionless: lengths over the mechanism's size, angles wrapped
        d = dq.reshape(len(dq), -1, 3).copy()
        d[:, :, :2] /= scale
        d[:, :, 2] = wrap_angle(d[:, :, 2])
        return np.sqrt(np.sum(d ** 2, axis=(1, 2)))
    hi = np.clip(np.searchsorted(t_coarse, t_fine), 1, len(t_coarse) - 1)
    step = size(q_coarse[hi] - q_coarse[hi - 1])
    with np.errstate(invalid="ignore"):
        return size(sol - guess) <= 0.5 * step + 1e-9


def _follow(spec: Spec, group: Group, q: np.ndarray, reached: np.ndarray, run: np.ndarray,
            travel: np.ndarray, pos: int, known: Poses, value, scale: float) -> int:
    """Follow ``run`` from its sample ``pos`` (those before it solved) in chunks: each guessed
    by extrapolating the last three solved poses along the travel, corrected by Newton; the
    chunk grows while it converges and shrinks when it does not. Returns where it stopped
    (the run's length, or the first sample it could not reach: a lock). Writes ``q`` and
    ``reached``."""
    chunk = 4
    while pos < len(run):
        if reached[run[pos]]:          # solved already (the forward run came round to here)
            pos += 1
            continue
        idx = run[pos:pos + chunk]
        idx = idx[:first_false(~reached[idx])]
        guess = _extrapolate(q[run[max(0, pos - 3):pos]], travel[max(0, pos - 3):pos],
                             travel[pos:pos + len(idx)])
        sol, ok = newton(spec, group, guess, known, idx, value, scale)
        good = first_false(ok & np.all(np.isfinite(sol), axis=1))
        if good:
            q[idx[:good]] = sol[:good]
            reached[idx[:good]] = True
            pos += good
            chunk = min(CHUNK_MAX, chunk * 2) if good == len(idx) else max(1, good)
        elif chunk > 1:
            chunk = max(1, chunk // 4)
        else:
            break                       # cannot follow even one sample ahead: a lock
    return pos


def _extrapolate(q_prev: np.ndarray, t_prev: np.ndarray, t_new: np.ndarray) -> np.ndarray:
    """Lagrange extrapolation of the last (up to three) solved poses to travels ``t_new``."""
    m = len(t_prev)
    out = np.zeros((len(t_new), q_prev.shape[1]))
    for i in range(m):
        wgt = np.ones(len(t_new))
        for j in range(m):
            if j != i:
                wgt *= (t_new - t_prev[j]) / (t_prev[i] - t_prev[j])
        out += wgt[:, None] * q_prev[i]
    return out


def solve_newton_group(spec: Spec, group: Group, known: Poses, path: SweepPath,
                       runs: list[np.ndarray], value, scale: float):
    """Poses of a group with no closed form over ``path.angles`` (NaN where not reached), how
    its assembly was chosen, and the runs cut where it locks."""
    sols, pick, rule = assemble(spec, group, known, path, value, scale)
    q, runs = continue_group(spec, group, sols[pick], known, path, runs, value, scale)
    name = f"{group.label} ({', '.join(group.links)})"
    return _as_poses(group, q), BranchChoice(name, group.class_name, pick + 1, rule), runs
