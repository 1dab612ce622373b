"""The report result model: every number a report prints, built once from an Analysis.

The report document (its Markdown and Typst writers), results.csv, summary.json, the plots
and the drawings all read a :class:`ReportModel`; none of them computes mechanics. Printed
values are strings already formatted by the one formatter (:mod:`mechreport.units`) in the spec's display units
(``report.units``; undefined values print as "—"); the plot data are float arrays (n,) over
the analysed crank angles [deg], in SI, converted by the plots through ``model.display``.
results.csv and summary.json are SI, with the unit in every column name or field.
"""
from __future__ import annotations

import datetime as _dt
import hashlib
import math
import os
import re
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..version import __version__
from .. import post as q
from ..kinematics.result import angle_ranges
from ..post.balance import NOTICEABLE
from ..post.bearings import bearing_carrier
from ..post.friction import efficiency_undefined
from ..post.columns import sweep_rows
from ..post.sweep import PowerCheck, SweepSummary
from ..forces import METHODS
from ..quantities import unit_of
from ..spec import GROUND, profile_at
from ..checks.failures import failed_expectations
from ..units import DASH, PRESSURE_UNITS, SIG_DIGITS, Display, clean, deg, fmt, kind_of
from .check_text import failure_rows, summary_line
from .dynamics import dynamics_json, dynamics_section
from .frames import Animation, animation_data
from .mpl import PALETTE
from .scene import Scene, build_scene
from .strength import StrengthSection, strength_json, strength_section
from .text import kinematics_rows



def num(x, digits: int = SIG_DIGITS) -> str:
    """``x`` (already in the unit it is shown in) by the one formatter; "—" for None/NaN."""
    return fmt(x, digits)


def jnum(x, scale: float | None = None) -> float | None:
    """A float for JSON (SI, round-off of its quantity's ``scale`` made 0): None where
    undefined."""
    if x is None or not math.isfinite(float(x)):
        return None
    return clean(float(x), scale)


@dataclass
class Figure:
    """A figure ``figures/<stem>.svg`` (vector: the PDF and the Markdown report show the same
    file), with its caption."""

    stem: str
    caption: str
    kind: str                     # drawing|torque|reactions|polar|shaking|flywheel|...

    @property
    def svg(self) -> str:
        return f"figures/{self.stem}.svg"

    @property
    def path(self) -> str:
        return self.svg


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


@dataclass
class CycleData:
    """Plot data over one turn on the cycle grid ``angles`` (N,) [deg], left-out angles filled
    in: driver ``torque`` (N,) [N m] and its ``mean``; ``energy`` (N,) [J], the running
    integral of torque minus mean; motor lines [N m] when given; ``sources`` the torque (N,)
    [N m] of each source (they sum to ``torque``); ``transmission`` (N,) [deg] by dyad and its
    lower limit; the inertial shaking force (N, 2) [N] without and with the counterweight;
    ``silent`` the sources whose torque is 0 at every angle (round-off: not drawn)."""

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
    silent: list[str] = field(default_factory=list)
    period: float = 360.0        # the cycle [deg]: 720 for a four-stroke engine
    # an engine's pressure loads (format 1.2): each one's pressure (N,) over the cycle grid,
    # as written (absolute or gauge, in ``pressure_unit``), by load name
    pressures: dict[str, np.ndarray] = field(default_factory=dict)
    pressure_unit: str = "Pa"

    @property
    def span(self) -> str:
        """What the figures run over: ``one turn``, or ``the 720° cycle``."""
        return "one turn" if self.period == 360.0 else f"the {self.period:g}° cycle"


@dataclass
class DesignSummary:
    """The report's first section. ``verdicts`` rows (design item, checked quantity, value,
    limit, margin, PASS/FAIL); ``values`` rows (meaning, cycle quantity, value with unit);
    ``bearings`` rows (joint, peak, mean, equivalent load, L10 life);
    ``problem`` why there are no cycle quantities ("" when there are); ``absent`` the cycle
    figures left out because they would show nothing, each with the sentence saying why
    (the report prints it where the figure would be)."""

    verdicts: list[list[str]]
    values: list[list[str]]
    counterweight: str
    interpolated: str
    problem: str
    passed: bool
    data: CycleData | None = None
    bearings: list[list[str]] = field(default_factory=list)   # joint, max, mean, equiv., L10
    absent: dict[str, str] = field(default_factory=dict)


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


@dataclass
class Meta:
    """Traceability and the spec's ``report`` metadata, as printed."""

    title: str
    project: str
    author: str
    revision: str
    date: str
    version: str
    sha256: str
    units: str

    def rows(self) -> list[list[str]]:
        """(label, value) rows for the first page; empty metadata left out."""
        rows = [["Project", self.project], ["Revision", self.revision],
                ["Author", self.author]]
        rows = [r for r in rows if r[1]]
        return rows + [["Date", self.date], ["mechreport", self.version],
                       ["Spec SHA-256", self.sha256], ["Units", self.units]]


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


@dataclass
class DxfData:
    """mechanism.dxf: one ``(layer, scene)`` per solved reference angle, drawn in the spec's
    length ``unit`` (``scale`` [m] per unit)."""

    unit: str
    scale: float
    layers: list[tuple[str, Scene]]


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
    methods: list[MethodRow]
    links: list[list[str]]
    joints: list[list[str]]
    branches: list[list[str]]
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
    left_out: str
    notes: list[str]
    failures: list[list[str]]
    design: DesignSummary
    figures: dict[str, Figure]
    sweep: SweepData
    scenes: list[Scene]
    csv_header: list[str]
    csv_rows: list[list[str]]
    summary: dict
    index_row: dict
    meta: Meta
    display: Display
    heads: dict[str, str]
    effort: str = "driver torque M"
    effort_name: str = "driver torque"      # the effort without its symbol
    coord: str = "crank angle"
    coord_unit: str = "°"
    friction: FrictionSection | None = None    # a spec with friction: its section
    dynamics: object | None = None    # a spec with dynamics: its section (.dynamics)
    strength: StrengthSection | None = None    # links with a section: their strength
    animation: Animation | None = None        # animation.gif's frames (report.animation)
    dxf: DxfData | None = None                # mechanism.dxf's layers (report.dxf)

# ------------------------------------------------------------------------ traceability

def build_time() -> _dt.datetime:
    """Now, or ``SOURCE_DATE_EPOCH`` (reproducible builds) when it is set, in UTC."""
    epoch = os.environ.get("SOURCE_DATE_EPOCH", "").strip()
    if epoch:
        try:
            return _dt.datetime.fromtimestamp(int(epoch), _dt.timezone.utc)
        except (ValueError, OverflowError, OSError):
            pass
    return _dt.datetime.now(_dt.timezone.utc).replace(microsecond=0)


def spec_sha256(path) -> str:
    """SHA-256 of the spec file's bytes ("" when there is no file)."""
    try:
        return hashlib.sha256(Path(path).read_bytes()).hexdigest()
    except (OSError, ValueError, TypeError):
        return ""


def display_of(analysis) -> Display:
    """The spec's display units with the scales [SI] of this analysis (round-off rule)."""
    units = dict(analysis.spec.report.units) or {}
    for key, si in (("length", "m"), ("force", "N"), ("moment", "N*m")):
        units.setdefault(key, analysis.spec.units.get(key, si))    # the spec's own units
    return Display(units["length"], units["force"], units["moment"], units.get("mass", "kg"),
                   analysis.scales(), stress=units.get("stress", "MPa"),
                   pressure=units.get("pressure", "Pa"))


# --------------------------------------------------------------------------- spec summary

def _colors(spec) -> dict[str, str]:
    """One colour per joint, in spec order, across every figure (:data:`PALETTE`)."""
    return {name: PALETTE[i % len(PALETTE)]
            for i, name in enumerate(spec.reported_reactions())}


def sweep_data(analysis) -> tuple[SweepData, Display]:
    """The report's plot data of ``analysis`` and its display units (for the plot
    functions, :mod:`mechreport.report.plots`)."""
    spec, d = analysis.spec, display_of(analysis)
    return _sweep(analysis, analysis.sweep_summary(), _symbols(spec), _colors(spec), d), d


def friction_data(analysis) -> tuple[FrictionPlot | None, Display]:
    """The data of the report's friction plot of ``analysis`` (None without friction) and
    its display units (for :func:`mechreport.report.plots.plot_friction`)."""
    sw, d = sweep_data(analysis)
    section = _friction(analysis, _design(analysis, d), sw, d)
    return (None if section is None else section.plot), d


def _symbols(spec) -> dict[str, str]:
    """Textbook reaction symbol of each joint: F<first><second> by link number; a pin
    joining several links: F<pin><link> for its force on its hub (on the others, it is the
    reaction of the hub's joint to each)."""
    out = {j.name: spec.symbol(*j.links) for j in spec.joints}
    for pin in spec.pins:
        out[pin.joint_name(pin.hub)] = f"F{pin.name}{spec.number(pin.hub)}"
    return {name: out[name] for name in spec.reported_reactions()}


def _xy(d: Display, p) -> str:
    return f"({d.num(p[0], 'length')}, {d.num(p[1], 'length')})"


def _link_rows(spec, d: Display) -> list[list[str]]:
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


def _joint_rows(spec, symbols, d: Display) -> list[list[str]]:
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
        rows.append([j.name, "pin (R)" if j.type == "R" else "slider (T)", links,
                     symbols[j.name], where])
    return rows


def _branch_rows(kin) -> list[list[str]]:
    """(dyad, type, how its assembly branch was chosen) per dyad, in solving order."""
    return [[b.dyad, b.kind, _branch_text(b.rule)] for b in kin.branches]


def _branch_text(rule: str) -> str:
    if rule == "unique":
        return "one solution only: no choice"
    if rule.startswith("hint"):
        return f"chosen by the assembly hint ({rule.split(':', 1)[1].strip()})"
    return rule


def _load_texts(spec, d: Display) -> list[str]:
    out = []
    for ld in spec.loads:
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
        at = f" at {ld.point}" if ld.point else ""
        opp = f", opposing its {ld.oppose}" if ld.oppose else ""
        name = f"{ld.label}: " if getattr(ld, "label", "") else ""
        kind_name = "pressure" if ld.pressure is not None else ld.kind.replace('_', ' ')
        out.append(f"{name}{kind_name} on {ld.link}{at}: {val}{opp}")
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


def _driver_text(spec) -> str:
    d = spec.driver
    joint = spec.joint(d.joint).written
    if d.at_rest:
        what = "stroke" if d.kind == "T" else "angle"
        if d.alpha == 0:
            return (f"joint {joint} holds {d.link} at rest at each {what} (a static "
                    "analysis: the holding effort and the reactions)")
        unit = "m/s²" if d.kind == "T" else "rad/s²"
        return (f"joint {joint} starts {d.link} from rest at each {what}, "
                f"{'accel' if d.kind == 'T' else 'α'} = {fmt(d.alpha)} {unit}")
    if getattr(d, "kind", "R") != "R":
        return f"joint {joint} drives {d.link} along its line at {fmt(d.omega)} m/s"
    rpm = d.rpm
    return (f"joint {joint} turns {d.link} at ω = {fmt(d.omega)} rad/s ({fmt(rpm)} rpm), "
            f"α = {fmt(d.alpha)} rad/s²")


# --------------------------------------------------------------------- reference angles

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


def _ref_angles(analysis, ref: str, symbols, colors, d: Display
                ) -> tuple[list[RefAngle], list[Scene]]:
    kin, spec = analysis.kinematics, analysis.spec
    refs, scenes = [], []
    _, _, coord, unit = effort_of(spec)
    for angle in spec.at:
        title = f"{coord[0].upper()}{coord[1:]} {deg(angle)}{unit}"
        anchor = re.sub(r"[^a-z0-9 _-]", "", title.lower()).replace(" ", "-")
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


# ------------------------------------------------------------------------ sweep results

def _sweep(analysis, summary: SweepSummary, symbols, colors, d: Display) -> SweepData:
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


def effort_of(spec) -> tuple[str, str, str, str]:
    """(kind, label, coordinate, unit suffix) of the driver: a crank's torque over the crank
    angle in degrees, or a T driver's force over its stroke in the spec's length unit."""
    d = spec.driver
    if getattr(d, "kind", "R") == "T":
        return "force", "driver force F", "stroke", " " + spec.units.get("length", "m")
    coord = getattr(d, "coordinate", "crank angle")
    return "moment", "driver torque M", coord, "°"


def _peak_text(p: q.Peak | None, kind: str, d: Display, unit: str = "°") -> str:
    """``155.3 N at 45°``; a peak that prints as 0 is 0 everywhere: ``0 N·m at every
    angle`` (``position`` for a stroke)."""
    if p is None:
        return DASH
    if d.zero(p.value, kind):
        return f"{d.q(0.0, kind)} at every {'angle' if unit == '°' else 'position'}"
    return f"{d.q(p.value, kind)} at {deg(p.angle)}{unit}"


def _torque_texts(st: q.TorqueStats | None, d: Display, kind: str = "moment",
                  unit: str = "°") -> dict[str, str]:
    if st is None:
        return {k: DASH for k in ("mean", "rms", "peak", "low", "high", "power")}

    def at(p):
        return _peak_text(p, kind, d, unit)
    return {"mean": d.q(st.mean, kind), "rms": d.q(st.rms, kind), "peak": at(st.peak),
            "low": at(st.low), "high": at(st.high), "power": d.q(st.power, "power")}


def _bearing_rows(summary: SweepSummary, sw: SweepData, d: Display) -> list[list[str]]:
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


def _agreement_rows(analysis, d: Display) -> list[list[str]]:
    spec = analysis.spec
    return [[a.quantity, fmt(a.relative, 2), _diag(a.absolute, _kind(a.quantity, spec), d),
             f"{METHODS[a.methods[0]].TITLE} vs {METHODS[a.methods[1]].TITLE}", deg(a.angle),
             str(a.n_methods)] for a in analysis.agreement]


def _power_check(pc: PowerCheck | None, method_title: str, d: Display, at_rest: bool = False
                 ) -> tuple[str, dict | None]:
    if pc is None:
        return "The power balance was not solved.", None
    balance = ("Virtual work (the driver at rest: M = −Σ of every other action times its "
               "velocity coefficient)" if at_rest else
               "Power balance (M ω = Σ of the power of every other action)")
    text = (f"{balance} against "
            f"{method_title}: largest torque difference {_diag(pc.max_abs, 'moment', d)} "
            f"({fmt(pc.relative, 2)} of the peak torque) at {deg(pc.angle)}°.")
    return text, {"max_abs_N_m": jnum(pc.max_abs), "relative": jnum(pc.relative),
                  "angle_deg": pc.angle}


# ------------------------------------------------------------------- failed expectations

# ---------------------------------------------------------------------------- csv / json

def _csv(analysis) -> tuple[list[str], list[list[str]]]:
    """One row per analysed crank angle; left-out angles keep their row, with the reason in
    ``flag`` and empty cells; undefined values (NaN) are empty cells; round-off is 0."""
    columns = analysis.columns()
    names = [c.name for c in columns]
    data = np.column_stack([c.values for c in columns]) if columns else \
        np.zeros((analysis.kinematics.n, 0))
    rows = []
    for a, k, why in zip(*sweep_rows(analysis.angles, analysis.flags)):
        cells = ([""] * len(names) if k is None else
                 [f"{v:.10g}" if math.isfinite(v) else "" for v in data[k].tolist()])
        rows.append([deg(a), why, *cells])
    return [analysis.spec.axis_column, "flag", *names], rows


def _peak_json(p: q.Peak | None, unit: str, scale: float | None = None) -> dict | None:
    return None if p is None else {"value": jnum(p.value, scale), "unit": unit,
                                   "angle_deg": p.angle}


def _summary(analysis, summary: SweepSummary, sw: SweepData, status_line: str,
             power: dict | None, symbols, meta: Meta, fails: list[dict], sc: dict) -> dict:
    st = summary.torque
    ref = summary.method
    F, M = sc["force"], sc["moment"]
    EU, ES = ("N", F) if sw.effort == "force" else ("N·m", M)   # a T driver pushes
    effort_key = "driver_force" if sw.effort == "force" else "driver_torque"
    largest = summary.largest
    refs = {}
    for angle in analysis.spec.at:
        k = analysis.kinematics.index_of(angle)
        if k is None:
            continue
        refs[deg(angle)] = {
            effort_key: {m: jnum(r.driver_torque[k], ES) for m, r in analysis.forces.items()},
            "reactions": {j: {m: {"fx": jnum(r.reactions[j].fx[k], F),
                                  "fy": jnum(r.reactions[j].fy[k], F)}
                              for m, r in analysis.forces.items() if j in r.reactions}
                          for j in symbols},
            "units": {effort_key: EU, "reactions": "N"}}
    w = analysis.worst
    cycle = analysis.review.values if analysis.review is not None else {}
    if analysis.strength is not None:   # the members' quantities: key figures too (diff)
        cycle = {**cycle, **analysis.strength.values}
    return {
        "mechreport_version": meta.version, "spec": analysis.spec.file,
        "axis_unit": analysis.spec.axis_unit,
        "spec_sha256": meta.sha256, "date": meta.date,
        "name": analysis.spec.name, "title": meta.title or analysis.spec.name,
        "project": meta.project or None, "author": meta.author or None,
        "revision": meta.revision or None,
        "status": "PASS" if analysis.passed else "FAIL", "check": status_line,
        "failures": fails,
        "reference_method": ref, "n_angles": int(analysis.kinematics.n),
        "units": {"force": "N", "torque": "N·m", "moment": "N·m", "power": "W",
                  "length": "m", "angle": "deg", "note": "summary.json and results.csv are SI"},
        effort_key: None if st is None else {
            "unit": EU, "mean": jnum(st.mean, ES), "rms": jnum(st.rms, ES),
            "peak": _peak_json(st.peak, EU, ES), "min": _peak_json(st.low, EU, ES),
            "max": _peak_json(st.high, EU, ES)},
        "driver_effort": "force" if EU == "N" else "torque",
        "mean_power": None if st is None else {"value": jnum(st.power), "unit": "W"},
        "reactions": {js.name: {"symbol": js.symbol, "unit": "N",
                                "peak": _peak_json(jl.peak, "N", F),
                                "peak_away_from_left_out": _peak_json(jl.peak_far, "N", F),
                                "rms": None if jl.rms is None else jnum(jl.rms, F),
                                "fx_peak": _peak_json(jl.fx_peak, "N", F),
                                "fy_peak": _peak_json(jl.fy_peak, "N", F)}
                      for js in sw.joints if (jl := summary.joints[js.name])},
        "largest_bearing_load": None if largest is None else {
            "joint": largest[0], **_peak_json(largest[1], "N", F),
            "away_from_left_out": _peak_json(summary.joints[largest[0]].peak_far, "N", F)},
        "shaking": {"force_peak": _peak_json(summary.shaking_force, "N", F),
                    "moment_peak": _peak_json(summary.shaking_moment, "N·m", M)},
        "reference_angles": refs,
        "branches": [{"dyad": b.dyad, "type": b.kind, "rule": b.rule}
                     for b in analysis.kinematics.branches],
        "agreement": {
            "worst": None if w is None else {"quantity": w.quantity, "relative": w.relative,
                                             "absolute": w.absolute,
                                             "unit": analysis.spec.unit_of(w.quantity) or "N",
                                             "methods": list(w.methods), "angle_deg": w.angle},
            "quantities": [{"quantity": a.quantity, "relative": a.relative,
                            "absolute": a.absolute,
                            "unit": analysis.spec.unit_of(a.quantity) or "N",
                            "methods": list(a.methods),
                            "angle_deg": a.angle} for a in analysis.agreement]},
        "power_balance": power,
        "residuals": [{"method": r.method, "force_N": r.force, "moment_N_m": r.moment}
                      for r in analysis.residuals],
        "flags": [{"angle_deg": f.angle, "kind": f.kind, "reason": f.reason}
                  for f in analysis.flags],
        "near_singular_deg": sw.near_deg,
        "notes": analysis.kinematics.notes(),
        "quantities": _quantities(summary, cycle, sc, EU),
    }


def _quantities(summary: SweepSummary, cycle: dict, sc: dict, effort_unit: str = "N·m") -> dict:
    """Every key figure by name -> {value [SI], unit}: what ``mechreport diff`` compares and
    the index lists, each once: where the cycle quantities are defined, a sweep peak that
    one of them states (a joint's peak load is ``joint.J.f_max``, the shaking force's and
    moment's ``cycle.shaking.*_max``, the effort's mean and RMS and the mean power are
    ``cycle.torque.mean``, ``cycle.torque.rms`` and ``cycle.power.mean``) is not listed again
    under another name. The driver's signed peak and its angle stay: no cycle quantity says
    where it is."""
    out: dict[str, dict] = {}
    cyclic = bool(cycle)

    def put(name, value, unit, kind=None, angle=None):
        if value is None:
            return
        entry = {"value": jnum(value, sc.get(kind) if kind else None), "unit": unit}
        if angle is not None:
            entry["angle_deg"] = float(angle)
        out[name] = entry

    st = summary.torque
    if st is not None:
        name, kind = (("driver.force", "force") if effort_unit == "N"
                      else ("driver.torque", "moment"))
        if "cycle.torque.rms" not in cycle:   # over a whole turn the cycle's names say them
            put(f"{name}.mean", st.mean, effort_unit, kind)
            put(f"{name}.rms", st.rms, effort_unit, kind)
            put("driver.power.mean", st.power, "W")
        put(f"{name}.peak", st.peak.value, effort_unit, kind, st.peak.angle)   # signed, where
    for name, jl in summary.joints.items():
        pk = jl.peak
        if pk is not None:
            if not cyclic or f"joint.{name}.f_max" not in cycle:
                put(f"joint.{name}.f.peak", pk.value, "N", "force", pk.angle)
            put(f"joint.{name}.f.rms", jl.rms, "N", "force")
    sh = summary.shaking_force
    if sh is not None and "cycle.shaking.force_max" not in cycle:
        put("shaking.force.peak", sh.value, "N", "force", sh.angle)
    shm = summary.shaking_moment
    if shm is not None and "cycle.shaking.moment_max" not in cycle:
        put("shaking.moment.peak", shm.value, "N·m", "moment", shm.angle)
    for name, value in cycle.items():
        unit = unit_of(name) or ""
        put(name, value, unit, kind_of(unit))
    return out


def _away_value(big: dict | None) -> float | None:
    """The largest bearing load's peak away from left-out angles, where it is another."""
    far = (big or {}).get("away_from_left_out")
    if not far or far.get("angle_deg") == big.get("angle_deg"):
        return None
    return far.get("value")


def _away(big: dict, at: str) -> str:
    """``; 973.6 N at 84° away from left-out angles`` where that is another value."""
    value = _away_value(big)
    if value is None:
        return ""
    return f"; {fmt(value)} N at {deg(big['away_from_left_out']['angle_deg'])}{at} away " \
           "from left-out angles"


def check_failure_reason(s: dict) -> str:
    """Why the check of a summary (summary.json) failed, in one line for the index: the
    design verdicts missed, the expectations failed, the methods' disagreement."""
    parts = []
    verdicts = ((s.get("design") or {}).get("verdicts")) or []
    missed = [v["item"] for v in verdicts if not v.get("passed")]
    if missed:
        parts.append(f"design verdict(s) missed: {', '.join(missed)}")
    fails = s.get("failures") or []
    if fails:
        unit = s.get("axis_unit", "deg")
        shown = [f["quantity"] + (f" at {deg(f['angle_deg'])} {unit}"
                                  if f.get("angle_deg") is not None else "")
                 for f in fails[:3]]
        more = f" and {len(fails) - 3} more" if len(fails) > 3 else ""
        parts.append(f"expectation(s) failed: {', '.join(shown)}{more}")
    if not parts:
        w = (s.get("agreement") or {}).get("worst")
        if not s.get("n_angles"):
            parts.append("no angle could be analysed")
        elif w:
            parts.append(f"methods disagree by {fmt(w['relative'], 2)} on {w['quantity']}")
    return "; ".join(parts) or "its check failed (see its report)"


def index_row(model_summary: dict, stem: str) -> dict:
    """One index row (index.md/pdf/csv/json) from a report's summary.json."""
    s = model_summary
    t = s.get("driver_torque") or s.get("driver_force") or {}
    big = s.get("largest_bearing_load")
    w = (s.get("agreement") or {}).get("worst")
    verdicts = ((s.get("design") or {}).get("verdicts")) or []
    failed = [v["item"] for v in verdicts if not v.get("passed")]
    power = s.get("mean_power")
    power_value = power.get("value") if isinstance(power, dict) else power

    def si(x, unit):
        return f"{fmt(x)} {unit}" if x is not None else DASH

    peak = t.get("peak") if t else None
    eu = t.get("unit", "N·m") if t else "N·m"
    at = "°" if s.get("axis_unit", "deg") == "deg" else " " + s["axis_unit"]
    return {
        "stem": stem, "spec": s["spec"], "name": s["name"], "ok": True,
        "status": s["status"],
        "peak": (f"{si(peak['value'], eu)} at {deg(peak['angle_deg'])}{at}" if peak else DASH),
        "rms": si(t.get("rms"), eu) if t else DASH,
        "bearing": (f"{si(big['value'], 'N')} ({big['joint']}, {deg(big['angle_deg'])}{at})"
                    + _away(big, at) if big else DASH),
        "power": si(power_value, "W") if power_value is not None else DASH,
        "worst": f"{fmt(w['relative'], 2)} ({w['quantity']})" if w else DASH,
        "verdicts": (f"{len(verdicts) - len(failed)}/{len(verdicts)} passed"
                     if verdicts else DASH),
        "failed_verdicts": failed,
        "failures": len(s.get("failures") or []),
        "report_md": f"{stem}/report.md", "report_pdf": f"{stem}/report.pdf",
        "message": "" if s["status"] == "PASS" else check_failure_reason(s),
        "data": {"peak_torque_N_m": peak["value"] if peak and eu != "N" else None,
                 "peak_torque_angle_deg": peak["angle_deg"] if peak and eu != "N" else None,
                 "rms_torque_N_m": t.get("rms") if t and eu != "N" else None,
                 "peak_driver_force_N": peak["value"] if peak and eu == "N" else None,
                 "rms_driver_force_N": t.get("rms") if t and eu == "N" else None,
                 "largest_bearing_load_N": big["value"] if big else None,
                 "largest_bearing_load_away_N": _away_value(big),
                 "largest_bearing_joint": big["joint"] if big else None,
                 "mean_power_W": power_value,
                 "worst_disagreement": w["relative"] if w else None,
                 "verdicts_passed": len(verdicts) - len(failed),
                 "verdicts_total": len(verdicts),
                 "failed_verdicts": failed,
                 "failed_expectations": len(s.get("failures") or []),
                 "spec_sha256": s.get("spec_sha256"),
                 "mechreport_version": s.get("mechreport_version")},
    }


# ------------------------------------------------------------------------------ entry

def build_model(analysis, source: str | Path | None = None, sha256: str | None = None,
                when: _dt.datetime | None = None, animation: bool = True) -> ReportModel:
    """The report model of ``analysis``; ``source`` is the spec path shown in the report.
    ``animation`` False leaves the animation out even where the spec's
    ``report.animation`` asks for it (``build --no-animation``)."""

    spec = analysis.spec
    source = str(source if source is not None else spec.file)
    stem = Path(source).stem
    summary = analysis.sweep_summary()
    ref = summary.method
    d = display_of(analysis)
    symbols = _symbols(spec)
    colors = _colors(spec)
    when = when or build_time()
    rs = spec.report
    meta = Meta(rs.title, rs.project, rs.author, rs.revision,
                when.strftime("%Y-%m-%d %H:%M UTC"), __version__,
                sha256 if sha256 is not None else spec_sha256(source), d.describe())
    status_line = summary_line(source, analysis)
    refs, scenes = _ref_angles(analysis, ref, symbols, colors, d)
    sw = _sweep(analysis, summary, symbols, colors, d)
    power_text, power_json = _power_check(summary.power_check, sw.method_title, d,
                                          spec.driver.at_rest)
    header, rows = _csv(analysis)
    design = _design(analysis, d)
    fails = failed_expectations(analysis)
    record = _summary(analysis, summary, sw, status_line, power_json, symbols, meta, fails,
                      d.scales)
    record["design"] = _design_json(analysis, d.scales)
    record["friction"] = _friction_json(analysis, d.scales)
    record["dynamics"] = dynamics_json(analysis)
    record["strength"] = strength_json(analysis)
    friction = _friction(analysis, design, sw, d)
    dynamics = dynamics_section(analysis, d)
    strength = strength_section(analysis, d, spec.axis_unit)
    figures = (_figures(sw, refs, ref, d) | _design_figures(design, d)
               | _friction_figures(friction, sw) | _dynamics_figures(dynamics)
               | _strength_figures(strength, d))
    shaking = {"force": _peak_text(summary.shaking_force, "force", d, sw.at_unit),
               "moment": _peak_text(summary.shaking_moment, "moment", d, sw.at_unit)}
    sweep = spec.sweep
    heads = {k: d.unit(k) for k in ("length", "velocity", "acceleration", "force", "moment",
                                    "mass", "inertia", "stress")}
    heads["axis"] = spec.axis_unit          # deg, or a stroke's length unit
    return ReportModel(
        stem=stem, source=source, name=spec.name,
        description=[p.strip() for p in spec.description.strip().split("\n\n") if p.strip()],
        status="PASS" if analysis.passed else "FAIL", status_line=status_line,
        method_title=METHODS[ref].TITLE,
        methods=[method_row(name) for name in METHODS if name in analysis.forces],
        links=_link_rows(spec, d), joints=_joint_rows(spec, symbols, d),
        branches=_branch_rows(analysis.kinematics),
        driver=_driver_text(spec), loads=_load_texts(spec, d),
        gravity=f"({fmt(spec.gravity[0])}, {fmt(spec.gravity[1])}) m/s²",
        sweep_text=(f"{effort_of(spec)[2]} {deg(sweep.start)}{effort_of(spec)[3]} to "
                    f"{deg(sweep.stop)}{effort_of(spec)[3]} in steps of "
                    f"{deg(sweep.step)}{effort_of(spec)[3]}: {analysis.kinematics.n} "
                    f"positions solved, {len(analysis.flags)} left out"),
        refs=refs, torque=_torque_texts(sw.stats, d, sw.effort, effort_of(spec)[3]),
        bearings=_bearing_rows(summary, sw, d), effort=sw.effort_label,
        effort_name="driver force" if sw.effort == "force" else "driver torque",
        coord=effort_of(spec)[2], coord_unit=effort_of(spec)[3],
        shaking=shaking, agreement=_agreement_rows(analysis, d), power_check=power_text,
        residuals=[[METHODS[r.method].TITLE, fmt(d.value(r.force, "force"), 2),
                    fmt(d.value(r.moment, "moment"), 2)] for r in analysis.residuals],
        flags=_flag_rows(analysis), left_out=_left_out_text(analysis, summary, sw, d),
        notes=analysis.kinematics.notes(), failures=failure_rows(fails), design=design,
        figures=figures, sweep=sw, scenes=scenes, csv_header=header, csv_rows=rows,
        summary=record, index_row=index_row(record, stem), meta=meta, display=d,
        heads=heads, friction=friction, dynamics=dynamics, strength=strength,
        animation=(animation_data(analysis, ref, sw, colors, symbols, sw.effort,
                                  effort_of(spec)[2], effort_of(spec)[3],
                                  [float(a) for a, r in zip(spec.at, refs) if r.flag is None],
                                  METHODS[ref].TITLE)
                   if animation and rs.animation else None),
        dxf=_dxf(spec, refs, scenes) if rs.dxf else None)


def _dxf(spec, refs: list[RefAngle], scenes: list[Scene]) -> DxfData:
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


def _left_out_text(analysis, summary: SweepSummary, sw: SweepData, d: Display) -> str:
    """One paragraph for the first page: which angles were left out and why, and which
    values lie near them (shown, but not used to scale the plots)."""
    if not analysis.flags:
        return "none: every angle of the sweep was solved and is trustworthy."
    rows = _flag_rows(analysis)
    shown = "; ".join(f"{a}°: {why}" for a, why in rows[:3])
    more = f"; and {len(rows) - 3} more (see Left-out angles)" if len(rows) > 3 else ""
    text = (f"{len(analysis.flags)} angle(s) left out of every table, plot and cycle "
            f"quantity (values there cannot be trusted to 1e-6): {shown}{more}.")
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


def _design(analysis, d: Display) -> DesignSummary:
    """Verdicts, cycle quantities, counterweight and the cycle's plot data."""
    spec, rev = analysis.spec, analysis.review
    verdict_rows = []
    for v in analysis.verdicts:
        kind = kind_of(v.unit)
        value = (d.q(v.value, kind) if v.value is not None else f"undefined: {v.why}")
        verdict_rows.append([v.item, v.quantity.replace("joint.*.", "largest joint ")
                             + (f" ({v.where})" if v.where else ""), value,
                             ("≥ " if v.at_least else "≤ ") + d.q(v.limit, kind),
                             _margin(v), "PASS" if v.passed else "FAIL"])
    passed = all(v.passed for v in analysis.verdicts)
    if rev is None:
        return DesignSummary(verdict_rows, [], "", "", analysis.review_problem, passed)
    values = []
    for name, value in rev.values.items():
        if name.startswith("joint."):
            continue
        kind = kind_of(unit_of(name))
        values.append([MEANING.get(name, name), name, d.q(value, kind)])
    bearings: dict[str, list[str]] = {}
    attrs = ["f_max", "f_mean", "f_equivalent", "life_h"]
    for name, value in rev.values.items():       # per joint: bearing loads and lives
        if name.startswith("joint."):     # joint.C.on.upper.f_max: a pin's force on a link
            joint, attr = name[len("joint."):].rsplit(".", 1)
            row = bearings.setdefault(joint, [joint] + [DASH] * len(attrs))
            if attr in attrs:
                row[1 + attrs.index(attr)] = d.num(value, kind_of(unit_of(name)))
    cw = rev.counterweight
    if cw.worthwhile:
        counter = (f"A point counterweight of m·r = {d.q(cw.mr, 'mass_length')} at "
                   f"{d.num(cw.angle, 'angle')}° from the crank's x-axis brings the RMS "
                   f"inertial shaking force from {d.q(cw.rms_before, 'force')} to "
                   f"{d.q(cw.rms_after, 'force')} ({fmt(-100 * cw.reduction, 3)} %).")
    elif cw.mr > 0:
        counter = (f"No counterweight is recommended: the best point counterweight on the "
                   f"crank (m·r = {d.q(cw.mr, 'mass_length')} at "
                   f"{d.num(cw.angle, 'angle')}°) would reduce the RMS inertial shaking "
                   f"force ({d.q(cw.rms_before, 'force')}) by less than "
                   f"{fmt(100 * NOTICEABLE)} %.")
    else:
        counter = ("The crank needs no counterweight: the inertial shaking force has no "
                   "component turning with it.")
    interp = ""
    if len(rev.cycle.interpolated):
        interp = ("Left-out angles inside the cycle, interpolated from their neighbours for "
                  "the cycle quantities: " + ", ".join(deg(a) for a in rev.cycle.interpolated)
                  + " deg.")
    sources = analysis.cycle_torque_by_source()
    data = CycleData(rev.cycle.angles, rev.torque, rev.values["cycle.torque.mean"], rev.energy,
                     spec.design.motor.get("rated_torque"), spec.design.motor.get("peak_torque"),
                     sources, rev.transmission,
                     spec.design.limits.get("transmission_angle"),
                     rev.inertial, rev.shaking_balanced,
                     [float(a) for a in rev.cycle.interpolated],
                     [name for name, part in sources.items() if d.zero(part, "moment")],
                     rev.cycle.period, *_pressures(spec, rev.cycle.angles))
    return DesignSummary(verdict_rows, values, counter, interp, "", passed, data,
                         list(bearings.values()), _absent_figures(spec, rev, d))


def _pressures(spec, angles: np.ndarray) -> tuple[dict[str, np.ndarray], str]:
    """Each pressure load's pressure at ``angles`` [deg] as written (the profile's values,
    phased by its shift; absolute or gauge as the profile is), in ``report.units.pressure``
    (default: the first pressure load's unit), and that unit."""
    loads = [ld for ld in spec.loads if ld.pressure is not None]
    if not loads:
        return {}, "Pa"
    unit = (spec.report.units or {}).get("pressure", loads[0].pressure.unit)
    scale = PRESSURE_UNITS[unit]
    return ({ld.label: profile_at(ld.pressure.profile, angles, spec.cycle, ld.shift)
             * (ld.pressure.scale / scale) for ld in loads}, unit)


def _absent_figures(spec, rev, d: Display) -> dict[str, str]:
    """The cycle figures that would show nothing, each with the sentence the report prints
    instead: the flywheel diagram where the driver's torque does no work that fluctuates
    (at rest, or a constant torque), the balancing diagram where there is no inertial
    shaking force (0 at every angle by the round-off rule)."""
    out = {}
    if spec.driver.at_rest:
        out["flywheel"] = ("No flywheel diagram: at rest the driver's torque does no work "
                           "over a turn.")
    elif d.zero(rev.values["cycle.energy_fluctuation"], "moment"):
        out["flywheel"] = ("No flywheel diagram: the driver's torque is the same at every "
                           "angle, so there is no energy fluctuation for a flywheel to take up.")
    if d.zero(rev.inertial, "force"):
        why = ("at rest no link accelerates" if spec.driver.at_rest else
               "the links' inertia forces cancel at every angle")
        out["balance"] = (f"No balancing diagram: {why}, so there is no inertial shaking "
                          "force for a counterweight to balance.")
    return out


# ------------------------------------------------------------------------------ friction

def _friction(analysis, design: DesignSummary, sw: SweepData, d: Display
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
        peak = _largest(values.get(fr.joint), analysis.angles)
        rows.append([fr.joint, "pin (R)" if j.type == "R" else "slider (T)",
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


def friction_symbol(spec, joint) -> str:
    """The textbook's name of a joint's friction: Mf12, the couple of link 1 on link 2 in an
    R joint; Ff03, the force of link 0 on link 3 along a T joint's line."""
    return spec.symbol(*joint.links, "Mf" if joint.type == "R" else "Ff")


def _largest(values: np.ndarray | None, angles: np.ndarray) -> tuple[float, float] | None:
    """(largest |value|, its angle [deg]) over the analysed angles; None without a finite
    value."""
    if values is None or not len(values):
        return None
    mag = np.abs(np.asarray(values, float))
    if not np.any(np.isfinite(mag)):
        return None
    k = int(np.nanargmax(mag))
    return float(mag[k]), float(angles[k])


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
    """The effort with and without friction: over the cycle grid when there is a review
    (the breakdown's ``friction`` source), else over the analysed angles of the sweep (the
    reference method's effort split by source)."""
    cd = design.data
    flipped = [float(a) for a in analysis.kinematics.reversed_by_friction]
    if cd is not None and "friction" in cd.sources:
        without = cd.torque - cd.sources["friction"]
        rev = analysis.review
        return FrictionPlot(cd.angles, cd.torque, without, "moment", effort_name,
                            (cd.mean, rev.cycle.mean(without)), list(cd.interpolated),
                            None, flipped)
    if not len(sw.angles):
        return None
    res = analysis.forces[analysis.sweep_summary().method]
    part = analysis.by_source(res.method).get("friction", {}).get(res.driver_quantity)
    if part is None:
        return None
    return FrictionPlot(sw.angles, sw.torque, sw.torque - part, sw.effort, effort_name,
                        None, [], sw, flipped)


def _friction_json(analysis, sc: dict) -> dict | None:
    """summary.json's ``friction`` (None without friction): per joint its data, its loss per
    cycle and largest value over the sweep; the energy lost per cycle and the efficiency
    (SI, with units; each value as in ``design.cycle``)."""
    spec, rev = analysis.spec, analysis.review
    if not spec.friction:
        return None
    losses = rev.friction if rev is not None else {}
    total = rev.values.get("cycle.friction.energy") if rev is not None else None
    joints = {}
    for fr in spec.friction:
        j = spec.joint(fr.joint)
        unit = "N·m" if j.type == "R" else "N"
        peak = _largest((analysis.kinematics.friction or {}).get(fr.joint), analysis.angles)
        lost = losses.get(fr.joint)
        joints[fr.joint] = {
            "type": j.type, "symbol": friction_symbol(spec, j), "mu": fr.mu,
            "radius": None if fr.radius is None else {"value": fr.radius, "unit": "m"},
            "length": None if fr.length is None else {"value": fr.length, "unit": "m"},
            "energy_per_cycle": None if lost is None else {"value": jnum(lost), "unit": "J"},
            "share": jnum(lost / total) if lost is not None and total else None,
            "largest": None if peak is None else {
                "value": jnum(peak[0], sc.get("moment" if j.type == "R" else "force")),
                "unit": unit, "angle_deg": peak[1]}}
    eff = rev.values.get("cycle.efficiency") if rev is not None else None
    if rev is None:
        why = f"no cycle quantities: {analysis.review_problem}"
    else:
        why = None if eff is not None else efficiency_undefined(analysis.spec)
    return {"joints": joints,
            "energy_per_cycle": None if total is None else {"value": jnum(total), "unit": "J"},
            "efficiency": None if eff is None else {"value": jnum(eff), "unit": ""},
            "efficiency_undefined": why,
            "reversed_by_friction_deg": [float(a) for a in
                                         analysis.kinematics.reversed_by_friction],
            "left_out_deg": [f.angle for f in analysis.flags if f.by_friction]}


def _dynamics_figures(section) -> dict[str, Figure]:
    """The Machine dynamics figure and its caption (none without dynamics)."""
    if section is None:
        return {}
    text = ("Crank speed from the start (left: the steady mean dashed, 95 % of it dotted)"
            + (" and over the steady turn (right)." if len(section.plot.angles) else "."))
    return {"dynamics": Figure("dynamics", text, "dynamics")}


def _friction_figures(section: FrictionSection | None, sw: SweepData) -> dict[str, Figure]:
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


def _strength_figures(section: StrengthSection | None, d: Display) -> dict[str, Figure]:
    """The Strength section's figures: N, V, M of the most loaded member, the stress over
    the sweep (none without a section)."""
    if section is None or section.plot is None:
        return {}
    sp = section.plot
    where = (f"φ = {deg(sp.angle)}°" if sp.xlabel.startswith("crank") else
             f"{sp.xlabel.split(' [')[0]} {deg(sp.angle)} {sp.xlabel.split('[')[-1][:-1]}")
    return {"strength": Figure("strength", f"Internal forces along member {sp.member} at "
                               f"{where}, where its stress is largest: axial force N "
                               "(tension positive), shear V and bending moment M (sagging "
                               "positive), s from its first point.", "strength"),
            "stress": Figure("stress", "The largest stress |N|/A + |M|c/I along each member "
                             "over the sweep.", "stress")}


#: what each cycle quantity means, for the Design summary table
MEANING = {
    "cycle.torque.max": "largest driver torque", "cycle.torque.min": "smallest driver torque",
    "cycle.torque.mean": "mean driver torque", "cycle.torque.rms": "RMS driver torque",
    "cycle.power.max": "peak driver power", "cycle.power.mean": "mean driver power",
    "cycle.energy_fluctuation": "energy fluctuation ΔE",
    "cycle.flywheel_inertia": "flywheel inertia for Cs",
    "cycle.friction.energy": "energy lost to friction per cycle",
    "cycle.efficiency": "mechanical efficiency",
    "cycle.shaking.force_max": "peak shaking force",
    "cycle.shaking.force_rms": "RMS shaking force",
    "cycle.shaking.moment_max": "peak shaking moment",
    "cycle.transmission_angle.min": "smallest transmission angle",
    "cycle.transmission_angle.max": "largest transmission angle",
    "cycle.inertia_shaking.force_rms": "RMS inertial shaking force",
    "balance.counterweight.mr": "best counterweight m·r",
    "balance.counterweight.angle": "its angle from the crank",
    "balance.inertia_shaking.force_rms": "RMS inertial shaking, balanced",
    "dynamics.speed_fluctuation": "speed fluctuation",
    "dynamics.mean_rpm": "mean crank speed",
    "dynamics.startup_time": "start-up time (to 95 %)",
    "dynamics.motor_rms_torque": "motor's RMS torque",
    "f_max": "peak bearing load", "f_mean": "mean bearing load",
    "f_equivalent": "equivalent (cube-mean) load", "life_h": "L10 rating life",
}


def _margin(v) -> str:
    """A verdict's margin: ``+24.1 %`` of the limit; ``value 537× limit`` when it is huge."""
    if v.margin is None:
        return DASH
    if abs(v.margin) > 9.99:
        ratio = v.value / v.limit if v.limit else float("inf")
        return f"value {fmt(ratio, 3)}× limit"
    text = f"{v.margin * 100:+.1f} %"
    return "0.0 %" if text in ("+0.0 %", "-0.0 %") else text


def _design_json(analysis, sc: dict) -> dict:
    """summary.json's ``design``: verdicts and cycle quantities, each value as in
    ``quantities`` (round-off of its kind made 0, :func:`jnum`)."""
    rev = analysis.review
    out: dict = {"verdicts": [{"item": v.item, "quantity": v.quantity, "value": jnum(v.value),
                               "limit": v.limit, "unit": v.unit, "lower_limit": v.at_least,
                               "margin": jnum(v.margin), "passed": v.passed,
                               "joint": v.where or None, "why": v.why or None}
                              for v in analysis.verdicts],
                 "cycle_undefined": analysis.review_problem or None}
    if rev is not None:
        out["cycle"] = {name: {"value": jnum(value, sc.get(kind_of(unit_of(name) or ""))),
                               "unit": unit_of(name)}
                        for name, value in rev.values.items()}
        out["method"] = rev.method
        out["interpolated_deg"] = [float(a) for a in rev.cycle.interpolated]
    return out


def _design_figures(design: DesignSummary, d: Display) -> dict[str, Figure]:
    """The Design summary's figures with their captions: the flywheel diagram, the torque
    by source, the transmission angle, the balancing diagram; those in ``design.absent``
    left out (the report says why instead)."""
    cd = design.data
    if cd is None:
        return {}
    silent = cd.silent
    if silent:
        names = ", ".join(silent)
        silent_text = (f" Not drawn: {names} ({'its' if len(silent) == 1 else 'their'} "
                       f"torque is {d.q(0.0, 'moment')} at every angle).")
    else:
        silent_text = ""
    span = cd.span
    figs = {"flywheel": Figure("flywheel", f"Driver torque over {span} against its mean: the "
                               "areas above (energy taken in) and below (given back) the mean "
                               "line; the largest energy fluctuation ΔE, which the flywheel "
                               "absorbs, lies between the two marked angles.", "flywheel"),
            "breakdown": Figure("breakdown", f"Driver torque by source over {span}: each "
                                "source's share stacked (positive above zero, negative below); "
                                f"the line is the total.{silent_text}", "breakdown"),
            "balance": Figure("balance", f"Inertial shaking force (sum of m a_C) over {span}, "
                              "without and with the best point counterweight on the crank.",
                              "balance")}
    if cd.pressures:
        several = len(cd.pressures) > 1
        figs["pressure"] = Figure("pressure", f"Pressure diagram: the pressure on "
                                  f"{'each piston' if several else 'the piston'} against the "
                                  f"crank angle over {span}, as the spec gives it "
                                  f"(absolute or gauge), in {cd.pressure_unit}.", "pressure")
        figs["turning_moment"] = Figure(
            "turning_moment", f"Turning-moment diagram: the crank effort (what the "
            f"{'cylinders give' if several else 'cylinder gives'} the shaft, minus the driver "
            f"torque) over {span} against its mean; each area between two crossings is "
            "labelled with its energy, + in excess of the mean, − short of it."
            + (" Below: each cylinder's share (its gas force's part of the torque)."
               if several else ""), "turning_moment")
    if cd.transmission:
        limit = (", with the design limit" if cd.transmission_limit is not None else "")
        figs["transmission"] = Figure("transmission", "Transmission angle of each group over "
                                      f"{span} (folded into 0-90°){limit}.", "transmission")
    return {k: f for k, f in figs.items() if k not in design.absent}


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


def _figures(sw: SweepData, refs: list[RefAngle], ref: str, d: Display) -> dict[str, Figure]:
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
