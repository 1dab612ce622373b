"""Design verdicts: every item of a spec's ``design:`` compared with its cycle quantity.

A verdict passes on equality. The margin is the fraction of the limit left over:
(limit - value) / limit for an upper limit, (value - limit) / limit for a lower one.
"""
from __future__ import annotations

from dataclasses import dataclass

from ..quantities import unit_of
from ..spec import Design
from .friction import NO_WORK, efficiency_undefined


@dataclass(frozen=True)
class Verdict:
    """``item`` the design key (``motor.rated_torque``, ``bearings.A.life_h`` ...) checked on
    ``quantity`` (its ``value`` [SI, ``unit``]) against ``limit``; ``at_least`` for a lower
    limit; ``where`` which joint set the value (joint_force); ``why`` when the value is
    undefined (then the verdict fails)."""

    item: str
    quantity: str
    value: float | None
    limit: float
    unit: str
    at_least: bool = False
    where: str = ""
    why: str = ""
    vacuous: bool = False     # nothing to check (no member in compression): passes, says why

    @property
    def margin(self) -> float | None:
        if self.value is None:
            return None
        gap = self.value - self.limit if self.at_least else self.limit - self.value
        return gap / self.limit

    @property
    def passed(self) -> bool:
        if self.value is None:
            return self.vacuous
        return self.value >= self.limit if self.at_least else self.value <= self.limit

    def describe(self, fmt=lambda x: f"{x:.6g}") -> str:
        """One line: ``motor.rated_torque: cycle.torque.rms = 41.2 N·m > limit 40 N·m``;
        numbers by ``fmt``."""
        if self.value is None:
            if self.vacuous:
                return f"{self.item}: passes: {self.why}"
            return f"{self.item}: {self.quantity} is undefined: {self.why}"
        where = (f" (member {self.where})" if self.quantity.startswith("member.")
                 else f" (joint {self.where})") if self.where else ""
        op = (">=" if self.passed else "<") if self.at_least else ("<=" if self.passed else ">")
        unit = f" {self.unit}" if self.unit else ""
        return (f"{self.item}: {self.quantity}{where} = {fmt(self.value)}{unit} {op} "
                f"limit {fmt(self.limit)}{unit}")


PEAK_TORQUE = "max |driver.torque|"


#: the design limits on the members' safety factors (lower limits, smallest over the members)
MEMBER_LIMITS = ("static_safety", "fatigue_safety", "buckling_safety")


def undefined_reasons(spec) -> dict[str, str]:
    """Why a cycle quantity is missing from the cycle quantities, by quantity, where the
    spec's own data say (the efficiency: see :func:`~.friction.efficiency_undefined`)."""
    return {"cycle.efficiency": efficiency_undefined(spec)} if spec.friction else {}


def verdicts(design: Design, values: dict[str, float] | None, why: str = "",
             members: dict[str, float] | None = None,
             reasons: dict[str, str] | None = None) -> list[Verdict]:
    """One verdict per design item, in the order motor, bearings, limits. ``values``: the
    cycle quantities (None when undefined, with the reason ``why``); ``members``: the
    members' quantities (``member.L.static_safety`` ...), defined for any sweep;
    ``reasons``: why a quantity missing from ``values`` is undefined (see
    :func:`undefined_reasons`), where the default reason would not say."""
    rows: list[tuple[str, str, float, bool, str]] = []   # item, quantity, limit, at_least, where
    v = values or {}
    motor = design.motor
    if "rated_torque" in motor:
        rows.append(("motor.rated_torque", "cycle.torque.rms", motor["rated_torque"], False, ""))
    if "peak_torque" in motor:
        rows.append(("motor.peak_torque", PEAK_TORQUE, motor["peak_torque"], False, ""))
    if "rated_power" in motor:
        rows.append(("motor.rated_power", "cycle.power.max", motor["rated_power"], False, ""))
    for joint, b in design.bearings.items():
        if b.life_h is not None:
            rows.append((f"bearings.{joint}.life_h", f"joint.{joint}.life_h", b.life_h, True, ""))
    limits = design.limits
    worst = max(((q[len("joint."):-len(".f_max")], x) for q, x in v.items()
                 if q.startswith("joint.") and q.endswith(".f_max")),
                key=lambda jx: jx[1], default=(None, None))
    if "joint_force" in limits:
        rows.append(("limits.joint_force", "joint.*.f_max", limits["joint_force"], False,
                     worst[0] or ""))
    if "transmission_angle" in limits:
        rows.append(("limits.transmission_angle", "cycle.transmission_angle.min",
                     limits["transmission_angle"], True, ""))
    if "shaking_force" in limits:
        rows.append(("limits.shaking_force", "cycle.shaking.force_max", limits["shaking_force"],
                     False, ""))
    if "efficiency" in limits:
        rows.append(("limits.efficiency", "cycle.efficiency", limits["efficiency"], True, ""))
    if "speed_fluctuation" in limits:
        rows.append(("limits.speed_fluctuation", "dynamics.speed_fluctuation",
                     limits["speed_fluctuation"], False, ""))
    out = []
    for item, quantity, limit, at_least, where in rows:
        if values is None:
            value, reason = None, why
        elif quantity == PEAK_TORQUE:
            value, reason = max(abs(v["cycle.torque.max"]), abs(v["cycle.torque.min"])), ""
        elif quantity == "joint.*.f_max":
            value, reason = worst[1], "" if worst[1] is not None else "no joint reaction"
        else:
            value = v.get(quantity)
            reason = "" if value is not None else (reasons or {}).get(quantity) or (
                "the mechanism has no RRR group and no slider fed by a rod"
                if "transmission" in quantity else
                NO_WORK if quantity == "cycle.efficiency" else "not computed")
        unit = unit_of(quantity)
        if unit is None:
            unit = "N·m" if quantity == PEAK_TORQUE else "N"
        out.append(Verdict(item, quantity, value, limit, unit, at_least, where, reason))
    for attr in MEMBER_LIMITS:
        if attr in limits:
            out.append(member_verdict(attr, limits[attr], members))
    return out


def member_verdict(attr: str, limit: float, members: dict[str, float] | None) -> Verdict:
    """The verdict on ``limits.<attr>``: the smallest ``member.*.<attr>`` against ``limit``
    (``where``: the member). With no member that has the value (none in compression, for
    buckling) there is nothing to fail: it passes, and says why. ``members`` None: the
    members were not computed (no joint reactions were solved): it fails, saying so."""
    item = f"limits.{attr}"
    if members is None:
        return Verdict(item, f"member.*.{attr}", None, limit, "", True, "",
                       "the members' internal forces need the joint reactions, which no "
                       "method solved")
    found = [(q[len("member."):-len(attr) - 1], v) for q, v in members.items()
             if q.startswith("member.") and q.endswith("." + attr)]
    if not found:
        why = ("no member is in compression" if attr == "buckling_safety" else
               "no member is loaded")
        return Verdict(item, f"member.*.{attr}", None, limit, "", True, "", why, vacuous=True)
    where, value = min(found, key=lambda wv: wv[1])
    return Verdict(item, f"member.*.{attr}", value, limit, "", True, where)
