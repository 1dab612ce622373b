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


def write_plots(model, outdir: Path) -> list[Path]:
    """Every sweep figure of ``model`` into ``outdir`` (PNG and SVG)."""
    sw, figs = model.sweep, model.figures
    out = []
    if len(sw.angles) == 0:
        return out
    makers = {"torque": torque_figure, "reactions": reactions_figure,
              "polar": polar_figure, "shaking": shaking_figure}
    for key, make in makers.items():
        if key in figs and (key != "reactions" or sw.joints):
            out += save(make(sw), outdir, figs[key].stem)
    return out
