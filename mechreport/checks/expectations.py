"""Check each ``expect:`` entry against the kinematics, or against every force method."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..forces import ForceResult
from ..kinematics import Kinematics
from ..quantities import MECHANISM_UNITS, is_kinematic, is_member
from ..quantities import split as split_quantity
from ..spec import Expectation


@dataclass(frozen=True)
class ExpectationResult:
    """``source`` is ``kinematics`` or a method name; ``got`` is None when there is no value
    (angle left out, point undefined); ``message`` says why it failed."""

    expect: Expectation
    source: str
    got: float | None
    ok: bool
    message: str = ""


def kinematic_value(kin: Kinematics, quantity: str, k: int,
                    instant: dict[str, np.ndarray] | None = None) -> float:
    """A quantity the kinematics gives (``is_kinematic``) at row ``k``; ``instant``: the
    mechanism's own quantities over the rows (``transmission_angle``, computed by the
    caller from the design review's definition), NaN where undefined."""
    if quantity in MECHANISM_UNITS:
        values = (instant or {}).get(quantity)
        return float("nan") if values is None else float(values[k])
    kind, name, attr = split_quantity(quantity)
    if kind == "point":
        s = kin.named_point(name)
        if attr in ("v", "a"):
            vec = s.v if attr == "v" else s.a
            return float(np.hypot(vec[k, 0], vec[k, 1]))
        vec = {"x": s.r, "y": s.r, "vx": s.v, "vy": s.v, "ax": s.a, "ay": s.a}[attr]
        return float(vec[k, 0 if attr.endswith("x") else 1])
    if kind == "joint":             # an R joint's relative angle, in (-180, 180]
        return float(kin.relative_angle_deg(*kin.mechanism.spec.joint(name).links)[k])
    if attr == "angle":
        return float(kin.angle_deg(name)[k])
    i = kin.index(name)
    return float({"omega": kin.omega, "alpha": kin.alpha}[attr][k, i])


def check_expectations(kin: Kinematics, results: dict[str, ForceResult], flags,
                       cycle: dict[str, float] | None = None,
                       cycle_why: str = "",
                       instant: dict[str, np.ndarray] | None = None,
                       members: dict[str, float] | None = None
                       ) -> list[ExpectationResult]:
    """Every ``expect`` entry: instantaneous quantities against the kinematics or every force
    method at their angle; cycle quantities (no angle) against ``cycle`` (the review's values,
    from the reference method; None when undefined, because ``cycle_why``); members'
    quantities against ``members`` (the strength review's values, any sweep)."""
    out = []
    spec = kin.mechanism.spec
    for e in spec.expect:
        if is_member(e.quantity):
            out.append(check_cycle(e, members or {}, ""))
            continue
        if e.angle is None:
            out.append(check_cycle(e, cycle, cycle_why))
            continue
        k = kin.index_of(e.angle)
        out += left_out(e, spec, flags) if k is None else at_angle(e, kin, results, k,
                                                                   instant)
    return out


def left_out(e: Expectation, spec, flags) -> list[ExpectationResult]:
    """The failed result of an expectation whose angle has no result (and why)."""
    why = next((f.reason for f in flags if abs(f.angle - e.angle) < 1e-9), "not analysed")
    return [ExpectationResult(e, "-", None, False,
                              f"{spec.driver.coordinate} {e.angle:g} {spec.axis_unit} is left "
                              f"out: {why}")]


def at_angle(e: Expectation, kin: Kinematics, results: dict[str, ForceResult],
             k: int, instant: dict[str, np.ndarray] | None = None) -> list[ExpectationResult]:
    """An instantaneous expectation checked at row ``k`` of ``kin``: against the kinematics,
    or against every force method that computes its quantity."""
    if is_kinematic(e.quantity):
        sources = {"kinematics": kinematic_value(kin, e.quantity, k, instant)}
    else:
        sources = {}
        for name, res in results.items():
            values = res.quantity(e.quantity, kin.mechanism.spec)
            if values is not None:
                sources[name] = float(values[k])
    return judge(e, sources, kin.mechanism.spec)


def judge(e: Expectation, sources: dict[str, float], spec) -> list[ExpectationResult]:
    """An instantaneous expectation against the value each source computed at its angle."""
    out = []
    for source, got in sources.items():
        if not np.isfinite(got):
            out.append(ExpectationResult(e, source, None, False,
                                         f"{e.quantity} is undefined at {e.angle:g} "
                                         f"{spec.axis_unit}"))
            continue
        ok = abs(got - e.value) <= e.tol
        msg = "" if ok else (f"{e.quantity} at {e.angle:g} {spec.axis_unit}: "
                             f"{_expected_got(e, got)} ({source})")
        out.append(ExpectationResult(e, source, got, ok, msg))
    return out


def _expected_got(e: Expectation, got: float) -> str:
    """``expected 232.4 ± 0.02 mm, got 232.5 mm``: in the unit the spec wrote (SI without
    one)."""
    unit = f" {e.unit}" if e.unit else ""
    s = e.scale
    return (f"expected {e.value / s:.10g} ± {e.tol / s:.2g}{unit}, got "
            f"{got / s:.10g}{unit}")


#: why a member's quantity can be undefined
MEMBER_UNDEFINED = {"buckling_safety": "the member is never in compression",
                    "static_safety": "the member carries no stress",
                    "fatigue_safety": "the member's stress neither alternates nor is tensile"}


def cycle_value(cycle: dict[str, float] | None, quantity: str,
                why: str = "") -> tuple[float | None, str]:
    """The value of cycle quantity ``quantity`` in ``cycle`` (a review's values; None when
    they are undefined, because ``why``), or None and the message saying why it has none."""
    got = None if cycle is None else cycle.get(quantity)
    if got is None:
        reason = why if cycle is None else (MEMBER_UNDEFINED.get(quantity.rpartition(".")[2],
                                                                 "not defined for this mechanism")
                                            if is_member(quantity)
                                            else "not defined for this mechanism")
        return None, f"{quantity} is undefined: {reason}"
    return got, ""


def check_cycle(e: Expectation, cycle: dict[str, float] | None, why: str) -> ExpectationResult:
    got, undefined = cycle_value(cycle, e.quantity, why)
    if got is None:
        return ExpectationResult(e, "cycle", None, False, undefined)
    ok = abs(got - e.value) <= e.tol
    msg = "" if ok else f"{e.quantity}: {_expected_got(e, got)} (over the cycle)"
    return ExpectationResult(e, "cycle", got, ok, msg)
