"""The report's plots, one SVG file each, shown by both the PDF and the Markdown report:
:func:`write_plots` writes every sweep and cycle figure of a report model; the ``plot_x``
functions draw one figure of an Analysis onto a notebook's Axes.

The figures live in modules of one job each, re-exported here: the sweep plots
(:mod:`.sweep_plots`: driver torque, joint reactions, shaking force and moment; their axis in
:mod:`.sweep_axes`), polar bearing diagrams (:mod:`.polar_plots`), the cycle and design plots
(:mod:`.cycle_plots`: flywheel diagram, torque by source, transmission angle, balancing), the
driver torque with and without friction (:mod:`.friction_plots`) and the strength plots
(:mod:`.strength_plots`). The matplotlib infrastructure they share (style, palette, figure,
saving, literal text, measuring text) is :mod:`.mpl`; the one label placer is
:mod:`.labels`.

Values are plotted in the report's display units (``model.display``) and labelled by the one
number formatter."""
from __future__ import annotations

from pathlib import Path

from .cycle_plots import (LIMIT_COLOR, LIMIT_REACH, balance_figure, breakdown_figure,  # noqa: F401
                          flywheel_figure, transmission_figure)
from .friction_plots import (FRICTION_COLOR, FRICTIONLESS_COLOR, LEGEND_SLACK,  # noqa: F401
                             draw_friction, friction_figure)
from .labels import CLEAR, LINE_CLEAR  # noqa: F401
from .mpl import (GREY, INK, MARGINS, OKABE_ITO, PALETTE, STYLES, WIDTH, figure,  # noqa: F401
                  legend_top, literal, save, style, styled)
from .polar_plots import POLAR_TITLE_OVERHANG, POLAR_TITLE_SIZE, polar_figure  # noqa: F401
from .strength_plots import strength_figure, stress_figure  # noqa: F401
from .sweep_axes import (OFF_SCALE_SIZE, REF_SIZE, crank_axis,  # noqa: F401
                         label_reference_lines, off_scale_labels, scale_to_trusted)
from .sweep_plots import (draw_reactions, draw_torque, reactions_figure,  # noqa: F401
                          shaking_figure, torque_figure)

SOURCE_COLORS = PALETTE          # the colours of the series, in order (as before)


@styled
def write_plots(model, outdir: Path) -> list[Path]:
    """Every sweep and cycle figure of ``model`` into ``outdir`` (SVG)."""
    sw, figs, d = model.sweep, model.figures, model.display
    out = []
    cd = model.design.data
    if cd is not None:
        for key, make in (("flywheel", flywheel_figure), ("breakdown", breakdown_figure),
                          ("transmission", transmission_figure), ("balance", balance_figure)):
            if key in figs:
                out += save(make(cd, d), outdir, figs[key].stem)
    fr = model.friction
    if "friction" in figs and fr is not None and fr.plot is not None:
        out += save(friction_figure(fr.plot, d), outdir, figs["friction"].stem)
    sp = model.strength.plot if model.strength is not None else None
    if sp is not None:
        for key, make in (("strength", strength_figure), ("stress", stress_figure)):
            if key in figs:
                out += save(make(sp, d), outdir, figs[key].stem)
    if len(sw.angles) == 0:
        return out
    makers = {"torque": torque_figure, "reactions": reactions_figure,
              "polar": polar_figure, "shaking": shaking_figure}
    for key, make in makers.items():
        if key in figs and (key != "reactions" or sw.joints):
            out += save(make(sw, d), outdir, figs[key].stem)
    return out


# ------------------------------------------------------------------------ for notebooks

def _axes(ax, height: float):
    """``ax``, or a new figure's one axes (report width, ``height`` inches)."""
    if ax is not None:
        return ax
    fig, axes = figure(height, margins=(0.72, 0.12, 0.46, 0.5))
    return axes[0, 0]


@styled
def plot_torque(analysis, ax=None):
    """The driver's effort over the sweep of ``analysis`` as the report draws it, on ``ax``
    (a matplotlib Axes; default: a new figure's); returns the Axes.

        fig, ax = plt.subplots()
        mechreport.report.plots.plot_torque(mechreport.analyse("specs/four_bar.yaml"), ax=ax)
    """
    from .model import sweep_data
    sw, d = sweep_data(analysis)
    ax = _axes(ax, 2.9)
    draw_torque(ax, sw, d)
    return ax


@styled
def plot_reactions(analysis, ax=None):
    """Every joint's reaction magnitude over the sweep of ``analysis`` as the report draws
    it, on ``ax`` (default: a new figure's); returns the Axes."""
    from .model import sweep_data
    sw, d = sweep_data(analysis)
    ax = _axes(ax, 3.0)
    draw_reactions(ax, sw, d)
    return ax


@styled
def plot_friction(analysis, ax=None):
    """The driver's effort with and without friction in the joints of ``analysis`` as the
    report draws it, on ``ax`` (default: a new figure's); returns the Axes. Raises
    ValueError when the spec has no friction."""
    from .model import friction_data
    fp, d = friction_data(analysis)
    if fp is None:
        raise ValueError(f"{analysis.spec.file}: no friction in its joints (a 'friction:' "
                         "entry with mu > 0) to plot")
    ax = _axes(ax, 2.9)
    draw_friction(ax, fp, d)
    return ax
