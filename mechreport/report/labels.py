"""Placing text where it is free: the one label placer of the report's figures (plots and
drawings). Layouts are fixed, and a figure is drawn once, when it is saved. Where text could
run into other text, a curve or the figure's edge (off-scale values, the ΔE label, limits off
the scale, reference angles, point and arrow names on a drawing), it is measured before that
with Agg's text metrics (:func:`~mechreport.report.mpl.text_renderer`: text layout only,
nothing is drawn) and placed at the first of a few candidate spots that is free; a figure
where the first spot is free is drawn as before. Boxes are (x0, y0, x1, y1) in display
units."""
from __future__ import annotations

import math

import numpy as np

from .mpl import pt_to_px, text_renderer

#: room kept between placed text and other text, and between placed text and a curve (half
#: its line width, and some air) [pt]
CLEAR = 1.5
LINE_CLEAR = 3.0


def grow(box, by: float):
    return (box[0] - by, box[1] - by, box[2] + by, box[3] + by)


def overlaps(a, b) -> bool:
    """Boxes (x0, y0, x1, y1) overlap (touching is not overlapping)."""
    return min(a[2], b[2]) > max(a[0], b[0]) and min(a[3], b[3]) > max(a[1], b[1])


def inside(box, outer, slack: float = 1.0) -> bool:
    return (box[0] >= outer[0] - slack and box[1] >= outer[1] - slack
            and box[2] <= outer[2] + slack and box[3] <= outer[3] + slack)


def crossings(box, lines) -> int:
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


def data_lines(ax, *xy) -> list[np.ndarray]:
    """Polylines (x, y) in data coordinates as display coordinates."""
    return [ax.transData.transform(np.column_stack([np.asarray(x, float),
                                                    np.asarray(y, float)])) for x, y in xy]


def hline(ax, y: float) -> np.ndarray:
    """A horizontal line across ``ax`` at data ``y``, in display coordinates."""
    lo, hi = ax.get_xlim()
    return data_lines(ax, ([lo, hi], [y, y]))[0]


def place(ax, text, candidates, lines=(), boxes=(), renderer=None):
    """Put the Annotation ``text`` at the first of ``candidates`` — (xy, offset [pt], ha,
    va) — where it stays inside the axes, LINE_CLEAR from the polylines ``lines`` and CLEAR
    from the ``boxes`` (display coordinates); else where it is least in the way. Returns the
    box it takes (display coordinates)."""
    r = renderer or text_renderer(ax.figure)
    outer = tuple(ax.bbox.extents)
    clear, line_clear = pt_to_px(ax.figure, CLEAR), pt_to_px(ax.figure, LINE_CLEAR)
    best, best_score = None, math.inf
    for xy, offset, ha, va in candidates:
        text.xy, text.xyann = xy, offset
        text.set_ha(ha)
        text.set_va(va)
        box = tuple(text.get_window_extent(r).extents)
        score = (0 if inside(box, outer) else 100) + crossings(grow(box, line_clear), lines) \
            + sum(overlaps(grow(box, clear), b) for b in boxes)
        if score < best_score:
            best, best_score = (xy, offset, ha, va, box), score
        if score == 0:
            break
    xy, offset, ha, va, box = best
    text.xy, text.xyann = xy, offset
    text.set_ha(ha)
    text.set_va(va)
    return box

