"""Plots over one steady turn (a report's CycleData ``cd``): the flywheel diagram, the torque
by source, the transmission angle and the balancing of the shaking force. Values in the
report's display units (``d``)."""
from __future__ import annotations

import math

import numpy as np

from ..units import fmt
from .labels import LINE_CLEAR, crossings, data_lines, grow, hline, place
from .mpl import (BLUE, GREEN, INK, ORANGE, PALETTE, PURPLE, SKY, STYLES, VERMILION, WIDTH,
                  figure, fit_y_labels, layout, legend_top, literal, pt_to_px, text_renderer,
                  text_size)

def cycle_axis(ax, cd, label: bool = True) -> None:
    """0-360 deg over one turn (0 to the cycle, ticks every 90 deg, over a longer cycle),
    interpolated (left-out) angles marked."""
    period = cd.period
    ax.set_xlim(0, period)
    ax.set_xticks(np.arange(0, period + 1, 45 if period == 360.0 else 90))
    if label:
        ax.set_xlabel("crank angle φ [deg]")
    for a in cd.interpolated:
        ax.axvspan(a - 0.5, a + 0.5, color="0.45", alpha=0.35, lw=0)


#: a motor limit further than this share of the torque's range beyond it is off the scale
LIMIT_REACH = 0.5
LIMIT_COLOR = PURPLE


def flywheel_figure(cd, d):
    """The classic flywheel diagram: torque against its mean, the energy areas shaded and the
    largest fluctuation marked; motor rated (RMS) and peak torque when given. The torque
    panel is scaled to the torque: a motor line further than LIMIT_REACH of its range beyond
    it is not drawn but marked at the panel's edge, an arrow with its value."""
    fig, axes = figure(3.6, 2, 1, gap=0.4, margins=(0.72, 0.12, 0.42, 0.5),
                       gridspec_kw={"height_ratios": [3, 2]}, sharex=True)
    r = text_renderer(fig)
    draw_flywheel(axes[0, 0], cd, d, label=False, renderer=r)
    draw_energy(axes[1, 0], cd, r)
    return fig


def draw_flywheel(ax, cd, d, label: bool = True, renderer=None) -> None:
    """The driver's torque over one turn against its mean on ``ax``, in the display unit
    of moments (``d``): the energy areas shaded, the motor's rated (RMS) and peak torque
    when given; a motor line further than LIMIT_REACH of the torque's range beyond it is not
    drawn but marked at the edge, an arrow with its value. ``label``: the x axis labelled."""
    M = d.unit("moment")
    a, t, mean = cd.angles, d.value(cd.torque, "moment"), d.value(cd.mean, "moment")
    ax.plot(a, t, color=INK, lw=1.5, label="driver torque")
    ax.axhline(mean, color=BLUE, lw=1.0, ls="--", label=f"mean {d.num(cd.mean, 'moment')} {M}")
    ax.fill_between(a, t, mean, where=t >= mean, interpolate=True, color=ORANGE, alpha=0.35,
                    lw=0, label="above the mean (energy in)")
    ax.fill_between(a, t, mean, where=t < mean, interpolate=True, color=SKY, alpha=0.35,
                    lw=0, label="below the mean (energy out)")
    lo, hi = min(float(np.min(t)), mean), max(float(np.max(t)), mean)
    reach = LIMIT_REACH * ((hi - lo) or max(abs(hi), 1.0))
    drawn, off = [mean], {"hi": [], "lo": []}
    for value, name, style in ((cd.rated_torque, "motor rated (RMS)", "-."),
                               (cd.peak_torque, "motor peak", ":")):
        if value:
            v = d.value(value, "moment")
            levels = [v] + ([-v] if name == "motor peak" and np.min(t) < 0 else [])
            labelled = False
            for level in levels:
                if lo - reach <= level <= hi + reach:
                    ax.axhline(level, color=LIMIT_COLOR, lw=1.0, ls=style,
                               label=None if labelled else f"{name} {d.num(value, 'moment')} {M}")
                    labelled = True
                    drawn.append(level)
                elif level == v:                  # -peak far off the scale means nothing
                    off["hi" if v > hi else "lo"].append(f"{name} {d.num(value, 'moment')} {M}")
    ax.set_ylabel(f"torque [{M}]")
    legend_top(ax, 3)
    cycle_axis(ax, cd, label=label)
    r = renderer or text_renderer(ax.figure)
    for side, names in off.items():
        if names:
            _limit_arrow(ax, side, "\n".join(names), [(a, t)], drawn, r)


def draw_energy(ax, cd, renderer=None) -> None:
    """The energy the driver's torque gives above its mean, ∫(M − mean) dφ [J], over one
    turn on ``ax``, its largest fluctuation ΔE marked with an arrow and labelled where the
    label is free."""
    a, e = cd.angles, cd.energy
    i_hi, i_lo = int(np.argmax(e)), int(np.argmin(e))
    ax.plot(a, e, color=GREEN, lw=1.4)
    ax.plot([a[i_hi], a[i_lo]], [e[i_hi], e[i_lo]], "o", color=VERMILION, ms=4)
    ax.annotate("", xy=(a[i_lo], e[i_lo]), xytext=(a[i_lo], e[i_hi]),
                arrowprops={"arrowstyle": "<->", "color": VERMILION, "lw": 1.0})
    right = a[i_lo] > 250
    delta = ax.annotate(f"ΔE = {fmt(e[i_hi] - e[i_lo])} J", (a[i_lo], (e[i_hi] + e[i_lo]) / 2),
                        fontsize=7.5, xytext=(-6 if right else 6, 0),
                        textcoords="offset points", color=VERMILION, va="center",
                        ha="right" if right else "left")
    ax.axhline(0, color="0.3", lw=0.5)
    ax.set_ylabel("∫(M − mean) dφ [J]")
    cycle_axis(ax, cd)
    _place_delta_e(ax, delta, a, e, i_hi, i_lo, right, renderer or text_renderer(ax.figure),
                   cd.interpolated)


def _place_delta_e(ax, text, a, e, i_hi, i_lo, right: bool, renderer, shaded=()) -> None:
    """Put the ΔE label beside its arrow where neither the energy curve nor a line across
    the panel (the zero line, the horizontal grid lines, the grey bands of the ``shaded``
    angles) crosses it: halfway up the arrow on the side with more room first, then higher
    and lower, then the other side."""
    x, top, bottom = a[i_lo], e[i_hi], e[i_lo]
    sides = [(-6, "right"), (6, "left")] if right else [(6, "left"), (-6, "right")]
    cands = [((x, bottom + f * (top - bottom)), (dx, 0), ha, "center")
             for dx, ha in sides for f in (0.5, 0.3, 0.7, 0.15, 0.85, 0.4, 0.6)]
    dots = data_lines(ax, ([a[i_hi]], [e[i_hi]]), ([a[i_lo]], [e[i_lo]]))
    lo, hi = ax.get_ylim()
    levels = {0.0} | {float(y) for y in ax.get_yticks() if lo <= y <= hi}
    across = [hline(ax, y) for y in sorted(levels)]
    across += data_lines(ax, *(([s, s], [lo, hi]) for s in shaded))
    place(ax, text, cands, data_lines(ax, (a, e)) + dots + across, (), renderer)


def _limit_arrow(ax, side: str, label: str, curves, levels, renderer) -> None:
    """Mark a limit off the scale of ``ax`` (above it: ``side`` "hi", below: "lo") with an
    arrow at that edge and ``label`` beside it, where neither crosses ``curves`` [(x, y)] or
    the horizontal lines at ``levels``."""
    fig = ax.figure
    curve_px = data_lines(ax, *curves)
    lines = curve_px + [hline(ax, y) for y in levels]
    up = side == "hi"
    edge = 1.0 if up else 0.0
    trans = ax.get_xaxis_transform()                   # x in data, y in axes fraction
    text = ax.annotate(label, (0.0, edge), xycoords=trans, xytext=(4, 0),
                       textcoords="offset points", fontsize=7, color=LIMIT_COLOR,
                       annotation_clip=False, linespacing=1.1)
    w = max(text_size(renderer, part, 7)[0] for part in label.split("\n"))
    spots = []
    for x in np.linspace(*ax.get_xlim(), 17)[1:-1]:
        x0, y0 = ax.transData.transform((x, ax.get_ylim()[1 if up else 0]))
        near = np.concatenate([c[:, 1][np.abs(c[:, 0] - x0) <= w] for c in curve_px])
        near = near[np.isfinite(near)]
        room = (y0 - np.max(near) if up else np.min(near) - y0) if near.size else np.inf
        for length in (16.0, 12.0, 9.0):               # the arrow [pt]
            tail = y0 - pt_to_px(fig, length) if up else y0 + pt_to_px(fig, length)
            shaft = grow((x0, min(y0, tail), x0, max(y0, tail)), pt_to_px(fig, LINE_CLEAR))
            spots.append((crossings(shaft, lines), -room, -length, x))
    spots.sort()                                    # a clear shaft, the most room, longest
    cands = [((x, edge), (dx, length / 2 if up else -length / 2), ha, "center")
             for _, _, length, x in spots for dx, ha in ((4, "left"), (-4, "right"))]
    place(ax, text, cands, lines, (), renderer)
    x, length = text.xy[0], 2 * abs(text.xyann[1])
    ax.annotate("", xy=(x, edge), xycoords=trans, xytext=(0, -length if up else length),
                textcoords="offset points", annotation_clip=False,
                arrowprops={"arrowstyle": "-|>", "color": LIMIT_COLOR, "lw": 1.2,
                            "mutation_scale": 9, "shrinkA": 0, "shrinkB": 0})


def breakdown_figure(cd, d):
    """Torque by source, stacked: positive parts above zero, negative parts below."""
    sources = {k: v for k, v in cd.sources.items() if k not in cd.silent}
    n = len(sources) + 1
    ncol = min(5, n)
    fig, axes = figure(2.9, margins=(0.72, 0.12, 0.46, 0.22 + 0.17 * math.ceil(n / ncol)))
    draw_breakdown(axes[0, 0], cd, d, ncol)
    return fig


def draw_breakdown(ax, cd, d, ncol: int = 5) -> None:
    """The driver's torque over one turn by source on ``ax``, stacked (positive parts above
    zero, negative parts below; a source's colour is its place in ``cd.sources``), and the
    total, in the display unit of moments (``d``); the legend in ``ncol`` columns."""
    sources = {k: v for k, v in cd.sources.items() if k not in cd.silent}
    M = d.unit("moment")
    a = cd.angles
    up, down = np.zeros_like(a), np.zeros_like(a)
    shown = []                  # the legend's entries, given: a name may start with "_"
    for name, part in sources.items():
        color = PALETTE[list(cd.sources).index(name) % len(PALETTE)]
        part = d.value(part, "moment")
        pos, neg = np.maximum(part, 0), np.minimum(part, 0)
        shown.append(ax.fill_between(a, up, up + pos, color=color, alpha=0.6, lw=0,
                                     label=literal(name)))
        ax.fill_between(a, down, down + neg, color=color, alpha=0.6, lw=0)
        up, down = up + pos, down + neg
    shown += ax.plot(a, d.value(cd.torque, "moment"), color=INK, lw=1.3, label="total")
    ax.axhline(0, color="0.3", lw=0.6)
    ax.set_ylabel(f"torque [{M}]")
    legend_top(ax, ncol, handles=shown)
    cycle_axis(ax, cd)


def transmission_figure(cd, d):
    """The transmission angle of each group over one turn (:func:`draw_transmission`)."""
    n = len(cd.transmission) + (cd.transmission_limit is not None)
    fig, axes = figure(2.5, margins=(0.72, 0.12, 0.46, 0.22 + 0.17 * math.ceil(n / 3)))
    draw_transmission(axes[0, 0], cd)
    return fig


def draw_transmission(ax, cd, d=None) -> None:
    """Each group's transmission angle [deg] over one turn on ``ax``, and the design's
    limit when it has one (``d``, the display units, is not needed: angles are degrees)."""
    for k, (label, ta) in enumerate(cd.transmission.items()):
        ax.plot(cd.angles, ta, color=PALETTE[k % len(PALETTE)], lw=1.4,
                ls=STYLES[k % 4], label=literal(f"group {label}"))
    if cd.transmission_limit is not None:
        ax.axhline(cd.transmission_limit, color=VERMILION, lw=1.0, ls="--",
                   label=f"limit {cd.transmission_limit:g}°")
    ax.set_ylim(0, 90)
    ax.set_yticks(np.arange(0, 91, 15))
    ax.set_ylabel("transmission angle [deg]")
    legend_top(ax, 3)
    cycle_axis(ax, cd)


def balance_figure(cd, d):
    """Polar trace of the inertial shaking force without and with the counterweight."""
    w = WIDTH * 0.55
    margins = (0.62, 0.12, 0.42, 0.45)
    fig, axes = figure(w, margins=margins, width=w)
    draw_balance(axes[0, 0], cd, d)
    fit_y_labels(fig, axes, lambda left, _: layout(fig, 1, 1, 0.55, 0.75,
                                                     (left, *margins[1:])), margins[0], 0.75)
    return fig


def draw_balance(ax, cd, d) -> None:
    """The inertial shaking force over one turn as a polar trace on ``ax`` (x against y, in
    the display unit of forces, ``d``), without and with the counterweight."""
    F = d.unit("force")
    for xy, name, color, style in ((cd.inertial, "without counterweight", BLUE, "-"),
                                   (cd.balanced, "with counterweight", VERMILION, "--")):
        xy = d.value(np.asarray(xy), "force")
        closed = np.vstack([xy, xy[:1]])
        ax.plot(closed[:, 0], closed[:, 1], color=color, lw=1.3, ls=style, label=name)
    ax.plot([0], [0], "+", color="k", ms=8)
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel(f"x [{F}]")
    ax.set_ylabel(f"y [{F}]")
    legend_top(ax, 1)
