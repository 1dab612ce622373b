"""The kinematics result: link-frame states over the analysed crank angles."""
from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np

from ..model import Mechanism
from ..spec import GROUND
from ..units import deg
from .frames import LinkFrames, perp
from .position import BranchChoice


@dataclass(frozen=True)
class Flag:
    """A crank angle left out of the results, and why. ``kind``: ``unreachable`` (beyond a
    lock), ``cannot close``, ``singular`` or ``near-singular`` (not trustworthy to
    ``TRUST_RTOL``); with friction in the joints, ``friction`` (self-locking: no determined
    friction) or ``friction direction`` (a joint's relative motion stops: the friction's
    sign is undetermined at that angle alone, its neighbours are regular)."""

    angle: float   # [deg]
    reason: str
    kind: str = "singular"

    @property
    def by_friction(self) -> bool:
        """Left out because the friction in a joint is not determined there."""
        return self.kind in ("friction", "friction direction")

    @property
    def isolated(self) -> bool:
        """Only this angle is affected: the values beside it do not rise towards a
        singularity (a joint whose motion reverses there)."""
        return self.kind == "friction direction"


@dataclass(frozen=True)
class Motion:
    """How far the driver moves continuously from the assembled first reference angle.

    ``low`` .. ``high`` [deg] is the range reached (for a whole-turn sweep unwrapped around the
    reference angle, so ``low`` may lie below the sweep's start); ``locks`` the (last reached,
    first not reached) sample pairs where the mechanism locks; ``full`` when nothing of the
    sweep is out of reach (for a whole turn: the crank turns fully)."""

    full: bool
    low: float
    high: float
    locks: tuple[tuple[float, float], ...]
    periodic: bool
    start: float = 0.0   # the sweep's start: wrapped angles are shown in [start, start + 360)
    unit: str = "deg"    # the sweep coordinate's unit (a stroke's length unit for a T driver)

    def _wrap(self, a: float) -> float:
        return self.start + (a - self.start) % 360.0 if self.periodic else a

    def contains(self, angle: float) -> bool:
        if self.full:
            return True
        a = self.low + (angle - self.low) % 360.0 if self.periodic else angle
        return self.low - 1e-9 <= a <= self.high + 1e-9

    def nearest_lock(self, angle: float) -> tuple[float, float] | None:
        """The lock nearest ``angle`` (circular distance for whole turns), wrapped for show."""
        def dist(lock):
            d = abs(angle - (lock[0] + lock[1]) / 2)
            return min(d % 360.0, 360.0 - d % 360.0) if self.periodic else d
        if not self.locks:
            return None
        lock = min(self.locks, key=dist)
        return self._wrap(lock[0]), self._wrap(lock[1])

    def describe(self) -> str | None:
        """One sentence for users, None when the whole sweep is reachable."""
        if self.full:
            return None
        u = self.unit
        locks = " and ".join(f"between {self._wrap(a):g} and {self._wrap(b):g} {u}"
                             for a, b in self.locks)
        if self.periodic:
            return (f"the driver cannot make a full turn: the mechanism locks {locks}; range "
                    f"of motion {self.high - self.low:g} deg, from {self._wrap(self.low):g} to "
                    f"{self._wrap(self.high):g} deg")
        return (f"only {self.low:g} to {self.high:g} {u} can be reached from the assembly: the "
                f"mechanism locks {locks}")


def motion_of(path, runs, omega: float, unit: str = "deg") -> Motion:
    """The range of motion from the ``runs`` of a SweepPath after they were cut at locks."""
    ref = float(path.angles[path.ref])
    ends, locks, full = [], [], []
    for k, (run, whole, travel) in enumerate(zip(runs, path.runs, path.travel)):
        sign = (1.0 if omega > 0 else -1.0) * (1.0 if k == 0 else -1.0)
        ends.append(ref + sign * float(travel[len(run) - 1]))
        full.append(len(run) == len(whole))
        if len(run) < len(whole):
            a, b = ref + sign * float(travel[len(run) - 1]), ref + sign * float(travel[len(run)])
            locks.append((min(a, b), max(a, b)))
    whole_turn = path.periodic and full[0]
    return Motion(whole_turn or all(full), min(ends), max(ends), tuple(locks), path.periodic,
                  float(np.min(path.angles[path.on_grid])), unit)


@dataclass(frozen=True)
class PointState:
    """Global position [m], velocity [m/s], acceleration [m/s^2] of a point, each (n, 2)."""

    r: np.ndarray
    v: np.ndarray
    a: np.ndarray


def angle_ranges(angles, step: float) -> str:
    """Sorted ``angles`` as runs of neighbours ``step`` apart: ``91–110, 236`` (an en dash,
    so that a range of strokes reads ``-10–10``)."""
    runs: list[list[float]] = []
    for a in sorted(map(float, angles)):
        if runs and a - runs[-1][-1] <= step * 1.000001:
            runs[-1].append(a)
        else:
            runs.append([a])
    return ", ".join(deg(r[0]) if len(r) == 1 else f"{deg(r[0])}–{deg(r[-1])}" for r in runs)


def reversal_note(angles, spec) -> str:
    """The note on the angles [deg] where friction alone reverses the driver's effort."""
    return (f"self-locking at {angle_ranges(angles, spec.sweep.step)} {spec.axis_unit}: "
            f"friction alone reverses the sign of {spec.driver.quantity} (without friction "
            "the loads would drive the mechanism there; with it they cannot)")


def friction_notes(flags, spec) -> list[str]:
    """The notes on friction that a reader must see before the numbers: where it jams the
    mechanism (:func:`jam_note`) and entries that act nowhere (``Spec.idle_friction_note``)."""
    return [n for n in (jam_note(flags, spec), spec.idle_friction_note()) if n]


def jam_note(flags, spec) -> str:
    """The note on every range of the sweep where friction self-locks (the mechanism jams:
    no finite driver effort moves it), "" when there is none."""
    jammed = [f.angle for f in flags if f.kind == "friction"]
    if not jammed:
        return ""
    return (f"the mechanism jams at {angle_ranges(jammed, spec.sweep.step)} {spec.axis_unit} "
            f"({len(jammed)} of the sweep's angles): friction self-locks there (its loop gain "
            "is 1 or more), no finite driver effort moves it, and it cannot be driven through "
            "its cycle")


@dataclass(frozen=True)
class Kinematics:
    """Positions, velocities and accelerations over the analysed angles that could be solved.

    Arrays are indexed ``[angle, link]`` with the link axis in link-number order (0 = ground):
    ``r`` (n, L+1, 2) origin of each link frame [m], ``theta`` (n, L+1) [rad], ``v`` [m/s],
    ``omega`` [rad/s], ``a`` [m/s^2], ``alpha`` [rad/s^2]. ``angles`` (n,) are crank angles
    [deg]; ``flags`` lists the angles left out (unreachable, cannot close, singular or
    near-singular); ``motion`` the range the driver reaches from the assembly; ``error`` (n,)
    the estimated relative error of the accelerations (see ``kinematic_error``).
    """

    mechanism: Mechanism
    angles: np.ndarray
    r: np.ndarray
    theta: np.ndarray
    v: np.ndarray
    omega: np.ndarray
    a: np.ndarray
    alpha: np.ndarray
    flags: tuple[Flag, ...]
    branches: tuple[BranchChoice, ...]
    motion: Motion | None = None
    error: np.ndarray | None = None   # (n,) estimated relative error of the accelerations
    # the joints' friction at these angles, once solved (mechreport.forces.friction): by
    # joint, the signed couple [N m] or force [N] on its second link, (n,); None without
    friction: dict[str, np.ndarray] | None = None
    # angles [deg] where friction alone reverses the sign of the driver's effort
    reversed_by_friction: tuple[float, ...] = ()
    # the driver's effort without friction (n,) [N m, or N for a T driver]: the same motion
    # and loads, the joints frictionless (solved with the friction); None without friction
    frictionless: np.ndarray | None = None
    # the driven coordinate's rate (n,) [rad/s or m/s] where it varies from angle to angle
    # (machine dynamics: the crank's true speed); None: the driver's constant omega
    rates: np.ndarray | None = None
    _memo: dict = field(init=False, default_factory=dict, repr=False, compare=False)
    # frames, once made (not a cached_property: that would materialise the instance's dict,
    # and every read of the kinematics' fields would be slower)
    _frames: list = field(init=False, default_factory=list, repr=False, compare=False)

    @property
    def n(self) -> int:
        return len(self.angles)

    def index(self, link: str) -> int:
        return self.mechanism.spec.number(link)

    def point(self, link: str, local) -> PointState:
        """State of the point at ``local`` [m] in ``link``'s frame (computed once; the arrays
        are read-only)."""
        # a local point is a pair of numbers, or one pair per row (stacked variants)
        key = (link, id(local)) if np.ndim(local) > 1 else (link, *map(float, local))
        if key not in self._memo:
            k = self.index(link)
            s = self.frames.rotate(link, local)
            w, al = self.omega[:, k][:, None], self.alpha[:, k][:, None]
            state = PointState(self.r[:, k] + s, self.v[:, k] + w * perp(s),
                               self.a[:, k] + al * perp(s) - w**2 * s)
            for x in (state.r, state.v, state.a):
                x.setflags(write=False)
            self._memo[key] = state
            self._memo[(key, "local")] = local     # keeps id(local) from being reused
        return self._memo[key]

    def prepare_points(self, wanted) -> None:
        """Compute the states of the points ``wanted``, (link, local (2,)) pairs, at once
        (one pass of numpy calls over all of them instead of a dozen per point) for
        :meth:`point` to find: the same numbers (each element by the same operations) and
        the same layout (each state's arrays contiguous, read-only). Points given per row
        (stacked variants) and points already computed are left to :meth:`point`."""
        todo: dict[tuple, tuple[int, tuple[float, float]]] = {}
        for link, local in wanted:
            if np.ndim(local) > 1:
                continue
            key = (link, *map(float, local))
            if key not in self._memo and key not in todo:
                todo[key] = (self.index(link), (key[1], key[2]))
        if not todo:
            return
        ks = [k for k, _ in todo.values()]
        xy = np.array([p for _, p in todo.values()])            # (P, 2)
        x, y = xy[:, :1], xy[:, 1:]
        trig = [self.frames.trig(key[0]) for key in todo]
        c = np.array([t[0] for t in trig])                     # (P, n)
        sn = np.array([t[1] for t in trig])
        count, n = c.shape
        s, ps = np.empty((count, n, 2)), np.empty((count, n, 2))
        s[..., 0] = c * x - sn * y                             # as frames.rotate
        s[..., 1] = sn * x + c * y
        np.negative(s[..., 1], out=ps[..., 0])                 # perp(s)
        ps[..., 1] = s[..., 0]
        w = self.omega[:, ks].T[:, :, None]                    # (P, n, 1)
        al = self.alpha[:, ks].T[:, :, None]
        r, v, a = np.empty((count, n, 2)), np.empty((count, n, 2)), np.empty((count, n, 2))
        np.add(self.r[:, ks].transpose(1, 0, 2), s, out=r)
        np.add(self.v[:, ks].transpose(1, 0, 2), w * ps, out=v)
        np.subtract(self.a[:, ks].transpose(1, 0, 2) + al * ps, w**2 * s, out=a)
        for x_ in (r, v, a):
            x_.setflags(write=False)
        for i, key in enumerate(todo):
            self._memo[key] = PointState(r[i], v[i], a[i])

    @property
    def frames(self) -> LinkFrames:
        """Every link's frame by name (``frames.rotate(link, v)`` turns a vector of the link's
        frame into the global one), each link's cos and sin computed once."""
        if not self._frames:
            spec = self.mechanism.spec
            names = [GROUND] + [link.name for link in spec.links]
            self._frames.append(LinkFrames({l: self.r[:, spec.number(l)] for l in names},
                                           {l: self.theta[:, spec.number(l)] for l in names}))
        return self._frames[0]

    def carry_points(self, source: "Kinematics", rows: slice) -> None:
        """Take the point states ``source`` has computed, at its ``rows`` (this kinematics'
        angles), instead of computing them again: a stacked batch's for one variant, whose
        local points are the rows' own values."""
        for key, state in list(source._memo.items()):
            if key[-1] == "local":
                continue
            if len(key) == 2:        # a local point given per row: this variant's is one pair
                local = source._memo[(key, "local")][rows.start]
                key = (key[0], float(local[0]), float(local[1]))
            if key not in self._memo:
                self._memo[key] = PointState(state.r[rows], state.v[rows], state.a[rows])

    def named_point(self, name: str, link: str | None = None) -> PointState:
        """A named point of ``link`` (default: the first link in spec order that has it)."""
        spec = self.mechanism.spec
        link = link or spec.point_owner(name)
        return self.point(link, spec.points_of(link)[name])

    def com(self, link: str) -> PointState:
        return self.point(link, self.mechanism.spec.link(link).com)

    def take(self, rows: np.ndarray, flags: tuple[Flag, ...]) -> "Kinematics":
        """The same kinematics at angle indices ``rows`` (index array or bool mask)."""
        return replace(self, angles=self.angles[rows], r=self.r[rows], theta=self.theta[rows],
                       v=self.v[rows], omega=self.omega[rows], a=self.a[rows],
                       alpha=self.alpha[rows], flags=flags,
                       error=None if self.error is None else self.error[rows],
                       friction=None if self.friction is None else
                       {j: m[rows] for j, m in self.friction.items()},
                       reversed_by_friction=tuple(
                           a for a in self.reversed_by_friction
                           if np.any(np.abs(self.angles[rows] - a) < 1e-9)),
                       frictionless=None if self.frictionless is None else
                       self.frictionless[rows],
                       rates=None if self.rates is None else self.rates[rows])

    @property
    def driver_rate(self) -> np.ndarray:
        """The driven coordinate's rate at each angle, (n,) [rad/s, or m/s for a T driver]:
        the driver's constant ``omega``, or the true speed of a machine-dynamics cycle."""
        if self.rates is not None:
            return self.rates
        return np.full(self.n, float(self.mechanism.spec.driver.omega))

    def angle_deg(self, link: str) -> np.ndarray:
        """Orientation of ``link``'s x-axis [deg] in (-180, 180], (n,)."""
        deg = (np.degrees(self.theta[:, self.index(link)]) + 180.0) % 360.0 - 180.0
        return np.where(deg == -180.0, 180.0, deg)

    def relative_angle_deg(self, first: str, second: str) -> np.ndarray:
        """``second``'s x-axis from ``first``'s [deg] in (-180, 180], (n,): an R joint's
        relative angle (``joint.J.angle``)."""
        rel = np.degrees(self.theta[:, self.index(second)]
                         - self.theta[:, self.index(first)]) % 360.0
        return np.where(rel > 180.0, rel - 360.0, rel)

    def notes(self) -> list[str]:
        """What a user must know before reading numbers: a driver that cannot make a full
        turn, and branches no hint could choose (one sentence each)."""
        out = []
        if self.motion is not None and not self.motion.full:
            out.append(self.motion.describe())
        out += [f"dyad {b.dyad}: {b.rule}" for b in self.branches
                if b.rule.startswith("undecided")]
        if self.turn_problem:
            out.append(self.turn_problem)
        if self.reversed_by_friction:
            out.append(reversal_note(self.reversed_by_friction, self.mechanism.spec))
        return out + friction_notes(self.flags, self.mechanism.spec)

    @property
    def turn_problem(self) -> str:
        """Why the motion does not repeat every turn ("" when it does, or is not a turn): a
        dyad that comes back on its other branch after a whole turn."""
        swapped = [b.dyad for b in self.branches if not b.closes]
        if not swapped:
            return ""
        return (f"after a whole turn, dyad {', '.join(swapped)} is on its other branch: the "
                "mechanism passes a change point (both branches meet there) and its motion "
                "repeats every two turns; the results after the change point belong to the "
                "other assembly")

    def index_of(self, angle: float) -> int | None:
        """Index of a crank angle among the analysed (solved) ones; None if it was not
        analysed or was left out. The lookup for code that tests presence."""
        hit = np.flatnonzero(np.abs(self.angles - angle) < 1e-9)
        return int(hit[0]) if hit.size else None

    def at(self, angle: float) -> int:
        """Index of a crank angle among the analysed ones, for indexing result arrays
        (``res.driver_torque[kin.at(45)]``). Raises ``KeyError`` naming the reason and the
        nearest analysed angles when ``angle`` was not analysed or was left out (an index of
        None would silently select the whole array); :meth:`index_of` does not raise."""
        k = self.index_of(angle)
        if k is not None:
            return k
        why = next((f"it was left out: {f.reason}" for f in self.flags
                    if abs(f.angle - angle) < 1e-9), "it was not analysed")
        if self.n == 0:
            raise KeyError(f"crank angle {angle:g} deg: {why}; no angle was solved")
        order = np.argsort(np.abs(self.angles - angle), kind="stable")
        below = [a for a in self.angles[order] if a < angle][:1]
        above = [a for a in self.angles[order] if a > angle][:1]
        near = " and ".join(f"{a:g}" for a in sorted(below + above))
        raise KeyError(f"crank angle {angle:g} deg: {why}; nearest analysed angles: {near} "
                       "deg (use index_of() to test whether an angle was analysed)")
