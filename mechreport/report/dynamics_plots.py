"""The Machine dynamics figure: the crank's speed from the start (start-up), and over the
steady turn against the crank angle, from a report's :class:`~.dynamics.DynamicsPlot`."""
from __future__ import annotations

from pathlib import Path

import numpy as np

from ..units import fmt
from .mpl import BLUE, GREY, figure, legend_top, save, styled

SPEED_COLOR = BLUE


def dynamics_figure(dp, d=None):
    """Two panels: the speed [rpm] against time from the start, with the steady mean and its
    95 % (the end of the start-up) dashed; and the speed over the steady turn against the
    crank angle, with its mean. One panel (the start-up) without a steady state."""
    two = len(dp.angles) > 0
    fig, axes = figure(2.6, 1, 2 if two else 1, wgap=0.75, margins=(0.62, 0.12, 0.46, 0.42))
    draw_startup(axes[0, 0], dp)
    if two:
        draw_steady_turn(axes[0, 1], dp)
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
    """The crank's speed [rpm] over the steady turn against the crank angle [deg] on
    ``ax``, with its mean (``dp`` a report's DynamicsPlot with a steady state)."""
    ax.plot(dp.angles, dp.turn_rpm, color=SPEED_COLOR, lw=1.3,
            label=f"steady turn (mean {fmt(dp.mean)} rpm)")
    ax.axhline(dp.mean, color=GREY, lw=0.8, ls=(0, (5, 2)))
    ax.set_xlim(0, 360)
    ax.set_xticks(np.arange(0, 361, 90))
    ax.set_xlabel("crank angle φ [deg]")
    ax.set_ylabel("crank speed [rpm]")
    span = float(np.ptp(dp.turn_rpm))
    pad = max(span * 0.25, abs(dp.mean) * 1e-4)
    ax.set_ylim(float(np.min(dp.turn_rpm)) - pad, float(np.max(dp.turn_rpm)) + pad)
    ax.ticklabel_format(axis="y", useOffset=False)
    legend_top(ax, 1)


@styled
def write_dynamics_plot(model, outdir: Path) -> list[Path]:
    """The Machine dynamics figure of ``model`` into ``outdir`` (SVG), if it has one."""
    sec = getattr(model, "dynamics", None)
    if sec is None or "dynamics" not in model.figures:
        return []
    return save(dynamics_figure(sec.plot, model.display), outdir, model.figures["dynamics"].stem)


__all__ = ["draw_startup", "draw_steady_turn", "dynamics_figure", "write_dynamics_plot"]
