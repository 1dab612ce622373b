"""The report result model: every number a report prints, built once from an Analysis.

Markdown and Typst templates, results.csv, summary.json, the plots and the drawings all read a
:class:`ReportModel`; none of them computes mechanics. Printed values are strings already
formatted (undefined values print as "—"); the plot data are float arrays (n,) over the
analysed crank angles [deg]. Units: SI throughout (m, kg, s, N, N m, W).
"""
from __future__ import annotations

import math
import re
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from .text import kinematics_rows
from ..forces import METHODS
from ..spec import GROUND
from .. import post as q
from ..quantities import unit_of
from .scene import Scene, build_scene

DASH = "—"
#: one colour per joint, in spec order, across every figure (matplotlib's tab10)
PALETTE = ["#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2",
           "#7f7f7f", "#bcbd22", "#17becf"]


def num(x, digits: int = 6) -> str:
    """``x`` to ``digits`` significant figures; "—" for None/NaN; "0" below 1e-9."""
    if x is None or not math.isfinite(float(x)):
        return DASH
    x = float(x)
    if abs(x) < 1e-9:
        return "0"
    return f"{x:.{digits}g}"


def deg(x: float) -> str:
    """A crank angle [deg] as printed: ``45``, ``12.5``."""
    return f"{float(x):g}"


def jnum(x) -> float | None:
    """A float for JSON: None where undefined."""
    return None if x is None or not math.isfinite(float(x)) else float(x)


@dataclass
class Figure:
    """A figure file pair ``<stem>.png`` (Markdown) and ``<stem>.svg`` (PDF) under
    ``figures/``, with its caption."""

    stem: str
    caption: str
    kind: str                     # drawing|torque|reactions|polar|shaking

    @property
    def png(self) -> str:
        return f"figures/{self.stem}.png"

    @property
    def svg(self) -> str:
        return f"figures/{self.stem}.svg"


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
    """Plot data over the analysed angles ``angles`` (n,) [deg]."""

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


@dataclass
class CycleData:
    """Plot data over one turn on the cycle grid ``angles`` (N,) [deg], left-out angles filled
    in: driver ``torque`` (N,) [N m] and its ``mean``; ``energy`` (N,) [J], the running
    integral of torque minus mean; motor lines [N m] when given; ``sources`` the torque (N,)
    [N m] of each source (they sum to ``torque``); ``transmission`` (N,) [deg] by dyad and its
    lower limit; the inertial shaking force (N, 2) [N] without and with the counterweight."""

    angles: np.ndarray
    torque: np.ndarray
    mean: float
    energy: np.ndarray
    rated_torque: float | None
    peak_torque: float | None
    sources: dict[str, np.ndarray]
    transmission: dict[str, np.ndarray]
    transmission_limit: float | None
    inertial: np.ndarray
    balanced: np.ndarray
    interpolated: list[float]


@dataclass
class DesignSummary:
    """The report's first section. ``verdicts`` rows (design item, checked quantity, value,
    limit, margin, PASS/FAIL); ``values`` rows (cycle quantity, value, unit); ``problem`` why
    there are no cycle quantities ("" when there are)."""

    verdicts: list[list[str]]
    values: list[list[str]]
    counterweight: str
    interpolated: str
    problem: str
    passed: bool
    data: CycleData | None = None


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


@dataclass
class ReportModel:
    """One spec's report. See the module docstring."""

    stem: str
    source: str
    name: str
    description: list[str]
    status: str
    status_line: str
    method_title: str
    methods: list[list[str]]
    links: list[list[str]]
    joints: list[list[str]]
    driver: str
    loads: list[str]
    gravity: str
    sweep_text: str
    refs: list[RefAngle]
    torque: dict[str, str]
    bearings: list[list[str]]
    shaking: dict[str, str]
    agreement: list[list[str]]
    power_check: str
    residuals: list[list[str]]
    flags: list[list[str]]
    notes: list[str]
    design: DesignSummary
    figures: dict[str, Figure]
    sweep: SweepData
    scenes: list[Scene]
    csv_header: list[str]
    csv_rows: list[list[str]]
    summary: dict
    index_row: dict

    @property
    def method_names(self) -> list[str]:
        return [m[1] for m in self.methods]


# --------------------------------------------------------------------------- spec summary

def _symbols(spec) -> dict[str, str]:
    """Textbook reaction symbol of each joint: F<first><second> by link number."""
    return {j.name: spec.symbol(*j.links) for j in spec.joints}


def _link_rows(spec) -> list[list[str]]:
    rows = [["0", GROUND, DASH, DASH, DASH, "frame: " + ", ".join(
        f"{n} ({num(x)}, {num(y)})" for n, (x, y) in spec.ground.items())]]
    for ln in spec.links:
        s = ln.shape
        shape = (f"{s.kind} {num(s.length)} × {num(s.height)} × {num(s.depth)} m" if s
                 else DASH)
        pts = ", ".join(f"{n} ({num(x)}, {num(y)})" for n, (x, y) in ln.points.items())
        rows.append([str(ln.number), ln.name, num(ln.mass), num(ln.inertia),
                     f"({num(ln.com[0])}, {num(ln.com[1])})", f"{shape}; points {pts}"])
    return rows


def _joint_rows(spec, symbols, colors) -> list[list[str]]:
    rows = []
    for j in spec.joints:
        a, b = j.links
        links = f"{a} ({spec.number(a)}) → {b} ({spec.number(b)})"
        if j.type == "T":
            d = j.line.direction
            through = j.line.through_name or f"({num(j.line.through[0])}, {num(j.line.through[1])})"
            where = (f"slider point {j.point} on the line through {through}, direction "
                     f"{num(math.degrees(math.atan2(d[1], d[0])))} deg in {a}'s frame")
        else:
            where = f"pin at {j.point}"
        rows.append([j.name, "pin (R)" if j.type == "R" else "slider (T)", links,
                     symbols[j.name], where])
    return rows


def _load_texts(spec) -> list[str]:
    out = []
    for ld in spec.loads:
        unit = "N" if ld.kind == "force" else "N·m"
        if ld.value is not None:
            val = (f"({num(ld.value[0])}, {num(ld.value[1])}) {unit}" if ld.kind == "force"
                   else f"{num(ld.value)} {unit}")
        else:
            prof = ", ".join(f"{deg(a)}°: {num(v)}" for a, v in ld.profile)
            d = f" along ({num(ld.direction[0])}, {num(ld.direction[1])})" if ld.direction else ""
            val = f"profile [{prof}] {unit}{d}"
        at = f" at {ld.point}" if ld.point else ""
        opp = f", opposing its {ld.oppose}" if ld.oppose else ""
        out.append(f"{ld.kind} on {ld.link}{at}: {val}{opp}")
    return out


def _driver_text(spec) -> str:
    d = spec.driver
    rpm = d.rpm_given if d.rpm_given is not None else d.omega * 30 / math.pi
    return (f"joint {d.joint} turns {d.link} at ω = {num(d.omega)} rad/s ({num(rpm)} rpm), "
            f"α = {num(d.alpha)} rad/s²")


# --------------------------------------------------------------------- reference angles

def _kin_tables(kin, k: int) -> tuple[list[list[str]], list[list[str]]]:
    return kinematics_rows(kin, k, num)


def _reaction_rows(spec, forces, symbols, k: int) -> list[list[str]]:
    rows = []
    for j in spec.joints:
        sym = symbols[j.name]
        comps = [("fx", f"{sym} x [N]"), ("fy", f"{sym} y [N]"), ("f", f"|{sym}| [N]")]
        if j.type == "T":
            comps += [("moment", f"M{sym[1:]} [N·m]"), ("px", "at x [m]"), ("py", "at y [m]")]
        for attr, label in comps:
            vals = []
            for res in forces.values():
                r = res.reactions.get(j.name)
                v = r.component(attr) if r is not None else None
                vals.append(num(v[k]) if v is not None else DASH)
            rows.append([j.name, label, *vals])
    rows.append(["driver", "M [N·m]", *(num(r.driver_torque[k]) for r in forces.values())])
    return rows


def _vectors(spec, res, symbols, k: int) -> list[str]:
    out = []
    for j in spec.joints:
        r = res.reactions.get(j.name)
        if r is None:
            continue
        fy = float(r.fy[k])
        sign = "-" if num(fy).startswith("-") else "+"
        text = (f"{j.name}: {symbols[j.name]} = {num(r.fx[k])} i {sign} "
                f"{num(abs(fy))} j N, |{symbols[j.name]}| = {num(r.f[k])} N")
        if r.moment is not None:
            text += f", M{symbols[j.name][1:]} = {num(r.moment[k])} N·m"
        out.append(text)
    out.append(f"driver torque M = {num(res.driver_torque[k])} N·m")
    return out


def _ref_angles(analysis, ref: str, symbols, colors) -> tuple[list[RefAngle], list[Scene]]:
    kin, spec = analysis.kinematics, analysis.spec
    refs, scenes = [], []
    for angle in spec.at:
        k = kin.at(angle)
        if k is None:
            why = next((f.reason for f in analysis.flags if abs(f.angle - angle) < 1e-9),
                       "not analysed")
            refs.append(RefAngle(deg(angle), why))
            continue
        pts, links = _kin_tables(kin, k)
        stem = f"drawing_{deg(angle).replace('.', 'p').replace('-', 'm')}"
        fig = Figure(stem, f"The mechanism at φ = {deg(angle)}°: joint reactions "
                     f"(first link on second, {METHODS[ref].TITLE}, coloured per joint), "
                     "applied loads (black) and the driver torque.", "drawing")
        refs.append(RefAngle(deg(angle), None, pts, links,
                             _reaction_rows(spec, analysis.forces, symbols, k),
                             _vectors(spec, analysis.forces[ref], symbols, k), fig))
        scenes.append(build_scene(analysis, analysis.forces[ref], k, colors, symbols))
    return refs, scenes


# ------------------------------------------------------------------------ sweep results

def _sweep(analysis, ref: str, symbols, colors) -> SweepData:
    res = analysis.forces[ref]
    spec = analysis.spec
    joints = [JointSeries(j.name, symbols[j.name], j.type, colors[j.name], r.fx, r.fy, r.f,
                          r.moment)
              for j in spec.joints if (r := res.reactions.get(j.name)) is not None]
    polar = []
    for j in spec.joints:
        if j.type == "R" and j.name in res.reactions:
            xy = q.bearing_trace(analysis.kinematics, res, j)
            eq = analysis.review.bearings[j.name].f_equivalent if analysis.review else None
            polar.append(PolarSeries(j.name, symbols[j.name], colors[j.name],
                                     q.bearing_carrier(j), xy[:, 0], xy[:, 1], eq))
    check = analysis.forces.get("power")
    return SweepData(analysis.angles, [float(a) for a in spec.at],
                     [f.angle for f in analysis.flags], METHODS[ref].TITLE, res.driver_torque,
                     None if check is None or check is res else check.driver_torque,
                     q.torque_stats(res, analysis.kinematics.omega[:, analysis.kinematics.index(
                         analysis.spec.driver.link)]), joints, polar,
                     q.frame_load(analysis.kinematics, res, analysis.loads))


def _peak_text(p: q.Peak | None, unit: str) -> str:
    return DASH if p is None else f"{num(p.value)} {unit} at {deg(p.angle)}°"


def _torque_texts(st: q.TorqueStats | None) -> dict[str, str]:
    if st is None:
        return {k: DASH for k in ("mean", "rms", "peak", "low", "high", "power")}
    return {"mean": f"{num(st.mean)} N·m", "rms": f"{num(st.rms)} N·m",
            "peak": _peak_text(st.peak, "N·m"), "low": _peak_text(st.low, "N·m"),
            "high": _peak_text(st.high, "N·m"), "power": f"{num(st.power)} W"}


def _bearing_rows(sw: SweepData) -> list[list[str]]:
    rows = []
    for js in sw.joints:
        pk = q.peak(sw.angles, js.f)
        kind = "pin" if js.type == "R" else "slider"
        rows.append([js.name, js.symbol, kind, num(pk.value) if pk else DASH,
                     deg(pk.angle) if pk else DASH,
                     num(float(np.sqrt(np.mean(js.f**2)))) if len(js.f) else DASH])
    return rows


def _largest_load(sw: SweepData) -> tuple[str, q.Peak] | None:
    best = None
    for js in sw.joints:
        pk = q.peak(sw.angles, js.f)
        if pk is not None and (best is None or pk.value > best[1].value):
            best = (js.name, pk)
    return best


def _unit(quantity: str) -> str:
    return "N·m" if quantity.endswith(".moment") or quantity == "driver.torque" else "N"


def _agreement_rows(analysis) -> list[list[str]]:
    return [[a.quantity, f"{a.relative:.1e}", f"{a.absolute:.1e} {_unit(a.quantity)}",
             f"{METHODS[a.methods[0]].TITLE} vs {METHODS[a.methods[1]].TITLE}", deg(a.angle),
             str(a.n_methods)] for a in analysis.agreement]


def _power_check(sw: SweepData) -> tuple[str, dict | None]:
    if sw.torque_check is None or len(sw.torque) == 0:
        return "The power balance was not solved.", None
    diff = np.abs(sw.torque_check - sw.torque)
    k = int(np.argmax(diff))
    scale = max(float(np.max(np.abs(sw.torque))), 1e-300)
    text = (f"Power balance (M ω = Σ of the power of every other action) against "
            f"{sw.method_title}: largest torque difference {diff[k]:.1e} N·m "
            f"({diff[k] / scale:.1e} of the peak torque) at {deg(sw.angles[k])}°.")
    return text, {"max_abs": jnum(diff[k]), "relative": jnum(diff[k] / scale),
                  "angle_deg": float(sw.angles[k])}


# ---------------------------------------------------------------------------- csv / json

def _csv_columns(analysis) -> tuple[list[str], list[np.ndarray]]:
    """Column names and (n,) arrays over the analysed (solved) angles."""
    kin, spec = analysis.kinematics, analysis.spec
    names, cols = [], []
    for ln in spec.links:
        i = ln.number
        names += [f"{ln.name}.theta [deg]", f"{ln.name}.omega [rad/s]",
                  f"{ln.name}.alpha [rad/s^2]"]
        cols += [kin.angle_deg(ln.name), kin.omega[:, i], kin.alpha[:, i]]
    for p, owner in spec.named_points():
        s = kin.named_point(p, owner)
        for lab, arr, unit in (("x", s.r[:, 0], "m"), ("y", s.r[:, 1], "m"),
                               ("vx", s.v[:, 0], "m/s"), ("vy", s.v[:, 1], "m/s"),
                               ("ax", s.a[:, 0], "m/s^2"), ("ay", s.a[:, 1], "m/s^2")):
            names.append(f"{p}.{lab} [{unit}]")
            cols.append(arr)
    for m, res in analysis.forces.items():
        names.append(f"{m}.driver.torque [N m]")
        cols.append(res.driver_torque)
        for j in spec.joints:
            r = res.reactions.get(j.name)
            if r is None:
                continue
            for attr, unit in (("fx", "N"), ("fy", "N"), ("moment", "N m"), ("px", "m"),
                               ("py", "m")):
                v = getattr(r, attr)
                if v is not None:
                    names.append(f"{m}.joint.{j.name}.{attr} [{unit}]")
                    cols.append(v)
    return names, cols


def _csv(analysis) -> tuple[list[str], list[list[str]]]:
    """One row per analysed crank angle; left-out angles keep their row, with the reason in
    ``flag`` and empty cells; undefined values (NaN) are empty cells."""
    names, cols = _csv_columns(analysis)
    data = np.column_stack(cols) if cols else np.zeros((analysis.kinematics.n, 0))
    reasons = {round(f.angle, 9): f.reason for f in analysis.flags}
    solved = {round(float(a), 9): k for k, a in enumerate(analysis.angles)}
    angles = sorted(set(solved) | set(reasons))
    rows = []
    for a in angles:
        k = solved.get(a)
        cells = ([""] * len(names) if k is None else
                 [f"{v:.10g}" if math.isfinite(v) else "" for v in data[k]])
        rows.append([f"{a:g}", reasons.get(a, ""), *cells])
    return ["crank_angle [deg]", "flag", *names], rows


def _peak_json(p: q.Peak | None) -> dict | None:
    return None if p is None else {"value": jnum(p.value), "angle_deg": p.angle}


def _summary(analysis, sw: SweepData, ref: str, status_line: str, power: dict | None,
             symbols) -> dict:
    st = sw.stats
    largest = _largest_load(sw)
    refs = {}
    for angle in analysis.spec.at:
        k = analysis.kinematics.at(angle)
        if k is None:
            continue
        refs[deg(angle)] = {
            "driver_torque": {m: jnum(r.driver_torque[k]) for m, r in analysis.forces.items()},
            "reactions": {j: {m: {"fx": jnum(r.reactions[j].fx[k]),
                                  "fy": jnum(r.reactions[j].fy[k])}
                              for m, r in analysis.forces.items() if j in r.reactions}
                          for j in symbols}}
    w = analysis.worst
    return {
        "spec": analysis.spec.file, "name": analysis.spec.name,
        "status": "PASS" if analysis.passed else "FAIL", "check": status_line,
        "reference_method": ref, "n_angles": int(analysis.kinematics.n),
        "units": {"force": "N", "torque": "N m", "power": "W", "angle": "deg"},
        "driver_torque": None if st is None else {
            "mean": st.mean, "rms": st.rms, "peak": _peak_json(st.peak),
            "min": _peak_json(st.low), "max": _peak_json(st.high)},
        "mean_power": None if st is None else st.power,
        "reactions": {js.name: {"symbol": js.symbol, "peak": _peak_json(q.peak(sw.angles, js.f)),
                                "fx_peak": _peak_json(q.peak(sw.angles, js.fx)),
                                "fy_peak": _peak_json(q.peak(sw.angles, js.fy))}
                      for js in sw.joints},
        "largest_bearing_load": None if largest is None else {
            "joint": largest[0], **_peak_json(largest[1])},
        "shaking": {"force_peak": _peak_json(q.peak(sw.angles, sw.shaking.f)),
                    "moment_peak": _peak_json(q.peak(sw.angles, sw.shaking.m))},
        "reference_angles": refs,
        "agreement": {
            "worst": None if w is None else {"quantity": w.quantity, "relative": w.relative,
                                             "absolute": w.absolute,
                                             "methods": list(w.methods), "angle_deg": w.angle},
            "quantities": [{"quantity": a.quantity, "relative": a.relative,
                            "absolute": a.absolute, "methods": list(a.methods),
                            "angle_deg": a.angle} for a in analysis.agreement]},
        "power_balance": power,
        "residuals": [{"method": r.method, "force": r.force, "moment": r.moment}
                      for r in analysis.residuals],
        "flags": [{"angle_deg": f.angle, "kind": f.kind, "reason": f.reason}
                  for f in analysis.flags],
        "notes": analysis.kinematics.notes(),
    }


def _index_row(model_summary: dict, stem: str) -> dict:
    s = model_summary
    t = s["driver_torque"] or {}
    big = s["largest_bearing_load"]
    w = s["agreement"]["worst"]
    return {
        "stem": stem, "spec": s["spec"], "name": s["name"], "ok": True,
        "status": s["status"],
        "peak": _peak_text(q.Peak(t["peak"]["value"], t["peak"]["angle_deg"]), "N·m")
        if t.get("peak") else DASH,
        "rms": f"{num(t['rms'])} N·m" if t else DASH,
        "bearing": (f"{num(big['value'])} N ({big['joint']}, {deg(big['angle_deg'])}°)"
                    if big else DASH),
        "power": f"{num(s['mean_power'])} W" if s["mean_power"] is not None else DASH,
        "worst": f"{w['relative']:.1e} ({w['quantity']})" if w else DASH,
        "report_md": f"{stem}/report.md", "report_pdf": f"{stem}/report.pdf",
        "message": "",
    }


# ------------------------------------------------------------------------------ entry

def build_model(analysis, source: str | Path | None = None) -> ReportModel:
    """The report model of ``analysis``; ``source`` is the spec path shown in the report."""
    from ..checks.run import summary_line

    spec = analysis.spec
    source = str(source if source is not None else spec.file)
    stem = Path(source).stem
    ref = q.reference_method(analysis.forces)
    symbols = _symbols(spec)
    colors = {j.name: PALETTE[i % len(PALETTE)] for i, j in enumerate(spec.joints)}
    status_line = summary_line(source, analysis)
    refs, scenes = _ref_angles(analysis, ref, symbols, colors)
    sw = _sweep(analysis, ref, symbols, colors)
    power_text, power_json = _power_check(sw)
    header, rows = _csv(analysis)
    design = _design(analysis)
    summary = _summary(analysis, sw, ref, status_line, power_json, symbols)
    summary["design"] = _design_json(analysis)
    figures = _figures(sw, refs, ref) | _design_figures(design)
    shaking = {"force": _peak_text(q.peak(sw.angles, sw.shaking.f), "N"),
               "moment": _peak_text(q.peak(sw.angles, sw.shaking.m), "N·m")}
    sweep = spec.sweep
    return ReportModel(
        stem=stem, source=source, name=spec.name,
        description=[p.strip() for p in spec.description.strip().split("\n\n") if p.strip()],
        status="PASS" if analysis.passed else "FAIL", status_line=status_line,
        method_title=METHODS[ref].TITLE,
        methods=[[name, m.TITLE, m.SECTION] for name, m in METHODS.items()
                 if name in analysis.forces],
        links=_link_rows(spec), joints=_joint_rows(spec, symbols, colors),
        driver=_driver_text(spec), loads=_load_texts(spec),
        gravity=f"({num(spec.gravity[0])}, {num(spec.gravity[1])}) m/s²",
        sweep_text=(f"{deg(sweep.start)}° to {deg(sweep.stop)}° in steps of "
                    f"{deg(sweep.step)}°: {analysis.kinematics.n} angles solved, "
                    f"{len(analysis.flags)} left out"),
        refs=refs, torque=_torque_texts(sw.stats), bearings=_bearing_rows(sw), shaking=shaking,
        agreement=_agreement_rows(analysis), power_check=power_text,
        residuals=[[METHODS[r.method].TITLE, f"{r.force:.1e}", f"{r.moment:.1e}"]
                   for r in analysis.residuals],
        flags=_flag_rows(analysis), notes=analysis.kinematics.notes(), design=design,
        figures=figures, sweep=sw, scenes=scenes, csv_header=header, csv_rows=rows,
        summary=summary, index_row=_index_row(summary, stem))


def _design(analysis) -> DesignSummary:
    """Verdicts, cycle quantities, counterweight and the cycle's plot data."""
    spec, rev = analysis.spec, analysis.review
    verdict_rows = [[v.item, v.quantity.replace("joint.*.", "largest joint ")
                     + (f" ({v.where})" if v.where else ""),
                     f"{num(v.value)} {v.unit}" if v.value is not None else f"undefined: {v.why}",
                     ("≥ " if v.at_least else "≤ ") + f"{num(v.limit)} {v.unit}",
                     _margin(v), 
                     "PASS" if v.passed else "FAIL"] for v in analysis.verdicts]
    passed = all(v.passed for v in analysis.verdicts)
    if rev is None:
        return DesignSummary(verdict_rows, [], "", "", analysis.review_problem, passed)
    values = [[name, num(value), unit_of(name) or ""] for name, value in rev.values.items()
              if not name.startswith("joint.")]
    cw = rev.counterweight
    counter = (f"A point counterweight of m·r = {num(cw.mr, 4)} kg·m at "
               f"{num(cw.angle, 4)}° from the crank's x-axis brings the RMS inertial shaking "
               f"force from {num(cw.rms_before, 4)} N to {num(cw.rms_after, 4)} N."
               if cw.mr > 0 else "The crank needs no counterweight: the inertial shaking "
                                 "force has no component turning with it.")
    interp = ""
    if len(rev.cycle.interpolated):
        interp = ("Left-out angles inside the cycle, interpolated from their neighbours for "
                  "the cycle quantities: " + ", ".join(deg(a) for a in rev.cycle.interpolated)
                  + " deg.")
    k = analysis.kinematics
    parts = {src: rev.cycle.sample(v["driver.torque"], k.angles)
             for src, v in analysis.by_source(rev.method).items()}
    data = CycleData(rev.cycle.angles, rev.torque, float(np.mean(rev.torque)), rev.energy,
                     spec.design.motor.get("rated_torque"), spec.design.motor.get("peak_torque"),
                     parts, rev.transmission, spec.design.limits.get("transmission_angle"),
                     rev.inertial, rev.shaking_balanced,
                     [float(a) for a in rev.cycle.interpolated])
    return DesignSummary(verdict_rows, values, counter, interp, "", passed, data)


def _margin(v) -> str:
    """A verdict's margin: ``+24.1 %`` of the limit; ``value 537x limit`` when it is huge."""
    if v.margin is None:
        return DASH
    if abs(v.margin) > 9.99:
        ratio = v.value / v.limit if v.limit else float("inf")
        return f"value {num(ratio, 3)}× limit"
    return f"{v.margin * 100:+.1f} %"


def _design_json(analysis) -> dict:
    rev = analysis.review
    out: dict = {"verdicts": [{"item": v.item, "quantity": v.quantity, "value": jnum(v.value),
                               "limit": v.limit, "unit": v.unit, "lower_limit": v.at_least,
                               "margin": jnum(v.margin), "passed": v.passed,
                               "joint": v.where or None, "why": v.why or None}
                              for v in analysis.verdicts],
                 "cycle_undefined": analysis.review_problem or None}
    if rev is not None:
        out["cycle"] = {name: {"value": jnum(value), "unit": unit_of(name)}
                        for name, value in rev.values.items()}
        out["method"] = rev.method
        out["interpolated_deg"] = [float(a) for a in rev.cycle.interpolated]
    return out


def _design_figures(design: DesignSummary) -> dict[str, Figure]:
    if design.data is None:
        return {}
    figs = {"flywheel": Figure("flywheel", "Driver torque over one turn against its mean: the "
                               "areas above (energy taken in) and below (given back) the mean "
                               "line; the largest energy fluctuation ΔE, which the flywheel "
                               "absorbs, lies between the two marked angles.", "flywheel"),
            "breakdown": Figure("breakdown", "Driver torque by source over one turn: each "
                                "source's share stacked (positive above zero, negative below); "
                                "the line is the total.", "breakdown"),
            "balance": Figure("balance", "Inertial shaking force (sum of m a_C) over one turn, "
                              "without and with the best point counterweight on the crank.",
                              "balance")}
    if design.data.transmission:
        figs["transmission"] = Figure("transmission", "Transmission angle of each group over "
                                      "one turn (folded into 0-90°), with the design limit.",
                                      "transmission")
    return figs


def _flag_rows(analysis) -> list[list[str]]:
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


def _figures(sw: SweepData, refs: list[RefAngle], ref: str) -> dict[str, Figure]:
    title = METHODS[ref].TITLE
    figs: dict[str, Figure] = {}
    for r in refs:
        if r.drawing is not None:
            figs[r.drawing.stem] = r.drawing
    if len(sw.angles) == 0:
        return figs
    figs |= {"torque": Figure("torque", f"Driver torque over a turn ({title}); mean and peak "
                             "marked, left-out angles shaded.", "torque"),
            "reactions": Figure("reactions", f"Joint reactions (first link on second, "
                                f"{title}): magnitude and global components.", "reactions"),
            "shaking": Figure("shaking", "Shaking force (resultant of the reactions on the "
                              "frame) and shaking moment about the driver pivot, including "
                              "the driver's reaction torque.", "shaking")}
    if not sw.joints:
        del figs["reactions"]
    if sw.polar:
        figs["polar"] = Figure("polar", "Polar load diagrams of the pins: the tip of the "
                               "reaction (first link on second) over a turn, in the frame of "
                               "the link named under each plot (ground: global frame); "
                               "dots mark the reference angles.", "polar")
    return figs
