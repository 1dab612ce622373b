"""Plots over the sweep: the driver's effort, the joints' reactions (and the couples of T
joints), the shaking force and moment. Values in the report's display units (``d``, a
Display); ``sw`` is a report's SweepData."""
from __future__ import annotations

import math

import numpy as np

from .mpl import BLUE, INK, ORANGE, PURPLE, STYLES, VERMILION, figure, legend_top, literal
from .quantities import with_gaps
from .sweep_axes import crank_axis, label_reference_lines, scale_to_trusted

def torque_figure(sw, d):
    fig, axes = figure(2.9, margins=(0.72, 0.12, 0.46, 0.5))
    draw_torque(axes[0, 0], sw, d)
    return fig


def draw_torque(ax, sw, d) -> None:
    """The driver's effort over the sweep on ``ax``: the reference method's, the power
    balance's, the mean and the peak; ``sw`` the report's SweepData, ``d`` its Display."""
    kind = sw.effort
    u = d.unit(kind)
    a, t = with_gaps(sw.angles, d.value(sw.torque, kind))
    ax.plot(a, t, color=INK, lw=1.6, label=f"{sw.effort_label} ({sw.method_title})")
    series = [d.value(sw.torque, kind)]
    curves = [(a, t)]
    if sw.torque_check is not None:
        _, tc = with_gaps(sw.angles, d.value(sw.torque_check, kind))
        ax.plot(a, tc, color=ORANGE, lw=1.0, ls=(0, (4, 3)), label="power balance (check)")
        curves.append((a, tc))
    levels = [0.0]
    st = sw.stats
    if st is not None:
        mean = d.value(st.mean, kind)
        ax.axhline(mean, color=BLUE, lw=1.0, ls="--",
                   label=f"mean {d.num(st.mean, kind)} {u} (RMS {d.num(st.rms, kind)} {u})")
        pk = d.value(st.peak.value, kind)
        at = f"{st.peak.angle:g}°" if sw.xrange is None else f"{st.peak.angle:g}"
        ax.plot([st.peak.angle], [pk], "o", color=VERMILION, ms=5,
                label=f"peak {d.num(st.peak.value, kind)} {u} at {at}")
        levels.append(mean)
        curves.append(([st.peak.angle], [pk]))
    for r in sw.ref_angles:
        ax.axvline(r, color="0.4", lw=0.7, ls=":")
    ax.axhline(0, color="0.3", lw=0.6)
    crank_axis(ax, sw)
    scale_to_trusted(ax, sw, series, u)
    label_reference_lines(ax, sw, curves, levels)
    ax.set_ylabel(f"{'force' if kind == 'force' else 'torque'} [{u}]")
    legend_top(ax, 2)


def reactions_figure(sw, d):
    """Every joint's |F| on one axis (colour and line style per joint); the couples of T
    joints on a second axis below when any is not zero."""
    couples = slider_couples(sw)
    rows = 2 if couples else 1
    ncol = min(len(sw.joints), 5)
    top = 0.22 + 0.17 * math.ceil(len(sw.joints) / ncol)
    fig, axes = figure(3.0 + 1.5 * (rows - 1), rows, 1, gap=0.85,
                       margins=(0.72, 0.12, 0.46, top),
                       gridspec_kw={"height_ratios": [2, 1]} if rows == 2 else None)
    draw_reactions(axes[0, 0], sw, d, ncol, label=rows == 1)
    if rows == 2:
        draw_couples(axes[1, 0], sw, d, couples)
    return fig


def slider_couples(sw) -> list:
    """The joints of ``sw`` whose couple (a T joint's) is not zero at every angle."""
    return [js for js in sw.joints if js.moment is not None
            and np.max(np.abs(js.moment), initial=0.0) > 1e-9 * max(
                1.0, float(np.max(np.abs(sw.torque), initial=0.0)))]


def draw_couples(ax, sw, d, couples=None) -> None:
    """The couples of the T joints ``couples`` (default: every one that is not zero,
    :func:`slider_couples`) over the sweep on ``ax``, in the display unit of moments."""
    couples = slider_couples(sw) if couples is None else couples
    M = d.unit("moment")
    mseries, lines = [], []
    for js in couples:
        m = d.value(js.moment, "moment")
        mseries.append(m)
        a, mm = with_gaps(sw.angles, m)
        lines += ax.plot(a, mm, color=js.color, lw=1.2,
                         label=literal(f"{js.name}: couple M{js.symbol[1:]}"))
    ax.axhline(0, color="0.3", lw=0.5)
    crank_axis(ax, sw)
    scale_to_trusted(ax, sw, mseries, M, names=[js.name for js in couples])
    ax.set_ylabel(f"slider couple [{M}]")
    legend_top(ax, min(len(couples), 4), handles=lines)


def draw_reactions(ax, sw, d, ncol: int = 5, label: bool = True) -> None:
    """Every joint's reaction magnitude |F| over the sweep on ``ax`` (colour and line style
    per joint, legend in ``ncol`` columns); ``label``: the x axis labelled."""
    F = d.unit("force")
    series, lines = [], []
    for i, js in enumerate(sw.joints):
        f = d.value(js.f, "force")
        series.append(f)
        a, ff = with_gaps(sw.angles, f)
        lines += ax.plot(a, ff, color=js.color, lw=1.4, ls=STYLES[i % 4],
                         label=literal(f"{js.name} ({js.symbol})"))
    crank_axis(ax, sw, label=label)
    scale_to_trusted(ax, sw, series, F, names=[js.name for js in sw.joints])
    ax.set_ylabel(f"|F| [{F}]")
    legend_top(ax, min(len(sw.joints), ncol), handles=lines)


def shaking_figure(sw, d):
    """The shaking force (magnitude and components) and the shaking moment over the sweep,
    one panel each; a part that is 0 at every angle (``sw.shaking_zero``: round-off) is left
    out, and the other panel fills the figure alone."""
    parts = [k for k in ("force", "moment") if k not in sw.shaking_zero] or ["force", "moment"]
    if len(parts) == 2:
        fig, axes = figure(4.2, 2, 1, gap=0.75, margins=(0.72, 0.12, 0.46, 0.3))
    else:
        fig, axes = figure(2.6, margins=(0.72, 0.12, 0.46, 0.3))
    panels = dict(zip(parts, axes[:, 0]))
    if "force" in panels:
        draw_shaking_force(panels["force"], sw, d, label="moment" not in panels)
    if "moment" in panels:
        draw_shaking_moment(panels["moment"], sw, d)
    return fig


def draw_shaking_force(ax, sw, d, label: bool = True) -> None:
    """The shaking force on the frame over the sweep on ``ax``: its magnitude and its x and
    y components, in the display unit of forces; ``label``: the x axis labelled."""
    sh = sw.shaking
    F = d.unit("force")
    fx, fy, f = (d.value(v, "force") for v in (sh.fx, sh.fy, sh.f))
    a, gfx, gfy, gf = with_gaps(sw.angles, fx, fy, f)
    ax.plot(a, gf, color=INK, lw=1.6, label="|F| shaking force")
    ax.plot(a, gfx, color=BLUE, lw=1.0, ls="--", label="x component")
    ax.plot(a, gfy, color=ORANGE, lw=1.0, ls=":", label="y component")
    ax.axhline(0, color="0.3", lw=0.5)
    ax.set_ylabel(f"force on frame [{F}]")
    legend_top(ax, 3)
    crank_axis(ax, sw, label=label)
    scale_to_trusted(ax, sw, [fx, fy, f], F, names=["x", "y", "|F|"])


def draw_shaking_moment(ax, sw, d) -> None:
    """The shaking moment on the frame about the driver's pivot over the sweep on ``ax``, in
    the display unit of moments."""
    M = d.unit("moment")
    m = d.value(sw.shaking.m, "moment")
    a, gm = with_gaps(sw.angles, m)
    ax.plot(a, gm, color=PURPLE, lw=1.4, label="shaking moment about the driver pivot")
    ax.axhline(0, color="0.3", lw=0.5)
    ax.set_ylabel(f"moment on frame [{M}]")
    legend_top(ax, 1)
    crank_axis(ax, sw)
    scale_to_trusted(ax, sw, [m], M)
