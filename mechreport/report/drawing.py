"""Draw a :class:`~mechreport.report.scene.Scene`: links, pins, sliders and guides, ground
hatching, point labels, load and reaction arrows, couples. Geometry comes from the scene
(global coordinates [m]); this module only draws, in the report's display units.

Links are stacked so that the driver (the crank) is drawn on top of every other link, bars
over blocks over plates. Labels (points, arrows, couples) are placed one by one, by the
report's label placer (:class:`~mechreport.report.labels.Labels`: their text measured), at
the first of several candidate spots that overlaps nothing already drawn or labelled. Point
names come from the spec and are drawn literally (:func:`~mechreport.report.mpl.literal`);
the arrows' and couples' labels are mechreport's symbols (F12, F3ext, M)."""
from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..units import fmt
from .labels import Labels
from .mpl import CUT_COLOR, LINK_FILL, WIDTH, save, styled

ARROW_LEN = 0.26        # longest arrow as a fraction of the mechanism's extent
ARROW_MIN = 0.05        # shortest drawn (non-zero) arrow, same unit
AX_FRACTION = 0.70      # the drawing's share of the figure width (the legend has the rest)
LEGEND_ENTRY_IN = 0.16  # height of one legend entry at 7.5 pt, inches (measured 0.157)
LEGEND_MAX_IN = 7.0     # the tallest a drawing grows for its legend, inches


@dataclass(frozen=True)
class View:
    """A fixed frame shared by drawings that must line up (the animation's frames): data
    limits ``lo``, ``hi`` (x, y) [m] matching the axes' aspect, the figure's ``size`` (w, h)
    [in], the mechanism axes' ``rect`` (left, bottom, width, height; figure fraction), the
    arrows' ``scale`` [m per N] and ``clip`` [m], the longest arrow drawn: a longer one is cut
    to it and marked. ``labels`` False leaves out every text on the drawing (point names,
    arrow and couple symbols): the frames of a GIF name them once, in a key (text is most of
    a raster frame's cost). A view never numbers the links (its frames are small)."""

    lo: tuple
    hi: tuple
    size: tuple
    rect: tuple
    scale: float
    clip: float
    labels: bool = True


def _poly(ax, xy, **kw) -> None:
    """A filled polygon through ``xy`` (m, 2) [m] (a patch added without touching the data
    limits, which a drawing sets itself: much faster than ``ax.fill``)."""
    from matplotlib.patches import Polygon
    ax.add_artist(Polygon(np.asarray(xy, float), closed=True, **kw))


def _line(ax, x, y, **kw) -> None:
    """A polyline (or markers) through ``x``, ``y`` [m], added like :func:`_poly`."""
    from matplotlib.lines import Line2D
    ax.add_artist(Line2D(np.asarray(x, float), np.asarray(y, float), **kw))


def _arrow(ax, start, tip, color: str, lw: float, head: float, zorder: float) -> None:
    """An arrow from ``start`` to ``tip`` [m]: a shaft ``lw`` points wide and a filled head
    0.4 ``head`` points long and as wide, as one polygon in data coordinates (the drawing's
    units are equal in x and y and its limits are set: a point is a fixed length in them).
    Drawn much faster than an annotation's arrow; it looks the same."""
    from matplotlib.patches import Polygon
    a, b = np.asarray(start, float), np.asarray(tip, float)
    length = float(np.hypot(*(b - a)))
    if length <= 0:
        return
    per_pt = ax.figure.dpi / 72.0 / abs(ax.transData.get_affine().get_matrix()[0, 0])
    u = (b - a) / length
    n = np.array([-u[1], u[0]])
    hl = min(0.4 * head * per_pt, length)              # head length and half width [m]
    hw, sw = 0.2 * head * per_pt, 0.5 * lw * per_pt
    base = b - hl * u
    xy = [a + sw * n, base + sw * n, base + hw * n, b, base - hw * n, base - sw * n, a - sw * n]
    ax.add_artist(Polygon(np.array(xy), closed=True, facecolor=color, edgecolor="none",
                          lw=0, zorder=zorder, gid="arrow"))


def _segments(ax, segs, lw, zorder: float) -> None:
    """Many short black strokes as one artist (hatching: one collection draws much faster
    than a line each); ``lw`` one width [pt] or one per stroke."""
    from matplotlib.collections import LineCollection
    if segs:
        ax.add_collection(LineCollection(segs, colors="k", linewidths=lw, zorder=zorder),
                          autolim=False)


def draw_ground_symbol(ax, x: float, y: float, size: float) -> None:
    """A fixed pivot: a triangle under the pin and a hatched base."""
    tri = np.array([[x, y], [x - size * 0.6, y - size], [x + size * 0.6, y - size]])
    _poly(ax, tri, facecolor="white", edgecolor="k", lw=1.0, zorder=3.5)
    base_y = y - size
    ticks = [[(x + t, base_y), (x + t - size * 0.3, base_y - size * 0.35)]
             for t in np.linspace(-size, size * 0.8, 6)]
    _segments(ax, [[(x - size, base_y), (x + size, base_y)]] + ticks,
              [1.2] + [0.7] * len(ticks), 3.5)


def guide_strokes(p0, p1, on_ground: bool, normal, offset: float):
    """The lines of a T joint's guide [m]: (walls, ticks), each a list of segments ((x, y),
    (x, y)). On ground: a wall either side of the line at ``offset`` along ``normal``, hatched
    outward; on a moving link: the line itself (drawn dashed), no ticks."""
    p0, p1, nrm = np.asarray(p0, float), np.asarray(p1, float), np.asarray(normal, float)
    if not on_ground:
        return [[tuple(p0), tuple(p1)]], []
    length = np.linalg.norm(p1 - p0)
    hatch = min(0.35 * offset, 0.03 * length) if offset > 0 else 0.03 * length
    u = (p1 - p0) / length
    walls, ticks = [], []
    for side in (-1, 1):
        off = side * nrm * offset
        a, b = p0 + off, p1 + off
        walls.append([tuple(a), tuple(b)])
        for t in np.linspace(0.02, 0.98, 16):
            q = a + t * (b - a)
            tip = q + side * nrm * hatch - u * hatch * 0.7
            ticks.append([tuple(q), tuple(tip)])
    return walls, ticks


def draw_guide(ax, p0, p1, on_ground: bool, normal, offset: float) -> None:
    walls, ticks = guide_strokes(p0, p1, on_ground, normal, offset)
    if not on_ground:
        _line(ax, *np.asarray(walls[0]).T, color="0.35", lw=0.8, ls=(0, (6, 3)), zorder=1)
        return
    _segments(ax, walls + ticks, [1.0] * len(walls) + [0.6] * len(ticks), 1)


def _arrow_geometry(scene, extent: float, view: "View | None" = None):
    """(arrow, magnitude, start, tip, cut) of each drawn arrow. Alone, a drawing scales its
    arrows so that the largest is ARROW_LEN of the extent (none shorter than ARROW_MIN); in a
    ``view`` every arrow is ``view.scale`` [m/N] times its force, and one longer than
    ``view.clip`` [m] is cut to that length (``cut`` True)."""
    mags = [math.hypot(*a.f) for a in scene.arrows]
    top = max(mags, default=0.0)
    out = []
    for a, mag in zip(scene.arrows, mags):
        if top <= 0 or mag < 1e-9 * top or (view is not None and mag * view.scale
                                            < 1e-3 * extent):
            out.append((a, mag, None, None, False))
            continue
        if view is None:
            length, cut = max(mag * ARROW_LEN * extent / top, ARROW_MIN * extent), False
        else:
            length = mag * view.scale
            cut = length > view.clip
            length = min(length, view.clip)
        d = np.asarray(a.f) / mag * length
        start = np.asarray(a.at, float)
        out.append((a, mag, start, start + d, cut))
    return out


def _cut_mark(ax, start, tip, extent: float) -> None:
    """Two short red strokes across an arrow cut to the view's longest: off scale."""
    u = (tip - start) / max(float(np.linalg.norm(tip - start)), 1e-300)
    n = np.array([-u[1], u[0]]) * 0.03 * extent
    segs = []
    for s in (0.55, 0.62):
        c = start + s * (tip - start)
        segs.append([tuple(c - n - 0.01 * extent * u), tuple(c + n + 0.01 * extent * u)])
    from matplotlib.collections import LineCollection
    ax.add_collection(LineCollection(segs, colors=CUT_COLOR, linewidths=1.6, zorder=6.5),
                      autolim=False)


def _links(ax, scene, numbered: bool = True) -> None:
    """Plates under blocks under bars; the driver link above all of them; blocks and bars
    with their link's number when ``numbered`` (links drawn on top of each other, as the
    pistons of an in-line engine whose cranks are in phase, share one label: "6/9", as their
    points share "P1/P4")."""
    numbers: list[list] = []                   # [centre, numbers, zorder] per label
    for s in scene.shapes:
        xy = np.asarray(s.xy)
        fill = LINK_FILL[(s.number - 1) % len(LINK_FILL)]
        top = 0.6 if s.link == scene.driver else 0.0
        if s.kind == "line":
            _line(ax, xy[:, 0], xy[:, 1], color="k", lw=3, solid_capstyle="round",
                  zorder=2.2 + top)
            continue
        z = {"plate": 1.5, "block": 2.0, "bar": 2.2}[s.kind] + top + 0.01 * s.number
        _poly(ax, xy, facecolor=fill, edgecolor="k", lw=1.0, zorder=z,
              alpha=0.8 if s.kind == "plate" else 0.92)
        if s.kind != "plate" and numbered:
            c = xy.mean(axis=0)
            same = next((n for n in numbers
                         if np.hypot(*(n[0] - c)) <= 0.02 * scene.extent), None)
            if same is None:
                numbers.append([c, [s.number], z])
            else:
                same[1].append(s.number)
                same[2] = max(same[2], z)
    for c, nums, z in numbers:
        ax.text(c[0], c[1], "/".join(map(str, nums)), fontsize=6.5, ha="center",
                va="center", color="0.25", zorder=z + 0.005)


def draw_element(ax, kind: str, p0, p1, size: float, color: str = "0.3") -> None:
    """A spring as a zig-zag, a damper as a dashpot (piston in a cylinder) between ``p0`` and
    ``p1``; a torsion spring as a spiral around its joint. ``size`` [m] sets their width."""
    p0, p1 = np.asarray(p0, float), np.asarray(p1, float)
    if kind == "torsion_spring":
        t = np.linspace(0, 3 * np.pi, 80)
        rad = size * (0.35 + 0.65 * t / t[-1])
        _line(ax, p0[0] + rad * np.cos(t), p0[1] + rad * np.sin(t), color=color, lw=0.9,
                zorder=3.5)
        return
    d = p1 - p0
    length = float(np.hypot(*d))
    if length == 0:
        return
    u = d / length
    n = np.array([-u[1], u[0]])
    at = lambda s, w=0.0: p0 + s * d + w * size * n   # noqa: E731 - a point along the element
    if kind == "spring":
        ts = np.linspace(0.2, 0.8, 13)
        zig = [at(0)] + [at(t, 0 if i in (0, 12) else (1 if i % 2 else -1))
                         for i, t in enumerate(ts)] + [at(1)]
        xy = np.array(zig)
        _line(ax, xy[:, 0], xy[:, 1], color=color, lw=1.0, zorder=3.5)
        return
    if kind == "link":                         # a plain connector
        _line(ax, [p0[0], p1[0]], [p0[1], p1[1]], color=color, lw=1.0, zorder=3.5)
        return
    segs = [(at(0), at(0.5)), (at(0.5, -0.8), at(0.5, 0.8)),          # rod and piston
            (at(0.35, -1), at(0.65, -1)), (at(0.35, 1), at(0.65, 1)),  # cylinder walls
            (at(0.65, -1), at(0.65, 1)), (at(0.65), at(1))]            # its end, the far rod
    for a, b in segs:
        _line(ax, [a[0], b[0]], [a[1], b[1]], color=color, lw=1.0, zorder=3.5)


def _bounds(scene, arrows) -> tuple[np.ndarray, np.ndarray]:
    pts = [p for s in scene.shapes for p in s.xy]
    pts += [p for _, p0, p1 in scene.elements for p in (p0, p1)]
    for p0, p1, *_ in scene.guides:
        pts += [p0, p1]
    pts += [(x, y) for x, y, _ in scene.pins]
    pts += [tuple(t) for _, _, _, t, _ in arrows if t is not None]
    xy = np.asarray(pts, float) if pts else np.zeros((1, 2))
    return xy.min(axis=0), xy.max(axis=0)


def view_axes(fig, view: View):
    """The axes of ``view`` in ``fig``: the view's limits, equal units, no frame."""
    ax = fig.add_axes(view.rect)
    ax.set_xlim(view.lo[0], view.hi[0])
    ax.set_ylim(view.lo[1], view.hi[1])
    ax.set_aspect("equal", adjustable="datalim")
    ax.axis("off")
    ax.apply_aspect()
    return ax


def _sized_axes(scene, arrows):
    """A figure for one drawing alone: the drawing's axes (equal units in x and y, height
    from the drawing's aspect) on the left, room for the legend on the right."""
    from matplotlib.figure import Figure
    ext = scene.extent
    lo, hi = _bounds(scene, arrows)
    span = np.maximum(hi - lo, 1e-9)
    pad = 0.1 * max(span) + 0.05 * ext
    lo, hi = lo - pad, hi + pad
    span = hi - lo
    ax_w = WIDTH * (AX_FRACTION - 0.01)
    height = float(np.clip(ax_w * span[1] / span[0] + 0.35, 2.4, 4.3))
    # tall enough for the legend beside it (measured: 0.157 in per entry at 7.5 pt), which a
    # flat mechanism with many forces (an in-line engine: 19 entries) would overflow
    height = max(height, min(LEGEND_ENTRY_IN * (len(arrows) + len(scene.couples)) + 0.25,
                             LEGEND_MAX_IN))
    ax_h = height * (1 - 0.02) - 0.3
    # widen the data range along one axis so that one unit is as long in x as in y
    want = ax_w / ax_h
    mid = (lo + hi) / 2
    if span[0] / span[1] < want:
        span = np.array([span[1] * want, span[1]])
    else:
        span = np.array([span[0], span[0] / want])
    lo, hi = mid - span / 2, mid + span / 2
    fig = Figure(figsize=(WIDTH, height))
    ax = fig.add_axes((0.01, 0.02, AX_FRACTION - 0.01, ax_h / height))
    ax.set_xlim(lo[0], hi[0])
    ax.set_ylim(lo[1], hi[1])
    ax.set_aspect("equal", adjustable="box")
    ax.axis("off")
    ax.apply_aspect()
    return fig, ax


@styled
def draw_scene(scene, d=None, title: str | None = None, view: View | None = None, ax=None):
    """A matplotlib figure of ``scene`` (equal axes, no frame), with a legend of the forces
    and couples (values in display units) on the right; or, in a ``view`` (a frame of the
    animation), the drawing alone in the view's axes: every arrow to the view's one scale,
    cut and marked where longer than its clip, no legend, the title in the top-left corner;
    drawn into ``ax`` (made by :func:`view_axes`) when given, else into a new figure."""
    from matplotlib.lines import Line2D

    F = d.unit("force") if d is not None else "N"
    M = d.unit("moment") if d is not None else "N·m"
    fv = (lambda x: d.num(x, "force")) if d is not None else fmt
    mv = (lambda x: d.num(x, "moment")) if d is not None else fmt
    ext = scene.extent
    arrows = _arrow_geometry(scene, ext, view)
    from matplotlib.figure import Figure
    if view is None:
        fig, ax = _sized_axes(scene, arrows)
    else:
        if ax is None:
            ax = view_axes(Figure(figsize=view.size), view)
        fig = ax.figure
    labels = Labels(ax)

    _links(ax, scene, view is None)
    if view is None:                           # the links' numbers: no label on them
        for sh in scene.shapes:
            if sh.kind in ("block", "bar"):
                c = np.asarray(sh.xy, float).mean(axis=0)
                labels.block(c[0], c[1], 4.0)
    size = 0.025 * ext
    shared: dict = {}                          # elements between the same two points
    for kind, p0, p1 in scene.elements:
        key = frozenset((tuple(np.round(p0, 9)), tuple(np.round(p1, 9))))
        k = shared[key] = shared.get(key, -1) + 1
        if k and p0 != p1:                     # side by side, not on top of each other
            along = np.subtract(p1, p0) / max(math.hypot(*np.subtract(p1, p0)), 1e-300)
            shift = ((k + 1) // 2 * (1 if k % 2 else -1) * 3 * size
                     * np.array([-along[1], along[0]]))
            draw_element(ax, "link", p0, np.add(p0, shift), size)       # short connectors
            draw_element(ax, "link", p1, np.add(p1, shift), size)
            p0, p1 = tuple(np.add(p0, shift)), tuple(np.add(p1, shift))
        draw_element(ax, kind, p0, p1, size)
    for p0, p1, on_ground, normal, offset in scene.guides:
        draw_guide(ax, p0, p1, on_ground, normal, offset)
        walls, ticks = guide_strokes(p0, p1, on_ground, normal, offset)
        for a, b in walls:                 # no label on a wall or in its hatching
            labels.block_line(a, b)
        for a, b in ticks:
            labels.block_segment(a, b, 2.0)
    for x, y, on_ground in scene.pins:
        if on_ground:
            draw_ground_symbol(ax, x, y, 0.04 * ext)
        labels.block(x, y, 4.0)
    if scene.pins:                             # every pin: one artist
        _line(ax, [p[0] for p in scene.pins], [p[1] for p in scene.pins], marker="o",
              ls="none", ms=5, mfc="white", mec="k", mew=1.2, zorder=4)
    handles = []
    for a, mag, start, tip, cut in arrows:
        load = a.kind == "load"
        if view is None:
            handles.append(Line2D([], [], color=a.color, lw=2, marker=">", ms=5,
                                  label=f"{a.label} = {fv(mag)} {F}"
                                  + (" (load)" if load else "")))
        if tip is None:
            continue
        _arrow(ax, start, tip, a.color, 1.6, 10, 6)
        labels.block_segment(start + 0.25 * (tip - start), tip)
        if cut:
            _cut_mark(ax, start, tip, ext)
    r = 0.06 * ext
    couple_spots = []
    for c in scene.couples:
        if view is None:
            handles.append(Line2D([], [], color=c.color, lw=1.1,
                                  marker="$\\circlearrowleft$", ms=7,
                                  label=f"{c.label} = {mv(c.value)} {M}"))
        if abs(c.value) < 1e-12:
            continue
        x, y = c.at
        start, end = (200, 470) if c.value > 0 else (470, 200)
        th = np.radians(np.linspace(start, end, 30))
        _line(ax, x + r * np.cos(th[:-3]), y + r * np.sin(th[:-3]), color=c.color, lw=1.1,
                zorder=5)
        _arrow(ax, (x + r * np.cos(th[-4]), y + r * np.sin(th[-4])),
               (x + r * np.cos(th[-1]), y + r * np.sin(th[-1])), c.color, 1.1, 9, 5)
        for t in th[::5]:
            labels.block(x + r * math.cos(t), y + r * math.sin(t), 2.5)
        couple_spots.append((c, x + r * 0.8, y - r * 0.8))
    # point labels first (they name the drawing), then arrows, then couples; an arrow cut
    # to the view's longest is labelled with its value, named or not
    named = view is None or view.labels
    labels.place_points(scene.labels if named else [], ext)
    for a, mag, start, tip, cut in arrows:
        if tip is not None and (named or cut):
            u = (tip - start) / max(np.linalg.norm(tip - start), 1e-300)
            text = a.label if named else ""
            if cut:
                text = f"{text} = {fv(mag)} {F}" if named else f"{fv(mag)} {F}"
            labels.place(text, tip[0], tip[1], color=a.color, prefer=(u[0], u[1]))
    for c, x, y in couple_spots if named else ():
        labels.place(c.label, x, y, color=c.color, prefer=(1, -1))
    if view is not None:                       # a frame: cheaper than an axes title
        fig.text(0.01, 0.99, title or f"φ = {scene.angle:g}°", ha="left", va="top",
                 fontsize=9)
        return fig
    ax.set_title(title or f"φ = {scene.angle:g}°", loc="left")
    if handles:
        fits = LEGEND_ENTRY_IN * len(handles) + 0.25 <= fig.get_figheight()
        fig.legend(handles=handles, loc="center left", bbox_to_anchor=(AX_FRACTION, 0.5),
                   fontsize=7.5, frameon=False, handlelength=1.8, ncols=1 if fits else 2)
    return fig


@styled
def write_drawings(model, outdir: Path) -> list[Path]:
    """One drawing per solved reference angle, SVG."""
    out = []
    refs = [r for r in model.refs if r.drawing is not None]
    for r, scene in zip(refs, model.scenes):
        title = f"φ = {r.angle}°" if model.coord_unit == "°" else r.title
        out += save(draw_scene(scene, model.display, title), outdir, r.drawing.stem)
    return out
