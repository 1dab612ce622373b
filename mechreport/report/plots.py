"""Sweep plots of a report model: driver torque, joint reactions, polar bearing diagrams,
shaking force and moment. Each figure is written as PNG (Markdown) and SVG (Typst/PDF).

matplotlib is imported lazily (Agg backend) so that numeric commands never load it."""
from __future__ import annotations

import io
import math
from pathlib import Path

import numpy as np

from .files import atomic_write_bytes
from .quantities import with_gaps

WIDTH = 6.5          # [in], the text width of the PDF
PNG_DPI = 120


def pyplot():
    """matplotlib.pyplot on the Agg backend, with the report's style."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    plt.rcParams.update({"font.size": 8.5, "axes.titlesize": 9, "axes.labelsize": 8.5,
                         "legend.fontsize": 7.5, "xtick.labelsize": 7.5,
                         "ytick.labelsize": 7.5, "axes.grid": True, "grid.alpha": 0.3,
                         "svg.fonttype": "path", "svg.hashsalt": "mechreport",
                         "axes.spines.top": False, "axes.spines.right": False})
    return plt


def save(fig, outdir: Path, stem: str) -> list[Path]:
    """Write ``fig`` as ``<stem>.png`` and ``<stem>.svg`` in ``outdir`` atomically; close it."""
    plt = pyplot()
    out = []
    for ext, kw in (("png", {"dpi": PNG_DPI}), ("svg", {"metadata": {"Date": None}})):
        buf = io.BytesIO()
        fig.savefig(buf, format=ext, bbox_inches="tight", pad_inches=0.04, **kw)
        out.append(atomic_write_bytes(Path(outdir) / f"{stem}.{ext}", buf.getvalue()))
    plt.close(fig)
    return out


def crank_axis(ax, sw, label: bool = True) -> None:
    """0-360 deg, ticks every 45 deg, left-out angles shaded."""
    ax.set_xlim(0, 360)
    ax.set_xticks(np.arange(0, 361, 45))
    if label:
        ax.set_xlabel("crank angle φ [deg]")
    for a in sw.flagged:
        ax.axvspan(a - 1.5, a + 1.5, color="0.5", alpha=0.25, lw=0)


def torque_figure(sw):
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(WIDTH, 2.9))
    a, t = with_gaps(sw.angles, sw.torque)
    ax.plot(a, t, color="#222222", lw=1.6, label=f"driver torque M ({sw.method_title})")
    if sw.torque_check is not None:
        _, tc = with_gaps(sw.angles, sw.torque_check)
        ax.plot(a, tc, color="#d62728", lw=0.9, ls=(0, (4, 3)),
                label="power balance (check)")
    st = sw.stats
    if st is not None:
        ax.axhline(st.mean, color="#1f77b4", lw=1.0, ls="--",
                   label=f"mean {st.mean:.4g} N·m (RMS {st.rms:.4g})")
        ax.plot([st.peak.angle], [st.peak.value], "o", color="#d62728", ms=5,
                label=f"peak {st.peak.value:.4g} N·m at {st.peak.angle:g}°")
    for r in sw.ref_angles:
        ax.axvline(r, color="0.4", lw=0.7, ls=":")
    ax.axhline(0, color="0.3", lw=0.6)
    crank_axis(ax, sw)
    ax.set_ylabel("torque [N·m]")
    ax.legend(loc="lower center", bbox_to_anchor=(0.5, 1.0), ncol=2, frameon=False)
    return fig


def reactions_figure(sw):
    plt = pyplot()
    n = max(len(sw.joints), 1)
    cols = 1 if n == 1 else 2
    rows = math.ceil(n / cols)
    fig, axes = plt.subplots(rows, cols, figsize=(WIDTH, 0.5 + 1.85 * rows), sharex=True,
                             squeeze=False)
    for ax, js in zip(axes.flat, sw.joints):
        a, f, fx, fy = with_gaps(sw.angles, js.f, js.fx, js.fy)
        ax.plot(a, f, color=js.color, lw=1.8)
        ax.plot(a, fx, color=js.color, lw=1.0, ls="--")
        ax.plot(a, fy, color=js.color, lw=1.0, ls=":")
        ax.axhline(0, color="0.3", lw=0.5)
        ax.set_title(f"joint {js.name} ({js.symbol})", loc="left", color=js.color,
                     fontweight="bold")
        ax.set_ylabel("force [N]")
        if js.moment is not None and np.max(np.abs(js.moment), initial=0.0) > 1e-9:
            _, m = with_gaps(sw.angles, js.moment)
            ax2 = ax.twinx()
            ax2.plot(a, m, color="0.45", lw=0.9, ls="-.")
            ax2.set_ylabel("couple [N·m]", color="0.35")
            ax2.grid(False)
            ax2.spines["right"].set_visible(True)
        crank_axis(ax, sw, label=False)
    for ax in axes.flat[len(sw.joints):]:
        ax.set_visible(False)
    for ax in axes[-1]:
        ax.set_xlabel("crank angle φ [deg]")
        ax.xaxis.set_tick_params(labelbottom=True)
    if len(sw.joints) % 2 == 1 and cols == 2:
        axes[-2, 1].set_xlabel("crank angle φ [deg]")
        axes[-2, 1].xaxis.set_tick_params(labelbottom=True)
    from matplotlib.lines import Line2D
    handles = [Line2D([], [], color="k", lw=1.8, label="magnitude |F|"),
               Line2D([], [], color="k", lw=1.0, ls="--", label="x component"),
               Line2D([], [], color="k", lw=1.0, ls=":", label="y component")]
    if any(js.moment is not None for js in sw.joints):
        handles.append(Line2D([], [], color="0.45", lw=0.9, ls="-.",
                              label="slider couple M (right axis)"))
    fig.tight_layout(h_pad=0.6, w_pad=1.0, rect=(0, 0, 1, 1 - 0.3 / fig.get_figheight()))
    fig.legend(handles=handles, loc="upper center", ncol=len(handles), frameon=False,
               bbox_to_anchor=(0.5, 1.0))
    return fig


def polar_figure(sw):
    plt = pyplot()
    n = len(sw.polar)
    cols = min(n, 3)
    rows = math.ceil(n / cols)
    size = WIDTH / cols
    fig, axes = plt.subplots(rows, cols, figsize=(WIDTH, size * rows + 0.2), squeeze=False)
    ref_idx = [int(np.argmin(np.abs(sw.angles - r))) for r in sw.ref_angles
               if len(sw.angles) and np.min(np.abs(sw.angles - r)) < 1e-9]
    for ax, ps in zip(axes.flat, sw.polar):
        _, x, y = with_gaps(sw.angles, ps.x, ps.y)
        if len(sw.flagged) == 0 and len(ps.x):
            x, y = np.append(x, ps.x[0]), np.append(y, ps.y[0])   # close the turn
        ax.plot(x, y, color=ps.color, lw=1.4)
        ax.plot([0], [0], "+", color="k", ms=8)
        if ps.equivalent:
            t = np.linspace(0, 2 * np.pi, 181)
            ax.plot(ps.equivalent * np.cos(t), ps.equivalent * np.sin(t), color="0.35",
                    lw=0.8, ls=(0, (3, 2)))
            ax.annotate(f"equivalent {ps.equivalent:.4g} N", (0, -ps.equivalent),
                        fontsize=6.2, color="0.3", xytext=(0, -8), textcoords="offset points",
                        ha="center")
        for k in ref_idx:
            ax.plot([0, ps.x[k]], [0, ps.y[k]], color=ps.color, lw=0.7, alpha=0.7)
            ax.plot([ps.x[k]], [ps.y[k]], "o", color=ps.color, ms=3.5)
            ax.annotate(f"{sw.angles[k]:g}°", (ps.x[k], ps.y[k]), fontsize=6.5,
                        xytext=(3, 3), textcoords="offset points")
        if len(ps.x):
            ax.annotate("0°", (ps.x[0], ps.y[0]), fontsize=6.5, xytext=(-8, -9),
                        textcoords="offset points", color="0.3")
        ax.set_aspect("equal", adjustable="datalim")
        ax.set_title(f"{ps.name} ({ps.symbol})", loc="left")
        frame = "global frame" if ps.carrier == "ground" else f"frame of {ps.carrier}"
        ax.set_xlabel(f"x [N], {frame}", fontsize=7)
        ax.set_ylabel("y [N]", fontsize=7)
        ax.tick_params(labelsize=6.5)
        ax.axhline(0, color="0.6", lw=0.5)
        ax.axvline(0, color="0.6", lw=0.5)
    for ax in axes.flat[n:]:
        ax.set_visible(False)
    fig.tight_layout(w_pad=0.8, h_pad=0.8)
    return fig


def shaking_figure(sw):
    plt = pyplot()
    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(WIDTH, 4.2), sharex=True)
    sh = sw.shaking
    a, fx, fy, f, m = with_gaps(sw.angles, sh.fx, sh.fy, sh.f, sh.m)
    ax1.plot(a, f, color="#222222", lw=1.6, label="|F| shaking force")
    ax1.plot(a, fx, color="#1f77b4", lw=1.0, ls="--", label="x component")
    ax1.plot(a, fy, color="#ff7f0e", lw=1.0, ls=":", label="y component")
    ax1.axhline(0, color="0.3", lw=0.5)
    ax1.set_ylabel("force on frame [N]")
    ax1.legend(loc="lower center", bbox_to_anchor=(0.5, 1.0), ncol=3, frameon=False)
    crank_axis(ax1, sw, label=False)
    ax1.xaxis.set_tick_params(labelbottom=True)
    ax2.plot(a, m, color="#9467bd", lw=1.4, label="shaking moment about the driver pivot")
    ax2.axhline(0, color="0.3", lw=0.5)
    ax2.set_ylabel("moment on frame [N·m]")
    ax2.legend(loc="lower center", bbox_to_anchor=(0.5, 1.0), frameon=False)
    crank_axis(ax2, sw)
    fig.tight_layout(h_pad=0.8)
    return fig


def _cycle_axis(ax, cd, label: bool = True) -> None:
    """0-360 deg over one turn, interpolated (left-out) angles marked."""
    ax.set_xlim(0, 360)
    ax.set_xticks(np.arange(0, 361, 45))
    if label:
        ax.set_xlabel("crank angle φ [deg]")
    for a in cd.interpolated:
        ax.axvspan(a - 1.5, a + 1.5, color="0.5", alpha=0.25, lw=0)


def flywheel_figure(cd):
    """The classic flywheel diagram: torque against its mean, the energy areas shaded and the
    largest fluctuation marked; motor rated (RMS) and peak torque when given."""
    plt = pyplot()
    fig, (ax, ax2) = plt.subplots(2, 1, figsize=(WIDTH, 4.4), sharex=True,
                                  gridspec_kw={"height_ratios": [3, 2]})
    a, t, mean = cd.angles, cd.torque, cd.mean
    ax.plot(a, t, color="#222222", lw=1.5, label="driver torque")
    ax.axhline(mean, color="#0072B2", lw=1.0, ls="--", label=f"mean {mean:.4g} N·m")
    ax.fill_between(a, t, mean, where=t >= mean, interpolate=True, color="#E69F00", alpha=0.35,
                    lw=0, label="above the mean (energy in)")
    ax.fill_between(a, t, mean, where=t < mean, interpolate=True, color="#56B4E9", alpha=0.35,
                    lw=0, label="below the mean (energy out)")
    for value, name, style in ((cd.rated_torque, "motor rated (RMS)", "-."),
                               (cd.peak_torque, "motor peak", ":")):
        if value:
            ax.axhline(value, color="#CC79A7", lw=1.0, ls=style, label=f"{name} {value:.4g} N·m")
            if name == "motor peak" and np.min(t) < 0:
                ax.axhline(-value, color="#CC79A7", lw=1.0, ls=style)
    ax.set_ylabel("torque [N·m]")
    ax.legend(loc="lower center", bbox_to_anchor=(0.5, 1.0), ncol=3, frameon=False)
    _cycle_axis(ax, cd, label=False)
    e = cd.energy
    hi, lo = int(np.argmax(e)), int(np.argmin(e))
    ax2.plot(a, e, color="#009E73", lw=1.4)
    ax2.plot([a[hi], a[lo]], [e[hi], e[lo]], "o", color="#D55E00", ms=4)
    ax2.annotate("", xy=(a[lo], e[lo]), xytext=(a[lo], e[hi]),
                 arrowprops={"arrowstyle": "<->", "color": "#D55E00", "lw": 1.0})
    ax2.annotate(f"ΔE = {e[hi] - e[lo]:.4g} J", (a[lo], (e[hi] + e[lo]) / 2), fontsize=7.5,
                 xytext=(6, 0), textcoords="offset points", color="#D55E00", va="center")
    ax2.axhline(0, color="0.3", lw=0.5)
    ax2.set_ylabel("∫(M − mean) dφ [J]")
    _cycle_axis(ax2, cd)
    fig.tight_layout(h_pad=0.6)
    return fig


SOURCE_COLORS = ["#0072B2", "#E69F00", "#009E73", "#CC79A7", "#56B4E9", "#D55E00", "#F0E442",
                 "#000000"]


def breakdown_figure(cd):
    """Torque by source, stacked: positive parts above zero, negative parts below."""
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(WIDTH, 2.9))
    a = cd.angles
    up, down = np.zeros_like(a), np.zeros_like(a)
    for k, (name, part) in enumerate(cd.sources.items()):
        color = SOURCE_COLORS[k % len(SOURCE_COLORS)]
        pos, neg = np.maximum(part, 0), np.minimum(part, 0)
        ax.fill_between(a, up, up + pos, color=color, alpha=0.55, lw=0, label=name)
        ax.fill_between(a, down, down + neg, color=color, alpha=0.55, lw=0)
        up, down = up + pos, down + neg
    ax.plot(a, cd.torque, color="#222222", lw=1.3, label="total")
    ax.axhline(0, color="0.3", lw=0.6)
    ax.set_ylabel("torque [N·m]")
    ax.legend(loc="lower center", bbox_to_anchor=(0.5, 1.0), ncol=min(5, len(cd.sources) + 1),
              frameon=False)
    _cycle_axis(ax, cd)
    return fig


def transmission_figure(cd):
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(WIDTH, 2.5))
    for k, (label, ta) in enumerate(cd.transmission.items()):
        ax.plot(cd.angles, ta, color=SOURCE_COLORS[k % len(SOURCE_COLORS)], lw=1.4,
                label=f"group {label}")
    if cd.transmission_limit is not None:
        ax.axhline(cd.transmission_limit, color="#D55E00", lw=1.0, ls="--",
                   label=f"limit {cd.transmission_limit:g}°")
    ax.set_ylim(0, 90)
    ax.set_yticks(np.arange(0, 91, 15))
    ax.set_ylabel("transmission angle [deg]")
    ax.legend(loc="lower center", bbox_to_anchor=(0.5, 1.0), ncol=3, frameon=False)
    _cycle_axis(ax, cd)
    return fig


def balance_figure(cd):
    """Polar trace of the inertial shaking force without and with the counterweight."""
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(WIDTH * 0.55, WIDTH * 0.55))
    for xy, name, color, style in ((cd.inertial, "without counterweight", "#0072B2", "-"),
                                   (cd.balanced, "with counterweight", "#D55E00", "--")):
        closed = np.vstack([xy, xy[:1]])
        ax.plot(closed[:, 0], closed[:, 1], color=color, lw=1.3, ls=style, label=name)
    ax.plot([0], [0], "+", color="k", ms=8)
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("x [N]")
    ax.set_ylabel("y [N]")
    ax.legend(loc="lower center", bbox_to_anchor=(0.5, 1.0), ncol=1, frameon=False)
    return fig


def write_plots(model, outdir: Path) -> list[Path]:
    """Every sweep figure of ``model`` into ``outdir`` (PNG and SVG)."""
    sw, figs = model.sweep, model.figures
    out = []
    cd = model.design.data
    if cd is not None:
        for key, make in (("flywheel", flywheel_figure), ("breakdown", breakdown_figure),
                          ("transmission", transmission_figure), ("balance", balance_figure)):
            if key in figs:
                out += save(make(cd), outdir, figs[key].stem)
    if len(sw.angles) == 0:
        return out
    makers = {"torque": torque_figure, "reactions": reactions_figure,
              "polar": polar_figure, "shaking": shaking_figure}
    for key, make in makers.items():
        if key in figs and (key != "reactions" or sw.joints):
            out += save(make(sw), outdir, figs[key].stem)
    return out
