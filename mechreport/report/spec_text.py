"""The first page's description of the spec: the methods used, the links, joints and
assembly branches as table rows, the driver and the loads in words (display units)."""
from __future__ import annotations

import math
from dataclasses import dataclass

from ..forces import METHODS
from ..spec import GROUND
from ..units import DASH, Display, deg, fmt
from .spec_items import JOINT_KINDS, driver_item, load_items


@dataclass(frozen=True)
class MethodRow:
    """A force method as the report names it: ``name`` (newton_euler ...), ``title``,
    ``cite`` where the textbook has it (``§4.1, 4.6.1, 4.7.1``) or what it is."""

    name: str
    title: str
    cite: str


def method_row(name: str) -> MethodRow:
    m = METHODS[name]
    section = m.SECTION
    cite = section[1:-1] if section.startswith("(") else f"§{section}"
    return MethodRow(name, m.TITLE, cite)


def _xy(d: Display, p) -> str:
    return f"({d.num(p[0], 'length')}, {d.num(p[1], 'length')})"


def link_rows(spec, d: Display) -> list[list[str]]:
    rows = [["0", GROUND, DASH, DASH, DASH, "frame: " + ", ".join(
        f"{n} {_xy(d, p)}" for n, p in spec.ground.items())]]
    for ln in spec.links:
        s = ln.shape
        shape = (f"{s.kind} {d.num(s.length, 'length')} × {d.num(s.height, 'length')} × "
                 f"{d.num(s.depth, 'length')}" if s else
                 "massless" if ln.mass == 0 else "no shape")
        pts = ", ".join(f"{n} {_xy(d, p)}" for n, p in ln.points.items())
        rows.append([str(ln.number), ln.name, d.num(ln.mass, "mass"),
                     d.num(ln.inertia, "inertia"), DASH if ln.mass == 0 else _xy(d, ln.com),
                     f"{shape}; points {pts}"])
    return rows


def joint_rows(spec, symbols, d: Display) -> list[list[str]]:
    rows = []
    for j in spec.joints:
        a, b = j.links
        links = f"{a} ({spec.number(a)}) → {b} ({spec.number(b)})"
        if j.type == "T":
            u = j.line.direction
            through = j.line.through_name or _xy(d, j.line.through)
            where = (f"slider point {j.point} on the line through {through}, direction "
                     f"{fmt(math.degrees(math.atan2(u[1], u[0])))} deg in {a}'s frame")
        elif spec.pin(j.point) is not None:
            where = (f"pin {j.point} joining {', '.join(spec.pin(j.point).links)}: its force "
                     f"on {b}")
        else:
            where = f"pin at {j.point}"
        rows.append([j.name, JOINT_KINDS[j.type], links,
                     symbols[j.name], where])
    return rows


def branch_rows(kin) -> list[list[str]]:
    """(dyad, type, how its assembly branch was chosen) per dyad, in solving order."""
    return [[b.dyad, b.kind, _branch_text(b.rule)] for b in kin.branches]


def _branch_text(rule: str) -> str:
    if rule == "unique":
        return "one solution only: no choice"
    if rule.startswith("hint"):
        return f"chosen by the assembly hint ({rule.split(':', 1)[1].strip()})"
    return rule


def load_texts(spec, d: Display) -> list[str]:
    """Each load in words, in display units (:func:`~mechreport.report.spec_items.load_items`)."""
    out = []
    for item in load_items(spec):
        ld = item.load
        kind = "force" if ld.kind == "force" else "moment"
        unit = d.unit(kind)
        if ld.value is not None:
            val = (f"({d.num(ld.value[0], kind)}, {d.num(ld.value[1], kind)}) {unit}"
                   if ld.kind == "force" else f"{d.num(ld.value, kind)} {unit}")
        elif ld.pressure is not None:
            val = _pressure_text(ld, d)
        elif ld.profile is not None:
            prof = ", ".join(f"{deg(a)}°: {d.num(v, kind)}" for a, v in ld.profile)
            u = (f" along ({fmt(ld.direction[0])}, {fmt(ld.direction[1])})"
                 if ld.direction else "")
            shift = f", shifted by {deg(ld.shift)}°" if ld.shift else ""
            val = f"profile [{prof}] {unit}{u}{shift}"
        else:
            val = _element_text(ld, d)
        at = f" at {item.point}" if item.point else ""
        opp = f", opposing its {ld.oppose}" if ld.oppose else ""
        name = f"{item.label}: " if item.label else ""
        out.append(f"{name}{item.what} on {item.link}{at}: {val}{opp}")
    return out


def _pressure_text(ld, d: Display) -> str:
    """A pressure load as written: its profile in its unit, the ambient, the bore or area,
    the direction and the shift."""
    pr = ld.pressure
    prof = ", ".join(f"{deg(a)}°: {fmt(p)}" for a, p in pr.profile)
    size = (f"bore {d.q(pr.bore, 'length')}" if pr.bore is not None
            else f"area {fmt(pr.area)} m²")
    shift = f", shifted by {deg(ld.shift)}°" if ld.shift else ""
    return (f"profile [{prof}] {pr.unit} less the ambient {fmt(pr.ambient)} {pr.unit}, on "
            f"{size}, along ({fmt(ld.direction[0])}, {fmt(ld.direction[1])}){shift}; its "
            "reaction on the frame (the cylinder head)")


def _element_text(ld, d: Display) -> str:
    """A spring, damper or torsion spring: its ends and constants (SI per unit of the
    constant: N/m, N·s/m, N·m/rad)."""
    parts = []
    ends = getattr(ld, "between", None)
    if ends:
        parts.append("between " + " and ".join(f"{p} of {l}" for l, p in ends))
    if getattr(ld, "joint", None):
        parts.append(f"at joint {ld.joint}")
    k = getattr(ld, "stiffness", None)
    if k is not None:
        parts.append(f"k = {fmt(k)} {'N·m/rad' if ld.kind == 'torsion_spring' else 'N/m'}")
    if getattr(ld, "free_length", None) is not None:
        parts.append(f"free length {d.q(ld.free_length, 'length')}")
    if getattr(ld, "free_angle", None) is not None:
        parts.append(f"free angle {fmt(ld.free_angle)}°")
    if getattr(ld, "damping", None) is not None:
        parts.append(f"c = {fmt(ld.damping)} N·s/m")
    return ", ".join(parts) or DASH


def driver_text(spec) -> str:
    """How the driver moves, in one phrase (:func:`~mechreport.report.spec_items.driver_item`)."""
    d = driver_item(spec)
    if d.at_rest:
        what = "stroke" if d.kind == "T" else "angle"
        if d.holds:
            return (f"joint {d.joint} holds {d.link} at rest at each {what} (a static "
                    "analysis: the holding effort and the reactions)")
        return (f"joint {d.joint} starts {d.link} from rest at each {what}, "
                f"{'accel' if d.kind == 'T' else 'α'} = {fmt(d.alpha)} {d.accel_unit}")
    if d.kind != "R":
        return f"joint {d.joint} drives {d.link} along its line at {fmt(d.omega)} {d.rate_unit}"
    return (f"joint {d.joint} turns {d.link} at ω = {fmt(d.omega)} rad/s ({fmt(d.rpm)} rpm), "
            f"α = {fmt(d.alpha)} rad/s²")