"""The report's plots, one SVG file each, shown by both the PDF and the Markdown report:
:func:`write_plots` writes every sweep and cycle figure of a report model; the ``plot_x``
functions draw one figure of an Analysis onto a notebook's Axes.

The figures live in modules of one job each, re-exported here: the sweep plots
(:mod:`.sweep_plots`: driver torque, joint reactions, shaking force and moment; their axis in
:mod:`.sweep_axes`), polar bearing diagrams (:mod:`.polar_plots`), the cycle and design plots
(:mod:`.cycle_plots`: flywheel diagram, torque by source, transmission angle, balancing), the
driver torque with and without friction (:mod:`.friction_plots`), the strength plots
(:mod:`.strength_plots`) and the machine's speed (:mod:`.dynamics_plots`). The matplotlib infrastructure they share (style, palette, figure,
saving, literal text, measuring text) is :mod:`.mpl`; the one label placer is
:mod:`.labels`.

Values are plotted in the report's display units (``model.display``) and labelled by the one
number formatter."""
from __future__ import annotations

from pathlib import Path

from .cycle_plots import (LIMIT_COLOR, LIMIT_REACH, balance_figure, breakdown_figure,  # noqa: F401
                          draw_balance, draw_breakdown, draw_energy, draw_flywheel,
                          draw_transmission, flywheel_figure, transmission_figure)
from .engine_plots import (draw_pressure, draw_shares, draw_turning_moment,  # noqa: F401
                           pressure_figure, turning_moment_figure)
from .dynamics_plots import draw_startup, draw_steady_turn, dynamics_figure  # noqa: F401
from .friction_plots import (FRICTION_COLOR, FRICTIONLESS_COLOR, LEGEND_SLACK,  # noqa: F401
                             draw_friction, friction_figure)
from .labels import CLEAR, LINE_CLEAR  # noqa: F401
from .mpl import (GREY, INK, MARGINS, OKABE_ITO, PALETTE, STYLES, WIDTH, figure,  # noqa: F401
                  legend_top, literal, save, style, styled)
from .polar_plots import (POLAR_TITLE_OVERHANG, POLAR_TITLE_SIZE, draw_polar,  # noqa: F401
                          polar_figure)
from .strength_plots import (draw_internal_force, draw_stress, strength_figure,  # noqa: F401
                             stress_figure)
from .sweep_axes import (OFF_SCALE_SIZE, REF_SIZE, crank_axis,  # noqa: F401
                         label_reference_lines, off_scale_labels, scale_to_trusted)
from .sweep_plots import (draw_couples, draw_reactions, draw_shaking_force,  # noqa: F401
                          draw_shaking_moment, draw_torque, reactions_figure, shaking_figure,
                          slider_couples, torque_figure)

SOURCE_COLORS = PALETTE          # the series' colours: the palette's (Okabe & Ito's before)


@styled
def write_plots(model, outdir: Path) -> list[Path]:
    """Every sweep and cycle figure of ``model`` into ``outdir`` (SVG)."""
    sw, figs, d = model.sweep, model.figures, model.display
    out = []
    cd = model.design.data
    if cd is not None:
        for key, make in (("pressure", pressure_figure),
                          ("turning_moment", turning_moment_figure),
                          ("flywheel", flywheel_figure), ("breakdown", breakdown_figure),
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
#
# plot_x(analysis, ax=None): figure x of an Analysis as the report draws it, on ``ax`` (a
# matplotlib Axes; default: a new figure's, outside pyplot), in the report's style and its
# display units; returns the Axes. Each builds the report's records of its figure and draws
# them with the figure's draw_x. ValueError where the spec has nothing to plot.

def _axes(ax, height: float, width: float | None = None):
    """``ax``, or a new figure's one axes (``width``, default the report's, by ``height``
    [in])."""
    if ax is not None:
        return ax
    if width is None:
        fig, axes = figure(height, margins=(0.72, 0.12, 0.46, 0.5))
    else:
        fig, axes = figure(height, margins=(0.62, 0.12, 0.42, 0.45), width=width)
    return axes[0, 0]


def _model(analysis):
    """The report model of ``analysis`` (no animation): its figures' records."""
    from .model import build_model
    return build_model(analysis, animation=False)


def _nothing(analysis, what: str):
    return ValueError(f"{analysis.spec.file}: no {what} to plot")


def _sweep(analysis):
    """The report's sweep records of ``analysis`` and its display units; ValueError when no
    position of the sweep was solved."""
    from .sweep_section import sweep_data
    sw, d = sweep_data(analysis)
    if len(sw.angles) == 0:
        raise _nothing(analysis, "solved position in the sweep")
    return sw, d


def _cycle(analysis):
    """The report's cycle records (CycleData) of ``analysis`` and its display units."""
    model = _model(analysis)
    if model.design.data is None:
        raise _nothing(analysis, "steady turn (a cycle over a whole turn)")
    return model.design.data, model.display


@styled
def plot_torque(analysis, ax=None):
    """The driver's effort over the sweep of ``analysis`` as the report draws it, on ``ax``
    (a matplotlib Axes; default: a new figure's); returns the Axes.

        fig, ax = plt.subplots()
        mechreport.report.plots.plot_torque(mechreport.analyse("specs/four_bar.yaml"), ax=ax)
    """
    from .sweep_section import sweep_data
    sw, d = sweep_data(analysis)
    ax = _axes(ax, 2.9)
    draw_torque(ax, sw, d)
    return ax


@styled
def plot_reactions(analysis, ax=None):
    """Every joint's reaction magnitude over the sweep of ``analysis`` as the report draws
    it, on ``ax`` (default: a new figure's); returns the Axes."""
    from .sweep_section import sweep_data
    sw, d = sweep_data(analysis)
    ax = _axes(ax, 3.0)
    draw_reactions(ax, sw, d)
    return ax


@styled
def plot_couples(analysis, ax=None):
    """The couples of the T joints of ``analysis`` over the sweep (those not zero at every
    angle), on ``ax`` (default: a new figure's); returns the Axes."""
    sw, d = _sweep(analysis)
    couples = slider_couples(sw)
    if not couples:
        raise _nothing(analysis, "slider couple (a T joint's, not zero)")
    ax = _axes(ax, 2.6)
    draw_couples(ax, sw, d, couples)
    return ax


@styled
def plot_shaking_force(analysis, ax=None):
    """The shaking force on the frame over the sweep of ``analysis`` (magnitude and
    components), on ``ax`` (default: a new figure's); returns the Axes."""
    sw, d = _sweep(analysis)
    ax = _axes(ax, 2.6)
    draw_shaking_force(ax, sw, d)
    return ax


@styled
def plot_shaking_moment(analysis, ax=None):
    """The shaking moment on the frame over the sweep of ``analysis``, on ``ax`` (default:
    a new figure's); returns the Axes."""
    sw, d = _sweep(analysis)
    ax = _axes(ax, 2.6)
    draw_shaking_moment(ax, sw, d)
    return ax


@styled
def plot_polar(analysis, joint: str | None = None, ax=None):
    """The polar diagram of the reaction of ``joint`` (its name; default: the first joint's)
    over the sweep of ``analysis``, on ``ax`` (default: a new square figure's); returns the
    Axes."""
    sw, d = _sweep(analysis)
    series = [ps for ps in sw.polar if joint is None or ps.name == joint]
    if not series:
        raise _nothing(analysis, "polar diagram" + (f" of joint {joint!r}" if joint else ""))
    ax = _axes(ax, 3.2, width=3.2)
    draw_polar(ax, sw, series[0], d)
    return ax


@styled
def plot_flywheel(analysis, ax=None):
    """The driver's torque over the steady turn of ``analysis`` against its mean, the energy
    areas shaded (the flywheel diagram's upper panel), on ``ax`` (default: a new figure's);
    returns the Axes."""
    cd, d = _cycle(analysis)
    ax = _axes(ax, 2.9)
    draw_flywheel(ax, cd, d)
    return ax


@styled
def plot_energy(analysis, ax=None):
    """The energy over the steady turn of ``analysis``, ∫(M − mean) dφ [J], with its largest
    fluctuation ΔE (the flywheel diagram's lower panel), on ``ax`` (default: a new
    figure's); returns the Axes."""
    cd, _ = _cycle(analysis)
    ax = _axes(ax, 2.4)
    draw_energy(ax, cd)
    return ax


def _engine(analysis):
    """The report's cycle records of an engine (a spec with pressure loads) and its display
    units; ValueError for a spec without pressure loads."""
    cd, d = _cycle(analysis)
    if not cd.pressures:
        raise _nothing(analysis, "pressure load (type: pressure)")
    return cd, d


@styled
def plot_pressure(analysis, ax=None):
    """The pressure diagram of the engine ``analysis``: each pressure load's pressure over
    the cycle, on ``ax`` (default: a new figure's); returns the Axes."""
    cd, d = _engine(analysis)
    ax = _axes(ax, 2.7)
    draw_pressure(ax, cd, d)
    return ax


@styled
def plot_turning_moment(analysis, ax=None):
    """The turning-moment diagram of the engine ``analysis``: its crank effort over the
    cycle against its mean, each area between crossings labelled with its energy, on ``ax``
    (default: a new figure's); returns the Axes."""
    cd, d = _engine(analysis)
    ax = _axes(ax, 2.9)
    draw_turning_moment(ax, cd, d)
    return ax


@styled
def plot_breakdown(analysis, ax=None):
    """The driver's torque over the steady turn of ``analysis`` by source, stacked, on
    ``ax`` (default: a new figure's); returns the Axes."""
    cd, d = _cycle(analysis)
    ax = _axes(ax, 2.9)
    draw_breakdown(ax, cd, d)
    return ax


@styled
def plot_transmission(analysis, ax=None):
    """The transmission angle of each group of ``analysis`` over the steady turn, on ``ax``
    (default: a new figure's); returns the Axes."""
    cd, _ = _cycle(analysis)
    if not cd.transmission:
        raise _nothing(analysis, "transmission angle")
    ax = _axes(ax, 2.5)
    draw_transmission(ax, cd)
    return ax


@styled
def plot_balance(analysis, ax=None):
    """The inertial shaking force of ``analysis`` over the steady turn, a polar trace without
    and with the counterweight, on ``ax`` (default: a new square figure's); returns the
    Axes."""
    cd, d = _cycle(analysis)
    if cd.inertial is None or cd.balanced is None:
        raise _nothing(analysis, "balancing")
    ax = _axes(ax, 3.6, width=3.6)
    draw_balance(ax, cd, d)
    return ax


@styled
def plot_friction(analysis, ax=None):
    """The driver's effort with and without friction in the joints of ``analysis`` as the
    report draws it, on ``ax`` (default: a new figure's); returns the Axes. Raises
    ValueError when the spec has no friction."""
    from .friction import friction_data
    fp, d = friction_data(analysis)
    if fp is None:
        raise ValueError(f"{analysis.spec.file}: no friction in its joints (a 'friction:' "
                         "entry with mu > 0) to plot")
    ax = _axes(ax, 2.9)
    draw_friction(ax, fp, d)
    return ax


def _strength(analysis):
    model = _model(analysis)
    sp = model.strength.plot if model.strength is not None else None
    if sp is None:
        raise _nothing(analysis, "strength (a 'strength:' section with a loaded member)")
    return sp, model.display


@styled
def plot_internal_force(analysis, part: str = "M", ax=None):
    """One internal force along the most loaded member of ``analysis`` at its worst angle:
    ``part`` "N", "V" or "M", on ``ax`` (default: a new figure's); returns the Axes."""
    sp, d = _strength(analysis)
    ax = _axes(ax, 2.4)
    draw_internal_force(ax, sp, d, part)
    return ax


@styled
def plot_stress(analysis, ax=None):
    """The largest stress along each member of ``analysis`` over the sweep, on ``ax``
    (default: a new figure's); returns the Axes."""
    sp, d = _strength(analysis)
    ax = _axes(ax, 2.6)
    draw_stress(ax, sp, d)
    return ax


def _dynamics(analysis):
    model = _model(analysis)
    if model.dynamics is None:
        raise _nothing(analysis, "machine dynamics (a 'dynamics:' section)")
    return model.dynamics.plot


@styled
def plot_startup(analysis, ax=None):
    """The crank's speed [rpm] of ``analysis`` from the start against the time [s], on
    ``ax`` (default: a new figure's); returns the Axes."""
    dp = _dynamics(analysis)
    ax = _axes(ax, 2.6)
    draw_startup(ax, dp)
    return ax


@styled
def plot_steady_turn(analysis, ax=None):
    """The crank's speed [rpm] of ``analysis`` over its steady turn against the crank
    angle, on ``ax`` (default: a new figure's); returns the Axes. ValueError without a
    steady state."""
    dp = _dynamics(analysis)
    if not len(dp.angles):
        raise _nothing(analysis, "steady turn of the machine dynamics")
    ax = _axes(ax, 2.6)
    draw_steady_turn(ax, dp)
    return ax


#: every figure's notebook function, by the name its draw_x has
PLOT_FUNCTIONS = {f.__name__[5:]: f for f in (
    plot_torque, plot_reactions, plot_couples, plot_shaking_force, plot_shaking_moment,
    plot_polar, plot_flywheel, plot_energy, plot_breakdown, plot_transmission, plot_balance,
    plot_friction, plot_internal_force, plot_stress, plot_startup, plot_steady_turn,
    plot_pressure, plot_turning_moment)}
