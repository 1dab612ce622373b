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

from .mpl import literal, pt_to_px, text_renderer, text_size

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


def measure(renderer, text: str, size: float, weight: str = "normal") -> tuple[float, float]:
    """(width, height) of the box matplotlib gives ``text`` (one line; mathtext where it has
    unescaped ``$``, else drawn as written, ``\\$`` as ``$``) at ``size`` points, in display
    units of ``renderer``: its width, and the height of its line (its ascent and descent,
    each at least that of "lp", as matplotlib lays out a line)."""
    from matplotlib import cbook
    from matplotlib.font_manager import FontProperties
    prop = FontProperties(size=size, weight=weight)
    if cbook.is_math_text(text):
        w, h, d = renderer.get_text_width_height_descent(text, prop, ismath=True)
    else:
        w, h, d = text_size(renderer, text.replace("\\$", "$"), size, weight)
    _, h_lp, d_lp = text_size(renderer, "lp", size, weight)
    return w, max(h - d, h_lp - d_lp) + max(d, d_lp)


class Labels:
    """Greedy placement of labels beside their points (a drawing's point names, arrow and
    couple symbols), in display space: each label's box (its text measured by the renderer,
    :meth:`size`) takes the first candidate offset where it overlaps no obstacle (pins,
    arrow shafts, guide walls, earlier labels) and stays inside the axes (beyond them lie
    the title, the key and the legend), else the least bad: a box's area outside the axes
    counts OUTSIDE times an overlap."""

    OUTSIDE = 4.0

    def __init__(self, ax, fontsize: float = 7.5, renderer=None):
        self.ax, self.fs = ax, fontsize
        self.boxes: list[tuple[float, float, float, float]] = []
        fig = ax.figure
        self.pt = fig.dpi / 72.0              # display units per point
        self._renderer = renderer             # made when the first label is measured
        self._m = ax.transData.get_affine().get_matrix()   # data -> display (linear axes)
        self.frame = tuple(ax.bbox.extents)

    def _px(self, x: float, y: float) -> tuple[float, float]:
        m = self._m
        return m[0, 0] * x + m[0, 1] * y + m[0, 2], m[1, 0] * x + m[1, 1] * y + m[1, 2]

    def block(self, x: float, y: float, r_pt: float = 4.0) -> None:
        """An obstacle: a square of half-size ``r_pt`` points around data point (x, y)."""
        px, py = self._px(x, y)
        r = r_pt * self.pt
        self.boxes.append((px - r, py - r, px + r, py + r))

    def block_segment(self, a, b, r_pt: float = 2.5) -> None:
        for t in np.linspace(0.0, 1.0, 8):
            self.block(a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), r_pt)

    def block_line(self, a, b, r_pt: float = 2.0) -> None:
        """An obstacle along the whole segment ``a``-``b`` (data): squares of half-size
        ``r_pt`` points, one every ``r_pt`` points (a long line, such as a guide's wall,
        with no gap a label could sit in)."""
        (ax_, ay_), (bx_, by_) = self._px(*a), self._px(*b)
        n = max(2, int(math.hypot(bx_ - ax_, by_ - ay_) / (r_pt * self.pt)) + 2)
        for t in np.linspace(0.0, 1.0, n):
            self.block(a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), r_pt)

    def size(self, text: str, fontsize: float, bold: bool = False) -> tuple[float, float]:
        """(width, height) of the box ``text`` takes at ``fontsize`` points, in display
        units, as matplotlib lays it out (see :func:`measure`)."""
        if self._renderer is None:
            self._renderer = text_renderer(self.ax.figure)
        return measure(self._renderer, text, fontsize, "bold" if bold else "normal")

    def _box(self, px, py, w, h, ha, va):
        x0 = px if ha == "left" else (px - w if ha == "right" else px - w / 2)
        y0 = py if va == "bottom" else (py - h if va == "top" else py - h / 2)
        return (x0, y0, x0 + w, y0 + h)

    @staticmethod
    def _overlap(a, b) -> float:
        dx = min(a[2], b[2]) - max(a[0], b[0])
        dy = min(a[3], b[3]) - max(a[1], b[1])
        return dx * dy if dx > 0 and dy > 0 else 0.0

    @staticmethod
    def _overlaps(a, boxes: np.ndarray) -> float:
        """``sum(_overlap(a, b) for b in boxes)`` (``boxes`` (n, 4)), bit for bit: the same
        min/max (Python's, NaN included), products and left-to-right sum, over arrays (the
        zero terms left out change no sum). Issue 48: the loop was 700 000 calls over the
        specs/ batch, 0.9 s of 55 under the profiler."""
        x0, y0, x1, y1 = boxes.T
        dx = np.where(x1 < a[2], x1, a[2]) - np.where(x0 > a[0], x0, a[0])
        dy = np.where(y1 < a[3], y1, a[3]) - np.where(y0 > a[1], y0, a[1])
        hit = (dx > 0) & (dy > 0)
        return sum((dx[hit] * dy[hit]).tolist())

    def place(self, text: str, x: float, y: float, color: str = "k", bold: bool = False,
              prefer=None, fontsize: float | None = None) -> None:
        """Write ``text`` (as given: literal where it carries a spec's name) beside data
        point (``x``, ``y``) at ``fontsize`` points (default: the placer's), at the first
        free candidate offset, the ones towards ``prefer`` (a direction (dx, dy)) first."""
        fs = fontsize or self.fs
        w, h = self.size(text, fs, bold)
        px, py = self._px(x, y)
        d = 5.0
        cands = [(d, d, "left", "bottom"), (-d, d, "right", "bottom"), (d, -d, "left", "top"),
                 (-d, -d, "right", "top"), (0, 1.6 * d, "center", "bottom"),
                 (0, -1.6 * d, "center", "top"), (1.6 * d, 0, "left", "center"),
                 (-1.6 * d, 0, "right", "center"), (2.6 * d, 2.6 * d, "left", "bottom"),
                 (-2.6 * d, 2.6 * d, "right", "bottom"), (2.6 * d, -2.6 * d, "left", "top"),
                 (-2.6 * d, -2.6 * d, "right", "top")]
        if prefer is not None:
            cands.sort(key=lambda c: -(c[0] * prefer[0] + c[1] * prefer[1]))
        # last resorts, further out: where a crowded spot (a pin between a guide's walls)
        # leaves no room near the point
        cands += [(sx * k * d, sy * k * d, "left" if sx > 0 else "right",
                   "bottom" if sy > 0 else "top") for k in (4.5, 6.5)
                  for sx, sy in ((1, 1), (-1, 1), (1, -1), (-1, -1))]
        best, best_score = None, math.inf
        placed = np.asarray(self.boxes, float).reshape(-1, 4)
        for dx, dy, ha, va in cands:
            box = self._box(px + dx * self.pt, py + dy * self.pt, w, h, ha, va)
            area = (box[2] - box[0]) * (box[3] - box[1])
            score = (self._overlaps(box, placed)
                     + self.OUTSIDE * (area - self._overlap(box, self.frame)))
            if score < best_score:
                best, best_score = (dx, dy, ha, va, box), score
            if score == 0:
                break
        self._annotate(text, x, y, best, fs, color, bold)

    def place_points(self, points, extent: float) -> None:
        """Name the points ``points`` [(x, y, name)], one label for names that share a
        place (A/O); ``extent`` the drawing's size (what "the same place" is relative to).
        The names are the spec's, drawn literally."""
        merged: dict[tuple, list] = {}
        for x, y, text in points:
            key = (round(x / extent, 4), round(y / extent, 4))
            merged.setdefault(key, [x, y, []])[2].append(literal(text))
        for x, y, names in merged.values():
            self.place("/".join(names), x, y, bold=True, fontsize=8.5, prefer=(-1, 1))

    def _annotate(self, text: str, x: float, y: float, best, fs: float, color: str,
                  bold: bool) -> None:
        """Write ``text`` at the chosen offset ``best`` = (dx, dy, ha, va, box) [pt] from its
        point, and keep its box out of the way of the labels after it."""
        dx, dy, ha, va, box = best
        self.boxes.append(box)
        self.ax.annotate(text, (x, y), xytext=(dx, dy), textcoords="offset points",
                         fontsize=fs, color=color, ha=ha, va=va, zorder=9,
                         fontweight="bold" if bold else "normal", annotation_clip=False)
