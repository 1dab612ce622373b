"""The plot functions a notebook calls are the report's own: they draw on the axes given,
leave matplotlib's global settings alone, and the report's figures come from them."""
from __future__ import annotations

from pathlib import Path

import numpy as np

import mechreport
from mechreport.report.plots import plot_reactions, plot_torque

ROOT = Path(__file__).resolve().parents[2]


def test_plots_draw_on_the_given_axes_and_leave_rcparams_alone():
    import matplotlib
    from matplotlib.figure import Figure
    a = mechreport.analyse(ROOT / "specs" / "four_bar.yaml")
    before = dict(matplotlib.rcParams)
    fig = Figure()
    ax1, ax2 = fig.subplots(2, 1)
    assert plot_torque(a, ax=ax1) is ax1 and plot_reactions(a, ax=ax2) is ax2
    assert dict(matplotlib.rcParams) == before
    (line, *_) = ax1.get_lines()
    x, y = line.get_data()
    np.testing.assert_array_equal(x, a.angles)              # no left-out angle: no gaps
    np.testing.assert_array_equal(y, a.forces["newton_euler"].driver_torque)
    assert len(ax2.get_lines()) == len(a.spec.joints)


def test_plots_make_their_own_figure_without_pyplot():
    a = mechreport.analyse(ROOT / "specs" / "four_bar.yaml")
    ax = plot_torque(a)
    assert ax.figure is not None and not hasattr(ax.figure, "number")   # not pyplot's
