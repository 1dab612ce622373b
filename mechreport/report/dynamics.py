"""The report's Machine dynamics section, summary.json's ``dynamics`` and the time histories
(dynamics.csv, dynamics.parquet), read from an analysis's machine-dynamics result
(:class:`mechreport.pipeline.dynamics.DynamicsResult`): the simulation's numbers are
computed there once; this module only arranges them."""
from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..dynamics.mean_speed import RTOL as SHOOTING_RTOL
from ..dynamics.simulate import RTOL, STARTUP_FRACTION, STEADY_RTOL
from ..units import RPM, Display, deg, fmt
from .text import cycle_name

#: the columns of dynamics.csv / dynamics.parquet, in order, as the format names them
HISTORY_COLUMNS = ("time [s]", "crank.angle [deg]", "crank.omega [rad/s]",
                   "crank.alpha [rad/s^2]", "motor.torque [N·m]")
#: the cycle quantities compared between the constant-speed sweep and the steady turn
COMPARED = ("cycle.torque.max", "cycle.torque.min", "cycle.torque.rms", "cycle.power.max",
            "cycle.shaking.force_max")


@dataclass
class DynamicsPlot:
    """The section's figure: the speed [rpm] against ``time`` [s] from the start, and over
    the steady turn against the crank ``angles`` [deg] (empty without a steady state);
    ``mean`` the steady mean speed [rpm] (None without)."""

    time: np.ndarray
    rpm: np.ndarray
    angles: np.ndarray = field(default_factory=lambda: np.zeros(0))
    turn_rpm: np.ndarray = field(default_factory=lambda: np.zeros(0))
    mean: float | None = None
    startup: float | None = None
    # the steady cycle's extremes (angle [deg within the cycle], speed [rpm]) and its
    # length [deg]; ``startup_shown`` False where there is no start-up (mean_rpm)
    highest: tuple[float, float] | None = None
    lowest: tuple[float, float] | None = None
    cycle: float = 360.0
    startup_shown: bool = True


@dataclass
class DynamicsSection:
    """The report's Machine dynamics section: ``intro`` (the motor, flywheel, start and the
    equation), ``outcome`` (how the simulation ended), ``rows`` (quantity, value, what it is)
    of the simulated quantities and the flywheel estimate beside them, ``why`` the reason
    they differ, ``compared`` (quantity, constant-speed sweep, steady turn) rows,
    ``verdicts`` the steady turn's design verdicts as lines, ``plot`` the figure's data,
    ``histories`` the time histories' columns (SI, HISTORY_COLUMNS)."""

    intro: str
    outcome: str
    rows: list[list[str]]
    why: str
    compared: list[list[str]]
    verdicts: list[str]
    plot: DynamicsPlot
    histories: list[np.ndarray]


def _drive_text(sd, sim) -> str:
    """What drives the crank: the motor (and its gearing), or mean_rpm's constant torque."""
    if sd.motor is None:
        return (f"a constant torque of {fmt(sim.drive_torque)} N·m, the cycle mean of the "
                f"torque the mechanism takes at a mean speed of {fmt(sd.mean_rpm)} rpm "
                "(dynamics.mean_rpm)")
    text = _motor_text(sd.motor)
    m = sd.motor
    if m.ratio != 1 or m.efficiency != 1:
        text += (f", geared to turn {fmt(m.ratio)} times as fast as the crank (efficiency "
                 f"{fmt(m.efficiency)}: the crank receives {fmt(m.ratio)} × {fmt(m.efficiency)}"
                 f" × its torque while it drives, {fmt(m.ratio)} × its torque / "
                 f"{fmt(m.efficiency)} driven back)")
    return text


def _flywheel_text(sd) -> str:
    if sd.flywheel_geared is None:
        return f"a flywheel of {fmt(sd.flywheel)} kg·m² on its shaft"
    inertia, ratio = sd.flywheel_geared
    return (f"a flywheel of {fmt(inertia)} kg·m² on a shaft turning {fmt(ratio)} times as "
            f"fast as the crank ({fmt(ratio)}² × {fmt(inertia)} = {fmt(sd.flywheel)} kg·m² on "
            "the crank)")


def _motor_text(motor) -> str:
    if motor.kind == "torque":
        return f"a constant motor torque of {fmt(motor.constant)} N·m"
    if motor.kind == "linear":
        return (f"a motor whose torque falls linearly from {fmt(motor.stall_torque)} N·m at "
                f"rest to 0 at {fmt(motor.no_load_rpm)} rpm")
    pts = ", ".join(f"{fmt(r)} rpm: {fmt(t)} N·m" for r, t in motor.curve)
    return f"a motor of torque curve ({pts}; linear between the points)"


def dynamics_section(analysis, d: Display) -> DynamicsSection | None:
    """The Machine dynamics section of ``analysis`` (None without ``dynamics:``)."""
    dyn = analysis.dynamics
    spec = analysis.spec
    if dyn is None or spec.dynamics is None:
        return None
    sim, cycle, sd = dyn.simulation, dyn.simulation.steady, spec.dynamics
    mean_speed = sd.mean_rpm is not None
    start = ("" if mean_speed else
             f", started at crank angle {deg(sd.start_angle)}° "
             + ("from rest" if sd.start_rpm == 0 else f"at {fmt(sd.start_rpm)} rpm"))
    how = ("its periodic state at that mean speed is found directly, with no start-up "
           "(shooting one cycle: the starting speed and the torque such that the speed "
           "returns and the cycle takes as long as at the mean speed, by Newton's method on "
           f"the integration, scipy solve_ivp, DOP853, relative tolerance {SHOOTING_RTOL:g})."
           if mean_speed else
           f"it is integrated in time (scipy solve_ivp, DOP853, relative tolerance {RTOL:g}).")
    intro = (f"The crank is driven by {_drive_text(sd, sim)}, with {_flywheel_text(sd)}"
             f"{start}. Its equation of motion, "
             "(J(φ) + I_f) α = M_m(ω) − B(φ) ω² − C(φ) ω − D(φ), has the mechanism's reduced "
             "inertia J on the crank (found from the reference method's driver torque; the "
             "kinetic energy of the velocity coefficients, Σ m v² + I ω², gives the same), "
             "B = J′/2, C its viscous "
             "loads and D its other loads and weights, all from the same kinematics and loads "
             f"as the sweep; {how}")
    rows, compared, verdicts, why = [], [], [], ""
    if cycle is None:
        outcome = (f"Integrated to t = {fmt(sim.time[-1])} s (dynamics.until) over "
                   f"{sim.turns} whole turn{'s' if sim.turns != 1 else ''}: the transient only; "
                   "the steady-state quantities need until: steady.")
    else:
        v = dyn.values
        swing, inertia, _ = dyn.estimate
        estimate = v["dynamics.speed_fluctuation_estimate"]
        cyc = cycle_name(spec.cycle)
        head = (f"Periodic state found at a time-mean speed of {fmt(sd.mean_rpm)} rpm under the "
                f"constant driving torque {fmt(sim.drive_torque)} N·m." if mean_speed else
                f"Steady state after {sim.turns} {cyc}s (t = {fmt(cycle.t0 + cycle.period)} "
                f"s): two successive {cyc}s agree in speed and period to {STEADY_RTOL:g}, the "
                f"speed within {STEADY_RTOL:g} of its extrapolated limit.")
        outcome = (f"{head} Over the steady {cyc} the crank runs at "
                   f"{fmt(v['dynamics.mean_rpm'])} rpm on average, between "
                   f"{fmt(cycle.omega_min / RPM)} rpm at φ = {fmt(cycle.omega_min_angle, 5)}° and "
                   f"{fmt(cycle.omega_max / RPM)} rpm at φ = {fmt(cycle.omega_max_angle, 5)}°; "
                   f"one {cyc} takes {fmt(cycle.period)} s." + _checked_text(dyn.steady))
        rows = [["dynamics.mean_rpm", f"{fmt(v['dynamics.mean_rpm'])} rpm",
                 f"the time-mean speed of the steady {cyc}"],
                ["dynamics.omega_max", f"{fmt(v['dynamics.omega_max'])} rad/s",
                 f"the largest speed ({fmt(v['dynamics.omega_max'] / RPM)} rpm), located "
                 "between samples"],
                ["dynamics.omega_max_angle", f"{fmt(v['dynamics.omega_max_angle'], 5)}°",
                 f"the crank angle where it occurs, within the {cyc}"],
                ["dynamics.omega_min", f"{fmt(v['dynamics.omega_min'])} rad/s",
                 f"the smallest speed ({fmt(v['dynamics.omega_min'] / RPM)} rpm)"],
                ["dynamics.omega_min_angle", f"{fmt(v['dynamics.omega_min_angle'], 5)}°",
                 "the crank angle where it occurs"],
                ["dynamics.speed_fluctuation", fmt(v["dynamics.speed_fluctuation"]),
                 f"(max − min) / mean of the steady {cyc}'s speed"],
                ["dynamics.speed_fluctuation_estimate", fmt(estimate),
                 f"first-order estimate ΔE / ((J_mean + I_f) ω²): ΔE = {fmt(swing)} J at a "
                 f"constant {fmt(v['dynamics.mean_rpm'])} rpm, J_mean + I_f = "
                 f"{fmt(inertia)} kg·m²"]]
        if "dynamics.startup_time" in v:
            rows.append(["dynamics.startup_time", f"{fmt(v['dynamics.startup_time'])} s",
                         f"from the start to {100 * STARTUP_FRACTION:g} % of the steady mean "
                         "speed"])
        rows.append(["dynamics.motor_rms_torque", f"{fmt(v['dynamics.motor_rms_torque'])} N·m",
                     f"the driving torque (constant)" if mean_speed else
                     f"the motor's RMS torque over the steady {cyc}, in time"])
        why = _why_they_differ(v["dynamics.speed_fluctuation"], estimate, sd.motor)
        compared = _compared(analysis, dyn.steady, d)
        verdicts = [vd.describe(fmt) + (" — met" if vd.passed else " — NOT MET")
                    for vd in dyn.verdicts]
    plot = DynamicsPlot(sim.time, sim.omega / RPM,
                        cycle.angles if cycle else np.zeros(0),
                        cycle.omega / RPM if cycle else np.zeros(0),
                        cycle.mean_omega / RPM if cycle else None,
                        sim.startup_time,
                        (cycle.omega_max_angle, cycle.omega_max / RPM) if cycle else None,
                        (cycle.omega_min_angle, cycle.omega_min / RPM) if cycle else None,
                        spec.cycle, not mean_speed)
    return DynamicsSection(intro, outcome, rows, why, compared, verdicts, plot,
                           histories_of(sim))


def histories_of(sim) -> list[np.ndarray]:
    """The columns of dynamics.csv (HISTORY_COLUMNS, SI) of a simulation."""
    return [sim.time, np.degrees(sim.angle), sim.omega, sim.alpha, sim.motor]


def _checked_text(steady) -> str:
    """How well the methods agree over the steady turn, and its largest residual."""
    worst = steady.worst
    if worst is None:
        return ""
    residual = max((r.force for r in steady.residuals), default=0.0)
    return (f" Over the steady turn the methods agree to {worst.relative:.1e} of each "
            f"quantity's largest value (worst: {worst.quantity}) and the largest equilibrium "
            f"residual is {residual:.1e} N.")


def _why_they_differ(simulated: float, estimate: float, motor) -> str:
    """Why the simulated fluctuation differs from the constant-speed estimate."""
    gap = (simulated - estimate) / estimate if estimate else 0.0
    motor_part = ("; and the motor's torque follows the speed (a torque that falls as the "
                  "speed rises takes up part of the energy swing itself)"
                  if motor is not None and motor.kind != "torque" else "")
    return (f"The simulated fluctuation is {fmt(abs(gap) * 100, 3)} % "
            f"{'above' if gap > 0 else 'below'} the flywheel estimate of the design review's "
            "formula. The estimate takes the speed as constant while the energy swings, and "
            "the inertia on the crank as its mean; the simulation lets the speed change the "
            "loads that depend on it and the inertia change with the crank angle"
            f"{motor_part}. The two meet as the flywheel grows.")


def _compared(analysis, steady, d: Display) -> list[list[str]]:
    """Cycle quantities at the sweep's constant speed beside the steady turn's."""
    if analysis.review is None or steady is None or steady.review is None:
        return []
    a, b = analysis.review.values, steady.review.values
    rows = []
    names = list(COMPARED) + sorted(k for k in b if k.startswith("joint.")
                                    and k.endswith(".f_max"))
    for name in names:
        if name in a and name in b:
            kind = "moment" if name.startswith("cycle.torque") else \
                "power" if "power" in name else "force"
            unit_value = (lambda x: f"{fmt(x)} W") if kind == "power" else \
                (lambda x: d.q(x, kind))
            rows.append([name, unit_value(a[name]), unit_value(b[name])])
    return rows


def write_histories(histories: list[np.ndarray], folder: Path) -> list[Path]:
    """dynamics.csv and dynamics.parquet of the time ``histories`` (:func:`histories_of`)
    in ``folder``."""
    import pyarrow as pa
    import pyarrow.parquet as pq

    from .files import atomic_write_bytes, atomic_write_text
    folder = Path(folder)
    cols = [np.asarray(c, float) for c in histories]
    lines = [",".join(HISTORY_COLUMNS)]
    lines += [",".join(repr(float(x)) for x in row) for row in zip(*cols)]
    out = [atomic_write_text(folder / "dynamics.csv", "\n".join(lines) + "\n")]
    table = pa.table({name: c for name, c in zip(HISTORY_COLUMNS, cols)})
    sink = pa.BufferOutputStream()
    pq.write_table(table, sink)
    out.append(atomic_write_bytes(folder / "dynamics.parquet", sink.getvalue().to_pybytes()))
    return out


__all__ = ["DynamicsPlot", "DynamicsSection", "HISTORY_COLUMNS",
           "dynamics_section", "histories_of", "write_histories"]
