"""The records every machine-readable output reads: a value for JSON (:func:`jnum`), a peak
(:func:`peak_record`), the key figures by name (:func:`key_quantities`: what summary.json's
``quantities``, the index and ``mechreport diff`` read) and the joints' and friction's
textbook names. SI throughout, the unit beside every value; nothing here formats text."""
from __future__ import annotations

import math

import numpy as np

from ..quantities import unit_of
from ..units import clean, kind_of
from .sweep import SweepSummary
from .torque import Peak


def jnum(x, scale: float | None = None) -> float | None:
    """A float for JSON (SI, round-off of its quantity's ``scale`` made 0): None where
    undefined."""
    if x is None or not math.isfinite(float(x)):
        return None
    return clean(float(x), scale)


def peak_record(p: Peak | None, unit: str, scale: float | None = None) -> dict | None:
    """``{value, unit, angle_deg}`` of a peak (None without one)."""
    return None if p is None else {"value": jnum(p.value, scale), "unit": unit,
                                   "angle_deg": p.angle}


def reaction_symbols(spec) -> dict[str, str]:
    """Textbook reaction symbol of each joint: F<first><second> by link number; a pin
    joining several links: F<pin><link> for its force on its hub (on the others, it is the
    reaction of the hub's joint to each)."""
    out = {j.name: spec.symbol(*j.links) for j in spec.joints}
    for pin in spec.pins:
        out[pin.joint_name(pin.hub)] = f"F{pin.name}{spec.number(pin.hub)}"
    return {name: out[name] for name in spec.reported_reactions()}


def friction_symbol(spec, joint) -> str:
    """The textbook's name of a joint's friction: Mf12, the couple of link 1 on link 2 in an
    R joint; Ff03, the force of link 0 on link 3 along a T joint's line."""
    return spec.symbol(*joint.links, "Mf" if joint.type == "R" else "Ff")


def largest(values: np.ndarray | None, angles: np.ndarray) -> tuple[float, float] | None:
    """(largest |value|, its angle [deg]) over the analysed angles; None without a finite
    value."""
    if values is None or not len(values):
        return None
    mag = np.abs(np.asarray(values, float))
    if not np.any(np.isfinite(mag)):
        return None
    k = int(np.nanargmax(mag))
    return float(mag[k]), float(angles[k])


def key_quantities(summary: SweepSummary, cycle: dict, sc: dict,
                   effort_unit: str = "N·m") -> dict:
    """Every key figure by name -> {value [SI], unit}: what ``mechreport diff`` compares and
    the index lists, each once: where the cycle quantities are defined, a sweep peak that
    one of them states (a joint's peak load is ``joint.J.f_max``, the shaking force's and
    moment's ``cycle.shaking.*_max``, the effort's mean and RMS and the mean power are
    ``cycle.torque.mean``, ``cycle.torque.rms`` and ``cycle.power.mean``) is not listed again
    under another name. The driver's signed peak and its angle stay: no cycle quantity says
    where it is."""
    out: dict[str, dict] = {}
    cyclic = bool(cycle)

    def put(name, value, unit, kind=None, angle=None):
        if value is None:
            return
        entry = {"value": jnum(value, sc.get(kind) if kind else None), "unit": unit}
        if angle is not None:
            entry["angle_deg"] = float(angle)
        out[name] = entry

    st = summary.torque
    if st is not None:
        name, kind = (("driver.force", "force") if effort_unit == "N"
                      else ("driver.torque", "moment"))
        if "cycle.torque.rms" not in cycle:   # over a whole turn the cycle's names say them
            put(f"{name}.mean", st.mean, effort_unit, kind)
            put(f"{name}.rms", st.rms, effort_unit, kind)
            put("driver.power.mean", st.power, "W")
        put(f"{name}.peak", st.peak.value, effort_unit, kind, st.peak.angle)   # signed, where
    for name, jl in summary.joints.items():
        pk = jl.peak
        if pk is not None:
            if not cyclic or f"joint.{name}.f_max" not in cycle:
                put(f"joint.{name}.f.peak", pk.value, "N", "force", pk.angle)
            put(f"joint.{name}.f.rms", jl.rms, "N", "force")
    sh = summary.shaking_force
    if sh is not None and "cycle.shaking.force_max" not in cycle:
        put("shaking.force.peak", sh.value, "N", "force", sh.angle)
    shm = summary.shaking_moment
    if shm is not None and "cycle.shaking.moment_max" not in cycle:
        put("shaking.moment.peak", shm.value, "N·m", "moment", shm.angle)
    for name, value in cycle.items():
        unit = unit_of(name) or ""
        put(name, value, unit, kind_of(unit))
    return out
