"""How a solution sheet derives a gas force at an angle from the printed indicator diagram:
the pressure read off the profile (phased by ``shift``), less the ambient, times the piston's
area, along the load's direction; the numbers a student reproduces from the problem's data."""
from __future__ import annotations

from ...spec import profile_at
from .expr import fmt
from .statement import sci


def pressure_rule(load, angle: float, cycle: float) -> str:
    """The working of pressure ``load``'s force at crank ``angle`` [deg] (``cycle`` [deg]
    the loads' period): p from the diagram, (p − p_a) A, its direction; SI area [m²]."""
    pr = load.pressure
    p = float(profile_at(pr.profile, [angle], cycle, load.shift)[0])
    read = (angle - load.shift) % cycle
    sign = "−" if load.shift > 0 else "+"
    at = (f"φ {sign} {fmt(abs(load.shift))}° = {fmt(read)}°" if load.shift
          else f"{fmt(read)}°")
    area = (f"A = π d²/4 = {sci(pr.area)} m² (d = {sci(pr.bore)} m)" if pr.bore is not None
            else f"A = {sci(pr.area)} m²")
    force = pr.pressure_pa(p) * pr.area
    ux, uy = load.direction
    return (f"p = {fmt(p)} {pr.unit} (the diagram at {at}), p_a = {fmt(pr.ambient)} {pr.unit}, "
            f"{area}: (p − p_a) A = {fmt(force)} N along ({fmt(ux)}, {fmt(uy)})")


__all__ = ["pressure_rule"]
