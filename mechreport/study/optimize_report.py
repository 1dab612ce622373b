"""An optimisation's outputs: history.csv (every evaluation), the figures (convergence, the
objective along each varied key through the optimum) and the document of optimize.md /
optimize.pdf (the original beside the optimum, every verdict and kept quantity, the active
constraints, the search and its proof).

Quantities are in SI (as results.csv and study.csv), varied values in the spec's own units
(as written in ``optimize.vary``)."""
from __future__ import annotations

import csv
import math
from pathlib import Path

import numpy as np

from ..report.document import Code, Doc, Print, Strong
from ..units import fmt, with_unit
from .optimize import OptimizeResult, Profile
from .outputs import csv_cell
from .report import key_units, method_title, provenance
from .table import column_name, quantity_unit

FIGURES = "optimize-figures"


# ------------------------------------------------------------------------------ history

def history_columns(result: OptimizeResult) -> list[str]:
    p = result.problem
    return (["evaluation", "phase", "generation"] + list(p.keys)
            + [column_name(q) for q in p.quantities]
            + [f"margin: {c.name}" for c in p.constraints]
            + ["violation", "feasible", "faults"])


def write_history(result: OptimizeResult, path: Path) -> Path:
    """history.csv: one row per evaluation, in order: the phase (search, polish), the
    generation, the varied values (spec units), the quantities read (SI), each constraint's
    relative margin (>= 0 holds; empty when undefined), the violation, feasible, the faults."""
    h = result.history
    with open(path, "w", encoding="utf-8", newline="") as fh:
        w = csv.writer(fh, lineterminator="\n")
        w.writerow(history_columns(result))
        for i, j in enumerate(h.judged):
            w.writerow([str(i + 1), h.phase[i], str(h.generation[i])]
                       + [csv_cell(v) for v in h.values[i]] + [csv_cell(v) for v in j.values]
                       + [csv_cell(m) for m in j.margins]
                       + [csv_cell(j.violation), "true" if j.feasible else "false",
                          "; ".join(j.faults)])
    return Path(path)


# ------------------------------------------------------------------------------ figures

def write_figures(result: OptimizeResult, folder: Path, profs: list[Profile]) -> dict[str, str]:
    """convergence.svg and profiles.svg; {name: relative path}."""
    from ..report.plots import GREY, OKABE_ITO, figure, legend_top, literal, save
    folder = Path(folder)
    out: dict[str, str] = {}
    p, h = result.problem, result.history
    if not h.n:
        return out
    n = np.arange(1, h.n + 1)
    obj = np.array([j.objective for j in h.judged])
    feas = h.feasible()
    sign = -1.0 if p.maximize else 1.0
    fig, axes = figure(3.2, 1, 1, margins=(0.8, 0.2, 0.5, 0.65))
    ax = axes[0][0]
    if not feas.any():                  # nothing feasible: how far each design missed
        viol = np.array([j.violation for j in h.judged])
        ax.scatter(n, viol, s=5, color=GREY, lw=0, label="violation of each evaluation")
        ax.plot(n, np.minimum.accumulate(viol), color=OKABE_ITO[0], lw=1.4,
                label="least violation so far")
        pos = viol[np.isfinite(viol) & (viol > 0)]
        if pos.size and pos.max() > 20 * pos.min():    # decades apart: a log scale
            ax.set_yscale("log")
        ax.set_xlabel("evaluation")
        ax.set_ylabel("violation (relative)")
        legend_top(ax, 2)
        save(fig, folder, "convergence")
        out["convergence"] = f"{FIGURES}/convergence.svg"
        return out | _profiles_figure(result, folder, profs)
    shown = feas & np.isfinite(obj)
    ax.scatter(n[shown], obj[shown], s=5, color=GREY, lw=0, label="feasible evaluation")
    best = np.full(h.n, np.nan)
    run = math.inf
    for k in range(h.n):
        if shown[k] and sign * obj[k] < run:
            run = sign * obj[k]
        best[k] = sign * run if math.isfinite(run) else np.nan
    ax.plot(n, best, color=OKABE_ITO[0], lw=1.4, label="best feasible so far")
    if result.original is not None and math.isfinite(result.original.objective):
        ax.axhline(result.original.objective, color=OKABE_ITO[5], lw=1.0, ls="--",
                   label="original design")
    polish = [k for k in range(h.n) if h.phase[k] == "polish"]
    if polish:
        ax.axvline(polish[0] + 1, color=OKABE_ITO[3], lw=0.8, ls=":", label="polish starts")
    finite = obj[shown]
    if finite.size:
        lo, hi = np.percentile(finite, [0, 95])
        ref = result.original.objective if math.isfinite(result.original.objective) else hi
        top, bottom = max(hi, ref), min(lo, ref)
        pad = 0.05 * (top - bottom or abs(top) or 1.0)
        ax.set_ylim(bottom - pad, top + pad)
    ax.set_xlabel("evaluation")
    ax.set_ylabel(literal(column_name(p.objective)))
    legend_top(ax, 2)
    save(fig, folder, "convergence")
    out["convergence"] = f"{FIGURES}/convergence.svg"
    return out | _profiles_figure(result, folder, profs)


def _profiles_figure(result: OptimizeResult, folder: Path, profs: list[Profile]
                     ) -> dict[str, str]:
    """profiles.svg: the objective along each varied key through the optimum."""
    from matplotlib.ticker import MaxNLocator

    from ..report.plots import GREY, OKABE_ITO, figure, literal, save
    p, h = result.problem, result.history
    out: dict[str, str] = {}
    if profs:
        units = key_units(p.base)
        d = len(profs)
        cols = min(d, 2)
        rows = math.ceil(d / cols)
        fig, axes = figure(2.3 * rows + 0.3, rows, cols, gap=0.75, wgap=0.8,
                           margins=(0.8, 0.15, 0.5, 0.4))
        centre = h.values[result.best]
        for k, pr in enumerate(profs):
            ax = axes[k // cols][k % cols]
            ok = pr.feasible & np.isfinite(pr.objective)
            bad = ~pr.feasible & np.isfinite(pr.objective)
            ax.plot(pr.x[ok], pr.objective[ok], "o-", color=OKABE_ITO[0], ms=2.5, lw=1.0,
                    label="feasible")
            ax.plot(pr.x[bad], pr.objective[bad], "x", color=OKABE_ITO[5], ms=4,
                    label="infeasible")
            ax.axvline(centre[k], color=GREY, lw=0.8, ls="--",
                       label="optimum" if result.feasible else "least violating")
            ax.set_xlabel(literal(with_unit(pr.key, units.get(pr.key, ""))), fontsize=7.5)
            ax.xaxis.set_major_locator(MaxNLocator(5))     # long tick labels stay apart
            if k % cols == 0:
                ax.set_ylabel(literal(column_name(p.objective)), fontsize=7.5)
        for k in range(d, rows * cols):
            axes[k // cols][k % cols].set_visible(False)
        handles, labels = axes[0][0].get_legend_handles_labels()
        fig.legend(handles, labels, loc="upper left", bbox_to_anchor=(0.8 / 6.5, 1.0),
                   ncol=3, frameon=False, borderaxespad=0.2)
        save(fig, folder, "profiles")
        out["profiles"] = f"{FIGURES}/profiles.svg"
    return out


# ----------------------------------------------------------------------------- document

class OptimizeDoc(Doc):
    """Wide tables split in print; captions under the figures in Markdown."""

    def table(self, header, rows, right=frozenset(), note="", print=None) -> None:
        super().table(header, rows, right, note, Print(max_columns=7, lead=1, wrap=True))

    def image(self, path, caption, height=None, **how) -> None:
        super().image(path, caption, height, caption_below=True, **how)


def _margin(m: float) -> str:
    if m is None or not math.isfinite(m):
        return "undefined"
    return f"{100 * m:+.3g} %"


def build_document(result: OptimizeResult, figures: dict[str, str], *, sha256: str = "",
                   date: str = "", report: str = "") -> Doc:
    p, h = result.problem, result.history
    spec = p.base.spec
    opt = spec.optimize
    units = key_units(p.base)
    doc = OptimizeDoc(f"Design optimisation: {spec.name}")
    provenance(doc, spec.file, sha256, date)
    sense = "maximize" if p.maximize else "minimize"
    j0 = result.original
    if result.feasible:
        j = result.judged
        change = ""
        if math.isfinite(j0.objective) and j0.objective:
            change = f" ({100 * (j.objective / j0.objective - 1):+.3g} %)"
        doc.p(Strong("A feasible optimum was found and proven."),
              f" {sense} {p.objective}: {fmt(j0.objective)} → {fmt(j.objective)} "
              f"{quantity_unit(p.objective)}{change}. It was re-analysed by every force method and "
              "checked as mechreport check does (the methods agree, every design verdict "
              "passes), and it meets every bound, stays on the spec's assembly branch and "
              "leaves out no angle the original analysis did not.")
    else:
        doc.p(Strong("No feasible design was found."),
              f" The least violating design of the {h.n} evaluated misses:")
        j = result.judged
        if j is not None:
            doc.items([[line] for line in j.missed(p)])

    doc.h("The search")
    n_feas = int(h.feasible().sum())
    n_pol = sum(ph == "polish" for ph in h.phase)
    doc.p(f"{h.n} evaluations (budget {opt.budget if result.budget is None else result.budget}),"
          f" {n_feas} feasible, in {result.seconds:.1f} s on {result.where}: differential "
          f"evolution (scipy, seed {result.seed}, {result.generations} generations of "
          "the whole population evaluated as one batch, each candidate analysed by ",
          Strong(method_title(p.method)),
          f" with the study's trust test){'' if not n_pol else f', then {n_pol} evaluations of an SLSQP polish' + (' (kept)' if result.polished else ' (no better feasible design)')}. "
          f"scipy says: {(result.message or '—').rstrip('.')}.")
    rows = []
    for pr in result.proofs:
        rows.append([str(pr.index + 1), "proven" if pr.ok else "refused", pr.why or "—"])
    if rows:
        doc.table(["evaluation", "proof", "why not"], rows, right={0})

    doc.h("Varied keys")
    best = result.best
    rows = []
    for k, v in enumerate(opt.vary):
        u = units.get(v.key, "")
        got = fmt(h.values[best][k], 8) if best is not None else "—"
        rows.append([v.key, u or "—", fmt(v.start, 6), fmt(v.stop, 6),
                     fmt(result.start[v.key], 8), got])
    doc.table(["key", "unit", "from", "to", "original",
               "optimum" if result.feasible else "least violating"], rows, right={2, 3, 4, 5})

    doc.h("Original and optimum")
    doc.p("Every design verdict and every quantity the optimisation reads, in SI; the "
          "margin is relative to the limit (positive: it holds).")
    a0, a1 = result.original_analysis, result.analysis
    v1 = {v.item: v for v in a1.verdicts} if a1 is not None else {}
    # without an optimum, the least violating design's verdicts as it was judged (its
    # margins: the search's one method; no full analysis of it is made)
    least = ({c.item: m for c, m in zip(p.constraints, result.judged.margins)
              if c.kind == "design"} if a1 is None and result.judged is not None else {})
    rows = []
    for v in a0.verdicts:
        w = v1.get(v.item)
        if w is not None:
            now = [fmt(w.value), "pass" if w.passed else "FAIL"]
        elif v.item in least:
            m = least[v.item]
            now = ["—", "undefined" if not math.isfinite(m) else
                   f"{'pass' if m >= 0 else 'FAIL'} ({_margin(m)})"]
        else:
            now = ["—", "—"]
        rows.append([v.item, f"{'≥' if v.at_least else '≤'} {fmt(v.limit)} {v.unit}",
                     fmt(v.value), "pass" if v.passed else "FAIL", *now])
    if rows:
        doc.table(["design verdict", "limit", "original", "",
                   "optimum" if result.feasible else "least violating", ""], rows,
                  right={2, 4})
    i = result.best
    rows = []
    for q_i, q in enumerate(p.quantities):
        now = h.judged[i].values[q_i] if i is not None else math.nan
        rows.append([q, quantity_unit(q) or "—", fmt(j0.values[q_i]), fmt(now)])
    doc.table(["quantity", "unit", "original",
               "optimum" if result.feasible else "least violating"], rows, right={2, 3})

    doc.h("Constraints")
    active = {c.name for c, _ in result.active()}
    rows = []
    for c_i, c in enumerate(p.constraints):
        m1 = h.judged[i].margins[c_i] if i is not None else math.nan
        rows.append([c.name, _margin(j0.margins[c_i]), _margin(m1),
                     "active" if c.name in active else ""])
    doc.table(["constraint", "original margin", "margin at the optimum" if result.feasible
               else "margin at the least violating", ""], rows,
              right={1, 2})
    if result.feasible:
        box = result.at_box()
        doc.p("Active constraints (margin at most 0.1 %): "
              + (", ".join(sorted(active)) if active else "none")
              + ". At an end of the box: " + (", ".join(box) if box else "none") + ".")

    doc.h("Convergence")
    if "convergence" in figures:
        doc.image(figures["convergence"], (
            f"{p.objective} at each evaluation (feasible ones) and the best feasible so far"
            if result.feasible or h.feasible().any() else
            "how far each evaluation missed (its violation) and the least so far"),
            height=3.2)
    doc.h("The objective along each varied key")
    if "profiles" in figures:
        doc.p(f"{p.objective} with one key moved over 20 % of its range on either side of the "
              f"{'optimum' if result.feasible else 'least violating design'}, the others held "
              "(crosses: infeasible designs).")
        rows_ = math.ceil(len(opt.vary) / 2)
        doc.image(figures["profiles"], f"{p.objective} along each varied key",
                  height=min(2.3 * rows_ + 0.3, 8.5))

    doc.h("Files")
    items = [[Code("history.csv"), ": every evaluation: phase, generation, the varied values "
              "(spec units), the quantities (SI), each constraint's relative margin, the "
              "violation, feasible, faults."]]
    if result.text:
        items.append([Code("optimum.yaml"), ": the spec with the "
                      + ("optimal" if result.feasible else "least violating")
                      + " values written in (its expect entries taken out)."])
    if report:
        items.append(["the optimum's full report: ", Code(report)])
    doc.items(items)
    return doc
