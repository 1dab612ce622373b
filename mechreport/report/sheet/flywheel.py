"""The solution sheet's flywheel problem (a spec with ``design.speed_fluctuation``), worked
as the textbooks work it: the turning-moment diagram (the driver torque over the cycle at
the constant speed, against its mean), its areas between the crossings with the mean and
the energy level after each, the largest energy fluctuation, and the flywheel
I = dE / (Cs omega^2); with machine dynamics, the simulated fluctuation beside it."""
from __future__ import annotations

import math
from dataclasses import dataclass

from ...forces import METHODS
from ...post.flywheel import energy_areas, largest_fluctuation
from ..document import Doc, Print, Table
from ...post.frame import reference_method
from ...units import fmt


@dataclass
class FlywheelSheet:
    """The flywheel problem's paragraphs (text), in order: ``intro`` before the table of
    ``rows`` (area, from, to, energy, level), ``steps`` after it."""

    intro: list[str]
    rows: list[list[str]]
    steps: list[str]


def flywheel_sheet(analysis) -> FlywheelSheet | None:
    """The flywheel problem of ``analysis`` (None without ``design.speed_fluctuation`` or a
    design review over a whole cycle)."""
    spec, review = analysis.spec, analysis.review
    cs = spec.design.speed_fluctuation
    if not cs or review is None or spec.driver.at_rest:
        return None
    method = reference_method(analysis.forces)
    torque = analysis.forces[method].driver_torque
    span = spec.sweep.stop - spec.sweep.start
    period = spec.cycle if span >= spec.cycle - 1e-9 else 360.0
    mean = review.values["cycle.torque.mean"]
    omega = abs(spec.driver.omega)
    areas = energy_areas(analysis.angles, torque, mean, period)
    swing, top, low = largest_fluctuation(areas)
    over = "turn" if period == 360 else f"cycle of {fmt(period)}°"
    intro = [
        "The turning-moment diagram is the driver torque M(φ) that turns the crank "
        f"at the constant speed ω = {fmt(omega)} rad/s ({fmt(spec.driver.rpm)} rpm) over a "
        f"{over} (the {METHODS[method].TITLE} solution at every analysed angle). Its "
        f"mean, M_mean = (1/{fmt(math.radians(period), 4)}) ∫ M dφ = {fmt(mean)} N·m "
        "(cycle.torque.mean), is the uniform torque that does the same work per cycle. "
        "Where M exceeds the mean, the mechanism takes more than a uniform drive gives and "
        "the flywheel gives up kinetic energy (the crank slows); where it falls short, the "
        "flywheel takes the excess up (the crank speeds up). Each area between two "
        "crossings of M with its mean is that energy, ∫ (M − M_mean) dφ (trapezoids on "
        "the analysed angles, the crossings interpolated); the energy level after an area "
        "sums the areas from the first crossing:"]
    scale = max(abs(x.energy) for x in areas)
    rows = [[f"A{i + 1}", f"{fmt(x.start, 5)}°",
             f"{fmt(x.end % period if x.end > period else x.end, 5)}°",
             fmt(x.energy, scale=scale), fmt(x.level, scale=scale)]
            for i, x in enumerate(areas)]

    def after(x) -> str:
        if x is None:
            return f"at the first crossing, φ = {fmt(areas[0].start, 5)}°"
        return f"after A{areas.index(x) + 1}, φ = {fmt(x.end % period, 5)}°"
    inertia = swing / (cs * omega ** 2)
    steps = [
        f"The areas sum to {fmt(areas[-1].level, scale=scale)} J over the cycle (the work "
        "of M equals that of its mean). The largest energy fluctuation is the highest level "
        f"minus the lowest: ΔE = {fmt(top.level if top else 0.0, scale=scale)} − "
        f"({fmt(low.level if low else 0.0, scale=scale)}) = {fmt(swing)} J. At the highest "
        f"level ({after(top)}) the mechanism has taken the most in excess of the uniform "
        "drive: the flywheel has given it up, and the speed is smallest; at the lowest "
        f"({after(low)}) the speed is largest.",
        f"For a coefficient of speed fluctuation Cs = (ω_max − ω_min) / ω = {fmt(cs)} the "
        "kinetic energy (I/2)(ω_max² − ω_min²) = I Cs ω² must take up ΔE, so the inertia on "
        f"the crank shaft is I = ΔE / (Cs ω²) = {fmt(swing)} / ({fmt(cs)} × {fmt(omega)}²) = "
        f"{fmt(inertia)} kg·m² (the report's cycle.flywheel_inertia, "
        f"{fmt(review.values.get('cycle.flywheel_inertia'))} kg·m², takes the energy's "
        "extremes at the analysed angles rather than at the crossings)."]
    steps += _dynamics_check(analysis, inertia)
    return FlywheelSheet(intro, rows, steps)


def _dynamics_check(analysis, inertia: float) -> list[str]:
    """The machine dynamics' flywheel beside the one sized (none without a steady state)."""
    dyn, sd = analysis.dynamics, analysis.spec.dynamics
    if dyn is None or sd is None or not dyn.values:
        return []
    v = dyn.values
    geared = ""
    if sd.flywheel_geared is not None:
        own, ratio = sd.flywheel_geared
        geared = (f" (its {fmt(own)} kg·m² turn {fmt(ratio)} times as fast as the crank: "
                  f"{fmt(ratio)}² × {fmt(own)} on the crank; the inertia sized above would be "
                  f"{fmt(inertia / ratio ** 2)} kg·m² on that shaft)")
    _, j_total, _ = dyn.estimate
    return [
        f"Check by the machine dynamics: with the flywheel I_f = {fmt(sd.flywheel)} kg·m² on "
        f"the crank{geared} and the mechanism's own mean reduced inertia, "
        f"J_mean + I_f = {fmt(j_total)} kg·m², the first-order estimate at the steady mean "
        f"speed is Cs ≈ ΔE / ((J_mean + I_f) ω²) = "
        f"{fmt(v['dynamics.speed_fluctuation_estimate'])} "
        "(dynamics.speed_fluctuation_estimate, ΔE of the torque at that speed); the "
        "integrated motion gives dynamics.speed_fluctuation = "
        f"{fmt(v['dynamics.speed_fluctuation'])}, the speed between "
        f"{fmt(v['dynamics.omega_min'])} rad/s at φ = {fmt(v['dynamics.omega_min_angle'], 5)}° "
        f"and {fmt(v['dynamics.omega_max'])} rad/s at φ = "
        f"{fmt(v['dynamics.omega_max_angle'], 5)}°."]


def flywheel_blocks(doc: Doc, fw: FlywheelSheet) -> None:
    """The flywheel problem's blocks at the end of the answer key."""
    doc.h("Flywheel")
    for p in fw.intro:
        doc.p(p)
    doc.add(Table(["area", "from", "to", "energy ∫ (M − M_mean) dφ [J]", "level after it [J]"],
                  fw.rows, right={1, 2, 3, 4}, print=Print(grid=True, size=8, inset=3)))
    for p in fw.steps:
        doc.p(p)


__all__ = ["FlywheelSheet", "flywheel_blocks", "flywheel_sheet"]
