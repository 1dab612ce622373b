"""An engine's figures over its cycle (a report's CycleData ``cd`` with pressure loads):
the pressure diagram (each cylinder's pressure against the crank angle) and the
turning-moment diagram (the crank effort against its mean, the energy of every area between
two crossings labelled, as the dynamic-force-analysis chapter draws it; for several
cylinders, each cylinder's share below). Values in the report's display units (``d``)."""
from __future__ import annotations

import numpy as np

from ..post.flywheel import energy_areas
from ..units import fmt
from .cycle_plots import cycle_axis
from .mpl import BLUE, INK, ORANGE, PALETTE, SKY, STYLES, figure, legend_top, literal

__all__ = ["pressure_figure", "draw_pressure", "turning_moment_figure",
           "draw_turning_moment", "draw_shares"]

#: an area of the turning-moment diagram below this share of the largest is not labelled
LABEL_SHARE = 0.04


def pressure_figure(cd, d):
    """The pressure diagram (:func:`draw_pressure`)."""
    n = len(cd.pressures)
    fig, axes = figure(2.7, margins=(0.72, 0.12, 0.46, 0.22 + 0.17 * -(-n // 4)))
    draw_pressure(axes[0, 0], cd, d)
    return fig


def draw_pressure(ax, cd, d=None) -> None:
    """Each pressure load's pressure over the cycle on ``ax``, as its profile gives it (the
    unit as written, ``cd.pressure_unit``); ``d`` is not needed."""
    for k, (name, p) in enumerate(cd.pressures.items()):
        ax.plot(cd.angles, p, color=PALETTE[k % len(PALETTE)], lw=1.4, ls=STYLES[k % 4],
                label=literal(name))
    ax.set_ylabel(f"pressure [{cd.pressure_unit}]")
    legend_top(ax, 4)
    cycle_axis(ax, cd)


def turning_moment_figure(cd, d):
    """The turning-moment diagram, and below it each cylinder's share when there are
    several (:func:`draw_turning_moment`, :func:`draw_shares`)."""
    several = len(cd.pressures) > 1
    if several:
        fig, axes = figure(4.6, 2, 1, gap=0.55, margins=(0.72, 0.12, 0.42, 0.45),
                           gridspec_kw={"height_ratios": [3, 2]}, sharex=True)
        draw_turning_moment(axes[0, 0], cd, d, label=False)
        draw_shares(axes[1, 0], cd, d)
    else:
        fig, axes = figure(2.9, margins=(0.72, 0.12, 0.46, 0.45))
        draw_turning_moment(axes[0, 0], cd, d)
    return fig


def draw_turning_moment(ax, cd, d, label: bool = True) -> None:
    """The engine's crank effort (minus the driver's torque: what the engine gives the
    shaft) over the cycle against its mean on ``ax``, the areas above (energy in excess) and
    below (energy lacking) shaded and each labelled with its energy [J] (those below
    LABEL_SHARE of the largest left unlabelled)."""
    M = d.unit("moment")
    a = cd.angles
    effort = -np.asarray(cd.torque, float)
    mean = -cd.mean
    t, m = d.value(effort, "moment"), d.value(mean, "moment")
    ax.plot(a, t, color=INK, lw=1.4, label="crank effort")
    ax.axhline(m, color=BLUE, lw=1.0, ls="--", label=f"mean {d.num(mean, 'moment')} {M}")
    ax.fill_between(a, t, m, where=t >= m, interpolate=True, color=ORANGE, alpha=0.35, lw=0,
                    label="above the mean (+ΔE)")
    ax.fill_between(a, t, m, where=t < m, interpolate=True, color=SKY, alpha=0.35, lw=0,
                    label="below the mean (−ΔE)")
    areas = [(x.start, x.end, x.energy) for x in energy_areas(a, effort, mean, cd.period)]
    largest = max(abs(e) for _, _, e in areas) or 1.0
    lo, hi = ax.get_ylim()
    for x0, x1, energy in areas:
        if abs(energy) < LABEL_SHARE * largest:
            continue
        mid = 0.5 * (x0 + x1)
        x = mid if mid <= a[-1] else mid - cd.period
        inside = (a >= x0) & (a <= x1) if x1 <= cd.period + a[0] else \
            (a >= x0) | (a <= x1 - cd.period)
        peak = t[inside][np.argmax(np.abs(t[inside] - m))] if inside.any() else m
        y = m + 0.5 * (peak - m)
        ax.annotate(f"{'+' if energy > 0 else '−'}{fmt(abs(energy))} J", (x, y),
                    ha="center", va="center", fontsize=6.5, color=INK,
                    bbox={"boxstyle": "round,pad=0.15", "fc": "white", "ec": "none",
                          "alpha": 0.8})
    ax.set_ylim(lo, hi)
    ax.set_ylabel(f"torque [{M}]")
    legend_top(ax, 4)
    cycle_axis(ax, cd, label=label)


def draw_shares(ax, cd, d) -> None:
    """Each cylinder's share of the crank effort over the cycle on ``ax``: minus its gas
    load's part of the driver's torque (the torque by source), and the total."""
    M = d.unit("moment")
    for k, name in enumerate(cd.pressures):
        part = cd.sources.get(name)
        if part is None:
            continue
        ax.plot(cd.angles, d.value(-np.asarray(part, float), "moment"),
                color=PALETTE[k % len(PALETTE)], lw=1.1, ls=STYLES[k % 4],
                label=literal(name))
    ax.plot(cd.angles, d.value(-np.asarray(cd.torque, float), "moment"), color=INK, lw=0.9,
            alpha=0.6, label="total")
    ax.axhline(0, color="0.3", lw=0.5)
    ax.set_ylabel(f"torque [{M}]")
    legend_top(ax, 5)
    cycle_axis(ax, cd)
