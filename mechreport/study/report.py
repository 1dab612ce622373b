"""study.md and study.pdf: what was varied and how, the counts, the ten best passing variants,
the Pareto front of the first two kept quantities, each kept quantity against each varied
key, why variants failed, and the cross-check. Figures are SVG files in ``study-figures/``.

Kept quantities are shown in SI (the units of the table's columns), varied values in the
spec's own units (as written in ``vary``). Varied keys and kept quantities are the spec's text
(they may hold link, point and joint names): the figures draw them literally
(:func:`mechreport.report.plots.literal`)."""
from __future__ import annotations

import math
from collections import Counter
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..forces import METHODS
from ..report.plots import styled
from ..units import fmt, pretty, with_unit
from ..report.document import Code, Doc, Print, Strong
from .plan import SAMPLING_NAMES
from .table import Table, badness, column_name, larger_is_better, quantity_unit

FIGURES = "study-figures"
BEST = 10                 # variants in the best-variants table
MAX_POINTS = 4000         # points drawn per scatter panel (a seeded sample of the rest)
PANELS = 3                # panels per figure row
MAX_TABLE_QUANTITIES = 4  # kept quantities shown in the best-variants table


@dataclass
class StudyRun:
    """Everything the study's outputs say. ``where``: how it ran (processes, cluster);
    ``method_why``: why this method; ``cross``: the cross-check (or None); ``reports``:
    (rank, variant index, folder or None, message) of the full reports built."""

    base: object
    table: Table
    method: str
    method_why: str
    seconds: float
    where: str
    chunk: int
    sha256: str = ""
    cross: object | None = None
    reports: list = field(default_factory=list)
    date: str = ""

    @property
    def plan(self):
        return self.table.plan


# ----------------------------------------------------------------------------- units

def key_unit(path: tuple, units: dict[str, str], loads: list | None = None) -> str:
    """The unit a varied leaf is written in (the spec's own units); "" when it has none or
    is not known. ``loads``: the spec's ``loads`` list as written (for load values)."""
    length, mass = units.get("length", "m"), units.get("mass", "kg")
    force, moment = units.get("force", "N"), pretty(units.get("moment", "N*m"))
    rate = "N/m" if force == "N" else f"{force}/{length}"    # (as the loader reads it)
    head, last = path[0], path[-1]
    names = [p for p in path if isinstance(p, str)]
    if head in ("ground", "assembly"):
        return length
    if head == "links":
        if "points" in names or "com" in names:
            return length
        if "shape" in names:
            return length
        return {"mass": mass, "density": "kg/m^3",
                "inertia": pretty(units.get("inertia", "kg*m^2"))}.get(last, "")
    if head == "joints":
        return length if "through" in names else ""
    if head == "driver":
        return {"rpm": "rpm", "omega": "rad/s", "alpha": "rad/s^2",
                "speed": f"{length}/s", "accel": f"{length}/s^2"}.get(last, "")
    if head in ("sweep", "at"):
        return "deg"
    if head == "gravity":
        return "m/s^2"
    if head == "design":
        table = {"rated_torque": moment, "peak_torque": moment, "rated_power": "W",
                 "rating": force, "life_h": "h", "joint_force": force,
                 "transmission_angle": "deg", "shaking_force": force}
        return table.get(last, "")
    if head == "loads" and len(path) >= 3 and loads is not None:
        item = loads[path[1]] if isinstance(path[1], int) and path[1] < len(loads) else {}
        kind = item.get("type") if isinstance(item, dict) else None
        effort = moment if kind == "moment" else force
        field_ = path[2]
        if field_ == "value":
            return effort
        if field_ == "profile":
            return "deg" if path[-1] == 0 else effort
        if field_ == "stiffness":
            return f"{moment}/rad" if kind == "torsion_spring" else rate
        if field_ == "free_length":
            return length
        if field_ == "free_angle":
            return "deg"
        if field_ == "damping":
            return "N s/m" if force == "N" else f"{rate}*s"
    return ""


def key_units(base) -> dict[str, str]:
    loads = base.data.get("loads") if isinstance(base.data.get("loads"), list) else None
    return {k: key_unit(p, base.spec.units, loads) for k, p in base.paths.items()}


# ---------------------------------------------------------------------------- figures

def _sample(n: int, keep_too: np.ndarray, limit: int = MAX_POINTS) -> np.ndarray:
    """Indices of at most ``limit`` of ``n`` rows (seeded), always with ``keep_too``."""
    if n <= limit:
        return np.arange(n)
    rng = np.random.default_rng(0)
    pick = rng.choice(n, size=limit, replace=False)
    return np.unique(np.concatenate([pick, np.asarray(keep_too, int)]))


def _best_line(x: np.ndarray, y: np.ndarray, better_large: bool, levels: int | None):
    """The best value of ``y`` per value (grid) or per bin (random, lhs) of ``x``."""
    if not len(x):
        return np.zeros(0), np.zeros(0)
    ux = np.unique(x)
    if levels is not None and len(ux) <= 60:
        xs, ys = [], []
        for v in ux:
            sel = y[x == v]
            ys.append(sel[np.argmax(sel)] if better_large else sel[np.argmin(np.abs(sel))])
            xs.append(v)
        return np.asarray(xs), np.asarray(ys)
    edges = np.linspace(np.min(x), np.max(x), 21)
    which = np.clip(np.digitize(x, edges) - 1, 0, 19)
    xs, ys = [], []
    for b in range(20):
        sel = which == b
        if not np.any(sel):
            continue
        yy = y[sel]
        xs.append(0.5 * (edges[b] + edges[b + 1]))
        ys.append(yy[np.argmax(yy)] if better_large else yy[np.argmin(np.abs(yy))])
    return np.asarray(xs), np.asarray(ys)


def robust_limits(values: np.ndarray) -> tuple[float, float] | None:
    """Axis limits for ``values`` without the few outliers that would flatten the rest
    (near-singular variants): the 1st to 99th percentile, widened by 15 %, when the whole
    range is more than three times that; None when the whole range fits."""
    v = np.asarray(values, float)
    v = v[np.isfinite(v)]
    if len(v) < 20:
        return None
    lo, hi = np.percentile(v, [1, 99])
    span = hi - lo
    if span <= 0 or (v.max() - v.min()) <= 3 * span:
        return None
    return float(lo - 0.15 * span), float(hi + 0.15 * span)


def _scatter(ax, x, y, sel, color, dot, alpha, raster, label, limits):
    """Dots of the rows ``sel``; with ``limits``, those beyond are drawn at the edge as
    triangles (so the scale shows the bulk of the variants)."""
    if limits is None:
        ax.scatter(x[sel], y[sel], s=dot, color=color, alpha=alpha, lw=0, rasterized=raster,
                   label=label)
        return
    lo, hi = limits
    inside = sel & (y >= lo) & (y <= hi)
    ax.scatter(x[inside], y[inside], s=dot, color=color, alpha=alpha, lw=0,
               rasterized=raster, label=label)
    for edge, mask, marker in ((lo, sel & (y < lo), "v"), (hi, sel & (y > hi), "^")):
        if np.any(mask):
            ax.scatter(x[mask], np.full(int(mask.sum()), edge), s=max(dot, 9), color=color,
                       marker=marker, lw=0, alpha=alpha, clip_on=False, rasterized=raster)


@styled
def write_figures(run: StudyRun, folder: Path) -> dict[str, str]:
    """The SVG figures; returns {name: relative path}."""
    from ..report.plots import GREY, INK, OKABE_ITO, figure, legend_top, literal, save
    t, plan = run.table, run.plan
    units = key_units(run.base)
    folder = Path(folder)
    out: dict[str, str] = {}
    ok, passing = t.ok, t.passing
    front = t.pareto()
    show = _sample(t.n, np.concatenate([front, t.ranked()[:BEST]]))
    shown_ok = np.zeros(t.n, bool)
    shown_ok[show] = True
    shown_all = shown_ok
    okf, passf = ok & shown_ok & ~passing, passing & shown_ok
    # a spec without `design:` has no review to pass or fail: its variants are just shown
    reviewed = not run.base.spec.design.empty
    fails_label = "fails the design review" if okf.any() else "_nolegend_"
    passes_label = "passes" if reviewed else "variant"
    n_shown = int(np.count_nonzero(ok & shown_ok))
    raster = n_shown > 400                       # many dots: a bitmap inside the SVG
    dot = 16 if n_shown <= 200 else 7 if n_shown <= 2000 else 3
    alpha = 0.8 if n_shown <= 200 else 0.5
    failed = ~ok & t.done
    d = len(plan.keys)
    for j, q in enumerate(t.keep):
        rows = max(1, math.ceil(d / PANELS))
        cols = min(d, PANELS)
        fig, axes = figure(1.95 * rows + 0.2, rows, cols, gap=0.75, wgap=0.55,
                           margins=(0.62, 0.12, 0.46, 0.36))
        y = t.values[:, j]
        limits = robust_limits(y[ok])
        for k, key in enumerate(plan.keys):
            ax = axes[k // PANELS][k % PANELS]
            x = plan.values[:, k]
            _scatter(ax, x, y, okf, GREY, dot, alpha, raster, fails_label, limits)
            _scatter(ax, x, y, passf, OKABE_ITO[0], dot, alpha, raster, passes_label, limits)
            bx, by = _best_line(x[passing], y[passing], larger_is_better(q),
                                1 if plan.sample == "grid" else None)
            if len(bx):
                if limits is not None:
                    by = np.clip(by, *limits)
                ax.plot(bx, by, color=OKABE_ITO[5], lw=1.2, marker="o", ms=2.5,
                        label="best passing")
            if np.any(failed):                  # where variants failed: a rug on the axis
                fx = np.unique(x[failed & shown_all])
                ax.plot(fx, np.full(len(fx), 0.03), "|", color=OKABE_ITO[3], ms=6,
                        mew=0.8, alpha=0.8 if len(fx) < 100 else 0.35,
                        transform=ax.get_xaxis_transform(), clip_on=False,
                        label="failed (no value)")
            if limits is not None:
                ax.set_ylim(*limits)
            ax.set_xlabel(literal(with_unit(key, units.get(key, ""))), fontsize=7.5)
            if k % PANELS == 0:
                ax.set_ylabel(literal(column_name(q)), fontsize=7.5)
        for k in range(d, rows * cols):
            axes[k // PANELS][k % PANELS].set_visible(False)
        handles, labels = axes[0][0].get_legend_handles_labels()
        fig.legend(handles, labels, loc="upper left", bbox_to_anchor=(0.62 / 6.5, 1.0),
                   ncol=4, frameon=False, borderaxespad=0.2, handlelength=2.0)
        name = f"quantity-{j + 1}"
        save(fig, folder, name)
        out[name] = f"{FIGURES}/{name}.svg"
    if len(t.keep) >= 2:
        fig, axes = figure(3.4, 1, 1, margins=(0.72, 0.2, 0.5, 0.4), width=5.2)
        ax = axes[0][0]
        a, b = t.values[:, 0], t.values[:, 1]
        la, lb = robust_limits(a[ok]), robust_limits(b[ok])
        inside = np.ones(t.n, bool)
        if la is not None:
            inside &= (a >= la[0]) & (a <= la[1])
            ax.set_xlim(*la)
        if lb is not None:
            inside &= (b >= lb[0]) & (b <= lb[1])
            ax.set_ylim(*lb)
        ax.scatter(a[okf & inside], b[okf & inside], s=dot, color=GREY, alpha=alpha, lw=0,
                   rasterized=raster, label=fails_label)
        ax.scatter(a[passf & inside], b[passf & inside], s=dot, color=OKABE_ITO[0],
                   alpha=alpha, lw=0, rasterized=raster, label=passes_label)
        if len(front):
            ax.plot(a[front], b[front], color=OKABE_ITO[5], lw=1.2, marker="o", ms=3.5,
                    label="Pareto front (passing)")
        outside = int(np.count_nonzero(ok & ~inside))
        if outside:
            ax.text(0.99, 0.02, f"{outside} variant(s) beyond the scale, not drawn",
                    transform=ax.transAxes, ha="right", va="bottom", fontsize=7, color=INK,
                    bbox={"facecolor": "white", "edgecolor": "none", "alpha": 0.8})
        ax.set_xlabel(literal(column_name(t.keep[0])))
        ax.set_ylabel(literal(column_name(t.keep[1])))
        legend_top(ax, 3)
        save(fig, folder, "pareto")
        out["pareto"] = f"{FIGURES}/pareto.svg"
    return out


# --------------------------------------------------------------------------- document

def _better(q: str) -> str:
    return "larger is better" if larger_is_better(q) else "smaller magnitude is better"


def _range_text(v, unit: str) -> str:
    if v.values is not None:
        shown = ", ".join(fmt(x, 6) for x in v.values[:8])
        more = f", ... ({len(v.values)} values)" if len(v.values) > 8 else ""
        return f"{shown}{more}"
    u = f" {unit}" if unit else ""
    count = f"{v.count} values " if v.count else ""
    return f"{count}from {fmt(v.start, 6)} to {fmt(v.stop, 6)}{u}"


def _sampling_text(run: StudyRun) -> str:
    study = run.base.spec.study
    if study.sample == "grid":
        note = (" (study.count is for random and lhs sampling: not used)"
                if study.count else "")
        return f"grid: every combination of the {len(study.vary)} varied key(s){note}"
    return f"{SAMPLING_NAMES[study.sample]} sampling, seed {study.seed}"


class StudyDoc(Doc):
    """The study report's document: its tables split into parts of at most
    :data:`MAX_COLUMNS` columns in print (repeating rank and variant), their headers
    breakable (long key paths); its figures' captions repeated under them in Markdown."""

    def table(self, header, rows, right=frozenset(), note="", print=None) -> None:
        lead = 2 if header[1:2] == ["variant"] else 1
        super().table(header, rows, right, note,
                      Print(max_columns=MAX_COLUMNS, lead=lead, wrap=True))

    def image(self, path, caption, height=None, **how) -> None:
        super().image(path, caption, height, caption_below=True, **how)


MAX_COLUMNS = 8   # columns of a study table that fit a page side by side


def provenance(doc: Doc, file: str, sha256: str = "", date: str = "") -> None:
    """The first line of a study, tolerance or optimisation report: the spec's file, the
    start of its SHA-256, the mechreport version and the date."""
    from ..version import __version__
    sha = f" (SHA-256 {sha256[:16]}...)" if sha256 else ""
    doc.p("Spec ", Code(file), f"{sha}; mechreport {__version__}", f"; {date}." if date else ".")


def build_document(run: StudyRun, figures: dict[str, str]) -> Doc:
    t, plan = run.table, run.plan
    spec = run.base.spec
    units = key_units(run.base)
    doc = StudyDoc(f"Design study: {spec.name}")
    ok, passing = t.ok, t.passing
    n_ok, n_pass = int(np.count_nonzero(ok)), int(np.count_nonzero(passing))
    n_failed = int(t.n - n_ok)
    provenance(doc, spec.file, run.sha256, run.date)
    doc.p(Strong(f"{t.n} variants"), f" ({_sampling_text(run)}), analysed by ",
          Strong(method_title(run.method)), f" ({run.method}: {run.method_why})"
          f" on {run.where}, in chunks of {run.chunk}, in {run.seconds:.1f} s. A study runs one "
          "force method for every variant; the full cross-check of all methods is for single "
          "reports (mechreport build), and --cross-check N re-runs N variants with every "
          "method.")
    design_note = ("" if not spec.design.empty else
                   " The spec has no design section: every completed variant counts as passing.")
    doc.table(["variants", "count"],
              [["analysed", str(t.n)], ["completed, with every kept quantity", str(n_ok)],
               ["pass the design review", str(n_pass)],
               ["fail the design review", str(n_ok - n_pass)],
               ["failed (see Failed variants)", str(n_failed)]], right={1}, note=design_note)

    doc.h("Varied keys")
    doc.p("Each variant is the spec with these leaves replaced, in the spec's own units.")
    doc.table(["key", "unit", "values"],
              [[v.key, units.get(v.key, "") or "—", _range_text(v, units.get(v.key, ""))]
               for v in spec.study.vary])

    doc.h("Kept quantities")
    doc.p("In SI, over the variants that completed; the best is taken over the passing ones.")
    rows = []
    for j, q in enumerate(t.keep):
        col = t.values[ok, j]
        if n_pass:                                  # best by this quantity alone
            sel = np.flatnonzero(passing)
            k = sel[int(np.nanargmin(badness(q, t.values[sel, j])))]
            best = f"{fmt(t.values[k, j])} (variant {k + 1})"
        else:
            best = "—"
        rows.append([q, quantity_unit(q) or "—", _better(q),
                     fmt(np.min(col)) if len(col) else "—",
                     fmt(np.max(col)) if len(col) else "—", best])
    doc.table(["quantity", "unit", "better", "smallest", "largest", "best passing"], rows,
              right={3, 4, 5})

    _best_section(doc, run, units)
    _pareto_section(doc, run, units, figures)

    doc.h("Each kept quantity against each varied key")
    many = t.n > MAX_POINTS
    doc.p("One dot per completed variant (blue: passes the design review, grey: fails it); "
          "the line joins the best passing value at each value of the key"
          + (" (grid)" if plan.sample == "grid" else " (in 20 bins of the key's range)")
          + "; the other keys vary too. Ticks on the key's axis mark where variants failed. "
          "When a few variants lie far from the rest (near-singular positions), the scale "
          "shows the 1st to 99th percentile and the others sit on its edge as triangles."
          + (f" {MAX_POINTS} variants drawn at random, plus the best and the Pareto front; "
             "every variant is in study.csv." if many else ""))
    for j, q in enumerate(t.keep):
        name = f"quantity-{j + 1}"
        if name in figures:
            rows_ = max(1, math.ceil(len(plan.keys) / PANELS))
            doc.image(figures[name], f"{q} against each varied key",
                      height=min(1.95 * rows_ + 0.2, 8.5))

    _failed_section(doc, run)
    _cross_section(doc, run)
    _files_section(doc, run)
    return doc


def method_title(name: str) -> str:
    """The force method's title as the reports print it ("Newton-Euler"), the name itself
    for one that is not a method."""
    return METHODS[name].TITLE if name in METHODS else name


def _variant_cells(run: StudyRun, i: int) -> list[str]:
    return [fmt(x, 6) for x in run.plan.values[i]]


def _best_section(doc: Doc, run: StudyRun, units: dict[str, str]) -> None:
    t, plan = run.table, run.plan
    doc.h("Best variants")
    ranked = t.ranked()
    shown_q = t.keep[:MAX_TABLE_QUANTITIES]
    if len(ranked):
        doc.p(f"The {min(BEST, len(ranked))} best of the {len(ranked)} variants that pass the "
              f"design review, ranked by {t.keep[0]} ({_better(t.keep[0])})"
              + (", ties by the next kept quantities" if len(t.keep) > 1 else "") + ".")
        picked, note = ranked[:BEST], ""
    else:
        best_any = t.ranked(t.ok)
        doc.p(Strong("No variant passes the design review."),
              f" The {min(BEST, len(best_any))} best completed variants, ranked by "
              f"{t.keep[0]}, with the design items they fail:")
        picked, note = best_any[:BEST], "fails"
    if not len(picked):
        doc.p("No variant completed.")
        return
    header = (["rank", "variant"] + [with_unit(k, units.get(k, "")) for k in plan.keys]
              + [column_name(q) for q in shown_q])
    rows = []
    for r, i in enumerate(picked, 1):
        row = [str(r), str(i + 1)] + _variant_cells(run, i) + [fmt(v) for v in
                                                               t.values[i, :len(shown_q)]]
        if note:
            row.append(t.failed[i] or "—")
        rows.append(row)
    if note:
        header.append("fails")
    more = (f"Only the first {MAX_TABLE_QUANTITIES} kept quantities are shown; study.csv has "
            "every one." if len(t.keep) > MAX_TABLE_QUANTITIES else "")
    doc.table(header, rows, right=set(range(0, 2 + len(plan.keys) + len(shown_q))), note=more)


def _pareto_section(doc: Doc, run: StudyRun, units: dict[str, str], figures) -> None:
    t, plan = run.table, run.plan
    doc.h("Pareto front")
    if len(t.keep) < 2:
        doc.p("The study keeps one quantity: a Pareto front needs two (the first two in keep).")
        return
    q1, q2 = t.keep[0], t.keep[1]
    front = t.pareto()
    doc.p(f"{q1} against {q2}: the passing variants that no other passing variant beats in "
          f"both ({q1}: {_better(q1)}; {q2}: {_better(q2)}). {len(front)} variant(s) on the "
          "front.")
    if "pareto" in figures:
        doc.image(figures["pareto"], f"{q1} against {q2}, with the Pareto front", height=3.4)
    if len(front):
        shown = front if len(front) <= 20 else front[np.linspace(0, len(front) - 1, 20)
                                                     .round().astype(int)]
        header = (["variant"] + [with_unit(k, units.get(k, "")) for k in plan.keys]
                  + [column_name(q) for q in (q1, q2)])
        rows = [[str(i + 1)] + _variant_cells(run, i) + [fmt(t.values[i, 0]),
                                                         fmt(t.values[i, 1])] for i in shown]
        note = (f"20 of the {len(front)} front variants, evenly spread; study.csv has every "
                "variant." if len(front) > 20 else "")
        doc.table(header, rows, right=set(range(len(header))), note=note)


def _failed_section(doc: Doc, run: StudyRun) -> None:
    t = run.table
    bad = [i for i in range(t.n) if t.reason[i]]
    doc.h("Failed variants")
    if not bad:
        doc.p("None: every variant completed with every kept quantity.")
        return
    groups = Counter(t.reason[i] for i in bad)
    first: dict[str, list[int]] = {}
    for i in bad:
        lst = first.setdefault(t.reason[i], [])
        if len(lst) < 3:
            lst.append(i + 1)
    rows = [[reason, str(count), ", ".join(str(v) for v in first[reason])]
            for reason, count in groups.most_common(12)]
    note = (f"and {len(groups) - 12} more reason(s); study.csv gives each variant's reason."
            if len(groups) > 12 else "")
    doc.p(f"{len(bad)} variant(s) have no result (or miss a kept quantity); they are rows "
          "of study.csv with status failed and their reason.")
    doc.table(["reason", "variants", "for example"], rows, right={1}, note=note)


def _cross_section(doc: Doc, run: StudyRun) -> None:
    cc = run.cross
    if cc is None:
        return
    doc.h("Cross-check")
    doc.p(cc.summary())
    if cc.rows:
        doc.table(["variant", "result", "worst relative difference", "where"],
                  [[str(r.index + 1), "agrees" if r.ok else "DISAGREES",
                    fmt(r.worst, 2) if r.worst is not None else "—", r.where]
                   for r in cc.rows], right={0, 2})


def _files_section(doc: Doc, run: StudyRun) -> None:
    doc.h("Files")
    items = [[Code("study.parquet"), ", ", Code("study.csv"),
              ": one row per variant: variant number, the varied values (spec units), the kept "
              "quantities (SI, the unit in each column name), design_pass, design_failed, "
              "status, reason."]]
    for rank, i, folder, message in run.reports:
        if folder:
            items.append([f"rank {rank}, variant {i + 1}: full report in ",
                          Code(f"{folder}/report.pdf")])
        else:
            items.append([f"rank {rank}, variant {i + 1}: no report: {message}"])
    doc.items(items)
