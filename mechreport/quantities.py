"""Quantity names: the one place that says which names exist and what unit each has.

Instantaneous quantities are values at an angle (``driver.torque``, ``joint.B.fx``,
``point.C.vx``, ``link.rod.omega``); cycle quantities are one number per whole turn of the crank
(``cycle.torque.rms``, ``joint.B.f_max``, ``balance.counterweight.mr``) and are given in
``expect`` without an angle. Units are SI.
"""
from __future__ import annotations

import math

CYCLE_UNITS = {
    "cycle.torque.max": "N·m", "cycle.torque.min": "N·m", "cycle.torque.mean": "N·m",
    "cycle.torque.rms": "N·m", "cycle.power.max": "W", "cycle.power.mean": "W",
    "cycle.energy_fluctuation": "J", "cycle.flywheel_inertia": "kg·m^2",
    "cycle.shaking.force_max": "N", "cycle.shaking.force_rms": "N",
    "cycle.shaking.moment_max": "N·m", "cycle.transmission_angle.min": "deg",
    "cycle.transmission_angle.max": "deg", "cycle.inertia_shaking.force_rms": "N",
    "balance.counterweight.mr": "kg·m", "balance.counterweight.angle": "deg",
    "balance.inertia_shaking.force_rms": "N",
    "cycle.friction.energy": "J", "cycle.efficiency": "",
    # the steady cycle of machine dynamics (``dynamics:``)
    "dynamics.speed_fluctuation": "", "dynamics.mean_rpm": "rpm", "dynamics.startup_time": "s",
    "dynamics.motor_rms_torque": "N·m",
    "dynamics.omega_max": "rad/s", "dynamics.omega_min": "rad/s",
    "dynamics.omega_max_angle": "deg", "dynamics.omega_min_angle": "deg",
    "dynamics.speed_fluctuation_estimate": "",
}
#: the cycle quantities machine dynamics gives (``dynamics:`` with ``until: steady``)
DYNAMICS_QUANTITIES = tuple(q for q in CYCLE_UNITS if q.startswith("dynamics."))
#: the force methods' names, in the order the reports list them (the methods themselves are
#: mechreport.forces.METHODS; the command line offers these names without importing them)
METHOD_NAMES = ("newton_euler", "dalembert", "dyad", "contour", "power")
#: a member's quantities over the sweep (``member.L.attr``, ``member.L.P_Q.attr``)
MEMBER_UNITS = {"stress_max": "Pa", "static_safety": "", "fatigue_safety": "",
                "buckling_safety": "", "buckling_plane": ""}   # plane: 1 in it, 2 out of it
JOINT_CYCLE_UNITS = {"f_max": "N", "f_mean": "N", "f_equivalent": "N", "life_h": "h"}
JOINT_UNITS = {"fx": "N", "fy": "N", "f": "N", "moment": "N·m", "px": "m", "py": "m",
               "angle": "deg"}      # angle: an R joint's relative angle (kinematics)
POINT_UNITS = {"x": "m", "y": "m", "vx": "m/s", "vy": "m/s", "ax": "m/s^2", "ay": "m/s^2",
               "v": "m/s", "a": "m/s^2"}           # v, a: magnitudes
#: instantaneous quantities of the whole mechanism, at an angle (the steady cycle's speed
#: and acceleration of machine dynamics too: one value per angle, not per force method)
MECHANISM_UNITS = {"transmission_angle": "deg", "dynamics.omega": "rad/s",
                   "dynamics.alpha": "rad/s^2"}
#: the instantaneous quantities of machine dynamics' steady cycle
DYNAMICS_INSTANT = ("dynamics.omega", "dynamics.alpha")
#: the instantaneous quantities the kinematics alone gives (not the force methods)
KINEMATIC_KINDS = ("point", "link")
LINK_UNITS = {"angle": "deg", "omega": "rad/s", "alpha": "rad/s^2"}
_UNITS_BY_KIND = {"joint": {**JOINT_UNITS, **JOINT_CYCLE_UNITS}, "point": POINT_UNITS,
                  "link": LINK_UNITS, "member": MEMBER_UNITS}


def split(quantity: str) -> tuple[str, str, str] | None:
    """``kind.name.attr`` as (kind, name, attr), the name being everything between the first
    dot and the last (``joint.E.on.crank.fx``: the force pin E exerts on the crank); None
    for a name of another shape (``driver.torque``, ``cycle.torque.rms`` split too)."""
    kind, _, rest = quantity.partition(".")
    name, _, attr = rest.rpartition(".")
    return (kind, name, attr) if kind and name and attr else None


def is_kinematic(quantity: str) -> bool:
    """True for a quantity the kinematics gives (points, links, a joint's relative angle,
    the transmission angle): checked once, not per force method."""
    parts = split(quantity)
    return (quantity in MECHANISM_UNITS or (parts is not None and parts[0] in KINEMATIC_KINDS)
            or (parts is not None and parts[0] == "joint" and parts[2] == "angle"))


def is_member(quantity: str) -> bool:
    """True for a member's quantity (``member.rod.static_safety``): one value over the
    sweep, for any sweep (a whole turn or not)."""
    parts = split(quantity)
    return parts is not None and parts[0] == "member" and parts[2] in MEMBER_UNITS


def is_cycle(quantity: str) -> bool:
    """True for a quantity with one value per sweep, given in ``expect`` without an angle:
    a cycle quantity (``cycle.*``, ``balance.*``, ``joint.J.f_max`` ...) or a member's."""
    if quantity in CYCLE_UNITS or is_member(quantity):
        return True
    parts = split(quantity)
    return parts is not None and parts[0] == "joint" and parts[2] in JOINT_CYCLE_UNITS


def unit_of(quantity: str) -> str | None:
    """The SI unit of any quantity name; None if the name has no known shape."""
    if quantity in CYCLE_UNITS:
        return CYCLE_UNITS[quantity]
    if quantity in MECHANISM_UNITS:
        return MECHANISM_UNITS[quantity]
    if quantity == "driver.torque":
        return "N·m"
    if quantity == "driver.force":
        return "N"
    parts = split(quantity)
    if parts is None:
        return None
    return _UNITS_BY_KIND.get(parts[0], {}).get(parts[2])


def joint_unit(attr: str, joint_type: str) -> str | None:
    """The SI unit of a joint's quantity ``attr`` for a joint of ``joint_type`` (R or T): a
    joint's friction is a couple [N·m] in an R joint, a force [N] in a T joint."""
    if attr == "friction":
        return "N·m" if joint_type == "R" else "N"
    return _UNITS_BY_KIND["joint"].get(attr)


def unit_kind(quantity: str) -> str:
    """``moment`` for quantities in N·m (torques, couples), else ``force``: agreement scales
    compare like with like."""
    return "moment" if unit_of(quantity) == "N·m" else "force"


def load_scales(tops: dict[str, float], size: float) -> dict[str, float]:
    """The load scale of each kind (``force`` [N], ``moment`` [N m]) from the largest
    magnitude of each kind ``tops`` and the mechanism's size [m] (``Spec.size``): a moment's
    is the largest moment or the largest force times the size, a force's the largest force or
    the largest moment over the size. The agreement check's floor and the round-off rule of
    every output read it (a moment that is round-off next to the forces prints 0)."""
    force, moment = tops.get("force", 0.0), tops.get("moment", 0.0)
    if not (size > 0 and math.isfinite(size)):
        return {"force": force, "moment": moment}
    return {"force": max(force, moment / size), "moment": max(moment, force * size)}
