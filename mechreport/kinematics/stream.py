"""The kinematics of a long sweep a chunk of angles at a time, in bounded memory.

Two passes, both over chunks:

1. **Branches** (:class:`_Tracker`): along each run of the path (see ``path``), a chunk of
   samples at a time, the driver's pose and every dyad's candidates, group after group. Each
   dyad's label swaps are decided by the rule of :func:`position.track_branches`, each chunk
   carrying the last three samples and the last two swaps of the one before it, so the labels
   are the whole-sweep tracking's. Kept: one bool per sample and dyad (which candidate), one
   per sample and group (reached), the runs as cut at locks, and each dyad's ``BranchChoice``
   (with whether a whole turn brings it back to its branch).
2. **Chunks** (iterating :class:`KinematicChunks`): the analysed angles in increasing order,
   ``size`` at a time; each dyad's poses from its kept labels, then rates, condition numbers
   and flags exactly as :func:`solve_kinematics` (:func:`finish`).

Only mechanisms of dyads are streamed (:func:`streamable`): a group without a closed form is
continued by Newton along the whole path.
"""
from __future__ import annotations

from dataclasses import dataclass, replace
from types import SimpleNamespace

import numpy as np

from ..model import Mechanism
from ..spec import GROUND
from . import driver_pose, finish, require_closes_at_ref
from .path import SweepPath, sweep_path
from .position import (BranchChoice, chosen_poses, dyad_candidates, dyad_closes, first_false,
                       label_swaps, nearer_plus, pick_branch, signature)
from .result import Kinematics, Motion, motion_of

TRACK_CHUNK = 65536   # samples per chunk of the branch-tracking pass (at least 3)


def streamable(mech: Mechanism) -> bool:
    """Whether the kinematics can be solved chunk by chunk: the driver's link and dyads only."""
    return all(g.dyad is not None or (g.driver is not None and len(g.links) == 1)
               for g in mech.groups)


@dataclass
class KinematicChunks:
    """A sweep's branch labels (pass 1); iterate it for the kinematics in chunks of ``size``
    analysed angles (pass 2). ``branches`` and ``motion`` as a whole sweep's ``Kinematics``."""

    mech: Mechanism
    angles: np.ndarray                   # (n,) the analysed angles [deg], increasing
    size: int
    plus: dict[str, np.ndarray]          # dyad label -> (n,) bool: its candidate + is taken
    reached: list[np.ndarray]            # per group, (n,) bool
    branches: tuple[BranchChoice, ...]
    motion: Motion

    def __iter__(self):
        for a in range(0, len(self.angles), self.size):
            yield self._solve(np.arange(a, min(a + self.size, len(self.angles))))

    def probes(self, count: int) -> Kinematics:
        """The kinematics at up to ``count`` analysed angles spread evenly over those every
        group reaches (where the contour method chooses its equations)."""
        idx = np.flatnonzero(self.reached[-1])
        pick = np.unique(np.linspace(0, len(idx) - 1, min(count, len(idx))).round()
                         .astype(int)) if len(idx) else np.zeros(0, int)
        return self._solve(idx[pick])

    @property
    def turn_problem(self) -> str:
        return self._summary().turn_problem

    def notes(self) -> list[str]:
        return self._summary().notes()

    def _summary(self) -> Kinematics:
        """A Kinematics with no angle: what the whole sweep's says of its branches and motion."""
        L = len(self.mech.spec.links) + 1
        e2, e1 = np.zeros((0, L, 2)), np.zeros((0, L))
        return Kinematics(self.mech, np.zeros(0), e2, e1, e2, e1, e2, e1, (), self.branches,
                          self.motion, np.zeros(0))

    def _solve(self, idx: np.ndarray) -> Kinematics:
        """The kinematics at analysed angles ``idx`` (indices, increasing), from the kept
        labels."""
        spec = self.mech.spec
        n = len(idx)
        r = {GROUND: np.zeros((n, 2))}
        th = {GROUND: np.zeros(n)}
        for g, group in enumerate(self.mech.groups):
            if group.dyad is None:           # the driver's link: everywhere
                chosen = driver_pose(spec, self.angles[idx] * spec.driver.unit)
            else:
                cands = dyad_candidates(spec, group.dyad, {k: (r[k], th[k]) for k in r})
                chosen = chosen_poses(cands, group.dyad.links, self.plus[group.dyad.label][idx],
                                      self.reached[g][idx])
            for link, (rr, tt) in chosen.items():
                r[link], th[link] = rr, tt
        return finish(self.mech, self.angles[idx], r, th, self.branches, self.motion)


def kinematic_chunks(mech: Mechanism, size: int) -> KinematicChunks:
    """Pass 1 over the spec's analysed angles (see the module's docstring); iterate the result
    for the kinematics, ``size`` angles at a time. Raises ``AssemblyError`` when a dyad cannot
    close at the first reference angle."""
    spec = mech.spec
    path = sweep_path(spec, spec.analysed_angles(), spec.at[0])
    tracker = _Tracker(mech, path)
    runs = tracker.run()
    a = path.analysed       # only the analysed angles' labels are kept (not the path's)
    return KinematicChunks(mech, path.angles[a], size,
                           {k: v[a] for k, v in tracker.plus.items()},
                           [r[a] for r in tracker.reached],
                           tuple(tracker.choices[g.dyad.label] for g in mech.groups
                                 if g.dyad is not None),
                           motion_of(path, runs, spec.driver.omega, spec.axis_unit))


@dataclass
class _Follow:
    """A two-branch dyad followed along one run: the sign chosen at the reference angle, the
    label parity at the last sample, the swaps of the last two intervals, and the last three
    samples' signatures (both candidates) and travel."""

    sign: int
    parity: int = 0
    swaps: tuple[bool, bool] = (False, False)
    tail: tuple | None = None

    def labels(self, xp: np.ndarray, xm: np.ndarray, t: np.ndarray) -> np.ndarray:
        """Whether candidate + is the followed branch (m,) at the next ``m`` samples of the
        run (signatures ``xp``, ``xm``, travel ``t``)."""
        incoming = self._swaps(xp, xm, t)     # the swap into each new sample
        parity = (self.parity + np.cumsum(incoming)) % 2
        self.parity = int(parity[-1]) if len(parity) else self.parity
        if self.tail is not None:
            xp, xm, t = (np.concatenate([a, b]) for a, b in zip(self.tail, (xp, xm, t)))
        self.tail = (xp[-3:], xm[-3:], t[-3:])
        return (parity == 0) == (self.sign == 1)

    def ring_swap(self, head: tuple, turn: float = 360.0) -> bool:
        """Whether the labels swap on the step from the run's last sample back to its first
        (``head``: both candidates' signatures there), a whole turn on."""
        return bool(self._swaps(head[0], head[1], np.array([turn]))[-1])

    def _swaps(self, xp: np.ndarray, xm: np.ndarray, t: np.ndarray) -> np.ndarray:
        """The label swap (m,) on the interval into each of the next samples (0 into the run's
        first), and the last two swaps kept for the next call. With three samples of history
        the window goes on from the carried swaps; with fewer, the history is the whole run so
        far, and the run's swaps are decided again from its start."""
        n_tail = 0 if self.tail is None else len(self.tail[0])
        if n_tail:
            tp, tm, tt = self.tail
            xp, xm, t = np.concatenate([tp, xp]), np.concatenate([tm, xm]), np.concatenate([tt, t])
        if n_tail == 3:
            known = label_swaps(xp, xm, t, carried=self.swaps)
            incoming, history = known[2:], known
        else:
            run = label_swaps(xp, xm, t)             # every swap of the run from its start
            incoming = run[n_tail - 1:] if n_tail else np.concatenate([[False], run])
            history = run
        history = np.concatenate([[False, False], history])
        self.swaps = (bool(history[-2]), bool(history[-1]))
        return incoming.astype(int)


class _Tracker:
    """Pass 1: every group's reach and every dyad's labels along the path's runs."""

    def __init__(self, mech: Mechanism, path: SweepPath):
        self.mech, self.spec, self.path = mech, mech.spec, path
        N = len(path.angles)
        self.groups = mech.groups
        self.plus = {g.dyad.label: np.ones(N, bool) for g in self.groups if g.dyad is not None}
        self.reached = [np.zeros(N, bool) for _ in self.groups]
        self.follow: dict[str, _Follow] = {}
        self.head: dict[str, tuple] = {}
        self.choices: dict[str, BranchChoice] = {}

    def run(self) -> list[np.ndarray]:
        """Track both runs, then the angles off the grid; the runs as cut at locks."""
        path = self.path
        cuts: list[int] = []
        for k, run in enumerate(path.runs):
            if k == 1 and path.periodic and cuts[0] == len(path.runs[0]):
                cuts.append(len(run))   # a whole turn forward leaves nothing to go back for
                continue
            alive = [len(run)] * len(self.groups)   # where each group's run ends
            for s in range(0, len(run), TRACK_CHUNK):
                if len(alive) > 1 and s >= alive[1]:
                    break
                self._chunk(run, path.travel[k], s, min(s + TRACK_CHUNK, len(run)), k, alive)
            cuts.append(alive[-1])
            if k == 0 and path.periodic:
                self._closes(alive, run)
            for f in self.follow.values():     # the backward run starts at the reference
                f.parity, f.swaps, f.tail = 0, (False, False), None
        self._off_grid()
        return [run[:c] for run, c in zip(path.runs, cuts)]

    def _closes(self, alive: list[int], run: np.ndarray) -> None:
        """Each two-branch dyad followed all the way round: back on its own branch?"""
        for g, group in enumerate(self.groups):
            label = group.dyad.label if group.dyad is not None else None
            if label in self.follow and alive[g] == len(run):
                f = self.follow[label]
                closes = (f.parity + f.ring_swap(self.head[label])) % 2 == 0
                self.choices[label] = replace(self.choices[label], closes=closes)

    def _chunk(self, run: np.ndarray, travel: np.ndarray, s: int, e: int, k: int,
               alive: list[int]) -> None:
        """Samples ``run[s:e]`` of run ``k``: every group in turn, each as far as it (and every
        group before it) closes; ``alive`` updated where a group first cannot."""
        spec = self.spec
        idx = run[s:e]
        r = {GROUND: np.zeros((len(idx), 2))}
        th = {GROUND: np.zeros(len(idx))}
        limit = len(idx)
        for g, group in enumerate(self.groups):
            limit = min(limit, alive[g] - s)
            if limit <= 0:
                break
            part = idx[:limit]
            known = {key: (r[key][:limit], th[key][:limit]) for key in r}
            if group.dyad is None:
                chosen = driver_pose(spec, self.path.angles[part] * spec.driver.unit)
                self.reached[g][part] = True
            else:
                chosen, closed = self._dyad(g, group.dyad, known, part, travel[s:s + limit],
                                            first=(k == 0 and s == 0))
                if closed < limit:
                    for j in range(g, len(alive)):
                        alive[j] = min(alive[j], s + closed)
                    limit = closed
            for link, (rr, tt) in chosen.items():
                r[link], th[link] = rr, tt

    def _dyad(self, g: int, dyad, known: dict, part: np.ndarray, travel: np.ndarray,
              first: bool) -> tuple[dict, int]:
        """One dyad over ``part`` (path indices along a run): its chosen poses up to where it
        first cannot close, and how many samples that is."""
        spec = self.spec
        cands = dyad_candidates(spec, dyad, known)
        sig = [signature(spec, dyad.links, c) for c in cands]
        closed = first_false(dyad_closes(sig))
        if first:                  # the first sample is the first reference angle
            require_closes_at_ref(spec, dyad, cands, 0)
            self._choose(dyad, cands, sig, part)
        cands = [{l: (c[l][0][:closed], c[l][1][:closed]) for l in c} for c in cands]
        sig = [x[:closed] for x in sig]
        part = part[:closed]
        label = dyad.label
        reached = self.reached[g]
        if len(cands) == 2:
            fresh = ~reached[part]
            labels = self.follow[label].labels(sig[0], sig[1], travel[:closed])
            self.plus[label][part[fresh]] = labels[fresh]
            if first:
                self.head[label] = (sig[0][:1], sig[1][:1])
        reached[part] = True
        return chosen_poses(cands, dyad.links, self.plus[label][part], reached[part]), closed

    def _choose(self, dyad, cands: list[dict], sig: list[np.ndarray],
                part: np.ndarray) -> None:
        """The branch at the first reference angle (``part[0]``), by ``pick_branch`` over the
        chunk that starts there."""
        name = f"{dyad.label} ({', '.join(dyad.links)})"
        if len(cands) == 1:
            self.choices[dyad.label] = BranchChoice(name, dyad.kind, 1, "unique")
            return
        local = SimpleNamespace(ref=0, runs=(np.arange(len(part)),),
                                angles=self.path.angles[part])
        sign, rule = pick_branch(self.spec, dyad, cands, sig, local)
        self.choices[dyad.label] = BranchChoice(name, dyad.kind, sign, rule)
        self.follow[dyad.label] = _Follow(sign)

    def _off_grid(self) -> None:
        """Angles off the tracking grid take the candidate nearest the tracked branch
        interpolated from their grid neighbours (as ``track_branches``)."""
        spec, path = self.spec, self.path
        off, lo, hi, w = path.off_grid_neighbours()
        if not off.size:
            return
        m = len(off)
        idx = np.concatenate([off, lo, hi])
        r = {GROUND: np.zeros((3 * m, 2))}
        th = {GROUND: np.zeros(3 * m)}
        for g, group in enumerate(self.groups):
            if group.dyad is None:
                chosen = driver_pose(spec, path.angles[idx] * spec.driver.unit)
                self.reached[g][off] = True
            else:
                dyad = group.dyad
                cands = dyad_candidates(spec, dyad, {k: (r[k], th[k]) for k in r})
                sig = [signature(spec, dyad.links, c) for c in cands]
                plus, reached = self.plus[dyad.label], self.reached[g]
                if len(cands) == 2:    # rows: the off-grid angles, then their neighbours
                    plus[off] = nearer_plus([x[:m] for x in sig], [x[m:2 * m] for x in sig],
                                            [x[2 * m:] for x in sig], plus[lo], plus[hi], w)
                reached[off] = reached[lo] & reached[hi] & dyad_closes(sig)[:m]
                chosen = chosen_poses(cands, dyad.links, plus[idx], reached[idx])
            for link, (rr, tt) in chosen.items():
                r[link], th[link] = rr, tt
