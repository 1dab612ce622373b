"""tolerance.md and tolerance.pdf: what is uncertain and how it was sampled, how many samples
could be built and analysed, the kept quantities' statistics, each design verdict's
probability of passing, which tolerance matters for each quantity, a histogram per kept
quantity, the worst sample and why samples had no result. Figures are SVG files in
``tolerance-figures/``.

Kept quantities are shown in SI (the units of tolerance.csv's columns), uncertain values in
the spec's own units. The numbers are :mod:`.tolerance_stats`' (computed once there)."""
from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..report.document import Code, Doc, Strong
from ..report.plots import styled
from ..units import fmt, with_unit
from .plan import SAMPLING_NAMES
from .report import StudyDoc, key_units, method_title, provenance, robust_limits
from .table import column_name
from .tolerance_stats import varies

FIGURES = "tolerance-figures"
PERCENT = 100.0


# ---------------------------------------------------------------------------- figures

@dataclass(frozen=True)
class HistData:
    """A histogram's records: ``values`` (m,) of the ok samples [SI, ``unit``], the
    ``nominal`` value, the 5th and 95th percentiles, the design ``limit`` (None if none;
    ``at_least`` for a lower limit)."""

    quantity: str
    unit: str
    values: np.ndarray
    nominal: float
    p5: float
    p95: float
    limit: float | None = None
    at_least: bool = False


def hist_data(result, j: int) -> HistData:
    """The histogram records of kept quantity ``j`` of ``result`` (a ToleranceResult)."""
    s = result.quantities[j]
    col = result.table.values[result.table.ok, j]
    return HistData(s.quantity, s.unit, col[np.isfinite(col)], s.nominal, s.p5, s.p95,
                    s.limit, s.at_least)


def draw_histogram(ax, h: HistData) -> None:
    """The distribution of one kept quantity on ``ax``: a histogram of the samples, the
    nominal value (solid), the 5th and 95th percentiles (dotted) and the design limit
    (dashed; beyond the scale, an arrow at the edge saying where it is)."""
    from ..report.plots import GREY, INK, LIMIT_COLOR, OKABE_ITO, literal
    v = h.values
    if not len(v):
        ax.text(0.5, 0.5, "no sample with a value", transform=ax.transAxes, ha="center")
        return
    unit = f" {h.unit}" if h.unit else ""
    if len(v) < 2 or not varies(float(np.std(v)), v):
        text = (f"one ok sample only: {fmt(float(v[0]))}{unit} (no spread to show)"
                if len(v) < 2 else f"every sample: {fmt(float(np.mean(v)))}{unit} (the "
                "tolerances do not move it)")
        ax.text(0.5, 0.5, text, transform=ax.transAxes, ha="center", va="center")
        ax.set_xticks([])
        ax.set_yticks([])
        ax.grid(False)
        ax.set_xlabel(literal(column_name(h.quantity)))
        return
    limits = robust_limits(v)
    shown = v if limits is None else v[(v >= limits[0]) & (v <= limits[1])]
    bins = int(np.clip(np.sqrt(len(shown)), 10, 50))
    ax.hist(shown, bins=bins, color=OKABE_ITO[0], alpha=0.75, edgecolor="white", lw=0.4)
    lo, hi = (float(np.min(shown)), float(np.max(shown))) if limits is None else limits
    span = hi - lo
    ax.set_xlim(lo - 0.05 * span, hi + 0.05 * span)
    if lo - 0.5 * span <= h.nominal <= hi + 0.5 * span:
        ax.set_xlim(min(lo, h.nominal) - 0.05 * span, max(hi, h.nominal) + 0.05 * span)
        ax.axvline(h.nominal, color=INK, lw=1.3, label=f"nominal {fmt(h.nominal)}{unit}")
    else:                   # far from every sample (a range beside the spec's value)
        right = h.nominal > hi
        ax.annotate(f"nominal {fmt(h.nominal)}{unit} " + ("→" if right else "←"),
                    xy=(0.99 if right else 0.01, 0.86), xycoords="axes fraction",
                    ha="right" if right else "left", va="top", fontsize=7.5, color=INK,
                    bbox=dict(facecolor="white", edgecolor="none", alpha=0.85, pad=1.0))
    for x, name in ((h.p5, "5th"), (h.p95, "95th")):
        ax.axvline(x, color=GREY, lw=1.0, ls=(0, (1.5, 1.5)),
                   label="5th and 95th percentiles" if name == "5th" else "_nolegend_")
    if h.limit is not None:
        side = "lower limit" if h.at_least else "limit"
        reach = 0.5 * span
        if lo - reach <= h.limit <= hi + reach:
            left, right_end = ax.get_xlim()
            ax.set_xlim(min(left, h.limit - 0.05 * span), max(right_end, h.limit + 0.05 * span))
            ax.axvline(h.limit, color=LIMIT_COLOR, lw=1.4, ls=(0, (5, 2)),
                       label=f"{side} {fmt(h.limit)}{unit}")
        else:
            right = h.limit > hi
            ax.annotate(f"{side} {fmt(h.limit)}{unit} " + ("→" if right else "←"),
                        xy=(0.99 if right else 0.01, 0.93), xycoords="axes fraction",
                        ha="right" if right else "left", va="top", fontsize=7.5,
                        color=LIMIT_COLOR)
    if limits is not None:
        out = int(len(v) - len(shown))
        ax.text(0.99, 0.80, f"{out} sample(s) beyond the scale", transform=ax.transAxes,
                ha="right", va="top", fontsize=7, color=INK)
    ax.set_xlabel(literal(column_name(h.quantity)))
    ax.set_ylabel("samples")
    ax.legend(loc="upper left", bbox_to_anchor=(0.0, 1.22), ncol=3, frameon=False,
              borderaxespad=0.0, handlelength=2.0, fontsize=7.5)


@styled
def plot_histogram(result, quantity: str | None = None, ax=None):
    """The histogram of ``quantity`` (default: the first kept) of ``result`` (what
    :func:`mechreport.tolerance` returns) as the report draws it, on ``ax`` (default: a new
    figure's); returns the Axes."""
    from ..report.plots import figure
    keep = list(result.table.keep)
    j = keep.index(quantity) if quantity is not None else 0
    if ax is None:
        _fig, axes = figure(2.6, margins=(0.72, 0.15, 0.46, 0.5))
        ax = axes[0, 0]
    draw_histogram(ax, hist_data(result, j))
    return ax


@styled
def write_figures(result, folder: Path) -> dict[str, str]:
    """One histogram per kept quantity as SVG; returns {name: relative path}."""
    from ..report.plots import figure, save
    out = {}
    for j in range(len(result.table.keep)):
        fig, axes = figure(2.6, margins=(0.72, 0.15, 0.46, 0.5))
        draw_histogram(axes[0, 0], hist_data(result, j))
        name = f"histogram-{j + 1}"
        save(fig, Path(folder), name)
        out[name] = f"{FIGURES}/{name}.svg"
    return out


# --------------------------------------------------------------------------- document

def distribution_text(v, unit: str) -> str:
    u = f" {unit}" if unit else ""
    if v.dist == "normal":
        if v.given == "sigma":
            return f"normal, σ = {fmt(v.sigma, 6)}{u} about the spec's value"
        return (f"normal about {fmt(v.mean, 6)}{u}, σ = {fmt(v.sigma, 6)}{u} (the "
                f"{'tolerance' if v.given == 'tol' else 'range'} is ±3σ)")
    if v.given == "tol":
        return f"uniform, ±{fmt((v.high - v.low) / 2, 6)}{u}"
    return f"uniform from {fmt(v.low, 6)} to {fmt(v.high, 6)}{u}"


def percent(p: float) -> str:
    """A probability or share ``p`` (0..1) as the tolerance analysis prints it, in its report
    and on the terminal: ``57.5 %``, ``99.50 %``, ``100 %``; "—" when undefined."""
    if not np.isfinite(p):
        return "—"
    x = p * PERCENT
    if x in (0.0, 100.0):
        return f"{x:.0f} %"
    return f"{x:.2f} %" if x < 1 or x > 99 else f"{x:.1f} %"


def interval(p) -> str:
    """A :class:`~.tolerance_stats.Probability`'s 95 % interval: ``40.9 % to 73.0 %``."""
    return f"{percent(p.low)} to {percent(p.high)}"


def build_document(result, figures: dict[str, str], date: str = "", sha256: str = "",
                   where: str = "", chunk: int | None = None) -> Doc:
    spec, t, plan = result.spec, result.table, result.plan
    tol = spec.tolerances
    units = key_units(result.base)
    doc = StudyDoc(f"Tolerance analysis: {spec.name}")
    provenance(doc, spec.file, sha256, date)
    what = f"{SAMPLING_NAMES[plan.sample]} sampling"
    ran = f" on {where}" + (f", in chunks of {chunk}" if chunk else "") if where else ""
    doc.p(Strong(f"{t.n} samples"), f" ({what}, seed {plan.seed}) of the spec's uncertain "
          "values, each analysed as a whole machine by ",
          Strong(method_title(result.method)),
          f" ({result.method}: {result.method_why}){ran}, in {result.seconds:.1f} s, each "
          "with the trust test of a study (a sample whose one method cannot vouch for its "
          "numbers is counted as untrusted, not used). The spec as written was solved by "
          "every method too, and they agree as mechreport check requires.")
    c = result.counts
    a = result.assembly
    doc.table(["samples", "count", "share"],
              [["analysed, every kept quantity (ok)", str(c.get("ok", 0)),
                percent(c.get("ok", 0) / t.n)],
               ["cannot be assembled over the sweep", str(c.get("no assembly", 0)),
                percent(c.get("no assembly", 0) / t.n)],
               ["a value the spec refuses", str(c.get("invalid", 0)),
                percent(c.get("invalid", 0) / t.n)],
               ["untrusted (trust test failed)", str(c.get("untrusted", 0)),
                percent(c.get("untrusted", 0) / t.n)],
               ["failed otherwise", str(c.get("failed", 0)), percent(c.get("failed", 0) / t.n)]],
              right={1, 2},
              note=(f"Probability that the mechanism assembles: {percent(a.p)} (95 % interval "
                    f"{interval(a)}). Samples without a result are listed with their reasons "
                    "at the end; every sample is a row of tolerance.csv."))

    doc.h("Uncertain values")
    doc.p("Each sample is the spec with these leaves replaced, in the spec's own units.")
    doc.table(["key", "unit", "spec's value", "distribution", "standard deviation"],
              [[v.key, units.get(v.key, "") or "—", fmt(v.nominal, 6),
                distribution_text(v, units.get(v.key, "")), fmt(v.std, 4)]
               for v in tol.vary], right={2, 4})

    doc.h("Kept quantities")
    doc.p(f"In SI, over the {c.get('ok', 0)} ok samples; nominal: the spec as written. Limit: "
          "the design limit judged on the quantity (≥: a lower limit).")
    rows = []
    for s in result.quantities:
        lim = "—" if s.limit is None else ("≥ " if s.at_least else "≤ ") + fmt(s.limit)
        rows.append([column_name(s.quantity), fmt(s.nominal), fmt(s.mean),
                     fmt(s.std, 3, scale=max(abs(s.low), abs(s.high))),
                     fmt(s.p5), fmt(s.p95), fmt(s.p99), lim])
    doc.table(["quantity", "nominal", "mean", "std. dev.", "5th pct", "95th pct",
               "99th pct", "limit"], rows, right={1, 2, 3, 4, 5, 6, 7})

    _verdict_section(doc, result)
    _ranking_section(doc, result)

    doc.h("Distributions")
    doc.p("A histogram of each kept quantity over the ok samples: the nominal value (solid), "
          "the 5th and 95th percentiles (dotted) and the design limit (dashed; an arrow at the "
          "edge when it lies far beyond the samples). When a few samples lie far from the "
          "rest, the scale shows the 1st to 99th percentile and says how many are beyond.")
    for j, q in enumerate(t.keep):
        name = f"histogram-{j + 1}"
        if name in figures:
            doc.image(figures[name], f"{q}: distribution over the samples", height=2.6)

    _worst_section(doc, result, units)
    _failed_section(doc, result)
    _files_section(doc)
    return doc


def _verdict_section(doc: Doc, result) -> None:
    doc.h("Design verdicts")
    if not result.verdicts:
        doc.p("The spec has no design section: there is no verdict to pass.")
        return
    doc.p("The probability that the built machine passes each verdict: the share of all "
          "samples that pass it, with its 95 % Clopper-Pearson (exact binomial) interval. A "
          "sample that cannot be assembled or analysed, or whose numbers are untrusted, "
          "counts as not passing.")
    rows = []
    for p in result.verdicts:
        unit = f" {p.unit}" if p.unit else ""
        rows.append([p.name, p.quantity, fmt(p.limit) + unit,
                     "pass" if p.nominal else "FAIL", percent(p.p), interval(p)])
    d = result.design
    rows.append(["every verdict", "", "", "pass" if d.nominal else "FAIL", percent(d.p),
                 interval(d)])
    doc.table(["design item", "judged on", "limit", "nominal", "P(pass)", "95 % interval"],
              rows, right={2, 4})


def _ranking_section(doc: Doc, result) -> None:
    doc.h("Which tolerance matters")
    doc.p("The share of each kept quantity's variance each tolerance explains: squared "
          "standardised regression coefficients of a linear fit of the quantity to every "
          "uncertain value over the ok samples (tolerances are small, so the quantities are "
          "nearly linear in them). R² says how much of the variance the linear fit, and so "
          "the ranking, accounts for; the shares add up to it. Each column's largest share "
          "is in bold.")
    keys = result.plan.keys
    header = ["tolerance"] + [r.quantity for r in result.ranking]
    share = {r.quantity: dict(r.shares) for r in result.ranking}
    top = {r.quantity: (r.shares[0][0] if r.shares and r.r2 is not None else None)
           for r in result.ranking}
    order = sorted(keys, key=lambda k: -max((share[q].get(k, 0.0) for q in share),
                                            default=0.0))
    rows = []
    for k in order:
        cells = [k]
        for r in result.ranking:
            if r.r2 is None:
                cells.append("—")
                continue
            text = percent(share[r.quantity].get(k, 0.0))
            cells.append(Strong(text) if top[r.quantity] == k else text)
        rows.append(cells)
    rows.append(["R² of the linear fit"] + [("—" if r.r2 is None else f"{r.r2:.4f}")
                                            for r in result.ranking])
    doc.table(header, rows, right=set(range(1, len(header))),
              note=("— : the quantity does not vary over the samples, or too few samples."
                    if any(r.r2 is None for r in result.ranking) else ""))
    weak = [r.quantity for r in result.ranking if r.r2 is not None and r.r2 < 0.9]
    if weak:
        doc.p(Strong("Nonlinear:"), f" the linear fit explains less than 90 % of the variance "
              f"of {', '.join(weak)}; its ranking is a first-order guide only.")


def _worst_section(doc: Doc, result, units) -> None:
    doc.h("Worst sample")
    i = result.worst
    if i is None:
        doc.p("No sample was analysed.")
        return
    t, plan = result.table, result.plan
    doc.p(f"Sample {i + 1}, {result.worst_why}.")
    rows = [[with_unit(k, units.get(k, "")), fmt(v.nominal, 6), fmt(plan.values[i, j], 6)]
            for j, (k, v) in enumerate(zip(plan.keys, result.spec.tolerances.vary))]
    rows += [[column_name(q), fmt(result.nominal.values[j]), fmt(t.values[i, j])]
             for j, q in enumerate(t.keep)]
    failed = [it for k, it in enumerate(t.items) if t.passes[i, k] == 0]
    doc.table(["value", "nominal", f"sample {i + 1}"], rows, right={1, 2},
              note=("It fails " + ", ".join(failed) + "." if failed
                    else "It passes every design verdict." if t.items else ""))


def _failed_section(doc: Doc, result) -> None:
    doc.h("Samples without a result")
    if not result.reasons:
        doc.p("None: every sample was assembled, analysed and trusted, with every kept "
              "quantity.")
        return
    n = sum(c for _s, _w, c, _f in result.reasons)
    doc.p(f"{n} sample(s), by status and reason; they are rows of tolerance.csv with that "
          "status and reason, and count as not passing.")
    shown = result.reasons[:12]
    doc.table(["status", "reason", "samples", "for example"],
              [[s, why, str(c), ", ".join(str(x) for x in first)]
               for s, why, c, first in shown], right={2},
              note=(f"and {len(result.reasons) - 12} more reason(s); tolerance.csv gives each "
                    "sample's." if len(result.reasons) > 12 else ""))


def _files_section(doc: Doc) -> None:
    doc.h("Files")
    doc.items([[Code("tolerance.parquet"), ", ", Code("tolerance.csv"),
                ": one row per sample: its number, the uncertain values (spec units), the kept "
                "quantities (SI, the unit in each column name), design_pass, verdict.<item> "
                "per design item, status, reason."],
               [Code("tolerance.json"), ": the tolerance.* quantities (SI), also added to "
                "the report's ", Code("summary.json"), " when the folder holds one."]])
