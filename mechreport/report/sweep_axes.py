"""The crank-angle axis of a sweep plot and what marks it: left-out angles shaded, near-singular
stretches hatched (within ``sweep.near_deg`` of a left-out angle: they do not set a plot's
scale), values off the scale marked at the edge with their value (one label for marks at the
same angle), and the names of the reference angles' lines. ``sw`` is a report's SweepData."""
from __future__ import annotations

import math

import numpy as np

from ..units import fmt
from .labels import data_lines, hline, place
from .mpl import INK, literal, pt_to_px, text_renderer, text_size

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
    turn: ticks every 90 deg over whole turns of a longer cycle), left-out angles shaded
    grey, near-singular hatched."""
    if sw.xrange is None:
        ax.set_xlim(0, 360)
        ax.set_xticks(np.arange(0, 361, 45))
    else:
        ax.set_xlim(*sw.xrange)
        lo, hi = sw.xrange
        span = hi - lo
        if span >= 720 and span % 360 == 0 and sw.xlabel.startswith("crank angle"):
            ax.set_xticks(np.arange(math.ceil(lo / 90) * 90, hi + 1e-9, 90))   # a long cycle
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
    r = text_renderer(fig)
    deg = "°" if sw.xrange is None else ""
    pt = pt_to_px(fig, 1.0)
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
            w = text_size(r, text, OFF_SCALE_SIZE)[0]
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


REF_SIZE = 6.5           # [pt], the names of the reference angles' lines


def label_reference_lines(ax, sw, curves, levels) -> None:
    """Name the dotted lines at the reference angles of ``sw`` (``φ = 30°``, or the sweep's
    quantity and value) at the top or bottom of ``ax``, beside the line, where the text
    crosses none of ``curves`` [(x, y) in data coordinates], the horizontal lines at
    ``levels``, the text already there or another reference line's name."""
    if not len(sw.ref_angles):
        return
    fig = ax.figure
    r = text_renderer(fig)
    lines = data_lines(ax, *curves) + [hline(ax, y) for y in levels]
    boxes = [tuple(t.get_window_extent(r).extents) for t in ax.texts if t.get_text()]
    for ln in ax.get_lines():                       # off-scale marks at the edges
        if not ln.get_clip_on() and len(ln.get_xdata()) == 1:
            lines += data_lines(ax, (ln.get_xdata(), ln.get_ydata()))
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
        boxes.append(place(ax, text, cands, lines, boxes, r))
