"""The report's Strength section (links with a ``section``): every member's safety factors
and where they occur, the N, V, M diagrams of the most loaded member at its worst angle, and
the largest stress of each member over the sweep. Read from the analysis' strength review
(:mod:`mechreport.post.strength`); nothing is computed here but display values."""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..post.strength import link_mass_note
from ..units import DASH, Display, deg, fmt

#: what each column of the table means, for the text under it
SECTION_TEXT = {"rect": "rectangle {width} x {height}", "round": "round, d = {d}",
                "tube": "tube, d = {d}, t = {t}",
                "area": "A = {area}, I = {inertia}, c = {c}"}


@dataclass(frozen=True)
class StrengthPlot:
    """Plot data: the most loaded ``member`` at crank ``angle`` [deg]: positions ``s`` (K,)
    [m] and ``N``, ``V`` [N], ``M`` [N m] (K,); over the analysed ``angles`` (n,) [deg] the
    largest stress along each member ``stress`` {member: (n,)} [Pa]; ``whole_turn``."""

    member: str
    angle: float
    s: np.ndarray
    N: np.ndarray
    V: np.ndarray
    M: np.ndarray
    angles: np.ndarray
    stress: dict[str, np.ndarray]
    whole_turn: bool = True
    xlabel: str = "crank angle φ [deg]"


@dataclass(frozen=True)
class StrengthSection:
    """``intro`` (the model and the rules), ``links`` one line per link with a section
    (its section and material), ``rows`` one per member (see the report document's headings),
    ``worst`` a sentence on the most loaded member, ``notes`` where a link's mass spreading
    differs from its own com and inertia, ``plot``."""

    intro: str
    links: list[str]
    rows: list[list[str]]
    worst: str
    notes: list[str] = field(default_factory=list)
    plot: StrengthPlot | None = None


def _section_text(sec, d: Display) -> str:
    sizes = dict(sec.sizes)
    L = d.unit("length")
    f = d.factor("length")
    shown = {k: (f"{fmt(v * f ** 2)} {L}²" if k == "area" else
                 f"{fmt(v * f ** 4)} {L}⁴" if k == "inertia" else f"{fmt(v * f)} {L}")
             for k, v in sizes.items()}
    return SECTION_TEXT[sec.kind].format(**shown)


def _slenderness_label(spec, m) -> str:
    """``L/r`` for a pinned-pinned column (k = 1 in the plane that governs), else ``kL/r``."""
    b = spec.link(m.link).strength.buckling_of(
        spec.link(m.link).strength.members.index((m.P, m.Q)))
    return "L/r" if (b.k if m.buckling_plane == 1 else b.k_out) == 1 else "kL/r"


def _material_text(mat, d: Display) -> str:
    """A material's E and strengths: E in GPa and the strengths in MPa, or all in the
    report's stress unit when it is another (psi, ksi)."""
    if d.stress == "MPa":
        return (f"E = {fmt(mat.E / 1e9)} GPa, yield {fmt(mat.yield_ / 1e6)} MPa, "
                f"ultimate {fmt(mat.ultimate / 1e6)} MPa, endurance "
                f"{fmt(mat.endurance / 1e6)} MPa")
    return (f"E = {d.q(mat.E, 'stress')}, yield {d.q(mat.yield_, 'stress')}, ultimate "
            f"{d.q(mat.ultimate, 'stress')}, endurance {d.q(mat.endurance, 'stress')}")


def strength_section(analysis, d: Display, axis: str = "deg") -> StrengthSection | None:
    """The Strength section of ``analysis`` (None when no link has a section)."""
    st = analysis.strength
    if st is None:
        return None
    spec = analysis.spec
    links = []
    for link in spec.links:
        if link.strength is None:
            continue
        mat = link.strength.material
        name = f"{mat.name}: " if mat.name else ""
        links.append(f"{link.name}: {_section_text(link.strength.section, d)}; "
                     f"{name}{_material_text(mat, d)}; members "
                     + ", ".join(f"{p}–{q}" for p, q in link.strength.members))
    rows = []
    for m in st.members.values():
        at = f"{deg(m.stress_angle)}, {d.num(m.stress_s, 'length')}"
        buck = (DASH if m.buckling_safety is None else fmt(m.buckling_safety))
        pcr = (f"{d.num(m.critical_load, 'force')} ({m.buckling_rule}, {m.plane_text}, "
               f"{_slenderness_label(spec, m)} = {fmt(m.slenderness, 3)})")
        comp = (f"{d.num(m.compression, 'force')} at {deg(m.compression_angle)}"
                if m.compression_angle is not None else "never in compression")
        rows.append([m.name, d.num(m.stress_max, "stress"), at,
                     DASH if m.static_safety is None else fmt(m.static_safety),
                     DASH if m.fatigue_safety is None else fmt(m.fatigue_safety),
                     f"{d.num(m.sigma_a, 'stress')} / {d.num(m.sigma_m, 'stress')} at "
                     f"{d.num(m.fatigue_s, 'length')}", buck, comp, pcr])
    worst = st.worst()
    # the notes in the report's units (the review's own are SI, for summary.json)
    links_of = {m.link for m in st.members.values() if m.note}
    notes = list(dict.fromkeys(link_mass_note(spec.link(name), d) for name in
                               dict.fromkeys(m.link for m in st.members.values())
                               if name in links_of))
    plot = None
    text = ""
    if worst is not None and worst.diagram is not None:
        k = int(np.flatnonzero(np.isclose(analysis.angles, worst.stress_angle))[0])
        dia = worst.diagram
        plot = StrengthPlot(worst.name, worst.stress_angle, dia.s, dia.N[k], dia.V[k],
                            dia.M[k], np.asarray(analysis.angles, float),
                            {m.name: m.stress.max(axis=1) for m in st.members.values()
                             if m.stress is not None},
                            spec.cycle_problem() is None,
                            "crank angle φ [deg]" if axis == "deg" else
                            f"stroke [{axis}]")
        text = (f"The most loaded member (the smallest static safety) is {worst.name}: "
                f"{d.q(worst.stress_max, 'stress')} at {deg(worst.stress_angle)}"
                f"{'°' if axis == 'deg' else ' ' + axis}, {d.q(worst.stress_s, 'length')} from "
                f"{worst.P}.")
    intro = ("Each link with a section is a straight beam along each of its members; its "
             "mass is spread uniformly along them. Along a member P–Q (s from P), the axial "
             "force N (tension positive), shear V and bending moment M (sagging positive) "
             "come from the joint reactions, loads and driver effort on the link, its "
             "distributed weight and its distributed d'Alembert inertia load, in the "
             "member's own frame. Largest stress σ = |N|/A + |M|c/I. Static safety: "
             "yield / largest σ. Fatigue safety: modified Goodman (σa/Se + σm/Su = 1/n; "
             "Se/σa for a compressive mean) at the section and outer fibre where it is "
             "smallest. Buckling safety: the member as a column in the plane of motion and "
             "out of it (pinned-pinned unless its buckling data say otherwise: effective "
             "length kL), the smaller buckling load (Euler, or Johnson below the transition "
             "slenderness; or Rankine's formula) against its largest compression.")
    return StrengthSection(intro, links, rows, text, notes, plot)


__all__ = ["StrengthPlot", "StrengthSection", "strength_section"]
