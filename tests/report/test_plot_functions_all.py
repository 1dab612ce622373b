"""Every figure has a public ``plot_x(analysis, ax=None)``: it draws onto the Axes given
(and returns them) or onto a new figure's (outside pyplot), for a few specs; a spec with
nothing to plot for a figure is a ValueError that says so."""
from __future__ import annotations

from pathlib import Path

import pytest

import mechreport
from mechreport.report.plots import PLOT_FUNCTIONS

ROOT = Path(__file__).resolve().parents[2]
SPECS = ["four_bar", "crank_press_strength", "crank_press_friction", "four_bar_motor",
         "slider_crank", "single_cylinder_engine"]
_analyses: dict = {}


def _analysis(name: str):
    if name not in _analyses:
        _analyses[name] = mechreport.analyse(ROOT / "specs" / f"{name}.yaml")
    return _analyses[name]


def _drawn(ax) -> bool:
    """Something is drawn on ``ax``: a line, a patch or a filled area."""
    return bool(ax.get_lines() or ax.patches or ax.collections)


@pytest.mark.parametrize("spec", SPECS)
@pytest.mark.parametrize("name", sorted(PLOT_FUNCTIONS))
def test_every_plot_draws_on_the_given_axes_and_on_a_new_one(name, spec):
    from matplotlib.figure import Figure
    plot = PLOT_FUNCTIONS[name]
    a = _analysis(spec)
    ax = Figure().subplots()
    try:
        returned = plot(a, ax=ax)
    except ValueError as err:                 # nothing of this kind in the spec
        assert "to plot" in str(err)
        with pytest.raises(ValueError):
            plot(a)
        return
    assert returned is ax and _drawn(ax)
    own = plot(a)
    assert own is not ax and _drawn(own)
    assert not hasattr(own.figure, "number")        # not pyplot's


def test_every_figure_has_a_plot_function_on_some_spec():
    """No plot function raises on every spec: each one is exercised."""
    drawn = set()
    from matplotlib.figure import Figure
    for spec in SPECS:
        for name, plot in PLOT_FUNCTIONS.items():
            if name in drawn:
                continue
            try:
                plot(_analysis(spec), ax=Figure().subplots())
            except ValueError:
                continue
            drawn.add(name)
    assert drawn == set(PLOT_FUNCTIONS)
