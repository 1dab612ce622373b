"""Cycle quantities of a whole-turn analysis: the numbers a design review asks for.

One owner for their names and units (``UNITS``): ``cycle.torque.max`` ... ``balance.*`` and
per joint ``joint.J.f_max`` ... ``joint.J.life_h``. Everything is computed on the cycle grid
(see :mod:`.cycle`) from the reference method's results; nothing here draws or formats.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .balance import Counterweight, counterweight
from .bearings import BearingLoad, bearing_load
from .cycle import Cycle, cycle_of
from .frame import frame_load, inertia_force, reference_method
from .transmission import transmission_angles

UNITS = {
    "cycle.torque.max": "N·m", "cycle.torque.min": "N·m", "cycle.torque.mean": "N·m",
    "cycle.torque.rms": "N·m", "cycle.power.max": "W", "cycle.power.mean": "W",
    "cycle.energy_fluctuation": "J", "cycle.flywheel_inertia": "kg·m^2",
    "cycle.shaking.force_max": "N", "cycle.shaking.force_rms": "N",
    "cycle.shaking.moment_max": "N·m", "cycle.transmission_angle.min": "deg",
    "cycle.transmission_angle.max": "deg", "cycle.inertia_shaking.force_rms": "N",
    "balance.counterweight.mr": "kg·m", "balance.counterweight.angle": "deg",
    "balance.inertia_shaking.force_rms": "N",
}
JOINT_UNITS = {"f_max": "N", "f_mean": "N", "f_equivalent": "N", "life_h": "h"}


def unit_of(quantity: str) -> str | None:
    """The SI unit of a cycle quantity name, None if it is not one."""
    if quantity in UNITS:
        return UNITS[quantity]
    parts = quantity.split(".")
    if len(parts) == 3 and parts[0] == "joint" and parts[2] in JOINT_UNITS:
        return JOINT_UNITS[parts[2]]
    return None


@dataclass(frozen=True)
class Review:
    """Cycle quantities of one analysis. ``values`` by quantity name [SI, see ``UNITS``];
    ``torque``, ``energy`` (N,) [N m, J] over ``cycle.angles`` (energy: running integral of
    torque minus its mean); ``bearings`` by joint; ``transmission`` (N,) [deg] per dyad;
    ``counterweight``; ``method`` the method the forces came from."""

    cycle: Cycle
    method: str
    values: dict[str, float]
    torque: np.ndarray
    energy: np.ndarray
    bearings: dict[str, BearingLoad]
    transmission: dict[str, np.ndarray]
    counterweight: Counterweight
    shaking: np.ndarray = field(repr=False)          # (N, 2) [N]
    shaking_balanced: np.ndarray = field(repr=False)  # (N, 2) [N] inertial, with counterweight


def review(analysis, speed_fluctuation: float | None = None,
           ratings: dict[str, float] | None = None) -> Review:
    """Every cycle quantity of ``analysis``. Raises ``CycleUndefined`` (with the reason) when
    the sweep is not one whole turn of a crank that turns fully. ``ratings``: dynamic load
    rating [N] by joint name, for ``joint.J.life_h``."""
    spec, kin = analysis.spec, analysis.kinematics
    motion = kin.motion
    cyc = cycle_of(spec, kin.angles, motion is None or motion.full)
    method = reference_method(analysis.forces)
    res = analysis.forces[method]
    omega = spec.driver.omega
    sample = lambda v: cyc.sample(v, kin.angles)   # noqa: E731 - one-line adapter
    torque = sample(res.driver_torque)
    mean = float(np.mean(torque))
    energy = cyc.integral(torque - mean)
    values = {
        "cycle.torque.max": float(np.max(torque)), "cycle.torque.min": float(np.min(torque)),
        "cycle.torque.mean": mean, "cycle.torque.rms": cyc.rms(torque),
        "cycle.power.max": float(np.max(torque * omega)), "cycle.power.mean": mean * omega,
        "cycle.energy_fluctuation": float(np.max(energy) - np.min(energy)),
    }
    if speed_fluctuation:
        values["cycle.flywheel_inertia"] = (values["cycle.energy_fluctuation"]
                                            / (speed_fluctuation * omega ** 2))
    frame = frame_load(kin, res, analysis.loads)
    shaking = sample(np.stack([frame.fx, frame.fy], axis=1))
    f = np.hypot(shaking[:, 0], shaking[:, 1])
    values["cycle.shaking.force_max"] = float(np.max(f))
    values["cycle.shaking.force_rms"] = cyc.rms(f)
    values["cycle.shaking.moment_max"] = float(np.max(np.abs(sample(frame.m))))
    angles = {label: sample(ta) for label, ta in transmission_angles(kin).items()}
    if angles:
        pooled = np.concatenate(list(angles.values()))
        values["cycle.transmission_angle.min"] = float(np.min(pooled))
        values["cycle.transmission_angle.max"] = float(np.max(pooled))
    inertial = sample(inertia_force(kin))
    crank = sample(kin.theta[:, kin.index(spec.driver.link)][:, None])[:, 0]
    crank = np.unwrap(crank) if len(crank) > 1 else crank
    cw = counterweight(inertial, crank, omega, spec.driver.alpha)
    values["cycle.inertia_shaking.force_rms"] = cw.rms_before
    values["balance.counterweight.mr"] = cw.mr
    values["balance.counterweight.angle"] = cw.angle
    values["balance.inertia_shaking.force_rms"] = cw.rms_after
    c = cw.mr * np.exp(1j * np.radians(cw.angle))
    added = c * np.exp(1j * crank) * (1j * spec.driver.alpha - omega ** 2)
    balanced = inertial + np.stack([added.real, added.imag], axis=1)
    rpm = abs(omega) * 30.0 / np.pi
    bearings = {}
    for name, r in res.reactions.items():
        rating = (ratings or {}).get(name)
        b = bearing_load(sample(r.f), rating, rpm)
        bearings[name] = b
        values[f"joint.{name}.f_max"] = b.f_max
        values[f"joint.{name}.f_mean"] = b.f_mean
        values[f"joint.{name}.f_equivalent"] = b.f_equivalent
        if b.life_h is not None:
            values[f"joint.{name}.life_h"] = b.life_h
    return Review(cyc, method, values, torque, energy, bearings, angles, cw, shaking,
                  balanced)
