"""The report result model: every number a report prints, built once from an Analysis.

The report document (its Markdown and Typst writers), results.csv, summary.json, the plots
and the drawings all read a :class:`ReportModel`; none of them computes mechanics. Printed
values are strings already formatted by the one formatter (:mod:`mechreport.units`) in the
spec's display units (``report.units``; undefined values print as "—"); the plot data
are float arrays (n,) over the analysed crank angles [deg], in SI, converted by the plots
through ``model.display``.
results.csv and summary.json are SI, with the unit in every column name or field.

This module only assembles the model: each section is built by its own module
(:mod:`.spec_text` the spec's description, :mod:`.ref_angles` the reference angles,
:mod:`.sweep_section` the sweep, :mod:`.design` the Design summary, :mod:`.friction`,
:mod:`.dynamics`, :mod:`.strength`, :mod:`.records` results.csv, summary.json and the
index row).
"""
from __future__ import annotations

import datetime as _dt
from dataclasses import dataclass
from pathlib import Path

from ..checks.failures import failed_expectations
from ..forces import METHODS
from ..units import Display, deg, fmt
from ..version import __version__
from .check_text import failure_rows, summary_line
from .design import DesignSummary, design_figures, design_summary
from .dynamics import dynamics_section
from .frames import Animation, animation_data
from .friction import FrictionSection, friction_figures, friction_section
from .provenance import Meta, build_time, spec_sha256
from .records import index_row, summary_json
from .ref_angles import DxfData, RefAngle, dxf_data, reference_angles
from .scene import Scene
from .section import Figure, display_of, effort_of, joint_colors, reaction_symbols
from .spec_text import (MethodRow, branch_rows, driver_text, joint_rows, link_rows,
                        load_texts, method_row)
from .strength import StrengthSection, strength_section
from .sweep_section import (SweepData, agreement_rows, bearing_rows, flag_rows,
                            left_out_text, peak_text, power_check_text,
                            sweep_figures, sweep_series, torque_texts)
from .text import cycle_name

#: what other modules import from here (a section's own names from its module above)
__all__ = ["ReportModel", "build_model"]


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
    symbols = reaction_symbols(spec)
    colors = joint_colors(spec)
    when = when or build_time()
    rs = spec.report
    meta = Meta(rs.title, rs.project, rs.author, rs.revision,
                when.strftime("%Y-%m-%d %H:%M UTC"), __version__,
                sha256 if sha256 is not None else spec_sha256(source), d.describe())
    status_line = summary_line(source, analysis)
    refs, scenes = reference_angles(analysis, ref, symbols, colors, d)
    sw = sweep_series(analysis, summary, symbols, colors, d)
    power_text = power_check_text(summary.power_check, sw.method_title, d, spec.driver.at_rest)
    header, rows = analysis.results_table()
    design = design_summary(analysis, d)
    fails = failed_expectations(analysis)
    record = summary_json(analysis, meta, status_line, fails)
    friction = friction_section(analysis, design, sw, d)
    dynamics = dynamics_section(analysis, d)
    strength = strength_section(analysis, d, spec.axis_unit)
    figures = (sweep_figures(sw, refs, ref, d) | design_figures(design, d)
               | friction_figures(friction, sw) | _dynamics_figures(dynamics)
               | _strength_figures(strength, d))
    shaking = {"force": peak_text(summary.shaking_force, "force", d, sw.at_unit),
               "moment": peak_text(summary.shaking_moment, "moment", d, sw.at_unit)}
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
        links=link_rows(spec, d), joints=joint_rows(spec, symbols, d),
        branches=branch_rows(analysis.kinematics),
        driver=driver_text(spec), loads=load_texts(spec, d),
        gravity=f"({fmt(spec.gravity[0])}, {fmt(spec.gravity[1])}) m/s²",
        sweep_text=(f"{effort_of(spec)[2]} {deg(sweep.start)}{effort_of(spec)[3]} to "
                    f"{deg(sweep.stop)}{effort_of(spec)[3]} in steps of "
                    f"{deg(sweep.step)}{effort_of(spec)[3]}: {analysis.kinematics.n} "
                    f"positions solved, {len(analysis.flags)} left out"),
        refs=refs, torque=torque_texts(sw.stats, d, sw.effort, effort_of(spec)[3]),
        bearings=bearing_rows(summary, sw, d), effort=sw.effort_label,
        effort_name="driver force" if sw.effort == "force" else "driver torque",
        coord=effort_of(spec)[2], coord_unit=effort_of(spec)[3],
        shaking=shaking, agreement=agreement_rows(analysis, d), power_check=power_text,
        residuals=[[METHODS[r.method].TITLE, fmt(d.value(r.force, "force"), 2),
                    fmt(d.value(r.moment, "moment"), 2)] for r in analysis.residuals],
        flags=flag_rows(analysis), left_out=left_out_text(analysis, summary, sw, d),
        notes=analysis.kinematics.notes(), failures=failure_rows(fails), design=design,
        figures=figures, sweep=sw, scenes=scenes, csv_header=header, csv_rows=rows,
        summary=record, index_row=index_row(record, stem), meta=meta, display=d,
        heads=heads, friction=friction, dynamics=dynamics, strength=strength,
        animation=(animation_data(analysis, ref, sw, colors, symbols, sw.effort,
                                  effort_of(spec)[2], effort_of(spec)[3],
                                  [float(a) for a, r in zip(spec.at, refs) if r.flag is None],
                                  METHODS[ref].TITLE)
                   if animation and rs.animation else None),
        dxf=dxf_data(spec, refs, scenes) if rs.dxf else None)


def _dynamics_figures(section) -> dict[str, Figure]:
    """The Machine dynamics figure and its caption (none without dynamics)."""
    if section is None:
        return {}
    plot = section.plot
    over = f"over the steady {cycle_name(plot.cycle)}, its largest and smallest speed marked"
    if not plot.startup_shown:          # mean_rpm: no start-up
        text = f"Crank speed {over} (the mean dashed)."
    else:
        text = ("Crank speed from the start (left: the steady mean dashed, 95 % of it dotted)"
                + (f" and {over} (right)." if len(plot.angles) else "."))
    return {"dynamics": Figure("dynamics", text, "dynamics")}


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
