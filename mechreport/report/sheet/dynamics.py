"""The solution sheet's equation of motion at a reference angle (a spec with ``dynamics:``):
the reduced inertia J(phi) term by term from the velocity coefficients, its slope, the
generalized force of the motor and the loads at the steady turn's speed there, and the
crank's acceleration they give, as paragraphs of text with their numbers."""
from __future__ import annotations


import numpy as np

from ...units import fmt, rad_s_to_rpm


def equation_of_motion_text(analysis, k: int) -> list[str]:
    """The paragraphs of the equation of motion at angle index ``k`` of ``analysis`` ([]
    without machine dynamics, or without a steady turn through that angle)."""
    dyn = analysis.dynamics
    if dyn is None or analysis.spec.dynamics is None:
        return []
    from ...dynamics import motor_torque
    from ...dynamics.equation import inertia_terms
    spec, kin = analysis.spec, analysis.kinematics
    angle = float(kin.angles[k])
    phi = np.radians([angle])
    eom = dyn.equation
    j, b, c, d = (float(x) for x in eom.at(phi)[0])
    fly = spec.dynamics.flywheel
    cycle = dyn.simulation.steady
    speed = cycle.mean_omega if cycle is not None else 1.0
    # round-off of C and D (sums of the method's solves) prints as 0 on the scale of both
    scale = float(np.max(np.abs(eom.C)) * speed + np.max(np.abs(eom.D)))
    terms, numbers = [], []
    for term in inertia_terms(kin, k):
        i = term.number
        terms.append(f"m{i} |vG{i}/ω|²" if term.kind == "mass" else f"IG{i} (ω{i}/ω)²")
        numbers.append(f"{fmt(term.value)} · {fmt(term.coefficient)}")
    out = [
        "Equation of motion of the crank (machine dynamics): the velocities are the velocity "
        "coefficients (velocities per unit crank speed, the kinematics above divided by ω) "
        "times ω, so the kinetic energy is J(φ) ω²/2 with the reduced inertia "
        f"J(φ) = {' + '.join(terms)} = {' + '.join(numbers)} = {fmt(j)} kg·m² at "
        f"φ = {fmt(angle)}°, and its slope dJ/dφ = 2B = {fmt(2 * b)} kg·m² per radian.",
        "(J(φ) + I_f) α = M_m(ω) − B(φ) ω² − C(φ) ω − D(φ), with the flywheel "
        f"I_f = {fmt(fly)} kg·m², the viscous loads C = {fmt(c, scale=scale / speed)} N·m·s "
        f"and the other loads and weights D = {fmt(d, scale=scale)} N·m (their generalized "
        "force, the power they take per unit crank speed, is −(C ω + D))"
        + ("; with friction in the joints, each joint's friction (found with α at each "
           "state, by the friction law) adds its own generalized force, and α below is the "
           "simulation's." if spec.friction else "."),
    ]
    if cycle is not None:
        hit = np.flatnonzero(np.abs(cycle.angles - angle) < 1e-9)
        if len(hit):
            w = float(cycle.omega[hit[0]])
            # the torque the crank receives (a geared motor's through its gearing; with
            # mean_rpm the constant driving torque)
            m = float(motor_torque(eom.motor, np.array([w]))[0])
            q = -(c * w + d)
            alpha = float(cycle.alpha[hit[0]])       # the simulation's, from these terms
            out.append(
                f"In the steady turn the crank passes φ = {fmt(angle)}° at ω = {fmt(w)} rad/s "
                f"({fmt(rad_s_to_rpm(w))} rpm): the motor gives M_m = {fmt(m)} N·m, the loads' "
                f"generalized force is −(C ω + D) = {fmt(q, scale=scale)} N·m, "
                f"B ω² = {fmt(b * w * w)} N·m, so "
                + (f"with the joints' friction α = {fmt(alpha)} rad/s². The " if spec.friction
                   else f"α = ({fmt(m)}{_term(-b * w * w)}{_term(q, scale)}) / ({fmt(j)} + "
                        f"{fmt(fly)}) = {fmt(alpha)} rad/s². The ")
                + "report's steady-turn forces are found with this ω and α; the equations "
                "below are the sweep's, at the driver's constant speed.")
    return out


def _term(x: float, scale: float | None = None) -> str:
    """`` + 1.5`` or `` − 1.5``: a term of a sum after its first."""
    text = fmt(abs(x), scale=scale)
    return f" − {text}" if x < 0 and text != "0" else f" + {text}"


__all__ = ["equation_of_motion_text"]
