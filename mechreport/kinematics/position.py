"""Closed-form position of each dyad, and the choice and tracking of its assembly branch.

Each dyad type reduces to one geometric primitive (textbook chapters 2-3):

- RRR: two circles (interior pin at fixed distances from the two outer pins);
- RRT / TRR: a circle and a line (the T outer joint fixes the orientation of its link);
- RTR: the common angle of guide and slider solves ``|D| cos(angle(D) - theta - angle(n)) = c``;
- TRT, RTT / TTR: orientations are fixed by the T joints; translations solve 2x2 linear
  systems (one branch only).

Two-branch types give candidates ``sign = +1`` and ``-1``. The branch at the first reference
angle is the one nearest the ``assembly`` hints (or the documented default, ``+1``); it is then
followed through the sweep: between neighbouring angles the branch label flips where the two
candidates meet (a touch, e.g. a slider-crank with AB = BC at 90 deg) and the other label
continues the motion smoothly, judged by extrapolating the last three angles.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..spec import GROUND, Joint, Spec
from ..model import Dyad
from .frames import Trig, cross, dot, norm, perp, rotate, rotate_cs
from .path import SweepPath

Poses = dict  # link name -> (r (n, 2) origin [m], theta (n,) [rad])
BRANCHES_MEET = 1e-9   # candidates this close (relative to the mechanism's size) are one pose

DEFAULT_BRANCH_RULES = {
    "RRR": "the interior pin lies to the left of the line from the outer pin of the link "
           "first by name to the outer pin of the other link",
    "RRT": "the interior pin lies ahead of the foot of the perpendicular from the other pin, "
           "along the guide direction",
    "RTR": "the guide's line direction points from its pivot toward the slider's side "
           "(theta = angle(D) - angle(n) + acos(c/|D|))",
}


@dataclass(frozen=True)
class BranchChoice:
    """How a dyad's assembly branch was chosen at the first reference angle. ``closes``:
    False when, followed through a whole turn, the dyad comes back on its other branch (it
    passes a change point, where both branches meet): its motion repeats every two turns."""

    dyad: str
    kind: str
    sign: int
    rule: str  # "hint: C", "default: <rule>", "undecided: <why>" or "unique"
    closes: bool = True


def point_global(poses: Poses, link: str, local, trig: Trig | None = None) -> np.ndarray:
    """Global position (n, 2) [m] of the point at ``local`` in ``link``'s frame (the frame's
    own point as it is: it never turns, and its origin is the global one). ``trig``: the
    link angles' cos and sin, if remembered."""
    r, th = poses[link]
    if link == GROUND:
        return r + np.asarray(local, float)
    return r + (rotate(local, th) if trig is None else trig.rotate(local, th))


def _other(joint: Joint, link: str) -> str:
    return joint.links[1] if joint.links[0] == link else joint.links[0]


def t_line(spec: Spec, joint: Joint, unknown: str, poses: Poses, theta_u: np.ndarray):
    """T ``joint`` with one side known: returns (n, c) with n . r_unknown = c, where r_unknown
    is the origin of link ``unknown`` whose orientation ``theta_u`` is already fixed."""
    line = joint.line
    n_loc = perp(np.asarray(line.direction, float))
    if unknown == joint.slider:
        guide_r, guide_th = poses[joint.guide]
        n = rotate(n_loc, guide_th)
        through = guide_r + rotate(line.through, guide_th)
        slider_point = spec.points_of(unknown)[joint.point]
        return n, dot(n, through - rotate(slider_point, theta_u))
    n = rotate(n_loc, theta_u)
    s = point_global(poses, joint.slider, spec.points_of(joint.slider)[joint.point])
    return n, dot(n, s - rotate(line.through, theta_u))


def _solve2(n1, c1, n2, c2):
    """Solve n1 . r = c1, n2 . r = c2 for r (n, 2); NaN where the lines are parallel."""
    det = cross(n1, n2)
    ok = np.abs(det) > 1e-12
    det = np.where(ok, det, np.nan)
    x = (c1 * n2[:, 1] - c2 * n1[:, 1]) / det
    y = (n1[:, 0] * c2 - n2[:, 0] * c1) / det
    return np.stack([x, y], axis=-1)


def _angle(v) -> np.ndarray:
    """Direction angle of a local vector (2,) (or one per row, (n, 2)) [rad]."""
    v = np.asarray(v, float)
    return np.arctan2(v[..., 1], v[..., 0])


def dyad_candidates(spec: Spec, dyad: Dyad, poses: Poses, trig: Trig | None = None
                    ) -> list[Poses]:
    """One or two candidate poses of the dyad's links for every angle; NaN where it cannot
    close. ``trig`` remembers the cos and sin of the angles (the known links' and the
    candidates'), for :func:`signature`."""
    trig = trig if trig is not None else Trig()
    rotate = trig.rotate

    def pin_pose(pivot, local_pivot, theta):
        return pivot - rotate(local_pivot, theta), theta

    kind = dyad.kind
    (i, j), (oi, oj), inner = dyad.links, dyad.outer, dyad.inner
    if kind in ("TRR", "TTR"):  # normalise: the R outer joint on link i
        i, j, oi, oj = j, i, oj, oi
        kind = kind[::-1]
    pi, pj = spec.points_of(i), spec.points_of(j)

    def pivot(outer: Joint, link: str):
        known = _other(outer, link)
        return point_global(poses, known, spec.points_of(known)[outer.point], trig)

    out: list[Poses] = []
    if kind == "RRR":
        ki, kj = pivot(oi, i), pivot(oj, j)
        ei, mi = np.array(pi[oi.point]), np.array(pi[inner.point])
        ej, mj = np.array(pj[oj.point]), np.array(pj[inner.point])
        li, lj = norm(mi - ei), norm(mj - ej)
        d = kj - ki
        dist = norm(d)
        with np.errstate(invalid="ignore", divide="ignore"):
            a = (li**2 - lj**2 + dist**2) / (2 * dist)
            h2 = li**2 - a**2
            h = np.sqrt(np.where(h2 >= -1e-12 * li**2, np.maximum(h2, 0), np.nan))
            unit = d / dist[:, None]
        for sign in (1, -1):
            jp = ki + a[:, None] * unit + sign * h[:, None] * perp(unit)
            thi = np.arctan2(*(jp - ki)[:, ::-1].T) - _angle(mi - ei)
            thj = np.arctan2(*(jp - kj)[:, ::-1].T) - _angle(mj - ej)
            out.append({i: pin_pose(ki, ei, thi), j: pin_pose(kj, ej, thj)})
    elif kind == "RRT":
        ki = pivot(oi, i)
        ei, mi = np.array(pi[oi.point]), np.array(pi[inner.point])
        li = norm(mi - ei)
        thj = poses[_other(oj, j)][1]
        n, c = t_line(spec, oj, j, poses, thj)
        mj = pj[inner.point]
        c_pin = c + dot(n, rotate(mj, thj))          # n . J = c_pin for the interior pin J
        u = np.stack([n[:, 1], -n[:, 0]], axis=-1)   # the guide direction
        off = c_pin - dot(n, ki)
        foot = ki + off[:, None] * n
        h2 = li**2 - off**2
        tol = -1e-12 * np.maximum(li**2, 1e-30)
        h = np.sqrt(np.where(h2 >= tol, np.maximum(h2, 0), np.nan))
        for sign in (1, -1):
            jp = foot + sign * h[:, None] * u
            thi = np.arctan2(*(jp - ki)[:, ::-1].T) - _angle(mi - ei)
            out.append({i: pin_pose(ki, ei, thi), j: (jp - rotate(mj, thj), thj)})
    elif kind == "RTR":
        g, s = inner.guide, inner.slider
        og, os_ = (oi, oj) if g == i else (oj, oi)
        kg, ks = pivot(og, g), pivot(os_, s)
        pg, ps = spec.points_of(g), spec.points_of(s)
        line = inner.line
        nl = perp(np.asarray(line.direction, float))
        a = (np.array(ps[inner.point]) - np.array(ps[os_.point]) - np.array(line.through)
             + np.array(pg[og.point]))
        c = -dot(a, nl)
        d = ks - kg
        dist = norm(d)
        with np.errstate(invalid="ignore", divide="ignore"):
            ratio = c / dist
            ok = np.abs(ratio) <= 1 + 1e-12
            half = np.arccos(np.where(ok, np.clip(ratio, -1, 1), np.nan))
        base = np.arctan2(d[:, 1], d[:, 0]) - _angle(nl)
        for sign in (1, -1):
            th = base + sign * half
            out.append({g: pin_pose(kg, pg[og.point], th), s: pin_pose(ks, ps[os_.point], th)})
    elif kind == "TRT":
        thi, thj = poses[_other(oi, i)][1], poses[_other(oj, j)][1]
        n1, c1 = t_line(spec, oi, i, poses, thi)
        n2, c2 = t_line(spec, oj, j, poses, thj)
        # r_j = r_i + R_i m_i - R_j m_j  (interior pin): substitute into the j line
        shift = rotate(pi[inner.point], thi) - rotate(pj[inner.point], thj)
        ri = _solve2(n1, c1, n2, c2 - dot(n2, shift))
        out.append({i: (ri, thi), j: (ri + shift, thj)})
    elif kind == "RTT":
        thj = poses[_other(oj, j)][1]
        ki = pivot(oi, i)
        ri = ki - rotate(pi[oi.point], thj)
        known = dict(poses)
        known[i] = (ri, thj)
        n1, c1 = t_line(spec, oj, j, known, thj)
        n2, c2 = t_line(spec, inner, j, known, thj)
        out.append({i: (ri, thj), j: (_solve2(n1, c1, n2, c2), thj)})
    else:  # pragma: no cover - decompose_groups() rejects TTT
        raise ValueError(kind)
    return out


def signature(spec: Spec, links, cand: Poses, trig: Trig | None = None) -> np.ndarray:
    """Global positions of every named point of ``links`` (a dyad's, a group's) in poses
    ``cand``, flattened: (n, 2 P) [m], in the order of :func:`signature_points`. Each angle
    array's cos and sin are computed once (``trig``: remembered from the candidates)."""
    trig = trig if trig is not None else Trig()
    cols = []
    for link in links:
        r, th = cand[link]
        c, s = trig(th)
        cols += [r + rotate_cs(p, c, s) for p in spec.link(link).points.values()]
    return np.concatenate(cols, axis=1)


def signature_points(spec: Spec, links) -> list[tuple[str, str]]:
    """(point, link) of each pair of signature columns."""
    return [(p, l) for l in links for p in spec.link(l).points]


def track_branches(spec: Spec, dyad: Dyad, cands: list[Poses], path: SweepPath,
                   runs: list[np.ndarray], sig: list[np.ndarray] | None = None,
                   ) -> tuple[Poses, BranchChoice, list[np.ndarray]]:
    """Pick the branch at the first reference angle (``path.ref``) and follow it along the
    ``runs``, each cut where the dyad cannot close (the mechanism locks there). Off-grid angles
    take the candidate nearest the tracked branch interpolated from their grid neighbours.
    Returns the chosen poses over ``path.angles`` (NaN where not reached), how the branch was
    chosen, and the cut runs. ``sig``: the candidates' signatures, if already computed."""
    name = f"{dyad.label} ({', '.join(dyad.links)})"
    sig = sig if sig is not None else [signature(spec, dyad.links, c) for c in cands]
    finite = dyad_closes(sig)
    runs = [run[:first_false(finite[run])] for run in runs]
    n = len(path.angles)
    reached = np.zeros(n, bool)
    use_plus = np.ones(n, bool)
    if len(cands) == 1:
        choice = BranchChoice(name, dyad.kind, 1, "unique")
        for run in runs:
            reached[run] = True
    else:
        sign, rule = pick_branch(spec, dyad, cands, sig, path)
        ring = None
        if path.periodic and len(runs[0]) == len(path.runs[0]):   # a whole turn: back home?
            ring = ring_swaps(sig, runs[0], path.travel[0])
        closes = ring is None or int(np.sum(ring)) % 2 == 0
        choice = BranchChoice(name, dyad.kind, sign, rule, closes)
        for k, (run, travel) in enumerate(zip(runs, path.travel)):
            todo = ~reached[run]
            if not todo.any():   # a full turn forward leaves nothing for the backward run
                continue
            if k == 0 and ring is not None:    # the whole turn's flips, but the step home
                flips = ring[:len(run) - 1]
            else:
                flips = label_swaps(sig[0][run], sig[1][run], travel[:len(run)])
            parity = np.concatenate([[0], np.cumsum(flips)]) % 2
            plus = (parity == 0) == (sign == 1)
            use_plus[run[todo]] = plus[todo]
            reached[run] = True
    off, lo, hi, w = path.off_grid_neighbours()
    if off.size:
        if len(cands) == 2:
            use_plus[off] = nearer_plus([x[off] for x in sig], [x[lo] for x in sig],
                                        [x[hi] for x in sig], use_plus[lo], use_plus[hi], w)
        reached[off] = reached[lo] & reached[hi] & finite[off]
    return chosen_poses(cands, dyad.links, use_plus, reached), choice, runs


def dyad_closes(sig: list[np.ndarray]) -> np.ndarray:
    """Where a dyad closes (n,) bool: every candidate's signature is finite."""
    return np.logical_and.reduce([np.isfinite(x).all(axis=1) for x in sig])


def chosen_poses(cands: list[Poses], links, use_plus: np.ndarray, reached: np.ndarray
                 ) -> Poses:
    """Each link's pose from candidate + where ``use_plus``, else from the other; NaN where
    not ``reached``."""
    out: Poses = {}
    for link in links:
        r = np.where(use_plus[:, None], cands[0][link][0], cands[-1][link][0])
        th = np.where(use_plus, cands[0][link][1], cands[-1][link][1])
        out[link] = (np.where(reached[:, None], r, np.nan), np.where(reached, th, np.nan))
    return out


def nearer_plus(at: list[np.ndarray], lo: list[np.ndarray], hi: list[np.ndarray],
                plus_lo: np.ndarray, plus_hi: np.ndarray, w: np.ndarray) -> np.ndarray:
    """At angles off the tracking grid: whether candidate + is nearer than the other to the
    tracked branch interpolated (weight ``w`` on the upper neighbour) between the grid
    neighbours. ``at``, ``lo``, ``hi``: both candidates' signatures there; ``plus_lo``,
    ``plus_hi``: whether + is the branch at the neighbours."""
    pick = [np.where(p[:, None], x[0], x[-1]) for p, x in ((plus_lo, lo), (plus_hi, hi))]
    guess = (1 - w)[:, None] * pick[0] + w[:, None] * pick[1]
    return np.sum((at[0] - guess) ** 2, axis=1) <= np.sum((at[1] - guess) ** 2, axis=1)


def ring_swaps(sig: list[np.ndarray], run: np.ndarray, travel: np.ndarray) -> np.ndarray:
    """The label swaps (len(run),) along a whole-turn ``run`` (from the reference angle, all
    the way round) and on the step back to its start: the branch comes back to the one it
    started on if their number is even. Those before the last are the run's own flips
    (:func:`label_swaps` decides each interval from the angles before it only)."""
    ring = np.concatenate([run, run[:1]])
    t = np.concatenate([travel[:len(run)], [360.0]])
    return label_swaps(sig[0][ring], sig[-1][ring], t)


def first_false(mask: np.ndarray) -> int:
    bad = np.flatnonzero(~mask)
    return int(bad[0]) if bad.size else len(mask)


def pick_branch(spec: Spec, dyad: Dyad, cands: list[Poses], sig: list[np.ndarray],
                 path: SweepPath) -> tuple[int, str]:
    """The branch sign at the first reference angle and the rule that chose it. Where the two
    branches meet there (a singular position), no hint can decide: say so, take the default
    and say where it leads."""
    ref = path.ref
    kind = dyad.kind if dyad.kind in DEFAULT_BRANCH_RULES else dyad.kind[::-1]
    # candidate +1 of an RRR dyad lies left of the line from link i's pivot to link j's; the
    # default is stated by name so that it does not depend on which link the split found first
    default = -1 if kind == "RRR" and dyad.links[0] > dyad.links[1] else 1
    hints = {p: v for p, v in spec.assembly.items() if spec.point_owner(p) in dyad.links}
    size = max(float(np.max(np.abs(np.concatenate([sig[0][ref], sig[1][ref]])))), 1e-12)
    if float(np.max(np.abs(sig[0][ref] - sig[1][ref]))) <= BRANCHES_MEET * size:
        follow = path.runs[0][1:]
        apart = follow[np.max(np.abs(sig[0][follow] - sig[1][follow]), axis=1)
                       > BRANCHES_MEET * size] if follow.size else follow
        where = ""
        if apart.size:
            k = int(apart[0])
            named = signature_points(spec, dyad.links)
            gap = np.abs(sig[0][k] - sig[1][k]).reshape(-1, 2).max(axis=1)
            p_name, p_link = named[int(np.argmax(gap))]   # the point the branches move most
            taken = cands[0] if default == 1 else cands[1]
            pos = point_global(taken, p_link, spec.link(p_link).points[p_name])[k]
            pos = np.where(np.abs(pos) < 1e-9 * size, 0.0, pos) + 0.0   # no round-off, no -0
            where = (f"; on it, at {path.angles[k]:g} {spec.axis_unit}, {p_name} is at "
                     f"({pos[0]:.6g}, {pos[1]:.6g}) m")
        why = (f"no hint can decide at {path.angles[ref]:g} {spec.axis_unit}, where both "
               "branches meet "
               f"(a singular position); took the default: {DEFAULT_BRANCH_RULES[kind]}{where}. "
               "Choose a first reference angle away from it to choose the branch")
        return default, "undecided: " + why
    if not hints:
        return default, "default: " + DEFAULT_BRANCH_RULES[kind]
    column = {key: 2 * i for i, key in enumerate(signature_points(spec, dyad.links))}
    err = []
    for s in sig:
        e = 0.0
        for p, target in hints.items():
            at = column[(p, spec.point_owner(p))]
            pos = s[ref, at:at + 2]
            e += float(np.sum((pos - np.asarray(target)) ** 2))
        err.append(e)
    return (1 if err[0] <= err[1] else -1), "hint: " + ", ".join(hints)


def label_swaps(xp: np.ndarray, xm: np.ndarray, angles: np.ndarray,
           carried: tuple[bool, bool] | None = None) -> np.ndarray:
    """For each interval k -> k+1 (n-1,): True where the branch labels swap roles.

    The tracked branch's last three positions (k-2, k-1, k) predict k+1 by quadratic
    extrapolation (two points where only two are known); a flip is where, for both labels, the
    other candidate is nearer the prediction and the candidates are close (a touch). The
    history must follow the tracked branch, so its labels at k-1 and k-2 depend on the flips
    before k: every case is decided, and ``_resolve`` picks the applicable ones.

    ``carried``: the flips of the first two intervals, decided already (the samples go on from
    the last three of a run followed before, whose earlier samples decided them); the others
    follow as along the whole run."""
    n = len(angles)
    flips = np.zeros(max(n - 1, 0), bool)
    if carried is not None:
        flips[:2] = carried[:len(flips[:2])]
    if n < 3:
        return flips

    def norm(x: np.ndarray) -> np.ndarray:  # over the flattened point coordinates
        return np.sqrt(np.sum(x * x, axis=1))

    scratch = np.empty((n - 1, xp.shape[1]))

    def dist(a: np.ndarray, b: np.ndarray) -> np.ndarray:   # |a - b| per row, for screening
        d = np.subtract(a, b, out=scratch[:len(a)])
        return np.sqrt(np.einsum("ij,ij->i", d, d))

    X = (xp, xm)
    apart = dist(xp[1:], xm[1:])
    step = dist(xp[2:], xp[1:-1]) + dist(xm[2:], xm[1:-1])
    gap = np.minimum(apart[:-1], apart[1:])
    decide = np.zeros((2, 2, n - 2), bool)   # [flip before k, flip before k-1, interval k-1]
    J = np.flatnonzero(gap <= 2 * step)      # only where the candidates are close (a touch)
    if J.size == 0:            # no touch: no flip (what _resolve gives for all-False)
        return flips
    t0, t1, t2, t3 = (angles[np.maximum(J - 1, 0)], angles[J], angles[J + 1], angles[J + 2])
    scale = ((t3 - t2) / (t2 - t1))[:, None]
    # Lagrange weights extrapolating (t0, t1, t2) to t3 (from the third angle of the run on)
    third = J >= 1
    with np.errstate(divide="ignore", invalid="ignore"):
        w0 = ((t3 - t1) * (t3 - t2) / ((t0 - t1) * (t0 - t2)))[:, None]
        w1 = ((t3 - t0) * (t3 - t2) / ((t1 - t0) * (t1 - t2)))[:, None]
        w2 = ((t3 - t0) * (t3 - t1) / ((t2 - t0) * (t2 - t1)))[:, None]
    back = np.maximum(J - 1, 0)
    for a in (0, 1):
        for b in (0, 1):
            votes = np.zeros(J.size)
            for lab in (0, 1):
                same, other = X[lab], X[1 - lab]
                x_k, x_k1 = same[J + 1], X[lab ^ a][J]
                pred = x_k + (x_k - x_k1) * scale                  # two-point prediction
                with np.errstate(invalid="ignore", over="ignore"):
                    quad = w0 * X[lab ^ a ^ b][back] + w1 * x_k1 + w2 * x_k
                use = third[:, None] & np.isfinite(quad)
                pred = np.where(use, quad, pred)
                votes += norm(other[J + 2] - pred) < norm(same[J + 2] - pred)
            decide[a, b, J] = votes == 2
    if carried is None:
        flips[1:] = _resolve(decide)
    else:   # the first interval decided here is the third: from the state the two carried
        flips[2:] = _resolve(decide[:, :, 1:], 2 * int(carried[1]) + int(carried[0]))
    return flips


def _resolve(decide: np.ndarray, start: int = 0) -> np.ndarray:
    """f[k] = decide[f[k-1], f[k-2], k] from the state ``start`` = 2 f[-1] + f[-2] (default:
    f[-1] = f[-2] = False), vectorised.

    Each step maps the state s = 2 f[k-1] + f[k-2] to 2 f[k] + f[k-1]; the states follow from
    the prefix compositions of these maps, computed by doubling (log2(n) gathers)."""
    m = decide.shape[2]
    if m == 0:
        return np.zeros(0, bool)
    maps = np.empty((m, 4), np.intp)
    for state in range(4):
        f1, f2 = state >> 1, state & 1
        maps[:, state] = 2 * decide[f1, f2].astype(np.intp) + f1
    d = 1
    while d < m:
        maps[d:] = np.take_along_axis(maps[d:], maps[:-d], axis=1)
        d *= 2
    return (maps[:, start] >> 1).astype(bool)
