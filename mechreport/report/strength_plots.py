"""Strength plots (a report's StrengthPlot ``sp``): N, V and M along the most loaded member
at its worst angle, and each member's largest stress over the sweep, in the report's display
units (``d``)."""
from __future__ import annotations

import math

import numpy as np

from .mpl import (BLUE, GREEN, PALETTE, STYLES, VERMILION, figure, fit_y_labels, layout,
                  legend_top, literal)


#: each internal force's name, kind of quantity and colour
PARTS = {"N": ("force", BLUE), "V": ("force", GREEN), "M": ("moment", VERMILION)}


def strength_figure(sp, d):
    """N, V and M along the most loaded member at its worst angle (a report's StrengthPlot
    ``sp``), three axes over one position axis, filled to zero."""
    fig, axes = figure(4.6, rows=3, gap=0.22, margins=(0.85, 0.12, 0.46, 0.15), sharex=True)
    for ax, part in zip(axes[:, 0], PARTS):
        draw_internal_force(ax, sp, d, part, label=part == "M")
    fit_y_labels(fig, axes, lambda left, _: layout(
        fig, 3, 1, 0.22, 0.75, (left, 0.12, 0.46, 0.15)), 0.85, 0.75)
    return fig


def draw_internal_force(ax, sp, d, part: str = "M", label: bool = True) -> None:
    """One internal force of the most loaded member at its worst angle on ``ax``: ``part``
    "N" (normal force), "V" (shear force) or "M" (bending moment) along the member, in the
    display units (``d``: its length and force or moment), filled to zero; ``label``: the
    position axis labelled."""
    kind, color = PARTS[part]
    s = d.value(sp.s, "length")
    v = d.value(np.asarray(getattr(sp, part), float), kind)
    ax.plot(s, v, color=color, lw=1.5)
    ax.fill_between(s, v, 0, color=color, alpha=0.18, lw=0)
    ax.axhline(0, color="0.3", lw=0.6)
    ax.set_ylabel(f"{part} [{d.unit(kind)}]")
    ax.set_xlim(s[0], s[-1])
    ax.margins(y=0.12)
    if label:
        ax.set_xlabel(literal(f"s along member {sp.member} [{d.unit('length')}]"))


def stress_figure(sp, d):
    """The largest stress along each member over the sweep (a report's StrengthPlot)."""
    n = len(sp.stress)
    fig, axes = figure(2.6, margins=(0.72, 0.12, 0.46, 0.22 + 0.17 * math.ceil(n / 4)))
    draw_stress(axes[0, 0], sp, d)
    return fig


def draw_stress(ax, sp, d) -> None:
    """The largest stress along each member over the sweep on ``ax`` (a colour and line style
    each), in the display unit of stresses (``d``)."""
    n = len(sp.stress)
    for k, (name, values) in enumerate(sp.stress.items()):
        ax.plot(sp.angles, d.value(values, "stress"), color=PALETTE[k % len(PALETTE)],
                lw=1.4, ls=STYLES[k % 4], label=literal(name))
    ax.set_ylabel(f"largest stress [{d.unit('stress')}]")
    ax.set_ylim(bottom=0)
    if sp.whole_turn:
        ax.set_xlim(0, 360)
        ax.set_xticks(np.arange(0, 361, 45))
    ax.set_xlabel(sp.xlabel)
    legend_top(ax, min(n, 4))
