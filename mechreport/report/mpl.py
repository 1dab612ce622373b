"""The matplotlib infrastructure every figure of a report uses: the style, the palette, a
figure with fixed margins, saving it as an SVG, literal text, and measuring text before a
figure is drawn.

Text stays text in the SVG (``svg.fonttype: none``, DejaVu Sans with sans-serif fallbacks): a
browser shows it in its sans-serif, and Typst typesets it in DejaVu Sans itself, from
matplotlib's own font files (see :func:`mechreport.report.pdf.compile_typst`); drawing glyphs
as paths cost a fifth of the plotting time. Names from the spec (links, joints, points,
loads, study keys and quantities) are drawn literally: every string that carries one goes
through :func:`literal`, so that matplotlib never reads it as mathtext.

matplotlib is imported lazily so that numeric commands never load it; figures are matplotlib
Figures outside pyplot, made and saved in the report's :func:`style` (rc parameters set for
the block only). Layouts are fixed (no tight bounding boxes: each figure is drawn once, when
saved); text that could run into something is measured first (:func:`text_renderer`,
:func:`text_size`) and placed where it is free (:mod:`mechreport.report.labels`)."""
from __future__ import annotations

import functools
import io
from pathlib import Path

from .files import atomic_write_bytes

WIDTH = 6.5          # [in], the text width of the PDF

# ----------------------------------------------------------------------------- palette
#
# The report's one palette: every figure (plots, drawings, sheets, the animation) takes its
# colours from here.

INK = "#222222"      # text-coloured lines: a total, a mark
GREY = "0.55"        # guides: a mean, a threshold
#: one colour per series (a joint, a source of torque, a group, a member), in order:
#: Okabe & Ito's colour-blind-safe set first, in an order where neighbours differ in
#: lightness as well as hue, then Tol's (black is kept for loads, wine for the driver
#: torque: :data:`MOMENT_COLOR`)
PALETTE = ["#0072B2", "#E69F00", "#009E73", "#CC79A7", "#56B4E9", "#D55E00", "#999933",
           "#44AA99", "#332288", "#117733"]
BLUE, ORANGE, GREEN, PURPLE, SKY, VERMILION = PALETTE[:6]
#: Okabe & Ito's set alone, in the palette's order (matplotlib's colour cycle in the
#: report's style, and the study's figures): the palette's first six, then yellow and black
OKABE_ITO = PALETTE[:6] + ["#F0E442", "#000000"]
MOMENT_COLOR = "#882255"   # the driver's torque and push (Tol's wine)
CUT_COLOR = "#b00000"      # the mark on an arrow cut to the view's longest (off scale)
LOAD_COLOR = "#000000"     # loads on a drawing (known forces and couples)
#: the solution sheets' free-body diagrams: the unknowns (reactions and the driver, drawn in
#: their positive direction), the known forces (weights and loads) and d'Alembert's inertia
#: force and couple (dashed)
UNKNOWN_COLOR, KNOWN_COLOR, INERTIA_COLOR = "#0b4f8a", INK, "#c0392b"
#: the links' fills on a drawing, by link number (pale tints)
LINK_FILL = ["#dbe6f4", "#f6e3cf", "#dcefdc", "#f3dada", "#e7def0", "#ece3dc", "#f7e1ef"]

#: line styles that tell series of one colour apart (a joint's reactions, a group's angle)
STYLES = ["-", (0, (5, 2)), (0, (1.5, 1.5)), (0, (6, 2, 1.5, 2)), "-", (0, (5, 2))]
#: margins [in]: left (tick labels and axis label), right, bottom (ticks and label), top
MARGINS = (0.72, 0.12, 0.46, 0.36)


def style():
    """The report's figure style for a block: matplotlib's rc parameters set for it and
    restored after, so that a caller's own settings (a notebook's) are left alone."""
    import matplotlib
    return matplotlib.rc_context({
        "font.size": 8.5, "axes.titlesize": 9, "axes.labelsize": 8.5,
        "legend.fontsize": 7.5, "xtick.labelsize": 7.5, "ytick.labelsize": 7.5,
        "axes.grid": True, "grid.alpha": 0.3, "svg.fonttype": "none",
        "svg.hashsalt": "mechreport", "axes.spines.top": False, "axes.spines.right": False,
        "axes.formatter.useoffset": False, "axes.unicode_minus": True,
        "axes.prop_cycle": matplotlib.cycler(color=OKABE_ITO), "hatch.linewidth": 0.5,
        "hatch.color": "0.6"})


def literal(text) -> str:
    r"""``text`` (user text: a name from the spec, or a label that contains one) escaped so
    that matplotlib draws it as it is, wherever it goes (a Text, title, axis label,
    annotation or legend entry): every ``$`` becomes ``\$``.

    matplotlib reads a string with an even, non-zero number of unescaped ``$`` as mathtext:
    ``$x^2$`` would be drawn as maths, and ``a$b_{$`` raises a ParseSyntaxException when the
    figure is drawn. A string with no unescaped ``$`` is drawn as written, except that each
    ``\$`` is drawn as ``$``; so escaping every ``$`` is exact (a name's own ``\$`` becomes
    ``\\$``, drawn ``\$``), and text without a ``$`` (backslashes, braces, ``_``, ``%``
    included) is passed unchanged. Not for mechreport's own mathtext (``$F_{21x}$`` on the
    solution sheets), which has no user text in it."""
    return str(text).replace("$", "\\$")


def styled(func):
    """``func`` run in the report's :func:`style` (its figures are made and saved in it)."""
    @functools.wraps(func)
    def run(*args, **kwargs):
        with style():
            return func(*args, **kwargs)
    return run


def save(fig, outdir: Path, stem: str) -> list[Path]:
    """Write ``fig`` as ``<stem>.svg`` in ``outdir`` atomically (reproducibly: no date, fixed
    ids); in the report's :func:`style`."""
    buf = io.BytesIO()
    with style():
        fig.savefig(buf, format="svg", metadata={"Date": None, "Creator": "mechreport"})
    return [atomic_write_bytes(Path(outdir) / f"{stem}.svg", buf.getvalue())]


def figure(height: float, rows: int = 1, cols: int = 1, gap: float = 0.55,
           wgap: float = 0.75, margins=MARGINS, width: float = WIDTH, **kw):
    """A figure ``width`` x ``height`` [in] of ``rows`` x ``cols`` axes with fixed
    ``margins`` [in] (see :func:`layout`); a matplotlib Figure outside pyplot: no backend,
    no global figure list. Returns (figure, 2-D array of axes)."""
    from matplotlib.figure import Figure
    fig = Figure(figsize=(width, height))          # no pyplot bookkeeping: closed by GC
    axes = fig.subplots(rows, cols, squeeze=False, **kw)
    layout(fig, rows, cols, gap, wgap, margins)
    return fig, axes


def layout(fig, rows: int, cols: int, gap: float, wgap: float, margins) -> None:
    """Place the axes grid of ``fig``: ``margins`` (left, right, bottom, top) and the gaps
    between rows (``gap``) and columns (``wgap``) [in]."""
    width, height = fig.get_size_inches()
    left, right, bottom, top = margins
    fig.subplots_adjust(left=left / width, right=1 - right / width, bottom=bottom / height,
                        top=1 - top / height, hspace=gap / max((height - bottom - top) / rows
                                                               - gap, 0.3),
                        wspace=wgap / max((width - left - right) / cols - wgap, 0.3))


def legend_top(ax, ncol: int, **kw) -> None:
    """``ax``'s legend above it, in ``ncol`` columns, without a frame (keyword arguments go
    to ``ax.legend``: the handles and labels, where given)."""
    ax.legend(loc="lower left", bbox_to_anchor=(0.0, 1.01), ncol=ncol, frameon=False,
              borderaxespad=0.0, handlelength=2.2, columnspacing=1.4, **kw)


# ------------------------------------------------------------------------ measuring text

def text_renderer(fig):
    """A renderer to measure the text of ``fig`` with before it is drawn (Agg's text
    metrics: text layout only, nothing is drawn)."""
    from matplotlib.backends.backend_agg import RendererAgg
    w, h = fig.bbox.size
    return RendererAgg(max(int(w), 1), max(int(h), 1), fig.dpi)


def pt_to_px(fig, pt: float) -> float:
    """``pt`` points in display units of ``fig``."""
    return pt * fig.dpi / 72.0


def text_size(rend, text: str, size: float, weight: str = "normal"
              ) -> tuple[float, float, float]:
    """(width, height, descent) of ``text`` (no mathtext) at ``size`` points, in display
    units of the renderer ``rend``."""
    from matplotlib.font_manager import FontProperties
    return rend.get_text_width_height_descent(text, FontProperties(size=size, weight=weight),
                                              ismath=False)


def fit_y_labels(fig, axes, relayout, left: float, wgap: float) -> None:
    """Widen the left margin (``left`` [in]) or the gap between columns (``wgap`` [in]) of
    ``fig`` until the y tick labels and label of every visible axes in ``axes`` (2-D, rows x
    columns) fit between the figure's edge or the axes to their left; ``relayout(left,
    wgap)`` places the grid again. Nothing changes where they fit (large numbers in N, or
    small ones in kN, are what need the room)."""
    r = text_renderer(fig)
    pad = pt_to_px(fig, 2.0)
    for _ in range(3):
        need_left = need_gap = 0.0
        for row in axes:
            prev = None
            for ax in row:
                if not ax.get_visible():
                    continue
                ax.apply_aspect()
                box = ax.yaxis.get_tightbbox(r)
                if box is None:                 # nothing drawn left of this axes
                    continue
                x0 = box.x0
                room = x0 - (prev.get_position().x1 * fig.bbox.width if prev is not None
                             else 0.0)
                short = max(pad - room, 0.0) / fig.dpi
                if prev is None:
                    need_left = max(need_left, short)
                else:
                    need_gap = max(need_gap, short)
                prev = ax
        if need_left <= 0 and need_gap <= 0:
            return
        left, wgap = left + need_left, wgap + need_gap
        relayout(left, wgap)
