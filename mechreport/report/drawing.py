"""Draw a :class:`~mechreport.report.scene.Scene`: links, pins, sliders and guides, ground
hatching, point labels, load and reaction arrows, couples. Geometry comes from the scene
(global coordinates [m]); this module only draws."""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from .plots import WIDTH, pyplot, save

LINK_FILL = ["#dbe6f4", "#f6e3cf", "#dcefdc", "#f3dada", "#e7def0", "#ece3dc", "#f7e1ef"]
ARROW_LEN = 0.26        # longest arrow as a fraction of the mechanism's extent
ARROW_MIN = 0.05        # shortest drawn (non-zero) arrow, same unit


def _ground_symbol(ax, x: float, y: float, size: float) -> None:
    """A fixed pivot: a triangle under the pin and a hatched base."""
    tri = np.array([[x, y], [x - size * 0.6, y - size], [x + size * 0.6, y - size]])
    ax.fill(tri[:, 0], tri[:, 1], facecolor="white", edgecolor="k", lw=1.0, zorder=3)
    base_y = y - size
    ax.plot([x - size, x + size], [base_y, base_y], color="k", lw=1.2, zorder=3)
    for t in np.linspace(-size, size * 0.8, 6):
        ax.plot([x + t, x + t - size * 0.3], [base_y, base_y - size * 0.35], color="k",
                lw=0.7, zorder=3)


def _guide(ax, p0, p1, on_ground: bool, normal, size: float) -> None:
    p0, p1, nrm = np.asarray(p0), np.asarray(p1), np.asarray(normal)
    if not on_ground:
        ax.plot(*np.stack([p0, p1]).T, color="0.35", lw=0.8, ls=(0, (6, 3)), zorder=1)
        return
    hatch = 0.4 * size if size < 0.1 * np.linalg.norm(p1 - p0) else 0.04 * np.linalg.norm(p1 - p0)
    for side in (-1, 1):
        off = side * nrm * size
        a, b = p0 + off, p1 + off
        ax.plot(*np.stack([a, b]).T, color="k", lw=1.0, zorder=1)
        for t in np.linspace(0.03, 0.97, 14):
            q = a + t * (b - a)
            tip = q + side * nrm * hatch - (b - a) / np.linalg.norm(b - a) * hatch * 0.7
            ax.plot([q[0], tip[0]], [q[1], tip[1]], color="k", lw=0.6, zorder=1)


def _arrows(ax, scene, extent: float) -> list:
    """Draw the force arrows (common scale: the largest is ARROW_LEN of the extent); the
    legend handles, one per arrow, carrying the magnitudes."""
    from matplotlib.lines import Line2D
    mags = [math.hypot(*a.f) for a in scene.arrows]
    top = max(mags, default=0.0)
    handles, tips = [], []
    for a, mag in zip(scene.arrows, mags):
        label = f"{a.label} = {mag:.4g} N" + (" (load)" if a.kind == "load" else "")
        handles.append(Line2D([], [], color=a.color, lw=2, marker=">", ms=5, label=label))
        if top <= 0 or mag < 1e-9 * top:
            continue
        length = max(mag * ARROW_LEN * extent / top, ARROW_MIN * extent)
        d = np.asarray(a.f) / mag * length
        x, y = a.at
        tips.append((x + d[0], y + d[1]))
        ax.annotate("", xy=tips[-1], xytext=(x, y), zorder=6,
                    arrowprops=dict(arrowstyle="-|>", color=a.color, lw=1.6,
                                    mutation_scale=10, shrinkA=0, shrinkB=0))
        ux, uy = d / length
        ax.annotate(a.label, tips[-1], fontsize=7, color=a.color, zorder=7,
                    xytext=(5 * ux, 5 * uy), textcoords="offset points",
                    ha="left" if ux >= -0.3 else "right", va="bottom" if uy >= 0 else "top")
    if tips:
        ax.update_datalim(np.asarray(tips))
    return handles


def _couples(ax, scene, extent: float) -> list:
    """Draw each couple as an arc arrow about its point; legend handles with the values."""
    from matplotlib.lines import Line2D
    r = 0.06 * extent
    handles = []
    for c in scene.couples:
        handles.append(Line2D([], [], color=c.color, lw=1.1, marker="$\\circlearrowleft$",
                              ms=7, label=f"{c.label} = {c.value:.4g} N·m"))
        if abs(c.value) < 1e-12:
            continue
        x, y = c.at
        start, end = (200, 470) if c.value > 0 else (470, 200)
        th = np.radians(np.linspace(start, end, 30))
        ax.plot(x + r * np.cos(th[:-3]), y + r * np.sin(th[:-3]), color=c.color, lw=1.1,
                zorder=5)
        ax.annotate("", xy=(x + r * np.cos(th[-1]), y + r * np.sin(th[-1])),
                    xytext=(x + r * np.cos(th[-4]), y + r * np.sin(th[-4])), zorder=5,
                    arrowprops=dict(arrowstyle="-|>", color=c.color, lw=1.1,
                                    mutation_scale=9, shrinkA=0, shrinkB=0))
        ax.annotate(c.label, (x + r * 0.75, y - r * 0.75), fontsize=7, color=c.color,
                    ha="left", va="top", zorder=7)
    return handles


def _links(ax, scene) -> None:
    for s in scene.shapes:
        xy = np.asarray(s.xy)
        fill = LINK_FILL[(s.number - 1) % len(LINK_FILL)]
        if s.kind == "line":
            ax.plot(xy[:, 0], xy[:, 1], color="k", lw=3, solid_capstyle="round", zorder=2)
            continue
        z = {"plate": 1.5, "bar": 2, "block": 2.5}[s.kind]
        ax.fill(xy[:, 0], xy[:, 1], facecolor=fill, edgecolor="k", lw=1.0, zorder=z,
                alpha=0.8 if s.kind == "plate" else 1.0)
        if s.kind != "plate":
            c = xy.mean(axis=0)
            ax.text(c[0], c[1], str(s.number), fontsize=6.5, ha="center", va="center",
                    color="0.25", zorder=z + 0.1)


def _figsize(scene) -> tuple[float, float]:
    """Width fixed to the text width; height from the mechanism's aspect, within limits."""
    xs = [p[0] for s in scene.shapes for p in s.xy] or [0.0, 1.0]
    ys = [p[1] for s in scene.shapes for p in s.xy] or [0.0, 1.0]
    aspect = (max(ys) - min(ys) + 0.3 * scene.extent) / (max(xs) - min(xs) + 0.3 * scene.extent)
    return WIDTH, float(np.clip(0.68 * WIDTH * aspect, 2.6, 5.6))


def draw_scene(scene):
    """A matplotlib figure of ``scene`` (equal axes, no frame), with a legend of the forces
    and couples (values) on the right."""
    plt = pyplot()
    fig, ax = plt.subplots(figsize=_figsize(scene))
    ext = scene.extent
    _links(ax, scene)
    for p0, p1, on_ground, normal, offset in scene.guides:
        _guide(ax, p0, p1, on_ground, normal, offset)
    for x, y, on_ground in scene.pins:
        if on_ground:
            _ground_symbol(ax, x, y, 0.04 * ext)
        ax.plot([x], [y], "o", ms=5, mfc="white", mec="k", mew=1.2, zorder=4)
    placed: list[tuple[float, float]] = []
    for x, y, text in scene.labels:
        dup = sum(1 for px, py in placed if math.hypot(px - x, py - y) < 0.02 * ext)
        placed.append((x, y))
        ax.annotate(text, (x, y), xytext=(-6 - 10 * dup, 4), textcoords="offset points",
                    fontsize=8.5, fontweight="bold", ha="right", zorder=8)
    handles = _arrows(ax, scene, ext) + _couples(ax, scene, ext)
    ax.set_aspect("equal", adjustable="datalim")
    ax.autoscale_view()
    ax.margins(0.08)
    ax.axis("off")
    ax.set_title(f"φ = {scene.angle:g}°", loc="left")
    if handles:
        ax.legend(handles=handles, loc="center left", bbox_to_anchor=(1.0, 0.5),
                  fontsize=7.5, frameon=False, handlelength=1.8)
    fig.tight_layout()
    return fig


def write_drawings(model, outdir: Path) -> list[Path]:
    """One drawing per solved reference angle, PNG and SVG."""
    out = []
    figs = [r.drawing for r in model.refs if r.drawing is not None]
    for fig_spec, scene in zip(figs, model.scenes):
        out += save(draw_scene(scene), outdir, fig_spec.stem)
    return out
