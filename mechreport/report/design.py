"""The Design summary: the verdicts, the cycle quantities, the bearings, the
counterweight and the cycle's plot data (:class:`CycleData`) and its figures; its record in
summary.json is written by :mod:`mechreport.pipeline.records`."""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..dynamics.simulate import STARTUP_FRACTION
from ..post.balance import NOTICEABLE
from ..quantities import unit_of
from ..spec import profile_at
from ..units import DASH, PRESSURE_UNITS, Display, deg, fmt, kind_of
from .section import Figure


@dataclass
class CycleData:
    """Plot data over one turn on the cycle grid ``angles`` (N,) [deg], left-out angles filled
    in: driver ``torque`` (N,) [N m] and its ``mean``; ``energy`` (N,) [J], the running
    integral of torque minus mean; motor lines [N m] when given; ``sources`` the torque (N,)
    [N m] of each source (they sum to ``torque``); ``transmission`` (N,) [deg] by dyad and its
    lower limit; the inertial shaking force (N, 2) [N] without and with the counterweight;
    ``silent`` the sources whose torque is 0 at every angle (round-off: not drawn)."""

    angles: np.ndarray
    torque: np.ndarray
    mean: float
    energy: np.ndarray
    rated_torque: float | None
    peak_torque: float | None
    sources: dict[str, np.ndarray]
    transmission: dict[str, np.ndarray]
    transmission_limit: float | None
    inertial: np.ndarray
    balanced: np.ndarray
    interpolated: list[float]
    silent: list[str] = field(default_factory=list)
    period: float = 360.0        # the cycle [deg]: 720 for a four-stroke engine
    # an engine's pressure loads (format 1.2): each one's pressure (N,) over the cycle grid,
    # as written (absolute or gauge, in ``pressure_unit``), by load name
    pressures: dict[str, np.ndarray] = field(default_factory=dict)
    pressure_unit: str = "Pa"

    @property
    def span(self) -> str:
        """What the figures run over: ``one turn``, or ``the 720° cycle``."""
        return "one turn" if self.period == 360.0 else f"the {self.period:g}° cycle"


@dataclass
class DesignSummary:
    """The report's first section. ``verdicts`` rows (design item, checked quantity, value,
    limit, margin, PASS/FAIL); ``values`` rows (meaning, cycle quantity, value with unit);
    ``bearings`` rows (joint, peak, mean, equivalent load, L10 life);
    ``problem`` why there are no cycle quantities ("" when there are); ``absent`` the cycle
    figures left out because they would show nothing, each with the sentence saying why
    (the report prints it where the figure would be)."""

    verdicts: list[list[str]]
    values: list[list[str]]
    counterweight: str
    interpolated: str
    problem: str
    passed: bool
    data: CycleData | None = None
    bearings: list[list[str]] = field(default_factory=list)   # joint, max, mean, equiv., L10
    absent: dict[str, str] = field(default_factory=dict)


def design_summary(analysis, d: Display) -> DesignSummary:
    """Verdicts, cycle quantities, counterweight and the cycle's plot data."""
    spec, rev = analysis.spec, analysis.review
    verdict_rows = []
    for v in analysis.verdicts:
        kind = kind_of(v.unit)
        value = (d.q(v.value, kind) if v.value is not None else f"undefined: {v.why}")
        verdict_rows.append([v.item, v.quantity.replace("joint.*.", "largest joint ")
                             + (f" ({v.where})" if v.where else ""), value,
                             ("≥ " if v.at_least else "≤ ") + d.q(v.limit, kind),
                             _margin(v), "PASS" if v.passed else "FAIL"])
    passed = all(v.passed for v in analysis.verdicts)
    if rev is None:
        return DesignSummary(verdict_rows, [], "", "", analysis.review_problem, passed)
    values = []
    for name, value in rev.values.items():
        if name.startswith("joint."):
            continue
        kind = kind_of(unit_of(name))
        values.append([MEANING.get(name, name), name, d.q(value, kind)])
    bearings: dict[str, list[str]] = {}
    attrs = ["f_max", "f_mean", "f_equivalent", "life_h"]
    for name, value in rev.values.items():       # per joint: bearing loads and lives
        if name.startswith("joint."):     # joint.C.on.upper.f_max: a pin's force on a link
            joint, attr = name[len("joint."):].rsplit(".", 1)
            row = bearings.setdefault(joint, [joint] + [DASH] * len(attrs))
            if attr in attrs:
                row[1 + attrs.index(attr)] = d.num(value, kind_of(unit_of(name)))
    cw = rev.counterweight
    if cw.worthwhile:
        counter = (f"A point counterweight of m·r = {d.q(cw.mr, 'mass_length')} at "
                   f"{d.num(cw.angle, 'angle')}° from the crank's x-axis brings the RMS "
                   f"inertial shaking force from {d.q(cw.rms_before, 'force')} to "
                   f"{d.q(cw.rms_after, 'force')} ({fmt(-100 * cw.reduction, 3)} %).")
    elif cw.mr > 0:
        counter = (f"No counterweight is recommended: the best point counterweight on the "
                   f"crank (m·r = {d.q(cw.mr, 'mass_length')} at "
                   f"{d.num(cw.angle, 'angle')}°) would reduce the RMS inertial shaking "
                   f"force ({d.q(cw.rms_before, 'force')}) by less than "
                   f"{fmt(100 * NOTICEABLE)} %.")
    else:
        counter = ("The crank needs no counterweight: the inertial shaking force has no "
                   "component turning with it.")
    interp = ""
    if len(rev.cycle.interpolated):
        interp = ("Left-out angles inside the cycle, interpolated from their neighbours for "
                  "the cycle quantities: " + ", ".join(deg(a) for a in rev.cycle.interpolated)
                  + " deg.")
    sources = analysis.cycle_torque_by_source()
    data = CycleData(rev.cycle.angles, rev.torque, rev.values["cycle.torque.mean"], rev.energy,
                     spec.design.motor.get("rated_torque"), spec.design.motor.get("peak_torque"),
                     sources, rev.transmission,
                     spec.design.limits.get("transmission_angle"),
                     rev.inertial, rev.shaking_balanced,
                     [float(a) for a in rev.cycle.interpolated],
                     [name for name, part in sources.items() if d.zero(part, "moment")],
                     rev.cycle.period, *_pressures(spec, rev.cycle.angles, d.pressure))
    return DesignSummary(verdict_rows, values, counter, interp, "", passed, data,
                         list(bearings.values()), _absent_figures(spec, rev, d))


def _pressures(spec, angles: np.ndarray, unit: str) -> tuple[dict[str, np.ndarray], str]:
    """Each pressure load's pressure at ``angles`` [deg] as written (the profile's values,
    phased by its shift; absolute or gauge as the profile is), in the display's ``unit``
    (``report.units.pressure``, default the first pressure load's), and that unit."""
    loads = [ld for ld in spec.loads if ld.pressure is not None]
    if not loads:
        return {}, "Pa"
    scale = PRESSURE_UNITS[unit]
    return ({ld.label: profile_at(ld.pressure.profile, angles, spec.cycle, ld.shift)
             * (ld.pressure.scale / scale) for ld in loads}, unit)


def _absent_figures(spec, rev, d: Display) -> dict[str, str]:
    """The cycle figures that would show nothing, each with the sentence the report prints
    instead: the flywheel diagram where the driver's torque does no work that fluctuates
    (at rest, or a constant torque), the balancing diagram where there is no inertial
    shaking force (0 at every angle by the round-off rule)."""
    out = {}
    if spec.driver.at_rest:
        out["flywheel"] = ("No flywheel diagram: at rest the driver's torque does no work "
                           "over a turn.")
    elif d.zero(rev.values["cycle.energy_fluctuation"], "moment"):
        out["flywheel"] = ("No flywheel diagram: the driver's torque is the same at every "
                           "angle, so there is no energy fluctuation for a flywheel to take up.")
    if d.zero(rev.inertial, "force"):
        why = ("at rest no link accelerates" if spec.driver.at_rest else
               "the links' inertia forces cancel at every angle")
        out["balance"] = (f"No balancing diagram: {why}, so there is no inertial shaking "
                          "force for a counterweight to balance.")
    return out


#: what each cycle quantity means, for the Design summary table
MEANING = {
    "cycle.torque.max": "largest driver torque", "cycle.torque.min": "smallest driver torque",
    "cycle.torque.mean": "mean driver torque", "cycle.torque.rms": "RMS driver torque",
    "cycle.power.max": "peak driver power", "cycle.power.mean": "mean driver power",
    "cycle.energy_fluctuation": "energy fluctuation ΔE",
    "cycle.flywheel_inertia": "flywheel inertia for Cs",
    "cycle.friction.energy": "energy lost to friction per cycle",
    "cycle.efficiency": "mechanical efficiency",
    "cycle.shaking.force_max": "peak shaking force",
    "cycle.shaking.force_rms": "RMS shaking force",
    "cycle.shaking.moment_max": "peak shaking moment",
    "cycle.transmission_angle.min": "smallest transmission angle",
    "cycle.transmission_angle.max": "largest transmission angle",
    "cycle.inertia_shaking.force_rms": "RMS inertial shaking force",
    "balance.counterweight.mr": "best counterweight m·r",
    "balance.counterweight.angle": "its angle from the crank",
    "balance.inertia_shaking.force_rms": "RMS inertial shaking, balanced",
    "dynamics.speed_fluctuation": "speed fluctuation",
    "dynamics.mean_rpm": "mean crank speed",
    "dynamics.startup_time": f"start-up time (to {100 * STARTUP_FRACTION:g} %)",
    "dynamics.motor_rms_torque": "motor's RMS torque",
    "dynamics.omega_max": "largest crank speed (steady cycle)",
    "dynamics.omega_min": "smallest crank speed (steady cycle)",
    "dynamics.omega_max_angle": "crank angle of the largest speed",
    "dynamics.omega_min_angle": "crank angle of the smallest speed",
    "dynamics.speed_fluctuation_estimate": "speed fluctuation, first-order estimate",
    "f_max": "peak bearing load", "f_mean": "mean bearing load",
    "f_equivalent": "equivalent (cube-mean) load", "life_h": "L10 rating life",
}


def _margin(v) -> str:
    """A verdict's margin: ``+24.1 %`` of the limit; ``value 537× limit`` when it is huge."""
    if v.margin is None:
        return DASH
    if abs(v.margin) > 9.99:
        ratio = v.value / v.limit if v.limit else float("inf")
        return f"value {fmt(ratio, 3)}× limit"
    text = f"{v.margin * 100:+.1f} %"
    return "0.0 %" if text in ("+0.0 %", "-0.0 %") else text


def design_figures(design: DesignSummary, d: Display) -> dict[str, Figure]:
    """The Design summary's figures with their captions: the flywheel diagram, the torque
    by source, the transmission angle, the balancing diagram; those in ``design.absent``
    left out (the report says why instead)."""
    cd = design.data
    if cd is None:
        return {}
    silent = cd.silent
    if silent:
        names = ", ".join(silent)
        silent_text = (f" Not drawn: {names} ({'its' if len(silent) == 1 else 'their'} "
                       f"torque is {d.q(0.0, 'moment')} at every angle).")
    else:
        silent_text = ""
    span = cd.span
    figs = {"flywheel": Figure("flywheel", f"Driver torque over {span} against its mean: the "
                               "areas above (energy taken in) and below (given back) the mean "
                               "line; the largest energy fluctuation ΔE, which the flywheel "
                               "absorbs, lies between the two marked angles.", "flywheel"),
            "breakdown": Figure("breakdown", f"Driver torque by source over {span}: each "
                                "source's share stacked (positive above zero, negative below); "
                                f"the line is the total.{silent_text}", "breakdown"),
            "balance": Figure("balance", f"Inertial shaking force (sum of m a_C) over {span}, "
                              "without and with the best point counterweight on the crank.",
                              "balance")}
    if cd.pressures:
        several = len(cd.pressures) > 1
        figs["pressure"] = Figure("pressure", f"Pressure diagram: the pressure on "
                                  f"{'each piston' if several else 'the piston'} against the "
                                  f"crank angle over {span}, as the spec gives it "
                                  f"(absolute or gauge), in {cd.pressure_unit}.", "pressure")
        figs["turning_moment"] = Figure(
            "turning_moment", f"Turning-moment diagram: the crank effort (what the "
            f"{'cylinders give' if several else 'cylinder gives'} the shaft, minus the driver "
            f"torque) over {span} against its mean; each area between two crossings is "
            "labelled with its energy, + in excess of the mean, − short of it."
            + (" Below: each cylinder's share (its gas force's part of the torque)."
               if several else ""), "turning_moment")
    if cd.transmission:
        limit = (", with the design limit" if cd.transmission_limit is not None else "")
        figs["transmission"] = Figure("transmission", "Transmission angle of each group over "
                                      f"{span} (folded into 0-90°){limit}.", "transmission")
    return {k: f for k, f in figs.items() if k not in design.absent}
