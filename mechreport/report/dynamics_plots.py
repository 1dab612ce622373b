"""The Machine dynamics figure: the crank's speed from the start (start-up), and over the
steady turn against the crank angle, from a report's :class:`~.dynamics.DynamicsPlot`."""
from __future__ import annotations

from pathlib import Path

import numpy as np

from ..units import fmt
from .mpl import BLUE, GREY, VERMILION, figure, legend_top, save, styled

SPEED_COLOR = BLUE


def dynamics_figure(dp, d=None):
    """Two panels: the speed [rpm] against time from the start, with the steady mean and its
    95 % (the end of the start-up) dashed; and the speed over the steady turn against the
    crank angle, with its mean. One panel (the start-up) without a steady state."""
    steady = len(dp.angles) > 0
    panels = [p for p, shown in ((draw_startup, dp.startup_shown),
                                 (draw_steady_turn, steady)) if shown] or [draw_startup]
    fig, axes = figure(2.6, 1, len(panels), wgap=0.75, margins=(0.62, 0.12, 0.46, 0.42))
    for k, draw in enumerate(panels):
        draw(axes[0, k], dp)
    return fig


def draw_startup(ax, dp, d=None) -> None:
    """The crank's speed [rpm] against the time from the start [s] on ``ax``, with the
    steady mean and its 95 % (the end of the start-up) dashed when there is a steady state
    (``dp`` a report's DynamicsPlot; speeds and times need no display unit)."""
    ax.plot(dp.time, dp.rpm, color=SPEED_COLOR, lw=1.3, label="speed")
    if dp.mean is not None:
        ax.axhline(dp.mean, color=GREY, lw=0.8, ls=(0, (5, 2)), label="steady mean")
        ax.axhline(0.95 * dp.mean, color=GREY, lw=0.8, ls=(0, (1.5, 1.5)), label="95 %")
    ax.set_xlim(0, float(dp.time[-1]) if len(dp.time) else 1.0)
    ax.set_ylim(bottom=min(0.0, float(np.min(dp.rpm))) if len(dp.rpm) else 0.0)
    ax.set_xlabel("time [s]")
    ax.set_ylabel("crank speed [rpm]")
    legend_top(ax, 3 if dp.mean is not None else 1)


def draw_steady_turn(ax, dp, d=None) -> None:
    """The crank's speed [rpm] over the steady cycle against the crank angle [deg] on
    ``ax``, with its mean and its extremes marked (the integrated motion's, located between
    samples: ``dp.highest``, ``dp.lowest``), each labelled with its speed and angle (``dp``
    a report's DynamicsPlot with a steady state)."""
    name = "steady turn" if dp.cycle == 360 else "steady cycle"
    ax.plot(dp.angles, dp.turn_rpm, color=SPEED_COLOR, lw=1.3,
            label=f"{name} (mean {fmt(dp.mean)} rpm)")
    ax.axhline(dp.mean, color=GREY, lw=0.8, ls=(0, (5, 2)))
    ax.set_xlim(0, dp.cycle)
    ax.set_xticks(np.arange(0, dp.cycle + 1, 90 if dp.cycle <= 360 else 180))
    ax.set_xlabel("crank angle φ [deg]")
    ax.set_ylabel("crank speed [rpm]")
    tops = [x for x in (dp.highest, dp.lowest) if x is not None]
    hi = max([float(np.max(dp.turn_rpm))] + [r for _, r in tops])
    lo = min([float(np.min(dp.turn_rpm))] + [r for _, r in tops])
    pad = max((hi - lo) * 0.3, abs(dp.mean) * 1e-4)
    ax.set_ylim(lo - pad, hi + pad)
    ax.ticklabel_format(axis="y", useOffset=False)
    for where, above in ((dp.highest, True), (dp.lowest, False)):
        if where is None:
            continue
        angle, rpm = where
        ax.plot([angle], [rpm], marker="v" if above else "^", color=VERMILION, ms=4.5, lw=0)
        right = angle < 0.6 * dp.cycle
        ax.annotate(f"{'max' if above else 'min'} {fmt(rpm, 5)} rpm at {fmt(angle, 4)}°",
                    (angle, rpm), xytext=(4 if right else -4, 5 if above else -5),
                    textcoords="offset points", ha="left" if right else "right",
                    va="bottom" if above else "top", fontsize=6.5, color=VERMILION)
    legend_top(ax, 1)


@styled
def write_dynamics_plot(model, outdir: Path) -> list[Path]:
    """The Machine dynamics figure of ``model`` into ``outdir`` (SVG), if it has one."""
    sec = getattr(model, "dynamics", None)
    if sec is None or "dynamics" not in model.figures:
        return []
    return save(dynamics_figure(sec.plot, model.display), outdir, model.figures["dynamics"].stem)


__all__ = ["draw_startup", "draw_steady_turn", "dynamics_figure", "write_dynamics_plot"]
