"""What friction costs over a cycle: each joint's loss, the energy lost per cycle and the
efficiency (format 1.1 ``friction:``; the friction itself is solved with the forces,
:mod:`mechreport.forces.friction`)."""
from __future__ import annotations

import numpy as np

from ..forces.friction import relative_rate
from ..kinematics import Kinematics, at_unit_rate


def friction_losses(kin: Kinematics) -> dict[str, np.ndarray]:
    """Each friction joint's loss per unit of the driven coordinate (n,) [J/rad, or J/m for a
    T driver]: |friction x the joint's relative rate| / |the driver's rate|, the velocity
    coefficients' at zero speed (what a virtual motion forward would dissipate)."""
    if not kin.friction:
        return {}
    spec = kin.mechanism.spec
    rates = at_unit_rate(kin) if spec.driver.at_rest else kin
    speed = 1.0 if spec.driver.at_rest else np.abs(kin.driver_rate)
    return {name: np.abs(m * relative_rate(rates, spec.joint(name))) / speed
            for name, m in kin.friction.items()}


NO_WORK = "the driver does no positive work over the cycle"


def efficiency_undefined(spec) -> str:
    """Why ``cycle.efficiency`` is undefined when it is missing from the cycle quantities:
    friction entries that act nowhere (at rest without ``friction_sense``), or no positive
    work of the driver."""
    return spec.idle_friction_note() or NO_WORK


def friction_values(losses: dict[str, float], torque: np.ndarray, cyc,
                    direction: float, efficiency: bool = True) -> dict[str, float]:
    """``cycle.friction.energy`` [J per cycle] from each joint's loss over the cycle
    ``losses`` [J], and ``cycle.efficiency`` = 1 - that / the driver's positive work over
    the cycle (``torque`` (N,) [N m] over the cycle grid ``cyc``; ``direction`` the sign of
    the driver's rotation), left out when the driver does no positive work, or when not
    every friction entry acts (``efficiency`` False: the efficiency would be overstated)."""
    lost = float(sum(losses.values()))
    work_in = 2 * np.pi * cyc.mean(np.maximum(torque * direction, 0.0))
    out = {"cycle.friction.energy": lost}
    if work_in > 0 and efficiency:
        out["cycle.efficiency"] = 1.0 - lost / work_in
    return out
