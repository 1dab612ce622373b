"""Sweep and cycle plots of a report model: driver torque, joint reactions, polar bearing
diagrams, shaking force and moment, flywheel diagram, torque by source, transmission angle,
balancing, the driver torque with and without friction. Each figure is one SVG file, shown
by both the PDF and the Markdown report.

Values are plotted in the report's display units (``model.display``) and labelled by the one
number formatter. Near-singular stretches (within ``sweep.near_deg`` of a left-out angle) are
hatched and do not set a plot's scale: a curve that runs off the scale there is clipped and
its extreme is marked at the edge with its value (one label for marks at the same angle).
Colours are Okabe & Ito's colour-blind-safe set. Layouts are fixed (no tight bounding boxes:
each figure is drawn once, when saved); text that could run into other text, a curve or an
edge is measured first and placed where it is free (see "measuring and placing" below).

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
    fig = Figure(figsize=(width, height))          # no pyplot bookkeeping: closed by GC
    axes = fig.subplots(rows, cols, squeeze=False, **kw)
    _layout(fig, rows, cols, gap, wgap, margins)
    return fig, axes


def _layout(fig, rows: int, cols: int, gap: float, wgap: float, margins) -> None:
    """Place the axes grid of ``fig``: ``margins`` (left, right, bottom, top) and the gaps
    between rows (``gap``) and columns (``wgap``) [in]."""
    width, height = fig.get_size_inches()
    left, right, bottom, top = margins
    fig.subplots_adjust(left=left / width, right=1 - right / width, bottom=bottom / height,
                        top=1 - top / height, hspace=gap / max((height - bottom - top) / rows
                                                               - gap, 0.3),
                        wspace=wgap / max((width - left - right) / cols - wgap, 0.3))


# ------------------------------------------------------------------ measuring and placing
#
# Layouts are fixed, and a figure is drawn once, when it is saved. Where text could run into
# other text, a curve or the figure's edge (off-scale values, the ΔE label, limits off the
# scale, reference angles, tick labels of large numbers), it is measured before that with
# Agg's text metrics (text layout only, nothing is drawn) and placed at the first of a few
# candidate spots that is free; a figure where the first spot is free is drawn as before.

#: room kept between placed text and other text, and between placed text and a curve (half
#: its line width, and some air) [pt]
CLEAR = 1.5
LINE_CLEAR = 3.0


def _renderer(fig):
    """A renderer to measure the text of ``fig`` with before it is drawn."""
    from matplotlib.backends.backend_agg import RendererAgg
    w, h = fig.bbox.size
    return RendererAgg(max(int(w), 1), max(int(h), 1), fig.dpi)


def _px(fig, pt: float) -> float:
    """``pt`` points in display units of ``fig``."""
    return pt * fig.dpi / 72.0


def _text_size(renderer, text: str, size: float) -> tuple[float, float, float]:
    """(width, height, descent) of ``text`` at ``size`` points, in display units."""
    from matplotlib.font_manager import FontProperties
    return renderer.get_text_width_height_descent(text, FontProperties(size=size), ismath=False)


def _grow(box, by: float):
    return (box[0] - by, box[1] - by, box[2] + by, box[3] + by)


def _overlaps(a, b) -> bool:
    """Boxes (x0, y0, x1, y1) overlap (touching is not overlapping)."""
    return min(a[2], b[2]) > max(a[0], b[0]) and min(a[3], b[3]) > max(a[1], b[1])


def _inside(box, outer, slack: float = 1.0) -> bool:
    return (box[0] >= outer[0] - slack and box[1] >= outer[1] - slack
            and box[2] <= outer[2] + slack and box[3] <= outer[3] + slack)


def _crossings(box, lines) -> int:
    """How many of the polylines ``lines`` (display coordinates, (n, 2) arrays; NaN rows are
    gaps) pass through ``box`` (x0, y0, x1, y1). Exact for straight segments."""
    x0, y0, x1, y1 = box
    count = 0
    for p in lines:
        p = np.asarray(p, float).reshape(-1, 2)
        if len(p) == 1:                                   # a marker: one point
            count += bool(x0 <= p[0, 0] <= x1 and y0 <= p[0, 1] <= y1)
            continue
        a, b = p[:-1], p[1:]
        ok = np.isfinite(a).all(axis=1) & np.isfinite(b).all(axis=1)
        a, b = a[ok], b[ok]
        lo = np.maximum(np.minimum(a[:, 0], b[:, 0]), x0)
        hi = np.minimum(np.maximum(a[:, 0], b[:, 0]), x1)
        sel = lo <= hi
        a, b, lo, hi = a[sel], b[sel], lo[sel], hi[sel]
        if not len(a):
            continue
        dx = b[:, 0] - a[:, 0]
        flat = np.abs(dx) < 1e-12
        safe = np.where(flat, 1.0, dx)
        t0 = np.where(flat, 0.0, (lo - a[:, 0]) / safe)
        t1 = np.where(flat, 1.0, (hi - a[:, 0]) / safe)
        ya = a[:, 1] + t0 * (b[:, 1] - a[:, 1])
        yb = a[:, 1] + t1 * (b[:, 1] - a[:, 1])
        count += bool(np.any((np.minimum(ya, yb) <= y1) & (np.maximum(ya, yb) >= y0)))
    return count


def _data_lines(ax, *xy) -> list[np.ndarray]:
    """Polylines (x, y) in data coordinates as display coordinates."""
    return [ax.transData.transform(np.column_stack([np.asarray(x, float),
                                                    np.asarray(y, float)])) for x, y in xy]


def _hline(ax, y: float) -> np.ndarray:
    """A horizontal line across ``ax`` at data ``y``, in display coordinates."""
    lo, hi = ax.get_xlim()
    return _data_lines(ax, ([lo, hi], [y, y]))[0]


def _place(ax, text, candidates, lines=(), boxes=(), renderer=None):
    """Put the Annotation ``text`` at the first of ``candidates`` — (xy, offset [pt], ha,
    va) — where it stays inside the axes, LINE_CLEAR from the polylines ``lines`` and CLEAR
    from the ``boxes`` (display coordinates); else where it is least in the way. Returns the
    box it takes (display coordinates)."""
    r = renderer or _renderer(ax.figure)
    outer = tuple(ax.bbox.extents)
    clear, line_clear = _px(ax.figure, CLEAR), _px(ax.figure, LINE_CLEAR)
    best, best_score = None, math.inf
    for xy, offset, ha, va in candidates:
        text.xy, text.xyann = xy, offset
        text.set_ha(ha)
        text.set_va(va)
        box = tuple(text.get_window_extent(r).extents)
        score = (0 if _inside(box, outer) else 100) + _crossings(_grow(box, line_clear), lines) \
            + sum(_overlaps(_grow(box, clear), b) for b in boxes)
        if score < best_score:
            best, best_score = (xy, offset, ha, va, box), score
        if score == 0:
            break
    xy, offset, ha, va, box = best
    text.xy, text.xyann = xy, offset
    text.set_ha(ha)
    text.set_va(va)
    return box


def _fit_y_labels(fig, axes, relayout, left: float, wgap: float) -> None:
    """Widen the left margin (``left`` [in]) or the gap between columns (``wgap`` [in]) of
    ``fig`` until the y tick labels and label of every visible axes in ``axes`` (2-D, rows x
    columns) fit between the figure's edge or the axes to their left; ``relayout(left,
    wgap)`` places the grid again. Nothing changes where they fit (large numbers in N, or
    small ones in kN, are what need the room)."""
    r = _renderer(fig)
    pad = _px(fig, 2.0)
    for _ in range(3):
        need_left = need_gap = 0.0
        for row in axes:
            prev = None
            for ax in row:
                if not ax.get_visible():
                    continue
                ax.apply_aspect()
                box = ax.yaxis.get_tightbbox(r)
                if box is None:                 # nothing drawn left of this axes
                    continue
                x0 = box.x0
                room = x0 - (prev.get_position().x1 * fig.bbox.width if prev is not None
                             else 0.0)
                short = max(pad - room, 0.0) / fig.dpi
                if prev is None:
                    need_left = max(need_left, short)
                else:
                    need_gap = max(need_gap, short)
                prev = ax
        if need_left <= 0 and need_gap <= 0:
            return
        left, wgap = left + need_left, wgap + need_gap
        relayout(left, wgap)


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
                     include_zero: bool = True, names: list[str] | None = None) -> bool:
    """Set the y-limits from the values away from left-out angles; where a curve runs beyond
    them near a left-out angle, clip it and mark its extreme at the edge with its value
    (``names``: each series' name, given in the labels). True if anything was clipped."""
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
        marks = []
        for i, s in enumerate(series):
            s = np.asarray(s, float)
            for side, k in (("hi", int(np.nanargmax(s))), ("lo", int(np.nanargmin(s)))):
                v = s[k]
                if (side == "hi" and v > yhi) or (side == "lo" and v < ylo):
                    y = yhi if side == "hi" else ylo
                    ax.plot([sw.angles[k]], [y], marker="^" if side == "hi" else "v",
                            color=INK, ms=5, clip_on=False, zorder=6)
                    name = names[i] if names is not None and len(series) > 1 else None
                    marks.append((side, float(sw.angles[k]), float(v), name))
        off_scale_labels(ax, sw, marks, unit)
    return clipped


OFF_SCALE_SIZE = 6.5     # [pt], the labels of values off the scale


def _off_scale_text(group, unit: str, deg: str) -> str:
    """One label for off-scale values ``group`` [(side, angle, value, name)]: the largest
    two with their names, the angle once when they share it, then how many more."""
    group = sorted(group, key=lambda m: -abs(m[2]))
    same = len({m[1] for m in group}) == 1
    parts = []
    for _, angle, v, name in group[:2]:
        part = f"{fmt(v)} {unit}" + (f" ({literal(name)})" if name is not None else "")
        parts.append(part if same else f"{part} at {angle:g}{deg}")
    text = ", ".join(parts)
    if len(group) > 2:
        text += f" and {len(group) - 2} more"
    return text + (f" at {group[0][1]:g}{deg}" if same else "")


def off_scale_labels(ax, sw, marks, unit: str) -> None:
    """Label the off-scale marks ``marks`` [(side "hi"/"lo", angle, value, name)] at the top
    and bottom edges of ``ax`` so that no two labels overlap: marks at (nearly) the same
    angle share one label (the values with the series' names, the angle once), and a label
    that would run into another, or past the axes' edge, goes on the other side of its mark
    or one line further in."""
    fig = ax.figure
    r = _renderer(fig)
    deg = "°" if sw.xrange is None else ""
    pt = _px(fig, 1.0)
    x0, x1 = ax.bbox.x0, ax.bbox.x1
    for side in ("hi", "lo"):
        clusters: list[list] = []
        for m in sorted((m for m in marks if m[0] == side), key=lambda m: m[1]):
            x = ax.transData.transform((m[1], 0.0))[0]
            if clusters and x - clusters[-1][-1][0] < 6 * pt:      # the marks touch
                clusters[-1].append((x, m))
            else:
                clusters.append([(x, m)])
        taken = []
        for cluster in clusters:
            group = [m for _, m in cluster]
            text = _off_scale_text(group, unit, deg)
            anchor = max(group, key=lambda m: abs(m[2]))[1]
            x = ax.transData.transform((anchor, 0.0))[0]
            w = _text_size(r, text, OFF_SCALE_SIZE)[0]
            spots = [(row, ha) for row in range(4) for ha in ("left", "right")]
            for row, ha in spots:
                a = x + 5 * pt if ha == "left" else x - 5 * pt - w
                span = (a, row, a + w)
                if a >= x0 - pt and a + w <= x1 + pt and not any(
                        t[1] == row and t[0] < span[2] + 3 * pt and span[0] < t[2] + 3 * pt
                        for t in taken):
                    break
            taken.append(span)
            y = ax.get_ylim()[1] if side == "hi" else ax.get_ylim()[0]
            dy = -9 - 9 * row if side == "hi" else 3 + 9 * row
            ax.annotate(text, (anchor, y), xytext=(5 if ha == "left" else -5, dy),
                        textcoords="offset points", fontsize=OFF_SCALE_SIZE, color=INK, ha=ha,
                        annotation_clip=False)


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
    curves = [(a, t)]
    if sw.torque_check is not None:
        _, tc = with_gaps(sw.angles, d.value(sw.torque_check, kind))
        ax.plot(a, tc, color="#E69F00", lw=1.0, ls=(0, (4, 3)), label="power balance (check)")
        curves.append((a, tc))
    levels = [0.0]
    st = sw.stats
    if st is not None:
        mean = d.value(st.mean, kind)
        ax.axhline(mean, color="#0072B2", lw=1.0, ls="--",
                   label=f"mean {d.num(st.mean, kind)} {u} (RMS {d.num(st.rms, kind)} {u})")
        pk = d.value(st.peak.value, kind)
        at = f"{st.peak.angle:g}°" if sw.xrange is None else f"{st.peak.angle:g}"
        ax.plot([st.peak.angle], [pk], "o", color="#D55E00", ms=5,
                label=f"peak {d.num(st.peak.value, kind)} {u} at {at}")
        levels.append(mean)
        curves.append(([st.peak.angle], [pk]))
    for r in sw.ref_angles:
        ax.axvline(r, color="0.4", lw=0.7, ls=":")
    ax.axhline(0, color="0.3", lw=0.6)
    crank_axis(ax, sw)
    scale_to_trusted(ax, sw, series, u)
    label_reference_lines(ax, sw, curves, levels)
    ax.set_ylabel(f"{'force' if kind == 'force' else 'torque'} [{u}]")
    legend_top(ax, 2)


REF_SIZE = 6.5           # [pt], the names of the reference angles' lines


def label_reference_lines(ax, sw, curves, levels) -> None:
    """Name the dotted lines at the reference angles of ``sw`` (``φ = 30°``, or the sweep's
    quantity and value) at the top or bottom of ``ax``, beside the line, where the text
    crosses none of ``curves`` [(x, y) in data coordinates], the horizontal lines at
    ``levels``, the text already there or another reference line's name."""
    if not len(sw.ref_angles):
        return
    fig = ax.figure
    r = _renderer(fig)
    lines = _data_lines(ax, *curves) + [_hline(ax, y) for y in levels]
    boxes = [tuple(t.get_window_extent(r).extents) for t in ax.texts if t.get_text()]
    for ln in ax.get_lines():                       # off-scale marks at the edges
        if not ln.get_clip_on() and len(ln.get_xdata()) == 1:
            lines += _data_lines(ax, (ln.get_xdata(), ln.get_ydata()))
    lo, hi = ax.get_ylim()
    if sw.xrange is None:
        name = "φ = {:g}°"
    else:
        quantity, unit = sw.xlabel.rsplit(" [", 1)
        name = f"{quantity} {{:g}} {unit.rstrip(']')}"
    for ref in sw.ref_angles:
        text = ax.annotate(name.format(ref), (ref, hi), textcoords="offset points",
                           xytext=(2, -2), fontsize=REF_SIZE, color="0.35", ha="left",
                           va="top", annotation_clip=False)
        cands = [((ref, hi), (2, -2), "left", "top"), ((ref, hi), (-2, -2), "right", "top"),
                 ((ref, lo), (2, 2), "left", "bottom"), ((ref, lo), (-2, 2), "right", "bottom")]
        boxes.append(_place(ax, text, cands, lines, boxes, r))


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
        scale_to_trusted(ax2, sw, mseries, M, names=[js.name for js in couples])
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
    scale_to_trusted(ax, sw, series, F, names=[js.name for js in sw.joints])
    ax.set_ylabel(f"|F| [{F}]")
    legend_top(ax, min(len(sw.joints), ncol), handles=lines)


def polar_figure(sw, d):
    n = len(sw.polar)
    cols = min(n, 3)
    rows = math.ceil(n / cols)
    cell = WIDTH / cols
    F = d.unit("force")
    margins, gap, wgap = (0.55, 0.1, 0.42, 0.3), 0.6, 0.6
    titles = _polar_titles(sw.polar, (WIDTH - margins[0] - margins[1]) / cols - wgap)
    if any("\n" in t for t in titles):             # a second line of title above each row
        margins, gap = (margins[0], margins[1], margins[2], margins[3] + 0.12), gap + 0.12
    fig, axes = figure(cell * rows, rows, cols, gap=gap, wgap=wgap, margins=margins)
    rend = _renderer(fig)
    ref_idx = [int(np.argmin(np.abs(sw.angles - r))) for r in sw.ref_angles
               if len(sw.angles) and np.min(np.abs(sw.angles - r)) < 1e-9]
    near = sw.near if len(sw.near) == len(sw.angles) else np.zeros(len(sw.angles), bool)
    from matplotlib.ticker import MaxNLocator
    for ax, ps, title in zip(axes.flat, sw.polar, titles):
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
        for group in _coincident(ref_idx, px, py, 0.05 * lim):
            k = group[0]
            ax.annotate(", ".join(f"{sw.angles[j]:g}°" for j in group), (px[k], py[k]),
                        fontsize=6.5, xytext=(4 if px[k] >= 0 else -4, 4 if py[k] >= 0 else -4),
                        textcoords="offset points", ha="left" if px[k] >= 0 else "right",
                        va="bottom" if py[k] >= 0 else "top", clip_on=True)
        ax.set_xlim(-lim, lim)
        ax.set_ylim(-lim, lim)
        ax.set_aspect("equal", adjustable="box")
        ax.apply_aspect()
        _keep_inside(ax, rend)
        ax.xaxis.set_major_locator(MaxNLocator(4, symmetric=True))
        ax.yaxis.set_major_locator(MaxNLocator(4, symmetric=True))
        ax.set_title(literal(title), loc="left", fontsize=POLAR_TITLE_SIZE)
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

    def relayout(left, wgap):
        _layout(fig, rows, cols, gap, wgap, (left, *margins[1:]))
        for ax in axes.flat[:n]:
            ax.apply_aspect()
            _keep_inside(ax, rend)
    _fit_y_labels(fig, axes, relayout, margins[0], wgap)
    return fig


#: the polar title's font size [pt], and how far it may run past its axes' right edge [in]
POLAR_TITLE_SIZE = 7.5
POLAR_TITLE_OVERHANG = 0.1


def _polar_titles(polar, axes_width: float) -> list[str]:
    """Each polar diagram's title, "name (symbol), frame", with the frame on a second line
    where one line would be wider than the axes (``axes_width`` [in]) and a little more
    (a force on one link of a pin, ``C.on.upper``, has long names)."""
    from matplotlib.backends.backend_agg import RendererAgg
    r = RendererAgg(10, 10, 72)                     # 1 px = 1 pt: widths in pt
    titles = []
    for ps in polar:
        frame = "global frame" if ps.carrier == "ground" else f"frame of {ps.carrier}"
        title = f"{ps.name} ({ps.symbol}), {frame}"
        if _text_size(r, title, POLAR_TITLE_SIZE)[0] > 72 * (axes_width + POLAR_TITLE_OVERHANG):
            title = f"{ps.name} ({ps.symbol}),\n{frame}"
        titles.append(title)
    return titles


def _coincident(indices, x, y, within: float) -> list[list[int]]:
    """``indices`` grouped where their points (``x``, ``y``) lie ``within`` of the group's
    first point, in the order of their first member: reference angles where a force is
    the same (a two-force member's force at angles symmetric about a dead centre) share one
    label, "30°, 200°", instead of printing one label on the other."""
    groups: list[list[int]] = []
    for k in indices:
        home = next((g for g in groups if math.hypot(x[k] - x[g[0]], y[k] - y[g[0]]) <= within),
                    None)
        if home is None:
            groups.append([k])
        else:
            home.append(k)
    return groups


def _keep_inside(ax, renderer) -> None:
    """Turn each reference angle's label on a polar diagram (away from the origin, on the
    side of its point) to another corner of its point where it would be cut by the axes'
    edge, or run into the label before it."""
    from matplotlib.text import Annotation
    boxes = []
    for text in ax.texts:
        if not isinstance(text, Annotation) or not text.get_clip_on():
            continue
        dx, dy = text.xyann
        sx, sy = (1 if dx >= 0 else -1), (1 if dy >= 0 else -1)
        cands = [(text.xy, (4 * a, 4 * b), "left" if a > 0 else "right",
                  "bottom" if b > 0 else "top")
                 for a, b in ((sx, sy), (-sx, sy), (sx, -sy), (-sx, -sy))]
        boxes.append(_place(ax, text, cands, (), boxes, renderer))


def shaking_figure(sw, d):
    """The shaking force (magnitude and components) and the shaking moment over the sweep,
    one panel each; a part that is 0 at every angle (``sw.shaking_zero``: round-off) is left
    out, and the other panel fills the figure alone."""
    parts = [k for k in ("force", "moment") if k not in sw.shaking_zero] or ["force", "moment"]
    if len(parts) == 2:
        fig, axes = figure(4.2, 2, 1, gap=0.75, margins=(0.72, 0.12, 0.46, 0.3))
    else:
        fig, axes = figure(2.6, margins=(0.72, 0.12, 0.46, 0.3))
    panels = dict(zip(parts, axes[:, 0]))
    sh = sw.shaking
    F, M = d.unit("force"), d.unit("moment")
    fx, fy, f, m = (d.value(v, k) for v, k in ((sh.fx, "force"), (sh.fy, "force"),
                                               (sh.f, "force"), (sh.m, "moment")))
    a, gfx, gfy, gf, gm = with_gaps(sw.angles, fx, fy, f, m)
    if "force" in panels:
        ax1 = panels["force"]
        ax1.plot(a, gf, color=INK, lw=1.6, label="|F| shaking force")
        ax1.plot(a, gfx, color="#0072B2", lw=1.0, ls="--", label="x component")
        ax1.plot(a, gfy, color="#E69F00", lw=1.0, ls=":", label="y component")
        ax1.axhline(0, color="0.3", lw=0.5)
        ax1.set_ylabel(f"force on frame [{F}]")
        legend_top(ax1, 3)
        crank_axis(ax1, sw, label="moment" not in panels)
        scale_to_trusted(ax1, sw, [fx, fy, f], F, names=["x", "y", "|F|"])
    if "moment" in panels:
        ax2 = panels["moment"]
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


#: a motor limit further than this share of the torque's range beyond it is off the scale
LIMIT_REACH = 0.5
LIMIT_COLOR = "#CC79A7"


def flywheel_figure(cd, d):
    """The classic flywheel diagram: torque against its mean, the energy areas shaded and the
    largest fluctuation marked; motor rated (RMS) and peak torque when given. The torque
    panel is scaled to the torque: a motor line further than LIMIT_REACH of its range beyond
    it is not drawn but marked at the panel's edge, an arrow with its value."""
    fig, axes = figure(3.6, 2, 1, gap=0.4, margins=(0.72, 0.12, 0.42, 0.5),
                       gridspec_kw={"height_ratios": [3, 2]}, sharex=True)
    ax, ax2 = axes[0, 0], axes[1, 0]
    M = d.unit("moment")
    a, t, mean = cd.angles, d.value(cd.torque, "moment"), d.value(cd.mean, "moment")
    ax.plot(a, t, color=INK, lw=1.5, label="driver torque")
    ax.axhline(mean, color="#0072B2", lw=1.0, ls="--", label=f"mean {d.num(cd.mean, 'moment')} {M}")
    ax.fill_between(a, t, mean, where=t >= mean, interpolate=True, color="#E69F00", alpha=0.35,
                    lw=0, label="above the mean (energy in)")
    ax.fill_between(a, t, mean, where=t < mean, interpolate=True, color="#56B4E9", alpha=0.35,
                    lw=0, label="below the mean (energy out)")
    lo, hi = min(float(np.min(t)), mean), max(float(np.max(t)), mean)
    reach = LIMIT_REACH * ((hi - lo) or max(abs(hi), 1.0))
    drawn, off = [mean], {"hi": [], "lo": []}
    for value, name, style in ((cd.rated_torque, "motor rated (RMS)", "-."),
                               (cd.peak_torque, "motor peak", ":")):
        if value:
            v = d.value(value, "moment")
            levels = [v] + ([-v] if name == "motor peak" and np.min(t) < 0 else [])
            labelled = False
            for level in levels:
                if lo - reach <= level <= hi + reach:
                    ax.axhline(level, color=LIMIT_COLOR, lw=1.0, ls=style,
                               label=None if labelled else f"{name} {d.num(value, 'moment')} {M}")
                    labelled = True
                    drawn.append(level)
                elif level == v:                  # -peak far off the scale means nothing
                    off["hi" if v > hi else "lo"].append(f"{name} {d.num(value, 'moment')} {M}")
    ax.set_ylabel(f"torque [{M}]")
    legend_top(ax, 3)
    _cycle_axis(ax, cd, label=False)
    e = cd.energy
    i_hi, i_lo = int(np.argmax(e)), int(np.argmin(e))
    ax2.plot(a, e, color="#009E73", lw=1.4)
    ax2.plot([a[i_hi], a[i_lo]], [e[i_hi], e[i_lo]], "o", color="#D55E00", ms=4)
    ax2.annotate("", xy=(a[i_lo], e[i_lo]), xytext=(a[i_lo], e[i_hi]),
                 arrowprops={"arrowstyle": "<->", "color": "#D55E00", "lw": 1.0})
    right = a[i_lo] > 250
    delta = ax2.annotate(f"ΔE = {fmt(e[i_hi] - e[i_lo])} J", (a[i_lo], (e[i_hi] + e[i_lo]) / 2),
                         fontsize=7.5, xytext=(-6 if right else 6, 0),
                         textcoords="offset points", color="#D55E00", va="center",
                         ha="right" if right else "left")
    ax2.axhline(0, color="0.3", lw=0.5)
    ax2.set_ylabel("∫(M − mean) dφ [J]")
    _cycle_axis(ax2, cd)
    r = _renderer(fig)
    _place_delta_e(ax2, delta, a, e, i_hi, i_lo, right, r, cd.interpolated)
    for side, names in off.items():
        if names:
            _limit_arrow(ax, side, "\n".join(names), [(a, t)], drawn, r)
    return fig


def _place_delta_e(ax, text, a, e, i_hi, i_lo, right: bool, renderer, shaded=()) -> None:
    """Put the ΔE label beside its arrow where neither the energy curve nor a line across
    the panel (the zero line, the horizontal grid lines, the grey bands of the ``shaded``
    angles) crosses it: halfway up the arrow on the side with more room first, then higher
    and lower, then the other side."""
    x, top, bottom = a[i_lo], e[i_hi], e[i_lo]
    sides = [(-6, "right"), (6, "left")] if right else [(6, "left"), (-6, "right")]
    cands = [((x, bottom + f * (top - bottom)), (dx, 0), ha, "center")
             for dx, ha in sides for f in (0.5, 0.3, 0.7, 0.15, 0.85, 0.4, 0.6)]
    dots = _data_lines(ax, ([a[i_hi]], [e[i_hi]]), ([a[i_lo]], [e[i_lo]]))
    lo, hi = ax.get_ylim()
    levels = {0.0} | {float(y) for y in ax.get_yticks() if lo <= y <= hi}
    across = [_hline(ax, y) for y in sorted(levels)]
    across += _data_lines(ax, *(([s, s], [lo, hi]) for s in shaded))
    _place(ax, text, cands, _data_lines(ax, (a, e)) + dots + across, (), renderer)


def _limit_arrow(ax, side: str, label: str, curves, levels, renderer) -> None:
    """Mark a limit off the scale of ``ax`` (above it: ``side`` "hi", below: "lo") with an
    arrow at that edge and ``label`` beside it, where neither crosses ``curves`` [(x, y)] or
    the horizontal lines at ``levels``."""
    fig = ax.figure
    curve_px = _data_lines(ax, *curves)
    lines = curve_px + [_hline(ax, y) for y in levels]
    up = side == "hi"
    edge = 1.0 if up else 0.0
    trans = ax.get_xaxis_transform()                   # x in data, y in axes fraction
    text = ax.annotate(label, (0.0, edge), xycoords=trans, xytext=(4, 0),
                       textcoords="offset points", fontsize=7, color=LIMIT_COLOR,
                       annotation_clip=False, linespacing=1.1)
    w = max(_text_size(renderer, part, 7)[0] for part in label.split("\n"))
    spots = []
    for x in np.linspace(*ax.get_xlim(), 17)[1:-1]:
        x0, y0 = ax.transData.transform((x, ax.get_ylim()[1 if up else 0]))
        near = np.concatenate([c[:, 1][np.abs(c[:, 0] - x0) <= w] for c in curve_px])
        near = near[np.isfinite(near)]
        room = (y0 - np.max(near) if up else np.min(near) - y0) if near.size else np.inf
        for length in (16.0, 12.0, 9.0):               # the arrow [pt]
            tail = y0 - _px(fig, length) if up else y0 + _px(fig, length)
            shaft = _grow((x0, min(y0, tail), x0, max(y0, tail)), _px(fig, LINE_CLEAR))
            spots.append((_crossings(shaft, lines), -room, -length, x))
    spots.sort()                                    # a clear shaft, the most room, longest
    cands = [((x, edge), (dx, length / 2 if up else -length / 2), ha, "center")
             for _, _, length, x in spots for dx, ha in ((4, "left"), (-4, "right"))]
    _place(ax, text, cands, lines, (), renderer)
    x, length = text.xy[0], 2 * abs(text.xyann[1])
    ax.annotate("", xy=(x, edge), xycoords=trans, xytext=(0, -length if up else length),
                textcoords="offset points", annotation_clip=False,
                arrowprops={"arrowstyle": "-|>", "color": LIMIT_COLOR, "lw": 1.2,
                            "mutation_scale": 9, "shrinkA": 0, "shrinkB": 0})


def breakdown_figure(cd, d):
    """Torque by source, stacked: positive parts above zero, negative parts below."""
    sources = {k: v for k, v in cd.sources.items() if k not in cd.silent}
    n = len(sources) + 1
    ncol = min(5, n)
    fig, axes = figure(2.9, margins=(0.72, 0.12, 0.46, 0.22 + 0.17 * math.ceil(n / ncol)))
    ax = axes[0, 0]
    M = d.unit("moment")
    a = cd.angles
    up, down = np.zeros_like(a), np.zeros_like(a)
    shown = []                  # the legend's entries, given: a name may start with "_"
    for name, part in sources.items():
        color = SOURCE_COLORS[list(cd.sources).index(name) % len(SOURCE_COLORS)]
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
    margins = (0.62, 0.12, 0.42, 0.45)
    fig, axes = figure(w, margins=margins, width=w)
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
    _fit_y_labels(fig, axes, lambda left, _: _layout(fig, 1, 1, 0.55, 0.75,
                                                     (left, *margins[1:])), margins[0], 0.75)
    return fig


#: room kept beyond a measured legend's width for the PDF's wider setting of its text
LEGEND_SLACK = 0.05
FRICTION_COLOR = "#D55E00"       # the effort with friction
FRICTIONLESS_COLOR = "#0072B2"   # and without it


def friction_figure(fp, d):
    """The driver's effort with and without friction (a report's FrictionPlot ``fp``); the
    angles where friction alone reverses its sign marked on the zero line. The legend takes
    one row above the axes, or two where one would run past the figure's edge."""
    margins = (0.72, 0.12, 0.46, 0.39)
    fig, axes = figure(2.9, margins=margins)
    ax = axes[0, 0]
    draw_friction(ax, fp, d)
    legend = ax.get_legend()
    box = legend.get_window_extent(_renderer(fig))
    # Agg's metrics run a few per cent narrower than the SVG's text as a PDF sets it
    if box.x1 + LEGEND_SLACK * box.width > fig.bbox.width - _px(fig, CLEAR):
        _layout(fig, 1, 1, 0.55, 0.75, (*margins[:3], margins[3] + 0.17))
        handles, labels = legend.legend_handles, [t.get_text() for t in legend.get_texts()]
        order = [0, 2, 1]               # columns filled first: with, without; then the marks
        legend_top(ax, 2, handles=[handles[i] for i in order],
                   labels=[labels[i] for i in order])
    return fig


def draw_friction(ax, fp, d) -> None:
    """The driver's effort with friction in the joints and without it on ``ax``, two lines
    on one scale: over one turn (``fp.means`` given: each in the legend), or over the sweep
    (``fp.sweep``: its axis, gaps at left-out angles, near-singular values kept off the
    scale); ``fp`` a report's FrictionPlot, ``d`` its Display."""
    kind = fp.effort
    u = d.unit(kind)
    with_f, without = d.value(fp.torque, kind), d.value(fp.frictionless, kind)
    labels = ["with friction", "without friction"]
    if fp.means is not None:
        labels = [f"{text} (mean {d.num(m, kind)} {u})"
                  for text, m in zip(labels, fp.means)]
    a, w, wo = (fp.angles, with_f, without) if fp.sweep is None else \
        with_gaps(fp.angles, with_f, without)
    ax.plot(a, wo, color=FRICTIONLESS_COLOR, lw=1.2, ls=(0, (5, 2)), label=labels[1])
    ax.plot(a, w, color=FRICTION_COLOR, lw=1.5, label=labels[0])
    ax.axhline(0, color="0.3", lw=0.6)
    if fp.reversed:
        ax.plot(fp.reversed, np.zeros(len(fp.reversed)), ls="none", marker="x", ms=5,
                mew=1.2, color=INK, zorder=5, label="sign reversed by friction")
    if fp.sweep is None:
        ax.set_xlim(0, 360)
        ax.set_xticks(np.arange(0, 361, 45))
        ax.set_xlabel("crank angle φ [deg]")
        for x in fp.shaded:
            ax.axvspan(x - 0.5, x + 0.5, color="0.45", alpha=0.35, lw=0)
    else:
        crank_axis(ax, fp.sweep)
        scale_to_trusted(ax, fp.sweep, [with_f, without], u, names=["with", "without"])
    ax.set_ylabel(f"{'force' if kind == 'force' else 'torque'} [{u}]")
    handles, texts = ax.get_legend_handles_labels()
    order = [1, 0] + list(range(2, len(handles)))        # with friction first
    legend_top(ax, len(handles), handles=[handles[i] for i in order],
               labels=[texts[i] for i in order])


# ------------------------------------------------------------------------------ strength

def strength_figure(sp, d):
    """N, V and M along the most loaded member at its worst angle (a report's StrengthPlot
    ``sp``), three axes over one position axis, filled to zero."""
    fig, axes = figure(4.6, rows=3, gap=0.22, margins=(0.85, 0.12, 0.46, 0.15), sharex=True)
    s = d.value(sp.s, "length")
    for ax, values, kind, name, color in (
            (axes[0, 0], sp.N, "force", "N", "#0072B2"),
            (axes[1, 0], sp.V, "force", "V", "#009E73"),
            (axes[2, 0], sp.M, "moment", "M", "#D55E00")):
        v = d.value(np.asarray(values, float), kind)
        ax.plot(s, v, color=color, lw=1.5)
        ax.fill_between(s, v, 0, color=color, alpha=0.18, lw=0)
        ax.axhline(0, color="0.3", lw=0.6)
        ax.set_ylabel(f"{name} [{d.unit(kind)}]")
        ax.set_xlim(s[0], s[-1])
        ax.margins(y=0.12)
    axes[2, 0].set_xlabel(literal(f"s along member {sp.member} [{d.unit('length')}]"))
    _fit_y_labels(fig, axes, lambda left, _: _layout(
        fig, 3, 1, 0.22, 0.75, (left, 0.12, 0.46, 0.15)), 0.85, 0.75)
    return fig


def stress_figure(sp, d):
    """The largest stress along each member over the sweep (a report's StrengthPlot)."""
    n = len(sp.stress)
    fig, axes = figure(2.6, margins=(0.72, 0.12, 0.46, 0.22 + 0.17 * math.ceil(n / 4)))
    ax = axes[0, 0]
    for k, (name, values) in enumerate(sp.stress.items()):
        ax.plot(sp.angles, d.value(values, "stress"), color=SOURCE_COLORS[k % len(SOURCE_COLORS)],
                lw=1.4, ls=STYLES[k % 4], label=literal(name))
    ax.set_ylabel(f"largest stress [{d.unit('stress')}]")
    ax.set_ylim(bottom=0)
    if sp.whole_turn:
        ax.set_xlim(0, 360)
        ax.set_xticks(np.arange(0, 361, 45))
    ax.set_xlabel(sp.xlabel)
    legend_top(ax, min(n, 4))
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
    fr = model.friction
    if "friction" in figs and fr is not None and fr.plot is not None:
        out += save(friction_figure(fr.plot, d), outdir, figs["friction"].stem)
    sp = model.strength.plot if model.strength is not None else None
    if sp is not None:
        for key, make in (("strength", strength_figure), ("stress", stress_figure)):
            if key in figs:
                out += save(make(sp, d), outdir, figs[key].stem)
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


@styled
def plot_friction(analysis, ax=None):
    """The driver's effort with and without friction in the joints of ``analysis`` as the
    report draws it, on ``ax`` (default: a new figure's); returns the Axes. Raises
    ValueError when the spec has no friction."""
    from .model import friction_data
    fp, d = friction_data(analysis)
    if fp is None:
        raise ValueError(f"{analysis.spec.file}: no friction in its joints (a 'friction:' "
                         "entry with mu > 0) to plot")
    ax = _axes(ax, 2.9)
    draw_friction(ax, fp, d)
    return ax
