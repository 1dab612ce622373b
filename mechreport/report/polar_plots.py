"""Polar bearing diagrams: each joint's reaction over the sweep as a curve in its carrier's
frame, the reference angles marked and named, the equivalent (RMS) load as a circle. Values
in the report's display units (``d``); ``sw`` is a report's SweepData."""
from __future__ import annotations

import math

import numpy as np

from ..units import fmt
from .labels import place
from .mpl import INK, WIDTH, figure, fit_y_labels, layout, literal, text_renderer, text_size
from .quantities import with_gaps

def polar_figure(sw, d):
    """Every joint's polar diagram (:func:`draw_polar`), three to a row."""
    n = len(sw.polar)
    cols = min(n, 3)
    rows = math.ceil(n / cols)
    cell = WIDTH / cols
    margins, gap, wgap = (0.55, 0.1, 0.42, 0.3), 0.6, 0.6
    titles = _polar_titles(sw.polar, (WIDTH - margins[0] - margins[1]) / cols - wgap)
    if any("\n" in t for t in titles):             # a second line of title above each row
        margins, gap = (margins[0], margins[1], margins[2], margins[3] + 0.12), gap + 0.12
    fig, axes = figure(cell * rows, rows, cols, gap=gap, wgap=wgap, margins=margins)
    rend = text_renderer(fig)
    for ax, ps, title in zip(axes.flat, sw.polar, titles):
        draw_polar(ax, sw, ps, d, title, rend)
    for ax in axes.flat[n:]:
        ax.set_visible(False)

    def relayout(left, wgap):
        layout(fig, rows, cols, gap, wgap, (left, *margins[1:]))
        for ax in axes.flat[:n]:
            ax.apply_aspect()
            _keep_inside(ax, rend)
    fit_y_labels(fig, axes, relayout, margins[0], wgap)
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
        if text_size(r, title, POLAR_TITLE_SIZE)[0] > 72 * (axes_width + POLAR_TITLE_OVERHANG):
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
        boxes.append(place(ax, text, cands, (), boxes, renderer))


def draw_polar(ax, sw, ps, d, title: str | None = None, renderer=None) -> None:
    """The polar diagram of one joint's reaction ``ps`` (a report's PolarSeries; ``sw`` its
    SweepData) on ``ax``: the force's tip over the sweep in the carrier's frame, in the
    display unit of forces (``d``), the reference angles' forces as spokes, named; the
    equivalent load as a dashed circle; a peak far beyond the rest left off the scale and
    given in a note. ``title`` (default: the joint, its symbol and frame, on two lines where
    one is wider than ``ax``) is drawn literally."""
    F = d.unit("force")
    if title is None:
        title = _polar_titles([ps], ax.get_position().width * ax.figure.get_figwidth())[0]
    rend = renderer or text_renderer(ax.figure)
    ref_idx = [int(np.argmin(np.abs(sw.angles - r))) for r in sw.ref_angles
               if len(sw.angles) and np.min(np.abs(sw.angles - r)) < 1e-9]
    near = sw.near if len(sw.near) == len(sw.angles) else np.zeros(len(sw.angles), bool)
    from matplotlib.ticker import MaxNLocator
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
