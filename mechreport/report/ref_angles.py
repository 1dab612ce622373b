"""The reference angles' sections: per angle its kinematics, the reactions by every
method, the vectors and the drawing (a :class:`~mechreport.report.scene.Scene`); the DXF's
layers of the same drawings."""
from __future__ import annotations

from dataclasses import dataclass, field

from ..forces import METHODS
from ..units import DASH, Display, deg
from .scene import Scene, build_scene
from .document import heading_id
from .section import Figure, effort_of
from .text import kinematics_rows


@dataclass
class RefAngle:
    """Tables at one reference crank angle; ``flag`` says why it was left out (then the
    tables are empty)."""

    angle: str
    flag: str | None
    points: list[list[str]] = field(default_factory=list)
    links: list[list[str]] = field(default_factory=list)
    reactions: list[list[str]] = field(default_factory=list)
    vectors: list[str] = field(default_factory=list)
    drawing: Figure | None = None
    title: str = ""          # "Crank angle 45°", "Stroke 300 mm"
    anchor: str = ""         # its Markdown heading anchor
    phrase: str = ""         # the title inside a sentence: "crank angle 45°"


def _reaction_rows(spec, forces, symbols, k: int, d: Display) -> list[list[str]]:
    rows = []
    F, M, L = d.unit("force"), d.unit("moment"), d.unit("length")
    for name, sym in symbols.items():
        comps = [("fx", f"{sym} x [{F}]", "force"), ("fy", f"{sym} y [{F}]", "force"),
                 ("f", f"|{sym}| [{F}]", "force")]
        if any(j.name == name and j.type == "T" for j in spec.joints):
            comps += [("moment", f"M{sym[1:]} [{M}]", "moment"),
                      ("px", f"at x [{L}]", "length"), ("py", f"at y [{L}]", "length")]
        for attr, label, kind in comps:
            vals = []
            for res in forces.values():
                r = res.reactions.get(name)
                v = r.component(attr) if r is not None else None
                vals.append(d.num(v[k], kind) if v is not None else DASH)
            rows.append([name, label, *vals])
    kind = effort_of(spec)[0]
    rows.append(["driver", f"{'F' if kind == 'force' else 'M'} [{d.unit(kind)}]",
                 *(d.num(r.driver_torque[k], kind) for r in forces.values())])
    return rows


def _vectors(spec, res, symbols, k: int, d: Display) -> list[str]:
    out = []
    F, M = d.unit("force"), d.unit("moment")
    for name, sym in symbols.items():
        r = res.reactions.get(name)
        if r is None:
            continue
        fy = d.num(r.fy[k], "force")
        sign, fy = ("-", fy[1:]) if fy.startswith("-") else ("+", fy)
        text = (f"{name}: {sym} = {d.num(r.fx[k], 'force')} i {sign} "
                f"{fy} j {F}, |{sym}| = {d.num(r.f[k], 'force')} {F}")
        if r.moment is not None:
            text += f", M{sym[1:]} = {d.num(r.moment[k], 'moment')} {M}"
        out.append(text)
    kind, label, _, _ = effort_of(spec)
    out.append(f"{label} = {d.num(res.driver_torque[k], kind)} {d.unit(kind)}")
    return out


def reference_angles(analysis, ref: str, symbols, colors, d: Display
                     ) -> tuple[list[RefAngle], list[Scene]]:
    kin, spec = analysis.kinematics, analysis.spec
    refs, scenes = [], []
    _, _, coord, unit = effort_of(spec)
    for angle in spec.at:
        title = f"{coord[0].upper()}{coord[1:]} {deg(angle)}{unit}"
        anchor = heading_id(title)
        k = kin.index_of(angle)
        if k is None:
            why = next((f.reason for f in analysis.flags if abs(f.angle - angle) < 1e-9),
                       "not analysed")
            refs.append(RefAngle(deg(angle), why, title=title, anchor=anchor,
                                 phrase=f"{coord} {deg(angle)}{unit}"))
            continue
        pts, links = kinematics_rows(kin, k, d)
        stem = f"drawing_{deg(angle).replace('.', 'p').replace('-', 'm')}"
        fig = Figure(stem, f"The mechanism at {coord} {deg(angle)}{unit}: joint reactions "
                     f"(first link on second, {METHODS[ref].TITLE}, coloured per joint), "
                     "applied loads (black) and the driver's "
                     + ("torque M" if spec.driver.kind == "R" else "push Fd along its line")
                     + " (wine red); arrow lengths to one scale, values in the legend.",
                     "drawing")
        refs.append(RefAngle(deg(angle), None, pts, links,
                             _reaction_rows(spec, analysis.forces, symbols, k, d),
                             _vectors(spec, analysis.forces[ref], symbols, k, d), fig,
                             title, anchor, f"{coord} {deg(angle)}{unit}"))
        scenes.append(build_scene(analysis, analysis.forces[ref], k, colors, symbols))
    return refs, scenes


@dataclass
class DxfData:
    """mechanism.dxf: one ``(layer, scene)`` per solved reference angle, drawn in the spec's
    length ``unit`` (``scale`` [m] per unit)."""

    unit: str
    scale: float
    layers: list[tuple[str, Scene]]


def dxf_data(spec, refs: list[RefAngle], scenes: list[Scene]) -> DxfData:
    """The DXF's layers: ``crank_angle_45`` (``stroke_300`` for a T driver) per solved
    reference angle, the angle written exactly (``crank_angle_45.00001``, not rounded as the
    report shows it), so that distinct angles never share a layer (the loader refuses an
    angle given twice)."""
    from ..units import LENGTH_UNITS
    unit = spec.units.get("length", "m")
    coord = effort_of(spec)[2].replace(" ", "_")
    solved = [a for a, r in zip(spec.at, refs) if r.drawing is not None]
    return DxfData(unit, LENGTH_UNITS[unit],
                   [(f"{coord}_{_exact(a)}", sc) for a, sc in zip(solved, scenes)])


def _exact(value: float) -> str:
    """``value`` in the fewest digits that read back as it: ``45``, ``45.00001``, ``1e-05``."""
    text = repr(float(value))
    return text[:-2] if text.endswith(".0") else text
