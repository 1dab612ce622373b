"""Cycle quantities of a whole-turn analysis: the numbers a design review asks for.

Their names and units are owned by :mod:`mechreport.quantities` (``cycle.torque.max`` ...
``balance.*``, per joint ``joint.J.f_max`` ... ``joint.J.life_h``). Everything is computed on
the cycle grid
(see :mod:`.cycle`) from the reference method's results; nothing here draws or formats.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..kinematics.result import jam_note
from ..units import rad_s_to_rpm
from .balance import Counterweight, counterweight
from .bearings import BearingLoad, bearing_load
from .cycle import Cycle, CycleUndefined, cycle_of
from .frame import frame_load, inertia_force, reference_method
from .friction import friction_losses, friction_values
from .transmission import transmission_angles


@dataclass(frozen=True)
class Review:
    """Cycle quantities of one analysis. ``values`` by quantity name [SI; the units are in
    ``mechreport.quantities``]; ``torque``, ``energy`` (N,) [N m, J] over ``cycle.angles``
    (energy: running integral of torque minus its mean); ``bearings`` by joint;
    ``transmission`` (N,) [deg] per dyad; ``counterweight``; ``method`` the method the forces
    came from."""

    cycle: Cycle
    method: str
    values: dict[str, float]
    torque: np.ndarray
    energy: np.ndarray
    bearings: dict[str, BearingLoad]
    transmission: dict[str, np.ndarray]
    counterweight: Counterweight
    shaking: np.ndarray = field(repr=False)          # (N, 2) [N] on the frame
    inertial: np.ndarray = field(repr=False)         # (N, 2) [N] sum of m a_C
    shaking_balanced: np.ndarray = field(repr=False)  # (N, 2) [N] inertial, with counterweight
    friction: dict[str, float] = field(default_factory=dict)   # J lost per cycle, by joint


def review(analysis, speed_fluctuation: float | None = None,
           ratings: dict[str, float] | None = None) -> Review:
    """Every cycle quantity of ``analysis`` (an Analysis). Raises ``CycleUndefined`` (with the
    reason) when the sweep is not one whole turn of a crank that turns fully. ``ratings``:
    dynamic load rating [N] by joint name, for ``joint.J.life_h``."""
    return review_of(analysis.kinematics, analysis.forces, analysis.loads, speed_fluctuation,
                     ratings)


@dataclass(frozen=True)
class Traces:
    """What the cycle review reads, over the analysed ``angles`` (n,) [deg], from the
    reference ``method``: the driver ``torque`` (n,) [N m or N], the frame load ``frame``
    (n, 3) (fx, fy [N], m [N m]), the inertial force ``inertial`` (n, 2) [N] (sum of m a_C),
    each dyad's ``transmission`` angle (n,) [deg], each joint's reaction magnitude
    ``reactions`` (n,) [N] and each friction joint's ``friction`` loss, the energy it takes per
    unit of the driven coordinate (n,) [J/rad]; ``rates`` (n,) the driver's rate where it
    varies (a machine-dynamics cycle), else None. A long sweep's traces are computed chunk by
    chunk and written one after the other into traces allocated once."""

    method: str
    angles: np.ndarray
    torque: np.ndarray
    frame: np.ndarray
    inertial: np.ndarray
    transmission: dict[str, np.ndarray]
    reactions: dict[str, np.ndarray]
    friction: dict[str, np.ndarray] = field(default_factory=dict)
    rates: np.ndarray | None = None

    def arrays(self) -> list[np.ndarray]:
        return [self.angles, self.torque, self.frame, self.inertial,
                *self.transmission.values(), *self.reactions.values(),
                *self.friction.values(), *([] if self.rates is None else [self.rates])]

    def allocate(self, n: int) -> "Traces":
        """Traces of ``n`` angles shaped like these, unset (for :meth:`write`)."""
        def e(a):
            return np.empty((n,) + a.shape[1:])
        return Traces(self.method, e(self.angles), e(self.torque), e(self.frame),
                      e(self.inertial), {k: e(v) for k, v in self.transmission.items()},
                      {k: e(v) for k, v in self.reactions.items()},
                      {k: e(v) for k, v in self.friction.items()},
                      None if self.rates is None else e(self.rates))

    def write(self, part: "Traces", at: int) -> None:
        """Copy ``part`` (the next chunk's traces) into rows ``at`` on."""
        for dst, src in zip(self.arrays(), part.arrays()):
            dst[at:at + len(src)] = src

    def head(self, n: int) -> "Traces":
        """The first ``n`` angles' traces (views)."""
        return Traces(self.method, self.angles[:n], self.torque[:n], self.frame[:n],
                      self.inertial[:n], {k: v[:n] for k, v in self.transmission.items()},
                      {k: v[:n] for k, v in self.reactions.items()},
                      {k: v[:n] for k, v in self.friction.items()},
                      None if self.rates is None else self.rates[:n])


def traces_of(kin, forces, loads) -> Traces:
    """The review's traces (see :class:`Traces`) of one kinematics and its force results."""
    method = reference_method(forces)
    res = forces[method]
    frame = frame_load(kin, res, loads)
    return Traces(method, kin.angles, np.asarray(res.driver_torque, float),
                  np.stack([frame.fx, frame.fy, frame.m], axis=1), inertia_force(kin),
                  transmission_angles(kin),
                  {name: r.f for name, r in res.reactions.items()}, friction_losses(kin),
                  kin.rates)


def review_of(kin, forces, loads, speed_fluctuation: float | None = None,
              ratings: dict[str, float] | None = None) -> Review:
    """:func:`review` from its parts: the kinematics, the force results by method and the
    evaluated loads."""
    motion = kin.motion
    spec = kin.mechanism.spec
    return review_from(traces_of(kin, forces, loads), spec,
                       motion is None or motion.full, kin.turn_problem, speed_fluctuation,
                       ratings, jam_note(kin.flags, spec))


def review_from(tr: Traces, spec, reachable: bool = True, turn_problem: str = "",
                speed_fluctuation: float | None = None,
                ratings: dict[str, float] | None = None, jam: str = "") -> Review:
    """The cycle quantities from a sweep's traces (``reachable``: the crank turns fully;
    ``turn_problem``: why the motion does not repeat every turn, or ""; ``jam``: where
    friction jams the mechanism, or "")."""
    cyc = cycle_of(spec, tr.angles, reachable, turn_problem, jam)
    omega = spec.driver.omega
    sample = lambda v: cyc.sample(v, tr.angles)   # noqa: E731 - one-line adapter
    torque = sample(tr.torque)
    mean = cyc.mean(torque)
    energy = cyc.integral(torque - mean)
    values = {
        "cycle.torque.max": float(np.max(torque)), "cycle.torque.min": float(np.min(torque)),
        "cycle.torque.mean": mean, "cycle.torque.rms": cyc.rms(torque),
        # the mean power is the work per cycle over its period: mean torque x mean speed
        # (a machine-dynamics cycle's spec carries the time-mean speed 2 pi / period)
        "cycle.power.max": float(np.max(torque * (omega if tr.rates is None
                                                  else sample(tr.rates)))),
        "cycle.power.mean": mean * omega,
        "cycle.energy_fluctuation": float(np.max(energy)) - float(np.min(energy)),
    }
    if speed_fluctuation:
        values["cycle.flywheel_inertia"] = (values["cycle.energy_fluctuation"]
                                            / (speed_fluctuation * omega ** 2))
    losses = {joint: 2 * np.pi * cyc.mean(sample(loss)) for joint, loss in tr.friction.items()}
    if losses:
        values.update(friction_values(losses, torque, cyc, np.sign(omega) or 1.0,
                                      efficiency=not spec.idle_friction))
    shaking = sample(tr.frame[:, :2])
    f = np.hypot(shaking[:, 0], shaking[:, 1])
    if tr.reactions:     # the shaking force is the ground joints' reactions: none, no value
        values["cycle.shaking.force_max"] = float(np.max(f))
        values["cycle.shaking.force_rms"] = cyc.rms(f)
        values["cycle.shaking.moment_max"] = float(np.max(np.abs(sample(tr.frame[:, 2]))))
    angles = {label: sample(ta) for label, ta in tr.transmission.items()}
    del f                 # a long sweep's review holds as few full-length arrays as it can
    if angles:
        values["cycle.transmission_angle.min"] = min(float(np.min(a)) for a in angles.values())
        values["cycle.transmission_angle.max"] = max(float(np.max(a)) for a in angles.values())
    inertial = sample(tr.inertial)
    crank = np.radians(cyc.angles)    # a crank's x-axis angle is the cycle's crank angle
    cw = counterweight(inertial, crank, omega, spec.driver.alpha)
    values["cycle.inertia_shaking.force_rms"] = cw.rms_before
    values["balance.counterweight.mr"] = cw.mr
    values["balance.counterweight.angle"] = cw.angle
    values["balance.inertia_shaking.force_rms"] = cw.rms_after
    balanced = cw.balanced
    rpm = rad_s_to_rpm(abs(omega))
    bearings = {}
    for name, magnitude in tr.reactions.items():
        rating = (ratings or {}).get(name)
        b = bearing_load(sample(magnitude), rating, rpm)
        bearings[name] = b
        values[f"joint.{name}.f_max"] = b.f_max
        values[f"joint.{name}.f_mean"] = b.f_mean
        values[f"joint.{name}.f_equivalent"] = b.f_equivalent
        if b.life_h is not None:
            values[f"joint.{name}.life_h"] = b.life_h
    return Review(cyc, tr.method, values, torque, energy, bearings, angles, cw, shaking,
                  inertial, balanced, losses)


def design_review(kin, forces, loads) -> tuple[Review | None, str]:
    """The cycle quantities of the spec's design review (its speed fluctuation, its bearings'
    ratings), or None and why they are undefined."""
    spec = kin.mechanism.spec
    if spec.cycle_problem() is not None:
        return None, spec.cycle_problem()
    motion = kin.motion
    return design_review_from(traces_of(kin, forces, loads), spec,
                              motion is None or motion.full, kin.turn_problem,
                              jam_note(kin.flags, spec))


def design_review_from(tr: Traces, spec, reachable: bool = True,
                       turn_problem: str = "", jam: str = "") -> tuple[Review | None, str]:
    """:func:`design_review` from a sweep's traces (a long sweep's, joined chunk by chunk)."""
    if spec.cycle_problem() is not None:
        return None, spec.cycle_problem()
    ratings = {j: b.rating for j, b in spec.design.bearings.items()}
    try:
        return review_from(tr, spec, reachable, turn_problem, spec.design.speed_fluctuation,
                           ratings, jam), ""
    except CycleUndefined as exc:
        return None, str(exc).split(": ", 1)[-1]
