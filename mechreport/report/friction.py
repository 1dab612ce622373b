"""The Friction section: per joint its friction, its loss per cycle and share, the
efficiency, where friction self-locks, the effort with and without friction (plot and
figure); its record in summary.json is written by :mod:`mechreport.pipeline.records`."""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..kinematics.result import angle_ranges
from ..post.friction import efficiency_undefined
from ..post.records import friction_symbol, largest
from ..units import DASH, Display, deg, fmt
from .design import DesignSummary, design_summary
from .section import Figure
from .spec_items import JOINT_KINDS
from .sweep_section import SweepData, sweep_data


@dataclass
class FrictionPlot:
    """Plot data of the driver's effort with and without friction: ``angles`` (N,) [deg]
    (the cycle grid, or the analysed angles of a sweep that has no cycle), ``torque`` (N,)
    the effort with friction and ``frictionless`` (N,) without it [N m, or N for a T
    driver's force]; their ``means`` (with, without) over the cycle (None over a sweep);
    ``shaded`` angles [deg] drawn grey (interpolated in the cycle, or left out of the sweep);
    ``sweep`` the sweep's plot data when the angles are the sweep's (its axis, its gaps);
    ``reversed`` the analysed angles [deg] where friction alone reverses the effort's sign."""

    angles: np.ndarray
    torque: np.ndarray
    frictionless: np.ndarray
    effort: str = "moment"
    effort_name: str = "driver torque"
    means: tuple[float, float] | None = None
    shaded: list[float] = field(default_factory=list)
    sweep: SweepData | None = None
    reversed: list[float] = field(default_factory=list)   # friction reverses the effort


@dataclass
class FrictionSection:
    """The report's Friction section (a spec with ``friction:``): ``rows`` one per friction
    joint (joint, type, friction symbol, mu, journal radius or slider length, energy lost per
    cycle [J], its share of the total, largest magnitude over the sweep, its angle) and the
    ``total`` row; ``energy`` (cycle.friction.energy, with its unit) and ``efficiency``
    (cycle.efficiency as a percentage, or why it is undefined) as printed ("—" without cycle
    quantities: ``problem`` says why); ``remarks`` sentences on self-locking and left-out
    angles; ``plot`` the with/without plot's data (None without angles); ``intro`` the law
    of each kind of joint present; ``size_head`` the heading of the radius/length column."""

    rows: list[list[str]]
    total: list[str] | None       # None without cycle quantities
    energy: str
    efficiency: str
    remarks: list[str]
    plot: FrictionPlot | None = None
    problem: str = ""             # why there are no cycle quantities ("" when there are)
    intro: str = ""               # what friction the joints have, and its law
    size_head: str = "r or L"     # the heading of the journal radius / slider length column


def friction_data(analysis) -> tuple[FrictionPlot | None, Display]:
    """The data of the report's friction plot of ``analysis`` (None without friction) and
    its display units (for :func:`mechreport.report.plots.plot_friction`)."""
    sw, d = sweep_data(analysis)
    section = friction_section(analysis, design_summary(analysis, d), sw, d)
    return (None if section is None else section.plot), d


def friction_section(analysis, design: DesignSummary, sw: SweepData, d: Display
                     ) -> FrictionSection | None:
    """The Friction section of ``analysis`` (None without friction in the spec), read from
    its result records: each joint's friction over the sweep (``Kinematics.friction``, the
    values every method was given), its loss per cycle and the efficiency (the review), and
    the effort without friction: the effort minus the breakdown's ``friction`` source."""
    spec, rev, kin = analysis.spec, analysis.review, analysis.kinematics
    if not spec.friction:
        return None
    losses = rev.friction if rev is not None else {}
    total = rev.values.get("cycle.friction.energy") if rev is not None else None
    values = kin.friction or {}
    rows = []
    types = {spec.joint(fr.joint).type for fr in spec.friction}
    named = len(types) > 1              # pins and sliders: each size says what it is
    for fr in spec.friction:
        j = spec.joint(fr.joint)
        kind = "moment" if j.type == "R" else "force"
        size = fr.radius if j.type == "R" else fr.length
        size = (DASH if size is None else ("r = " if j.type == "R" else "L = ") * named
                + d.num(size, "length"))
        lost = losses.get(fr.joint)
        share = (f"{fmt(100 * lost / total, 3)} %" if lost is not None and total else DASH)
        peak = largest(values.get(fr.joint), analysis.angles)
        rows.append([fr.joint, ("pin (R, friction circle)" if j.type == "R" and
                                fr.model == "circle" else JOINT_KINDS[j.type]),
                     friction_symbol(spec, j), fmt(fr.mu), size,
                     DASH if lost is None else fmt(lost),
                     share, DASH if peak is None else d.q(peak[0], kind),
                     DASH if peak is None else deg(peak[1])])
    total_row = (None if total is None else
                 ["total", "", "", "", "", fmt(total), "100 %" if total else DASH, "", ""])
    effort_name = "driver force" if sw.effort == "force" else "driver torque"
    if rev is None:
        energy = efficiency = DASH
    else:
        energy = d.q(total, "energy")
        eff = rev.values.get("cycle.efficiency")
        efficiency = (f"{fmt(100 * eff)} %" if eff is not None else
                      f"undefined: {efficiency_undefined(spec)}")
    L = d.unit("length")
    size_head = (f"r or L [{L}]" if len(types) > 1 else
                 f"journal radius r [{L}]" if types == {"R"} else f"slider length L [{L}]")
    return FrictionSection(rows, total_row, energy, efficiency,
                           _friction_remarks(analysis, effort_name, sw.at_unit),
                           _friction_plot(analysis, design, sw, effort_name),
                           analysis.review_problem if rev is None else "",
                           _friction_intro(spec), size_head)


def _friction_intro(spec) -> str:
    """What friction the joints of ``spec`` have: the law of each kind present."""
    joints = [spec.joint(fr.joint) for fr in spec.friction]
    laws = []
    if any(j.type == "R" for j in joints):
        laws.append("in a pin (R), a couple of magnitude μ r |F| (r the journal radius, F "
                    "the joint's reaction)")
    if any(j.type == "T" and fr.length is None for j, fr in zip(joints, spec.friction)):
        laws.append("in a slider (T), a force along its line of magnitude μ |N| (N the "
                    "normal force)")
    if any(fr.length is not None for fr in spec.friction):
        laws.append("in a slider of length L, a force along its line of magnitude "
                    "μ (|N1| + |N2|), where N1 and N2 are the normal forces at its two ends "
                    "that carry the slider's normal force and couple")
    n = len(joints)
    idle = spec.idle_friction_note()
    return (f"Coulomb friction in {n} joint{'s' if n > 1 else ''}, solved with the forces "
            "(every table and plot of this report includes it): " + "; ".join(laws)
            + (". Each opposes its joint's relative motion." if n > 1 else
               ". It opposes the joint's relative motion.")
            + (f" But {idle}." if idle else ""))


def _friction_remarks(analysis, effort_name: str, unit: str) -> list[str]:
    """Sentences on where friction self-locks: the angles where it alone reverses the
    driver's effort, and those left out because it is undetermined there."""
    out = []
    kin, spec = analysis.kinematics, analysis.spec
    if kin.reversed_by_friction:
        out.append(f"At {angle_ranges(kin.reversed_by_friction, spec.sweep.step)}{unit}, friction "
                   f"alone reverses the sign of the {effort_name}: without friction the loads "
                   "would drive the mechanism there; with it they cannot, and the driver has "
                   "to (self-locking: marked × on the zero line of the plot below).")
    left = [f for f in analysis.flags if f.by_friction]
    if left:
        n = len(left)
        out.append(f"{n} angle{'s are' if n > 1 else ' is'} left out because the friction "
                   "there has no determined value (self-locking, or the relative motion in a "
                   "joint stops): see Left-out angles.")
    return out


def _friction_plot(analysis, design: DesignSummary, sw: SweepData, effort_name: str
                   ) -> FrictionPlot | None:
    """The effort with and without friction (``Kinematics.frictionless``, solved with the
    friction): over the cycle grid when there is a review (sampled as the effort is), else
    over the analysed angles of the sweep."""
    cd, kin = design.data, analysis.kinematics
    flipped = [float(a) for a in kin.reversed_by_friction]
    if kin.frictionless is None:
        return None
    if cd is not None:
        rev = analysis.review
        without = rev.cycle.sample(kin.frictionless, analysis.angles)
        return FrictionPlot(cd.angles, cd.torque, without, "moment", effort_name,
                            (cd.mean, rev.cycle.mean(without)), list(cd.interpolated),
                            None, flipped)
    if not len(sw.angles):
        return None
    return FrictionPlot(sw.angles, sw.torque, kin.frictionless, sw.effort, effort_name,
                        None, [], sw, flipped)


def friction_figures(section: FrictionSection | None, sw: SweepData) -> dict[str, Figure]:
    """The friction plot's figure and caption (none without friction or without angles)."""
    if section is None or section.plot is None:
        return {}
    fp = section.plot
    name = fp.effort_name[0].upper() + fp.effort_name[1:]
    if fp.means is not None:
        text = (f"{name} over one turn with friction in the joints (solid) and without it "
                "(dashed: the same motion and loads, the joints frictionless); the "
                "difference of their means times 2π is the energy lost to friction per "
                "cycle." + (" Grey: left-out angles, filled in by interpolation."
                            if fp.shaded else ""))
    else:
        text = (f"{name} over the sweep with friction in the joints (solid) and without it "
                "(dashed: the same motion and loads, the joints frictionless)"
                + (", the curves broken at the left-out angles." if sw.flagged else "."))
    return {"friction": Figure("friction", text, "friction")}
