"""The figures of a solution sheet and its problem version, as SVG (matplotlib):

- the mechanism at a reference angle, links numbered and joints lettered as in the textbook
  (Fig. 4.7a), with the applied loads and the driver's rotation, and no result;
- a free-body diagram of every moving link (Fig. 4.7b): the link with its joints, each
  joint's reaction as its unknown components (F21x, F21y; a slider's along the normal of its
  line, and its couple M03), the weight G, the external loads, the driver's M, and dashed the
  inertia force Fin and couple Min that d'Alembert's principle adds, each labelled with the
  symbol the equations use. Arrows show directions, not magnitudes: an unknown is drawn in
  its positive direction, a known force along its value at the angle.

Geometry comes from :func:`mechreport.report.scene.build_scene` and is drawn with the report
drawings' helpers (:mod:`mechreport.report.drawing`). The symbols are mathtext that mechreport
writes (from link numbers, never from names); the points' names are the spec's, drawn
literally (:func:`mechreport.report.mpl.literal`)."""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from ..drawing import draw_element, draw_ground_symbol, draw_guide
from ..labels import Labels
from ..mpl import (INERTIA_COLOR, KNOWN_COLOR, LINK_FILL, UNKNOWN_COLOR, literal, save,
                   styled)
from ..scene import build_scene
from .symbols import split_symbol

class SheetLabels(Labels):
    """The sheets' label placer (a mathtext label measured as it prints: $F_{21x}$ is four
    glyphs wide, not ten), keeping labels inside the figure and near their point:
    the candidate offsets are tried ring by ring (nearest first), each ring from the
    preferred side round, and the first box that touches no obstacle is taken (else the least
    bad). Obstacles are pins, link outlines, arrow shafts, couple arcs and earlier labels."""

    D = 4.0                  # the nearest offset [pt]
    RINGS = (1.0, 2.2, 3.6)  # offsets tried, in units of D

    def block_path(self, xy, r_pt: float = 2.5) -> None:
        """Obstacles along the polyline ``xy`` (data units), one every ``r_pt`` points."""
        px = self.ax.transData.transform(np.asarray(xy, float).reshape(-1, 2))
        for a, b in zip(px[:-1], px[1:]):
            n = max(int(np.hypot(*(b - a)) / (r_pt * self.pt)), 1)
            r = r_pt * self.pt
            for t in np.linspace(0.0, 1.0, n + 1):
                q = a + t * (b - a)
                self.boxes.append((q[0] - r, q[1] - r, q[0] + r, q[1] + r))

    def block_area(self, lo, hi) -> None:
        """An obstacle: the rectangle from ``lo`` to ``hi`` (data units)."""
        (x0, y0), (x1, y1) = self.ax.transData.transform(np.asarray([lo, hi], float))
        self.boxes.append((min(x0, x1), min(y0, y1), max(x0, x1), max(y0, y1)))

    def place(self, text: str, x: float, y: float, color: str = "k", bold: bool = False,
              prefer=None, fontsize: float | None = None) -> None:
        fs = fontsize or self.fs
        w, h = self.size(text, fs, bold)
        px, py = self.ax.transData.transform((x, y))
        fig_w, fig_h = self.ax.figure.bbox.width, self.ax.figure.bbox.height
        pref = np.asarray(prefer if prefer is not None else (1.0, 1.0), float)
        pref = pref / max(float(np.hypot(*pref)), 1e-12)
        boxes = np.asarray(self.boxes, float).reshape(-1, 4)
        best, best_score = None, math.inf
        for ring in self.RINGS:
            d = self.D * ring
            cands = [(d, d, "left", "bottom"), (-d, d, "right", "bottom"),
                     (d, -d, "left", "top"), (-d, -d, "right", "top"),
                     (0, 1.3 * d, "center", "bottom"), (0, -1.3 * d, "center", "top"),
                     (1.3 * d, 0, "left", "center"), (-1.3 * d, 0, "right", "center")]
            cands.sort(key=lambda c: -(c[0] * pref[0] + c[1] * pref[1]) / math.hypot(c[0], c[1]))
            for dx, dy, ha, va in cands:
                box = self._box(px + dx * self.pt, py + dy * self.pt, w, h, ha, va)
                ox = np.minimum(box[2], boxes[:, 2]) - np.maximum(box[0], boxes[:, 0])
                oy = np.minimum(box[3], boxes[:, 3]) - np.maximum(box[1], boxes[:, 1])
                score = float(np.sum(np.where((ox > 0) & (oy > 0), ox * oy, 0.0)))
                inside = (min(box[2], fig_w) - max(box[0], 0)) * \
                    (min(box[3], fig_h) - max(box[1], 0))
                score += 4 * ((box[2] - box[0]) * (box[3] - box[1]) - max(inside, 0))
                score *= 1 + 0.25 * ring             # farther is worse, when none is free
                if score < best_score:
                    best, best_score = (dx, dy, ha, va, box), score
                if score == 0:
                    break
            if best_score == 0:
                break
        self._annotate(text, x, y, best, fs, color, bold)


UNKNOWN = UNKNOWN_COLOR   # reactions and the driver: unknown, drawn in their positive direction
KNOWN = KNOWN_COLOR       # weights and loads
INERTIA = INERTIA_COLOR   # d'Alembert's inertia force and couple (dashed)


def tex_symbol(symbol: str, comp: str = "") -> str:
    """matplotlib mathtext of an action symbol: F21 + x -> $F_{21x}$, Fin2 -> $F_{in2}$."""
    base, sub = split_symbol(symbol)
    if comp:
        sub = sub + ("," + comp if sub and not sub[-1].isdigit() else comp)
    sub = sub.replace("in", r"\mathrm{in}").replace("ext", r"\mathrm{ext}")
    return f"${base}_{{{sub}}}$" if sub else f"${base}$"


def _scene(analysis, k: int):
    res = next(iter(analysis.forces.values()))
    spec = analysis.spec
    sc = build_scene(analysis, res, k, {j.name: KNOWN for j in spec.joints},
                     {j.name: "" for j in spec.joints})
    sc.arrows = [a for a in sc.arrows if a.kind == "load"]
    sc.couples = [c for c in sc.couples if c.label != "M"]
    return sc


def _frame(extent_xy: tuple[np.ndarray, np.ndarray], width: float, max_h: float,
           margin: float = 0.3):
    """A figure ``width`` inches wide with equal axes showing ``lo..hi``, and ``margin``
    inches around them for labels that stick out."""
    from matplotlib.figure import Figure
    lo, hi = extent_xy
    span = np.maximum(hi - lo, 1e-9)
    inner_w = width - 2 * margin
    inner_h = float(np.clip(inner_w * span[1] / span[0], 0.6, max_h - 2 * margin))
    height = inner_h + 2 * margin
    fig = Figure(figsize=(width, height))
    ax = fig.add_axes((margin / width, margin / height, inner_w / width, inner_h / height))
    want = inner_w / inner_h
    mid = (lo + hi) / 2
    span = np.array([span[1] * want, span[1]]) if span[0] / span[1] < want else \
        np.array([span[0], span[0] / want])
    ax.set_xlim(mid[0] - span[0] / 2, mid[0] + span[0] / 2)
    ax.set_ylim(mid[1] - span[1] / 2, mid[1] + span[1] / 2)
    ax.set_aspect("equal", adjustable="box")
    ax.axis("off")
    ax.apply_aspect()
    return fig, ax


def _arrow(ax, start, vec, color, dashed=False, lw=1.3):
    start = np.asarray(start, float)
    ax.annotate("", xy=tuple(start + vec), xytext=tuple(start), zorder=6,
                arrowprops=dict(arrowstyle="-|>", color=color, lw=lw, mutation_scale=9,
                                shrinkA=0, shrinkB=0, ls=(0, (3, 2)) if dashed else "-"))


def _arc(ax, at, r, ccw: bool, color, dashed=False, labels=None):
    """A couple's arc about ``at`` (an obstacle to ``labels``); returns where its label goes."""
    x, y = at
    a0, a1 = (200, 470) if ccw else (470, 200)
    th = np.radians(np.linspace(a0, a1, 30))
    ax.plot(x + r * np.cos(th[:-3]), y + r * np.sin(th[:-3]), color=color, lw=1.1, zorder=5,
            ls=(0, (3, 2)) if dashed else "-")
    if labels is not None:
        labels.block_path(np.stack([x + r * np.cos(th), y + r * np.sin(th)], axis=1), 2.0)
    ax.annotate("", xy=(x + r * np.cos(th[-1]), y + r * np.sin(th[-1])),
                xytext=(x + r * np.cos(th[-4]), y + r * np.sin(th[-4])), zorder=5,
                arrowprops=dict(arrowstyle="-|>", color=color, lw=1.1, mutation_scale=8,
                                shrinkA=0, shrinkB=0))
    return x + r * math.cos(math.radians(-40)), y + r * math.sin(math.radians(-40))


def _shapes(ax, shapes, labels=True) -> None:
    """Link outlines, each link's number in a circle at its middle."""
    done = set()
    for s in sorted(shapes, key=lambda s: {"plate": 0, "block": 1, "bar": 2, "line": 2}[s.kind]):
        xy = np.asarray(s.xy)
        fill = LINK_FILL[(s.number - 1) % len(LINK_FILL)]
        if s.kind == "line":
            ax.plot(xy[:, 0], xy[:, 1], color="k", lw=3, solid_capstyle="round", zorder=2.2)
        else:
            ax.fill(xy[:, 0], xy[:, 1], facecolor=fill, edgecolor="k", lw=1.0,
                    zorder={"plate": 1.5, "block": 2.0, "bar": 2.2}[s.kind],
                    alpha=0.8 if s.kind == "plate" else 0.95)
    if not labels:
        return
    for s in shapes:
        if s.link in done:
            continue
        done.add(s.link)
        own = [np.asarray(t.xy) for t in shapes if t.link == s.link]
        c = np.concatenate(own).mean(axis=0)
        ax.text(c[0], c[1], str(s.number), fontsize=7, ha="center", va="center", zorder=8,
                bbox=dict(boxstyle="circle,pad=0.15", fc="white", ec="0.3", lw=0.6))


def _block_shapes(labels, shapes, numbers: bool = True) -> None:
    """Link outlines (and their number circles) as label obstacles."""
    own: dict[str, list] = {}
    for s in shapes:
        xy = np.asarray(s.xy, float)
        labels.block_path(np.vstack([xy, xy[:1]]) if s.kind != "line" else xy, 2.0)
        own.setdefault(s.link, []).append(xy)
    for xys in own.values() if numbers else ():
        c = np.concatenate(xys).mean(axis=0)
        labels.block(c[0], c[1], 5.0)


def _bounds(points) -> tuple[np.ndarray, np.ndarray]:
    xy = np.asarray(points, float).reshape(-1, 2)
    return xy.min(axis=0), xy.max(axis=0)


@styled
def mechanism_figure(analysis, k: int, path: Path) -> Path:
    """The mechanism at angle index ``k`` (links numbered, joints lettered, loads and the
    driver's rotation), without any result."""
    sc = _scene(analysis, k)
    spec = analysis.spec
    ext = sc.extent
    pts = [p for s in sc.shapes for p in s.xy] + [p for g in sc.guides for p in g[:2]]
    pts += [(x, y) for x, y, _ in sc.pins]
    L = 0.2 * ext
    for a in sc.arrows:
        m = math.hypot(*a.f)
        if m > 0:
            pts.append(tuple(np.asarray(a.at) + np.asarray(a.f) / m * L))
    if spec.driver.crank:                      # the driver's arc, whole
        pivot = np.asarray(analysis.joint_points()[spec.driver.joint][k], float)
        pts += [tuple(pivot - 0.09 * ext), tuple(pivot + 0.09 * ext)]
    lo, hi = _bounds(pts)
    pad = 0.04 * ext
    fig, ax = _frame((lo - pad, hi + pad), 4.6, 3.4, margin=0.3)
    labels = SheetLabels(ax, 8)
    _shapes(ax, sc.shapes)
    _block_shapes(labels, sc.shapes)
    for kind, p0, p1 in sc.elements:
        draw_element(ax, kind, p0, p1, 0.025 * ext)
        labels.block_path([p0, p1], 2.0)
    for p0, p1, on_ground, normal, offset in sc.guides:
        draw_guide(ax, p0, p1, on_ground, normal, offset)
        for side in ((-1, 1) if on_ground else (0,)):
            off = side * offset * np.asarray(normal, float)
            labels.block_path([np.asarray(p0) + off, np.asarray(p1) + off], 2.0)
    for x, y, on_ground in sc.pins:
        if on_ground:
            draw_ground_symbol(ax, x, y, 0.04 * ext)
            labels.block_area((x - 0.04 * ext, y - 0.055 * ext), (x + 0.04 * ext, y))
        ax.plot([x], [y], "o", ms=5, mfc="white", mec="k", mew=1.2, zorder=4)
        labels.block(x, y, 4.0)
    tips = []
    for a in sc.arrows:
        m = math.hypot(*a.f)
        if m <= 0:
            continue
        v = np.asarray(a.f) / m * L
        _arrow(ax, a.at, v, KNOWN)
        labels.block_segment(np.asarray(a.at) + 0.15 * v, np.asarray(a.at) + v)
        tips.append((tex_symbol(a.label), np.asarray(a.at) + v, tuple(v / L), KNOWN))
    for c in sc.couples:
        if abs(c.value) > 0:
            spot = _arc(ax, c.at, 0.06 * ext, c.value > 0, KNOWN, labels=labels)
            tips.append((tex_symbol(c.label), spot, (1, -1), KNOWN))
    drv = spec.driver
    if drv.crank and not drv.holds:   # no speed on a crank at rest
        pivot = analysis.joint_points()[drv.joint][k]
        n = spec.number(drv.link)
        ccw = drv.alpha >= 0 if drv.at_rest else drv.omega >= 0
        spot = _arc(ax, pivot, 0.09 * ext, ccw, UNKNOWN, labels=labels)
        sym = r"\alpha" if drv.at_rest else r"\omega"
        tips.append((rf"${sym}_{{{n}}}$", spot, (1, -1), UNKNOWN))
    # the joints' letters first (each at its point), then the loads' and the driver's symbols
    labels.place_points(sc.labels, ext)
    for text, at, prefer, color in tips:
        labels.place(text, at[0], at[1], color=color, prefer=prefer)
    return save(fig, path.parent, path.stem)[0]


def _actions(analysis, link: str):
    """The actions on ``link`` as a free body, as the d'Alembert equations have them."""
    return analysis.free_body_actions([link])


@styled
def fbd_figure(analysis, k: int, link: str, path: Path, zero: set) -> tuple[Path, list[str]]:
    """The free-body diagram of ``link`` at angle index ``k``; also the symbols of the
    actions that vanish at that angle (left out of the drawing). ``zero``: reaction unknowns
    a slider's normal constraint sets to zero (not drawn)."""
    spec, kin, points = analysis.spec, analysis.kinematics, analysis.joint_points()
    sc = _scene(analysis, k)
    shapes = [s for s in sc.shapes if s.link == link]
    lk = spec.link(link)
    n = lk.number
    acts = _actions(analysis, link)
    body = [p for s in shapes for p in s.xy]
    size = float(np.max(np.ptp(np.asarray(body), axis=0))) if body else sc.extent * 0.2
    size = max(size, 0.15 * sc.extent)
    L = 0.42 * size
    com = np.asarray(kin.com(link).r[k], float)
    draws = []          # (kind, at, vec or ccw, label, color, dashed)
    omitted = []
    for a in acts:
        dashed = a.category == "inertia"
        color = INERTIA if dashed else (UNKNOWN if a.unknowns else KNOWN)
        if a.kind == "couple":
            at = com
            if a.category == "reaction":
                joint = next(j for j in spec.joints
                             if a.unknowns[0] == f"joint.{j.name}.moment")
                at = np.asarray(points[joint.name][k], float)
            elif a.category == "driver":
                at = np.asarray(points[spec.driver.joint][k], float)
            if a.unknowns:
                draws.append(("couple", at, True, tex_symbol(a.symbol), color, dashed))
            else:
                v = float(np.broadcast_to(a.value, (kin.n,))[k])
                if abs(v) <= 1e-12 * (1 + abs(v)) or v == 0:
                    omitted.append(a.symbol)
                else:
                    draws.append(("couple", com, v > 0, tex_symbol(a.symbol), color, dashed))
            continue
        at = np.asarray(a.at[k], float)
        if a.direction is not None:                  # the actuator's push, unknown magnitude
            u = np.asarray(a.direction[k], float) * a.sign
            draws.append(("force", at, u * L, tex_symbol(a.symbol), color, dashed))
        elif a.unknowns:                             # a reaction: its unknown components
            for comp, u, axis in (("x", a.unknowns[0], (1.0, 0.0)),
                                  ("y", a.unknowns[1], (0.0, 1.0))):
                if u in zero:
                    continue
                draws.append(("force", at, np.asarray(axis) * L, tex_symbol(a.symbol, comp),
                              color, dashed))
        else:
            f = np.asarray(np.broadcast_to(a.value, (kin.n, 2))[k], float)
            m = math.hypot(*f)
            if m <= 1e-12 * (1 + m) or m == 0:
                omitted.append(a.symbol)
                continue
            draws.append(("force", at, f / m * L, tex_symbol(a.symbol), color, dashed))
    applied = [at for _, at, *_ in draws]
    draws = _spread(draws, L)
    pts = body + [tuple(com)]
    for kind, at, v, *_ in draws:
        pts.append(tuple(at))
        if kind == "force":
            pts.append(tuple(at + v))
        else:
            pts += [tuple(at + 0.25 * L), tuple(at - 0.25 * L)]
    lo, hi = _bounds(pts)
    pad = 0.05 * L
    fig, ax = _frame((lo - pad, hi + pad), 2.2, 2.5, margin=0.34)
    labels = SheetLabels(ax, 7.5)
    _shapes(ax, shapes, labels=False)
    _block_shapes(labels, shapes, numbers=False)
    for j in spec.joints:
        if link in j.links and j.type == "R":
            x, y = points[j.name][k]
            ax.plot([x], [y], "o", ms=4.5, mfc="white", mec="k", mew=1.0, zorder=4)
            labels.block(x, y, 3.5)
    ax.plot([com[0]], [com[1]], marker="o", ms=5, mfc="white", mec="k", mew=0.8, zorder=4.5)
    ax.plot([com[0]], [com[1]], marker="+", ms=5, color="k", mew=0.8, zorder=4.6)
    labels.block(com[0], com[1], 3.5)
    for kind, at, v, text, color, dashed in draws:
        if kind == "force":
            _arrow(ax, at, v, color, dashed)
            labels.block_segment(at + 0.15 * v, at + v)
    spots = []
    for kind, at, v, text, color, dashed in draws:
        if kind == "couple":
            spots.append((text, _arc(ax, at, 0.22 * L, v, color, dashed, labels), color))
    # names first: the points, then the forces' symbols at their tips
    named = {}
    for name, local in lk.points.items():
        r = kin.point(link, local).r[k]
        named.setdefault((round(r[0] / size, 4), round(r[1] / size, 4)),
                         [r, []])[1].append(literal(name))
    for r, names in named.values():
        labels.place("/".join(names), r[0], r[1], bold=True, fontsize=8, prefer=(-1, 1))
    c_name = f"$C_{{{n}}}$"
    if not any(np.allclose(r, com) for r, _ in named.values()):
        labels.place(c_name, com[0], com[1], prefer=(-1, -1))
    centre = np.mean(np.asarray(pts, float), axis=0)
    for kind, at, v, text, color, dashed in draws:
        if kind == "force":
            d = v / L
            end = at + v                             # the free end: the tip, or the tail of
            if any(np.allclose(end, q) for q in applied):    # a force drawn arriving
                end, d = at, -d
            side = np.array([-d[1], d[0]])           # beside it, away from the middle
            if np.dot(side, end - centre) < 0:
                side = -side
            labels.place(text, end[0], end[1], color=color, prefer=tuple(side + 0.4 * d))
    for text, spot, color in spots:
        labels.place(text, *spot, color=color, prefer=(1, -1))
    return save(fig, path.parent, path.stem)[0], omitted


def _spread(draws: list, L: float) -> list:
    """Forces at one point along the same direction would hide each other: the second is
    drawn arriving at the point (its head there, as textbooks also draw forces), a third
    shifted sideways."""
    out = []
    taken: list[tuple[np.ndarray, np.ndarray]] = []     # (point, direction occupied)

    def free(at, d) -> bool:
        for p, q in taken:
            if np.allclose(p, at, atol=1e-9 * (1 + L)) and float(np.dot(q, d)) > 0.97:
                return False
        return True

    for item in draws:
        kind, at, v = item[:3]
        if kind != "force":
            out.append(item)
            continue
        d = v / max(float(np.hypot(*v)), 1e-300)
        if free(at, d):
            taken.append((at, d))
            out.append(item)
        elif free(at, -d):
            taken.append((at, -d))
            out.append((kind, at - v, v) + tuple(item[3:]))
        else:
            shift = 0.12 * L * np.array([-d[1], d[0]]) * (1 + len(taken) % 3)
            out.append((kind, at + shift, v) + tuple(item[3:]))
    return out
