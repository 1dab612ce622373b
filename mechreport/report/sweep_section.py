"""The sweep's results: the plot data over the analysed angles (:class:`SweepData`), the
effort's statistics, the bearing table, the methods' agreement and the power balance, the
left-out angles, and the sweep figures with their captions."""
from __future__ import annotations

import re
from dataclasses import dataclass, field

import numpy as np

from .. import post as q
from ..forces import METHODS
from ..kinematics import TRUST_RTOL
from ..post.bearings import bearing_carrier
from ..post.sweep import PowerCheck, SweepSummary
from ..units import DASH, Display, deg, fmt, kind_of
from .ref_angles import RefAngle
from .section import Figure, display_of, effort_of, joint_colors, reaction_symbols


@dataclass
class JointSeries:
    """Reaction of one joint over the sweep (reference method): ``fx``, ``fy``, ``f`` (n,)
    [N]; ``moment`` (n,) [N m] for T joints."""

    name: str
    symbol: str
    type: str
    color: str
    fx: np.ndarray
    fy: np.ndarray
    f: np.ndarray
    moment: np.ndarray | None = None


@dataclass
class PolarSeries:
    """A pin's reaction traced in its carrier link's frame: ``x``, ``y`` (n,) [N]."""

    name: str
    symbol: str
    color: str
    carrier: str
    x: np.ndarray
    y: np.ndarray
    equivalent: float | None = None    # cube-mean load over a turn [N], drawn as a circle


@dataclass
class SweepData:
    """Plot data over the analysed angles ``angles`` (n,) [deg]. ``near`` (n,) marks angles
    within ``near_deg`` of a left-out angle (near-singular: shown, but not used to scale a
    plot)."""

    angles: np.ndarray
    ref_angles: list[float]
    flagged: list[float]
    method_title: str
    torque: np.ndarray                       # (n,) [N m], reference method
    torque_check: np.ndarray | None          # (n,) [N m], power balance, if solved
    stats: q.TorqueStats | None
    joints: list[JointSeries]
    polar: list[PolarSeries]
    shaking: q.FrameLoad
    near: np.ndarray = field(default_factory=lambda: np.zeros(0, bool))
    near_deg: float = 0.0
    effort: str = "moment"              # the driver's effort: a torque, or a force (T driver)
    effort_label: str = "driver torque M"
    xlabel: str = "crank angle φ [deg]"
    xrange: tuple | None = None         # (start, stop) of a sweep that is not one whole turn
    #: the parts of the shaking load (force, moment) that are 0 at every angle (round-off
    #: of their kind): the shaking figure leaves them out and its caption says so
    shaking_zero: tuple[str, ...] = ()

    @property
    def at_unit(self) -> str:
        """What follows a sweep value in text: ``°``, or `` mm`` for a stroke."""
        return "°" if self.xlabel.endswith("[deg]") else " " + self.xlabel.rsplit("[", 1)[1][:-1]


def sweep_data(analysis) -> tuple[SweepData, Display]:
    """The report's plot data of ``analysis`` and its display units (for the plot
    functions, :mod:`mechreport.report.plots`)."""
    spec, d = analysis.spec, display_of(analysis)
    return sweep_series(analysis, analysis.sweep_summary(), reaction_symbols(spec),
                        joint_colors(spec), d), d


def sweep_series(analysis, summary: SweepSummary, symbols, colors, d: Display) -> SweepData:
    """The plot data of the sweep: the reference method's arrays and the summary's traces."""
    res = analysis.forces[summary.method]
    spec = analysis.spec
    joints = [JointSeries(name, sym, r.type, colors[name], r.fx, r.fy, r.f, r.moment)
              for name, sym in symbols.items() if (r := res.reactions.get(name)) is not None]
    polar = []
    for j in spec.joints:
        xy = summary.traces.get(j.name)
        if xy is None:
            continue
        eq = None
        if analysis.review is not None and j.name in analysis.review.bearings:
            eq = analysis.review.bearings[j.name].f_equivalent
        polar.append(PolarSeries(j.name, symbols[j.name], colors[j.name],
                                 bearing_carrier(j), xy[:, 0], xy[:, 1], eq))
    check = analysis.forces.get("power")
    flagged = [f.angle for f in analysis.flags]
    kind, label, coord, unit = effort_of(spec)
    whole = spec.sweep.whole_turn and unit == "°"
    return SweepData(analysis.angles, [float(a) for a in spec.at], flagged,
                     METHODS[summary.method].TITLE, res.driver_torque,
                     None if check is None or check is res else check.driver_torque,
                     summary.torque, joints, polar, summary.frame, summary.near,
                     summary.near_deg, kind, label,
                     f"{coord} [{'deg' if unit == '°' else unit.strip()}]",
                     None if whole else (float(spec.sweep.start), float(spec.sweep.stop)),
                     tuple(k for k, v in (("force", summary.frame.f), ("moment", summary.frame.m))
                           if d.zero(v, k)))


def peak_text(p: q.Peak | None, kind: str, d: Display, unit: str = "°") -> str:
    """``155.3 N at 45°``; a peak that prints as 0 is 0 everywhere: ``0 N·m at every
    angle`` (``position`` for a stroke)."""
    if p is None:
        return DASH
    if d.zero(p.value, kind):
        return f"{d.q(0.0, kind)} at every {'angle' if unit == '°' else 'position'}"
    return f"{d.q(p.value, kind)} at {deg(p.angle)}{unit}"


def torque_texts(st: q.TorqueStats | None, d: Display, kind: str = "moment",
                  unit: str = "°") -> dict[str, str]:
    if st is None:
        return {k: DASH for k in ("mean", "rms", "peak", "low", "high", "power")}

    def at(p):
        return peak_text(p, kind, d, unit)
    return {"mean": d.q(st.mean, kind), "rms": d.q(st.rms, kind), "peak": at(st.peak),
            "low": at(st.low), "high": at(st.high), "power": d.q(st.power, "power")}


def bearing_rows(summary: SweepSummary, sw: SweepData, d: Display) -> list[list[str]]:
    """Per joint: the peak over the analysed angles and its angle (the value every output
    gives as the joint's peak), the RMS, and the peak away from left-out angles where that
    is another (the peak lies within ``near_deg`` of one)."""
    rows = []
    for js in sw.joints:
        jl = summary.joints[js.name]
        pk, fp = jl.peak, jl.peak_far
        kind = "pin" if js.type == "R" else "slider"
        rows.append([js.name, js.symbol, kind, d.num(pk.value, "force") if pk else DASH,
                     deg(pk.angle) if pk else DASH,
                     d.num(jl.rms, "force") if jl.rms is not None else DASH,
                     far_text(pk, fp, d, sw.at_unit)])
    return rows


def far_text(pk, fp, d: Display, unit: str) -> str:
    """The peak away from left-out angles, ``973.6 at 84°``, where it is not the peak
    itself; "—" otherwise."""
    if pk is None or fp is None or pk.angle == fp.angle:
        return DASH
    return f"{d.num(fp.value, 'force')} at {deg(fp.angle)}{unit}"


def _kind(quantity: str, spec) -> str:
    return kind_of(spec.unit_of(quantity) or "N")


def _diag(x: float, kind: str, d: Display) -> str:
    """A diagnostic (a disagreement, a residual): 2 digits, in display units, never zeroed
    as round-off (round-off is what it measures)."""
    return f"{fmt(d.value(x, kind), 2)} {d.unit(kind)}"


def agreement_rows(analysis, d: Display) -> list[list[str]]:
    spec = analysis.spec
    return [[a.quantity, fmt(a.relative, 2), _diag(a.absolute, _kind(a.quantity, spec), d),
             f"{METHODS[a.methods[0]].TITLE} vs {METHODS[a.methods[1]].TITLE}", deg(a.angle),
             str(a.n_methods)] for a in analysis.agreement]


def power_check_text(pc: PowerCheck | None, method_title: str, d: Display,
                     at_rest: bool = False) -> str:
    """The power balance's check against the reference method, in one sentence."""
    if pc is None:
        return "The power balance was not solved."
    balance = ("Virtual work (the driver at rest: M = −Σ of every other action times its "
               "velocity coefficient)" if at_rest else
               "Power balance (M ω = Σ of the power of every other action)")
    text = (f"{balance} against "
            f"{method_title}: largest torque difference {_diag(pc.max_abs, 'moment', d)} "
            f"({fmt(pc.relative, 2)} of the peak torque) at {deg(pc.angle)}°.")
    return text


def left_out_text(analysis, summary: SweepSummary, sw: SweepData, d: Display) -> str:
    """One paragraph for the first page: which angles were left out and why, and which
    values lie near them (shown, but not used to scale the plots)."""
    if not analysis.flags:
        return "none: every angle of the sweep was solved and is trustworthy."
    rows = flag_rows(analysis)
    shown = "; ".join(f"{a}°: {why}" for a, why in rows[:3])
    more = f"; and {len(rows) - 3} more (see Left-out angles)" if len(rows) > 3 else ""
    text = (f"{len(analysis.flags)} angle(s) left out of every table, plot and cycle "
            f"quantity (values there cannot be trusted to {TRUST_RTOL:g}): {shown}{more}.")
    jumps = []
    for js in sw.joints:
        pk, fp = summary.joints[js.name].peak, summary.joints[js.name].peak_far
        if pk is not None and fp is not None and abs(pk.value) > 1.25 * abs(fp.value):
            jumps.append((abs(pk.value), js.name, pk))
    if jumps:
        _, name, pk = max(jumps, key=lambda t: t[0])
        text += (f" Within {deg(sw.near_deg)}° of them the reactions rise steeply (up to "
                 f"{d.q(pk.value, 'force')} at joint {name}, {deg(pk.angle)}°): such values "
                 "are listed, but the plots are scaled to the rest of the turn and mark them.")
    return text


def flag_rows(analysis) -> list[list[str]]:
    """Left-out angles as rows (angles, reason): runs of neighbouring angles left out for the
    same reason share a row ("54 to 306 (253 angles)"); near-singular runs share one however
    their condition numbers differ."""
    kept = np.asarray(analysis.angles, float)
    runs: list[list] = []      # [key, first, last, count, reason]
    for f in analysis.flags:
        key = (f.kind, re.sub(r" \(condition [^)]*\)", "", f.reason))
        if runs and runs[-1][0] == key and not np.any((kept > runs[-1][2]) & (kept < f.angle)):
            runs[-1][2], runs[-1][3] = f.angle, runs[-1][3] + 1
        else:
            runs.append([key, f.angle, f.angle, 1, key[1]])
    return [[deg(a) if n == 1 else f"{deg(a)} to {deg(b)} ({n} angles)", why]
            for _, a, b, n, why in runs]


def _shaking_caption(sw: SweepData, d: Display) -> str:
    """The shaking figure's caption: what it draws, and which part of the load on the frame
    is 0 at every angle and so is not drawn."""
    force = "Shaking force (resultant of the reactions on the frame)"
    moment = ("shaking moment about the driver pivot, including the driver's reaction "
              "torque")
    zero, every = sw.shaking_zero, "angle" if sw.at_unit == "°" else "position"
    if not zero:
        return f"{force} and {moment}."
    if zero == ("moment",):
        return f"{force}; the {moment}, is {d.q(0.0, 'moment')} at every {every} (not drawn)."
    if zero == ("force",):
        return (f"{moment[0].upper()}{moment[1:]}; the shaking force is "
                f"{d.q(0.0, 'force')} at every {every} (not drawn).")
    return ""


def sweep_figures(sw: SweepData, refs: list[RefAngle], ref: str, d: Display) -> dict[str, Figure]:
    title = METHODS[ref].TITLE
    figs: dict[str, Figure] = {}
    for r in refs:
        if r.drawing is not None:
            figs[r.drawing.stem] = r.drawing
    if len(sw.angles) == 0:
        return figs
    near = (f" Hatched: within {deg(sw.near_deg)}° of a left-out angle (near-singular; not "
            "used for the scale, values beyond it are marked at the edge)."
            if np.any(sw.near) else "")
    effort = "Driver torque" if sw.effort == "moment" else "Driver force"
    unit = sw.at_unit
    at = ", ".join(f"{deg(a)}{unit}" for a in sw.ref_angles)
    refs_text = (f", dotted lines at the reference {'angles' if unit == '°' else 'positions'} "
                 f"({at})" if sw.ref_angles else "")
    gaps = ", the curves broken at the left-out angles" if sw.flagged else ""
    figs |= {"torque": Figure("torque", f"{effort} over the sweep ({title}); mean and "
                              f"peak marked{refs_text}{gaps}.{near}", "torque"),
             "reactions": Figure("reactions", f"Magnitude of each joint's reaction over the "
                                 f"sweep ({title}; components are in results.csv){gaps}."
                                 f"{near}", "reactions"),
             "shaking": Figure("shaking", _shaking_caption(sw, d) + near, "shaking")}
    if not sw.joints:
        del figs["reactions"]
    if len(sw.shaking_zero) == 2:              # nothing to draw: the caption's words stand alone
        del figs["shaking"]
    if sw.polar:
        figs["polar"] = Figure("polar", "Polar load diagrams of the pins: the tip of the "
                               "reaction (first link on second) over a turn, in the frame of "
                               "the link named above each plot (ground: global frame); "
                               "dots mark the reference angles, the dashed circle the "
                               "equivalent (cube-mean) load.", "polar")
    return figs
