"""A problem's statement written from its data (when the spec gives no ``sheet.statement``),
and the numbers of a sheet in engineering notation.

The statement names the mechanism's links and joints, says how it is driven and defines every
coordinate the sheet speaks of (a stroke s: the point it follows, its origin and its
direction), so that a student needs nothing but the sheet. The spec's ``description`` is
written for engineers (keys, files, the report) and is never part of it."""
from __future__ import annotations

import math

from ...spec import GROUND
from ..spec_items import driver_item, link_label
from .expr import fmt

_SUPER = str.maketrans("0123456789-+", "⁰¹²³⁴⁵⁶⁷⁸⁹⁻⁺")
#: SI prefixes for engineering notation (exponent -> prefix)
_PREFIX = {-9: "n", -6: "µ", -3: "m", 0: "", 3: "k", 6: "M", 9: "G", 12: "T"}


def sci(x: float, digits: int | None = None) -> str:
    """``x`` as the sheets print it, a power of ten written as a textbook writes it:
    ``4.5·10⁻⁸`` rather than ``4.5e-08``."""
    s = fmt(x) if digits is None else _digits(x, digits)
    if "e" not in s:
        return s
    mant, exp = s.split("e")
    return f"{mant}·10{str(int(exp)).translate(_SUPER)}"


def _digits(x: float, digits: int) -> str:
    from ...units import fmt as number
    return number(x, digits)


def eng(x: float, unit: str) -> str:
    """``x`` [``unit``, SI] with an SI prefix making it 1 to 1000: ``210 GPa`` for 2.1e11 Pa,
    ``490 MPa``; a unit with a power (m², m⁴) is not prefixed but written with a power of ten
    (:func:`sci`)."""
    x = float(x)
    if x == 0 or not math.isfinite(x) or any(c in unit for c in "²³⁴^/·*"):
        return f"{sci(x)} {unit}"
    exp = 3 * math.floor(math.log10(abs(x)) / 3)
    exp = min(max(exp, -9), 12)
    return f"{sci(x / 10 ** exp)} {_PREFIX[exp]}{unit}"


def driver_statement(spec) -> str:
    """How the mechanism is driven, with the driven coordinate defined
    (:func:`~mechreport.report.spec_items.driver_item`)."""
    d = driver_item(spec)
    joint = spec.joint(spec.driver.joint)
    moving = d.label
    if d.kind == "R":
        if spec.driver.crank:
            coord = (f"The crank angle φ is the angle of {moving}'s x-axis (through its points "
                     "as tabulated) from the global x-axis, counter-clockwise.")
        else:
            a, b = joint.links
            coord = (f"The angle φ is the angle of {link_label(spec, b)}'s x-axis relative to "
                     f"{link_label(spec, a)}'s, counter-clockwise.")
        if d.holds:
            how = (f"The mechanism is at rest: a torque M at joint {d.joint} holds "
                   f"{moving} in each position given below.")
        elif d.at_rest:
            how = (f"The mechanism starts from rest: joint {d.joint} drives {moving} "
                   f"with an angular acceleration of {fmt(d.alpha)} rad/s² and no speed yet.")
        else:
            sense = "counter-clockwise" if d.omega > 0 else "clockwise"
            how = (f"A torque M at joint {d.joint} drives {moving} at {fmt(abs(d.rpm))} "
                   f"rpm ({fmt(abs(d.omega))} rad/s) {sense}"
                   + (", constant." if d.alpha == 0 else
                      f", accelerating at {fmt(d.alpha)} rad/s²."))
        return f"{how} {coord}"
    guide, slider = joint.links
    unit = d.length_unit
    through = joint.line.through
    origin = (f"point {joint.line.through_name}" if joint.line.through_name else
              f"the point ({fmt(through[0])}, {fmt(through[1])}) m")
    coord = (f"The stroke s is the displacement of point {joint.point} of "
             f"{link_label(spec, slider)} along the line of joint {joint.name}, measured from "
             f"{origin} of {link_label(spec, guide)}'s frame and "
             f"positive along ({fmt(joint.line.direction[0])}, "
             f"{fmt(joint.line.direction[1])}) in that frame; it is given in {unit}.")
    if d.holds:
        how = (f"The actuator {joint.name} is at rest: its force F_d holds the mechanism in "
               "each position given below.")
    else:
        how = (f"The actuator {joint.name}, between {link_label(spec, guide)} and "
               f"{link_label(spec, slider)}, "
               f"extends at {fmt(d.omega)} m/s" + ("." if d.alpha == 0 else
                                                   f", accelerating at {fmt(d.alpha)} m/s²."))
    return f"{how} {coord}"


def statement(spec, positions: str) -> list[str]:
    """The paragraphs of a statement written from the data; ``positions`` the sheet's
    reference values as text (``φ = 30°, φ = 120°``)."""
    moving = [l for l in spec.links if l.name != GROUND]
    kinds = {"R": "pins", "T": "sliders"}
    used = sorted({j.type for j in spec.joints}, key="RT".index)
    joined = " and ".join(kinds[t] for t in used)
    parts = [f"The planar mechanism in the figure has {len(moving)} moving link"
             f"{'s' if len(moving) != 1 else ''} (" + ", ".join(
                 f"{l.number} {l.name}" for l in moving) + f"), joined to each other and to "
             f"the frame (link 0) by {joined} as tabulated below. " + driver_statement(spec)]
    weight = ("The links' weights act (gravity as given in the data)."
              if any(l.mass > 0 for l in spec.links) else "The links have no mass.")
    loads = " The loads listed below act on it." if spec.loads else ""
    parts.append(f"{weight}{loads} Analyse the mechanism at {positions}.")
    return parts
