"""The driver's effort with and without friction in the joints (a report's FrictionPlot
``fp``), in the report's display units (``d``)."""
from __future__ import annotations

import numpy as np

from .labels import CLEAR
from .mpl import BLUE, INK, VERMILION, figure, layout, legend_top, pt_to_px, text_renderer
from .quantities import with_gaps
from .sweep_axes import crank_axis, scale_to_trusted

LEGEND_SLACK = 0.05
FRICTION_COLOR = VERMILION       # the effort with friction
FRICTIONLESS_COLOR = BLUE   # and without it


def friction_figure(fp, d):
    """The driver's effort with and without friction (a report's FrictionPlot ``fp``); the
    angles where friction alone reverses its sign marked on the zero line. The legend takes
    one row above the axes, or two where one would run past the figure's edge."""
    margins = (0.72, 0.12, 0.46, 0.39)
    fig, axes = figure(2.9, margins=margins)
    ax = axes[0, 0]
    draw_friction(ax, fp, d)
    legend = ax.get_legend()
    box = legend.get_window_extent(text_renderer(fig))
    # Agg's metrics run a few per cent narrower than the SVG's text as a PDF sets it
    if box.x1 + LEGEND_SLACK * box.width > fig.bbox.width - pt_to_px(fig, CLEAR):
        layout(fig, 1, 1, 0.55, 0.75, (*margins[:3], margins[3] + 0.17))
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
