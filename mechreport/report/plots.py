"""Sweep and cycle plots of a report model: driver torque, joint reactions, polar bearing
diagrams, shaking force and moment, flywheel diagram, torque by source, transmission angle,
balancing. Each figure is one SVG file, shown by both the PDF and the Markdown report.

Values are plotted in the report's display units (``model.display``) and labelled by the one
number formatter. Near-singular stretches (within ``sweep.near_deg`` of a left-out angle) are
hatched and do not set a plot's scale: a curve that runs off the scale there is clipped and
its extreme is marked at the edge with its value. Colours are Okabe & Ito's colour-blind-safe
set. Layouts are fixed (no tight bounding boxes: each figure is drawn once, when saved).

Text stays text in the SVG (``svg.fonttype: none``, DejaVu Sans with sans-serif fallbacks): a
browser shows it in its sans-serif, and Typst typesets it in DejaVu Sans itself, from
matplotlib's own font files (see :func:`mechreport.report.pdf.compile_typst`); drawing glyphs
as paths cost a fifth of the plotting time. Names from the spec (links, joints, points,
loads, study keys and quantities) are drawn literally: every string that carries one goes
through :func:`literal`, so that matplotlib never reads it as mathtext.

matplotlib is imported lazily so that numeric commands never load it; figures are matplotlib
Figures outside pyplot, made and saved in the report's :func:`style` (rc parameters set for
the block only)."""
from __future__ import annotations

import functools
import io
import math
from pathlib import Path

import numpy as np

from ..units import fmt
from .files import atomic_write_bytes
from .quantities import with_gaps

WIDTH = 6.5          # [in], the text width of the PDF
INK = "#222222"
GREY = "0.55"
#: Okabe & Ito, in an order where neighbours differ in lightness as well as hue
OKABE_ITO = ["#0072B2", "#E69F00", "#009E73", "#CC79A7", "#56B4E9", "#D55E00", "#F0E442",
             "#000000"]
SOURCE_COLORS = OKABE_ITO
STYLES = ["-", (0, (5, 2)), (0, (1.5, 1.5)), (0, (6, 2, 1.5, 2)), "-", (0, (5, 2))]
#: margins [in]: left (tick labels and axis label), right, bottom (ticks and label), top
MARGINS = (0.72, 0.12, 0.46, 0.36)


def style():
    """The report's figure style for a block: matplotlib's rc parameters set for it and
    restored after, so that a caller's own settings (a notebook's) are left alone."""
    import matplotlib
    return matplotlib.rc_context({
        "font.size": 8.5, "axes.titlesize": 9, "axes.labelsize": 8.5,
        "legend.fontsize": 7.5, "xtick.labelsize": 7.5, "ytick.labelsize": 7.5,
        "axes.grid": True, "grid.alpha": 0.3, "svg.fonttype": "none",
        "svg.hashsalt": "mechreport", "axes.spines.top": False, "axes.spines.right": False,
        "axes.formatter.useoffset": False, "axes.unicode_minus": True,
        "axes.prop_cycle": matplotlib.cycler(color=OKABE_ITO), "hatch.linewidth": 0.5,
        "hatch.color": "0.6"})


def literal(text) -> str:
    r"""``text`` (user text: a name from the spec, or a label that contains one) escaped so
    that matplotlib draws it as it is, wherever it goes (a Text, title, axis label,
    annotation or legend entry): every ``$`` becomes ``\$``.

    matplotlib reads a string with an even, non-zero number of unescaped ``$`` as mathtext:
    ``$x^2$`` would be drawn as maths, and ``a$b_{$`` raises a ParseSyntaxException when the
    figure is drawn. A string with no unescaped ``$`` is drawn as written, except that each
    ``\$`` is drawn as ``$``; so escaping every ``$`` is exact (a name's own ``\$`` becomes
    ``\\$``, drawn ``\$``), and text without a ``$`` (backslashes, braces, ``_``, ``%``
    included) is passed unchanged. Not for mechreport's own mathtext (``$F_{21x}$`` on the
    solution sheets), which has no user text in it."""
    return str(text).replace("$", "\\$")


def styled(func):
    """``func`` run in the report's :func:`style` (its figures are made and saved in it)."""
    @functools.wraps(func)
    def run(*args, **kwargs):
        with style():
            return func(*args, **kwargs)
    return run


def save(fig, outdir: Path, stem: str) -> list[Path]:
    """Write ``fig`` as ``<stem>.svg`` in ``outdir`` atomically (reproducibly: no date, fixed
    ids); in the report's :func:`style`."""
    buf = io.BytesIO()
    with style():
        fig.savefig(buf, format="svg", metadata={"Date": None, "Creator": "mechreport"})
    return [atomic_write_bytes(Path(outdir) / f"{stem}.svg", buf.getvalue())]


def figure(height: float, rows: int = 1, cols: int = 1, gap: float = 0.55,
           wgap: float = 0.75, margins=MARGINS, width: float = WIDTH, **kw):
    """A figure of ``rows`` x ``cols`` axes with fixed margins [in] (a matplotlib Figure,
    outside pyplot: no backend, no global figure list)."""
    from matplotlib.figure import Figure
    left, right, bottom, top = margins
    fig = Figure(figsize=(width, height))          # no pyplot bookkeeping: closed by GC
    axes = fig.subplots(rows, cols, squeeze=False, **kw)
    fig.subplots_adjust(left=left / width, right=1 - right / width, bottom=bottom / height,
                        top=1 - top / height, hspace=gap / max((height - bottom - top) / rows
                                                               - gap, 0.3),
                        wspace=wgap / max((width - left - right) / cols - wgap, 0.3))
    return fig, axes


def legend_top(ax, ncol: int, **kw) -> None:
    ax.legend(loc="lower left", bbox_to_anchor=(0.0, 1.01), ncol=ncol, frameon=False,
              borderaxespad=0.0, handlelength=2.2, columnspacing=1.4, **kw)


def _near_spans(angles, near) -> list[tuple[float, float]]:
    """Runs of near-singular angles as (start, end) [deg]."""
    spans = []
    if not len(near) or not np.any(near):
        return spans
    a = np.asarray(angles, float)
    idx = np.flatnonzero(near)
    start = prev = idx[0]
    for i in idx[1:]:
        if i != prev + 1:
            spans.append((a[start], a[prev]))
            start = i
        prev = i
    spans.append((a[start], a[prev]))
    return spans


def crank_axis(ax, sw, label: bool = True) -> None:
    """0-360 deg, ticks every 45 deg (or the sweep's range, for a sweep that is not one whole
    turn), left-out angles shaded grey, near-singular hatched."""
    if sw.xrange is None:
        ax.set_xlim(0, 360)
        ax.set_xticks(np.arange(0, 361, 45))
    else:
        ax.set_xlim(*sw.xrange)
    if label:
        ax.set_xlabel(sw.xlabel)
    step = float(np.median(np.diff(sw.angles))) if len(sw.angles) > 2 else 1.0
    for a in sw.flagged:
        ax.axvspan(a - step / 2, a + step / 2, color="0.45", alpha=0.35, lw=0, zorder=0)
    for a, b in _near_spans(sw.angles, sw.near):
        ax.axvspan(a - step / 2, b + step / 2, facecolor="none", hatch="////", lw=0,
                   edgecolor="0.7", zorder=0)


def scale_to_trusted(ax, sw, series: list[np.ndarray], unit: str, pad: float = 0.08,
                     include_zero: bool = True) -> bool:
    """Set the y-limits from the values away from left-out angles; where a curve runs beyond
    them near a left-out angle, clip it and mark its extreme at the edge with its value.
    True if anything was clipped."""
    near = sw.near if len(sw.near) == len(sw.angles) else np.zeros(len(sw.angles), bool)
    allv = np.concatenate([np.asarray(s, float) for s in series]) if series else np.zeros(0)
    if not allv.size:
        return False
    far = np.concatenate([np.asarray(s, float)[~near] for s in series])
    if not far.size:
        far = allv
    lo, hi = float(np.nanmin(far)), float(np.nanmax(far))
    if include_zero:
        lo, hi = min(lo, 0.0), max(hi, 0.0)
    span = hi - lo or max(abs(hi), 1.0)
    flo, fhi = float(np.nanmin(allv)), float(np.nanmax(allv))
    clipped = fhi > hi + 0.25 * span or flo < lo - 0.25 * span
    if not clipped:
        lo, hi = min(lo, flo), max(hi, fhi)
        span = hi - lo or max(abs(hi), 1.0)
    ylo, yhi = lo - pad * span, hi + pad * span
    ax.set_ylim(ylo, yhi)
    if clipped:
        for s in series:
            s = np.asarray(s, float)
            for side, k in (("hi", int(np.nanargmax(s))), ("lo", int(np.nanargmin(s)))):
                v = s[k]
                if (side == "hi" and v > yhi) or (side == "lo" and v < ylo):
                    y = yhi if side == "hi" else ylo
                    ax.plot([sw.angles[k]], [y], marker="^" if side == "hi" else "v",
                            color=INK, ms=5, clip_on=False, zorder=6)
                    where = f"{sw.angles[k]:g}" + ("°" if sw.xrange is None else "")
                    ax.annotate(f"{fmt(v)} {unit} at {where}", (sw.angles[k], y),
                                xytext=(5, -9 if side == "hi" else 3),
                                textcoords="offset points", fontsize=6.5, color=INK,
                                ha="left" if k < 0.8 * len(sw.angles) else "right",
                                annotation_clip=False)
    return clipped


def torque_figure(sw, d):
    fig, axes = figure(2.9, margins=(0.72, 0.12, 0.46, 0.5))
    draw_torque(axes[0, 0], sw, d)
    return fig


def draw_torque(ax, sw, d) -> None:
    """The driver's effort over the sweep on ``ax``: the reference method's, the power
    balance's, the mean and the peak; ``sw`` the report's SweepData, ``d`` its Display."""
    kind = sw.effort
    u = d.unit(kind)
    a, t = with_gaps(sw.angles, d.value(sw.torque, kind))
    ax.plot(a, t, color=INK, lw=1.6, label=f"{sw.effort_label} ({sw.method_title})")
    series = [d.value(sw.torque, kind)]
    if sw.torque_check is not None:
        _, tc = with_gaps(sw.angles, d.value(sw.torque_check, kind))
        ax.plot(a, tc, color="#E69F00", lw=1.0, ls=(0, (4, 3)), label="power balance (check)")
    st = sw.stats
    if st is not None:
        mean, rms = d.value(st.mean, kind), d.value(st.rms, kind)
        ax.axhline(mean, color="#0072B2", lw=1.0, ls="--",
                   label=f"mean {fmt(mean)} {u} (RMS {fmt(rms)} {u})")
        pk = d.value(st.peak.value, kind)
        at = f"{st.peak.angle:g}°" if sw.xrange is None else f"{st.peak.angle:g}"
        ax.plot([st.peak.angle], [pk], "o", color="#D55E00", ms=5,
                label=f"peak {fmt(pk)} {u} at {at}")
    for r in sw.ref_angles:
        ax.axvline(r, color="0.4", lw=0.7, ls=":")
    ax.axhline(0, color="0.3", lw=0.6)
    crank_axis(ax, sw)
    scale_to_trusted(ax, sw, series, u)
    ax.set_ylabel(f"{'force' if kind == 'force' else 'torque'} [{u}]")
    legend_top(ax, 2)


def reactions_figure(sw, d):
    """Every joint's |F| on one axis (colour and line style per joint); the couples of T
    joints on a second axis below when any is not zero."""
    couples = [js for js in sw.joints if js.moment is not None
               and np.max(np.abs(js.moment), initial=0.0) > 1e-9 * max(
                   1.0, float(np.max(np.abs(sw.torque), initial=0.0)))]
    rows = 2 if couples else 1
    ncol = min(len(sw.joints), 5)
    top = 0.22 + 0.17 * math.ceil(len(sw.joints) / ncol)
    fig, axes = figure(3.0 + 1.5 * (rows - 1), rows, 1, gap=0.85,
                       margins=(0.72, 0.12, 0.46, top),
                       gridspec_kw={"height_ratios": [2, 1]} if rows == 2 else None)
    draw_reactions(axes[0, 0], sw, d, ncol, label=rows == 1)
    if rows == 2:
        ax2 = axes[1, 0]
        M = d.unit("moment")
        mseries, lines = [], []
        for js in couples:
            m = d.value(js.moment, "moment")
            mseries.append(m)
            a, mm = with_gaps(sw.angles, m)
            lines += ax2.plot(a, mm, color=js.color, lw=1.2,
                              label=literal(f"{js.name}: couple M{js.symbol[1:]}"))
        ax2.axhline(0, color="0.3", lw=0.5)
        crank_axis(ax2, sw)
        scale_to_trusted(ax2, sw, mseries, M)
        ax2.set_ylabel(f"slider couple [{M}]")
        legend_top(ax2, min(len(couples), 4), handles=lines)
    return fig


def draw_reactions(ax, sw, d, ncol: int = 5, label: bool = True) -> None:
    """Every joint's reaction magnitude |F| over the sweep on ``ax`` (colour and line style
    per joint, legend in ``ncol`` columns); ``label``: the x axis labelled."""
    F = d.unit("force")
    series, lines = [], []
    for i, js in enumerate(sw.joints):
        f = d.value(js.f, "force")
        series.append(f)
        a, ff = with_gaps(sw.angles, f)
        lines += ax.plot(a, ff, color=js.color, lw=1.4, ls=STYLES[i % 4],
                         label=literal(f"{js.name} ({js.symbol})"))
    crank_axis(ax, sw, label=label)
    scale_to_trusted(ax, sw, series, F)
    ax.set_ylabel(f"|F| [{F}]")
    legend_top(ax, min(len(sw.joints), ncol), handles=lines)


def polar_figure(sw, d):
    n = len(sw.polar)
    cols = min(n, 3)
    rows = math.ceil(n / cols)
    cell = WIDTH / cols
    F = d.unit("force")
    fig, axes = figure(cell * rows, rows, cols, gap=0.6, wgap=0.6,
                       margins=(0.55, 0.1, 0.42, 0.3))
    ref_idx = [int(np.argmin(np.abs(sw.angles - r))) for r in sw.ref_angles
               if len(sw.angles) and np.min(np.abs(sw.angles - r)) < 1e-9]
    near = sw.near if len(sw.near) == len(sw.angles) else np.zeros(len(sw.angles), bool)
    from matplotlib.ticker import MaxNLocator
    for ax, ps in zip(axes.flat, sw.polar):
        px, py = d.value(ps.x, "force"), d.value(ps.y, "force")
        _, x, y = with_gaps(sw.angles, px, py)
        if len(sw.flagged) == 0 and len(px):
            x, y = np.append(x, px[0]), np.append(y, py[0])   # close the turn
        ax.plot(x, y, color=ps.color, lw=1.3)
        ax.plot([0], [0], "+", color="k", ms=7)
        far = ~near if (~near).any() else np.ones(len(px), bool)
        r_far = float(np.max(np.hypot(px[far], py[far]), initial=0.0)) or 1.0
        r_all = float(np.max(np.hypot(px, py), initial=0.0))
        eq = d.value(ps.equivalent, "force") if ps.equivalent else None
        lim = max(r_far, eq or 0.0) * 1.18
        clipped = r_all > 1.25 * max(r_far, eq or 0.0)
        if eq:
            t = np.linspace(0, 2 * np.pi, 121)
            ax.plot(eq * np.cos(t), eq * np.sin(t), color="0.4", lw=0.8, ls=(0, (3, 2)))
        for k in ref_idx:
            ax.plot([0, px[k]], [0, py[k]], color=ps.color, lw=0.7, alpha=0.7)
            ax.plot([px[k]], [py[k]], "o", color=ps.color, ms=3.5)
            ax.annotate(f"{sw.angles[k]:g}°", (px[k], py[k]), fontsize=6.5,
                        xytext=(4 if px[k] >= 0 else -4, 4 if py[k] >= 0 else -4),
                        textcoords="offset points", ha="left" if px[k] >= 0 else "right",
                        va="bottom" if py[k] >= 0 else "top", clip_on=True)
        ax.set_xlim(-lim, lim)
        ax.set_ylim(-lim, lim)
        ax.set_aspect("equal", adjustable="box")
        ax.xaxis.set_major_locator(MaxNLocator(4, symmetric=True))
        ax.yaxis.set_major_locator(MaxNLocator(4, symmetric=True))
        frame = "global frame" if ps.carrier == "ground" else f"frame of {ps.carrier}"
        ax.set_title(literal(f"{ps.name} ({ps.symbol}), {frame}"), loc="left", fontsize=7.5)
        if clipped:
            ax.text(0.02, 0.02, f"peak {fmt(r_all)} {F}\noff scale", transform=ax.transAxes,
                    fontsize=6.2, color=INK, va="bottom", ha="left",
                    bbox={"facecolor": "white", "edgecolor": "none", "alpha": 0.8, "pad": 1})
        ax.set_xlabel(f"x [{F}]", fontsize=7)
        ax.set_ylabel(f"y [{F}]", fontsize=7, labelpad=1)
        ax.tick_params(labelsize=6.5)
        ax.axhline(0, color="0.6", lw=0.5)
        ax.axvline(0, color="0.6", lw=0.5)
    for ax in axes.flat[n:]:
        ax.set_visible(False)
    return fig


def shaking_figure(sw, d):
    fig, axes = figure(4.2, 2, 1, gap=0.75, margins=(0.72, 0.12, 0.46, 0.3))
    ax1, ax2 = axes[0, 0], axes[1, 0]
    sh = sw.shaking
    F, M = d.unit("force"), d.unit("moment")
    fx, fy, f, m = (d.value(v, k) for v, k in ((sh.fx, "force"), (sh.fy, "force"),
                                               (sh.f, "force"), (sh.m, "moment")))
    a, gfx, gfy, gf, gm = with_gaps(sw.angles, fx, fy, f, m)
    ax1.plot(a, gf, color=INK, lw=1.6, label="|F| shaking force")
    ax1.plot(a, gfx, color="#0072B2", lw=1.0, ls="--", label="x component")
    ax1.plot(a, gfy, color="#E69F00", lw=1.0, ls=":", label="y component")
    ax1.axhline(0, color="0.3", lw=0.5)
    ax1.set_ylabel(f"force on frame [{F}]")
    legend_top(ax1, 3)
    crank_axis(ax1, sw, label=False)
    scale_to_trusted(ax1, sw, [fx, fy, f], F)
    ax2.plot(a, gm, color="#CC79A7", lw=1.4, label="shaking moment about the driver pivot")
    ax2.axhline(0, color="0.3", lw=0.5)
    ax2.set_ylabel(f"moment on frame [{M}]")
    legend_top(ax2, 1)
    crank_axis(ax2, sw)
    scale_to_trusted(ax2, sw, [m], M)
    return fig


def _cycle_axis(ax, cd, label: bool = True) -> None:
    """0-360 deg over one turn, interpolated (left-out) angles marked."""
    ax.set_xlim(0, 360)
    ax.set_xticks(np.arange(0, 361, 45))
    if label:
        ax.set_xlabel("crank angle φ [deg]")
    for a in cd.interpolated:
        ax.axvspan(a - 0.5, a + 0.5, color="0.45", alpha=0.35, lw=0)


def flywheel_figure(cd, d):
    """The classic flywheel diagram: torque against its mean, the energy areas shaded and the
    largest fluctuation marked; motor rated (RMS) and peak torque when given."""
    fig, axes = figure(3.6, 2, 1, gap=0.4, margins=(0.72, 0.12, 0.42, 0.5),
                       gridspec_kw={"height_ratios": [3, 2]}, sharex=True)
    ax, ax2 = axes[0, 0], axes[1, 0]
    M = d.unit("moment")
    a, t, mean = cd.angles, d.value(cd.torque, "moment"), d.value(cd.mean, "moment")
    ax.plot(a, t, color=INK, lw=1.5, label="driver torque")
    ax.axhline(mean, color="#0072B2", lw=1.0, ls="--", label=f"mean {fmt(mean)} {M}")
    ax.fill_between(a, t, mean, where=t >= mean, interpolate=True, color="#E69F00", alpha=0.35,
                    lw=0, label="above the mean (energy in)")
    ax.fill_between(a, t, mean, where=t < mean, interpolate=True, color="#56B4E9", alpha=0.35,
                    lw=0, label="below the mean (energy out)")
    for value, name, style in ((cd.rated_torque, "motor rated (RMS)", "-."),
                               (cd.peak_torque, "motor peak", ":")):
        if value:
            v = d.value(value, "moment")
            ax.axhline(v, color="#CC79A7", lw=1.0, ls=style, label=f"{name} {fmt(v)} {M}")
            if name == "motor peak" and np.min(t) < 0:
                ax.axhline(-v, color="#CC79A7", lw=1.0, ls=style)
    ax.set_ylabel(f"torque [{M}]")
    legend_top(ax, 3)
    _cycle_axis(ax, cd, label=False)
    e = cd.energy
    hi, lo = int(np.argmax(e)), int(np.argmin(e))
    ax2.plot(a, e, color="#009E73", lw=1.4)
    ax2.plot([a[hi], a[lo]], [e[hi], e[lo]], "o", color="#D55E00", ms=4)
    ax2.annotate("", xy=(a[lo], e[lo]), xytext=(a[lo], e[hi]),
                 arrowprops={"arrowstyle": "<->", "color": "#D55E00", "lw": 1.0})
    right = a[lo] > 250
    ax2.annotate(f"ΔE = {fmt(e[hi] - e[lo])} J", (a[lo], (e[hi] + e[lo]) / 2), fontsize=7.5,
                 xytext=(-6 if right else 6, 0), textcoords="offset points", color="#D55E00",
                 va="center", ha="right" if right else "left")
    ax2.axhline(0, color="0.3", lw=0.5)
    ax2.set_ylabel("∫(M − mean) dφ [J]")
    _cycle_axis(ax2, cd)
    return fig


def breakdown_figure(cd, d):
    """Torque by source, stacked: positive parts above zero, negative parts below."""
    n = len(cd.sources) + 1
    ncol = min(5, n)
    fig, axes = figure(2.9, margins=(0.72, 0.12, 0.46, 0.22 + 0.17 * math.ceil(n / ncol)))
    ax = axes[0, 0]
    M = d.unit("moment")
    a = cd.angles
    up, down = np.zeros_like(a), np.zeros_like(a)
    shown = []                  # the legend's entries, given: a name may start with "_"
    for k, (name, part) in enumerate(cd.sources.items()):
        color = SOURCE_COLORS[k % len(SOURCE_COLORS)]
        part = d.value(part, "moment")
        pos, neg = np.maximum(part, 0), np.minimum(part, 0)
        shown.append(ax.fill_between(a, up, up + pos, color=color, alpha=0.6, lw=0,
                                     label=literal(name)))
        ax.fill_between(a, down, down + neg, color=color, alpha=0.6, lw=0)
        up, down = up + pos, down + neg
    shown += ax.plot(a, d.value(cd.torque, "moment"), color=INK, lw=1.3, label="total")
    ax.axhline(0, color="0.3", lw=0.6)
    ax.set_ylabel(f"torque [{M}]")
    legend_top(ax, ncol, handles=shown)
    _cycle_axis(ax, cd)
    return fig


def transmission_figure(cd, d):
    n = len(cd.transmission) + (cd.transmission_limit is not None)
    fig, axes = figure(2.5, margins=(0.72, 0.12, 0.46, 0.22 + 0.17 * math.ceil(n / 3)))
    ax = axes[0, 0]
    for k, (label, ta) in enumerate(cd.transmission.items()):
        ax.plot(cd.angles, ta, color=SOURCE_COLORS[k % len(SOURCE_COLORS)], lw=1.4,
                ls=STYLES[k % 4], label=literal(f"group {label}"))
    if cd.transmission_limit is not None:
        ax.axhline(cd.transmission_limit, color="#D55E00", lw=1.0, ls="--",
                   label=f"limit {cd.transmission_limit:g}°")
    ax.set_ylim(0, 90)
    ax.set_yticks(np.arange(0, 91, 15))
    ax.set_ylabel("transmission angle [deg]")
    legend_top(ax, 3)
    _cycle_axis(ax, cd)
    return fig


def balance_figure(cd, d):
    """Polar trace of the inertial shaking force without and with the counterweight."""
    w = WIDTH * 0.55
    fig, axes = figure(w, margins=(0.62, 0.12, 0.42, 0.45), width=w)
    ax = axes[0, 0]
    F = d.unit("force")
    for xy, name, color, style in ((cd.inertial, "without counterweight", "#0072B2", "-"),
                                   (cd.balanced, "with counterweight", "#D55E00", "--")):
        xy = d.value(np.asarray(xy), "force")
        closed = np.vstack([xy, xy[:1]])
        ax.plot(closed[:, 0], closed[:, 1], color=color, lw=1.3, ls=style, label=name)
    ax.plot([0], [0], "+", color="k", ms=8)
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel(f"x [{F}]")
    ax.set_ylabel(f"y [{F}]")
    legend_top(ax, 1)
    return fig


@styled
def write_plots(model, outdir: Path) -> list[Path]:
    """Every sweep and cycle figure of ``model`` into ``outdir`` (SVG)."""
    sw, figs, d = model.sweep, model.figures, model.display
    out = []
    cd = model.design.data
    if cd is not None:
        for key, make in (("flywheel", flywheel_figure), ("breakdown", breakdown_figure),
                          ("transmission", transmission_figure), ("balance", balance_figure)):
            if key in figs:
                out += save(make(cd, d), outdir, figs[key].stem)
    if len(sw.angles) == 0:
        return out
    makers = {"torque": torque_figure, "reactions": reactions_figure,
              "polar": polar_figure, "shaking": shaking_figure}
    for key, make in makers.items():
        if key in figs and (key != "reactions" or sw.joints):
            out += save(make(sw, d), outdir, figs[key].stem)
    return out


# ------------------------------------------------------------------------ for notebooks

def _axes(ax, height: float):
    """``ax``, or a new figure's one axes (report width, ``height`` inches)."""
    if ax is not None:
        return ax
    fig, axes = figure(height, margins=(0.72, 0.12, 0.46, 0.5))
    return axes[0, 0]


@styled
def plot_torque(analysis, ax=None):
    """The driver's effort over the sweep of ``analysis`` as the report draws it, on ``ax``
    (a matplotlib Axes; default: a new figure's); returns the Axes.

        fig, ax = plt.subplots()
        mechreport.report.plots.plot_torque(mechreport.analyse("specs/four_bar.yaml"), ax=ax)
    """
    from .model import sweep_data
    sw, d = sweep_data(analysis)
    ax = _axes(ax, 2.9)
    draw_torque(ax, sw, d)
    return ax


@styled
def plot_reactions(analysis, ax=None):
    """Every joint's reaction magnitude over the sweep of ``analysis`` as the report draws
    it, on ``ax`` (default: a new figure's); returns the Axes."""
    from .model import sweep_data
    sw, d = sweep_data(analysis)
    ax = _axes(ax, 3.0)
    draw_reactions(ax, sw, d)
    return ax
