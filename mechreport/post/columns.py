"""Every result of an analysis as named columns over the angles: what results.csv and
:meth:`mechreport.pipeline.Analysis.to_dataframe` hold, built here once.

A column's name carries its SI unit (``crank.omega [rad/s]``, ``dyad.joint.B.fx [N]``); its
values are (n,) over the analysed angles, with round-off made 0: a value within
``ZERO_RTOL`` of the largest magnitude of its kind (its ``scale``) is 0, never -0.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..quantities import (JOINT_UNITS, LINK_UNITS, MECHANISM_UNITS, POINT_UNITS, joint_unit,
                          load_scales, unit_of)
from ..units import ZERO_RTOL, kind_of, with_unit
from .transmission import smallest_transmission_angle


@dataclass(frozen=True)
class Column:
    """One result over the analysed angles: ``name`` (with its unit in brackets), ``values``
    (n,) [SI], round-off made 0, NaN where undefined (a slider's point where its force
    vanishes)."""

    name: str
    values: np.ndarray


def sweep_rows(angles: np.ndarray, flags) -> tuple[list[float], list[int | None], list[str]]:
    """The rows of results.csv and of ``to_dataframe()``: every angle of the sweep, analysed
    (``angles``) or left out (``flags``), in order; for each, its index among the analysed
    angles (None where left out) and why it was left out ("")."""
    reasons = {round(f.angle, 9): f.reason for f in flags}
    solved = {round(float(a), 9): k for k, a in enumerate(angles)}
    every = sorted(set(solved) | set(reasons))
    return every, [solved.get(a) for a in every], [reasons.get(a, "") for a in every]


def _top(*arrays) -> float:
    vals = [float(np.max(np.abs(a))) for a in arrays if a is not None and np.size(a)]
    vals = [v for v in vals if math.isfinite(v)]
    return max(vals, default=0.0) or 1.0


def kinematic_scales(kin) -> dict[str, float]:
    """Largest magnitude [SI] of each kinematic kind of quantity of ``kin`` (its named points
    and centres of mass, its links): length, velocity, acceleration, omega, alpha, angle.

    Rates share their scale across kinds the way they grow together: a velocity is measured
    against the largest too and the largest omega times the largest length, an acceleration
    against the largest velocity squared over the largest length, an angular acceleration
    against the largest omega squared; so that a value that is round-off of the motion prints
    0 even where it is the largest of its kind (a rod's alpha of 3e-16 rad/s² at one angle
    of a crank turning at 1 rad/s)."""
    spec = kin.mechanism.spec
    pts = [kin.named_point(p, o) for p, o in spec.named_points()]
    coms = [kin.com(l.name) for l in spec.links]
    ground = [np.asarray(list(spec.ground.values()), float)] if spec.ground else []
    length = _top(*[p.r for p in pts], *ground)
    omega = _top(kin.omega)
    velocity = max(_top(*[p.v for p in pts], *[c.v for c in coms]), omega * length)
    return {"length": length, "velocity": velocity,
            "acceleration": max(_top(*[p.a for p in pts], *[c.a for c in coms]),
                                velocity ** 2 / length),
            "omega": omega, "alpha": max(_top(kin.alpha), omega ** 2), "angle": 360.0}


def scales(kin, forces: dict, loads) -> dict[str, float]:
    """Largest magnitude [SI] of each kind of quantity of an analysis (kinematics ``kin``,
    ``forces`` by method, the applied ``loads``): a value below ``ZERO_RTOL`` of it is
    round-off. Kinds: length, velocity, acceleration, force, moment, omega, alpha, angle,
    mass, inertia. The kinematic kinds are :func:`kinematic_scales`.

    Forces and moments share one load scale through the mechanism's size (``Spec.size``,
    the agreement check's :func:`~mechreport.quantities.load_scales`): a moment is
    measured against the largest moment and the largest force times the size, a force
    against the largest force and the largest moment over the size; so that a moment that
    is round-off next to the forces (a static press's shaking moment, 1e-13 N m beside
    20 kN) is 0."""
    spec = kin.mechanism.spec
    fs, moments = [], []
    for res in forces.values():
        moments.append(res.driver_torque)
        for r in res.reactions.values():
            fs += [r.fx, r.fy]
            if r.moment is not None:
                moments.append(r.moment)
    for ld in loads:
        (fs if ld.force is not None else moments).append(
            ld.force if ld.force is not None else ld.moment)
    loads = load_scales({"force": _top(*fs), "moment": _top(*moments)}, spec.size)
    return {**kinematic_scales(kin), "force": loads["force"], "moment": loads["moment"],
            "mass": _top(np.array([l.mass for l in spec.links])),
            "inertia": _top(np.array([l.inertia for l in spec.links]))}


def result_columns(kin, forces: dict, scale: dict[str, float]) -> list[Column]:
    """Every link's angle, rate and acceleration, every named point's position, velocity
    and acceleration, and every method's driver effort and joint reactions, in that order,
    with round-off of each kind (``scale``, see :func:`scales`) made 0."""
    spec = kin.mechanism.spec
    out: list[Column] = []

    def add(name: str, unit: str, values: np.ndarray) -> None:
        """The column ``name [unit]``; round-off of the unit's kind of quantity made 0."""
        tol = ZERO_RTOL * scale.get(kind_of(unit), 0.0)
        with np.errstate(invalid="ignore"):
            out.append(Column(with_unit(name, unit),
                              np.where(np.abs(values) <= tol, 0.0, values) + 0.0))

    # the units are the quantities' (mechreport.quantities), the names results.csv's own
    # (a link's angle is ``L.theta``, a point's ``P.x``: the quantities link.L.angle, point.P.x)
    for ln in spec.links:
        i = ln.number
        add(f"{ln.name}.theta", LINK_UNITS["angle"], kin.angle_deg(ln.name))
        add(f"{ln.name}.omega", LINK_UNITS["omega"], kin.omega[:, i])
        add(f"{ln.name}.alpha", LINK_UNITS["alpha"], kin.alpha[:, i])
    for p, owner in spec.named_points():
        s = kin.named_point(p, owner)
        for lab, arr in (("x", s.r[:, 0]), ("y", s.r[:, 1]), ("vx", s.v[:, 0]),
                         ("vy", s.v[:, 1]), ("ax", s.a[:, 0]), ("ay", s.a[:, 1]),
                         ("v", np.hypot(s.v[:, 0], s.v[:, 1])),
                         ("a", np.hypot(s.a[:, 0], s.a[:, 1]))):
            add(f"{p}.{lab}", POINT_UNITS[lab], arr)
    for j in spec.joints:                       # an R joint's relative angle, (-180, 180]
        if j.type == "R":
            add(f"joint.{j.name}.angle", JOINT_UNITS["angle"], kin.relative_angle_deg(*j.links))
    transmission = smallest_transmission_angle(kin)
    if np.isfinite(transmission).any():
        add("transmission_angle", MECHANISM_UNITS["transmission_angle"], transmission)
    for m, res in forces.items():
        effort = "driver.torque" if spec.driver.kind == "R" else "driver.force"
        add(f"{m}.{effort}", unit_of(effort), res.driver_torque)
        for name in spec.reported_reactions():
            r = res.reactions.get(name)
            if r is None:
                continue
            for attr in ("fx", "fy", "moment", "px", "py"):
                v = getattr(r, attr)
                if v is not None:
                    add(f"{m}.joint.{name}.{attr}", JOINT_UNITS[attr], v)
            if r.friction is not None:     # a couple in an R joint, a force in a T joint
                add(f"{m}.joint.{name}.friction", joint_unit("friction", r.type), r.friction)
    return out
