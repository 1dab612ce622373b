"""The pressure diagram is drawn in ``report.units.pressure`` when the spec gives it (an
indicator diagram written in bar, shown in psi as a US reader asks), else in the pressure
load's own unit; the values are the profile's converted, never the written numbers under
another unit's label."""
from __future__ import annotations

import numpy as np
import pytest

import mechreport
from mechreport.report.plots import plot_pressure

ENGINE = """\
mechreport: 1.2
name: engine pressure units
cycle: 720
ground: {O: [0, 0]}
units: {length: mm, mass: kg}
REPORT
links:
  crank: {points: {O: [0, 0], B: [43, 0]}, mass: 3, com: [0, 0], inertia: 0.012}
  rod: {points: {B: [0, 0], C: [145, 0]}, mass: 0.55, com: [40, 0], inertia: 1.7e-3}
  piston: {points: {C: [0, 0]}, mass: 0.45, com: [0, 0], inertia: 0}
joints:
  O: {type: R, links: [ground, crank]}
  B: {type: R, links: [crank, rod]}
  C: {type: R, links: [rod, piston]}
  bore: {type: T, links: [ground, piston], point: C, line: {through: O, direction: 0}}
driver: {joint: O, rpm: 3000}
sweep: {start: 0, stop: 720, step: 10}
assembly: {C: [188, 0]}
loads:
  - {type: pressure, name: gas, link: piston, point: C, bore: 86, direction: [-1, 0],
     unit: bar, ambient: 1, profile: [[0, 1], [360, 50], [540, 3], [720, 1]]}
"""


def _line(report: str):
    from matplotlib.figure import Figure
    a = mechreport.analyse(ENGINE.replace("REPORT", report))
    ax = plot_pressure(a, ax=Figure().subplots())
    x, y = ax.get_lines()[0].get_data()
    return np.asarray(x), np.asarray(y), ax.get_ylabel()


def test_the_pressure_diagram_is_drawn_in_the_report_pressure_unit():
    x, y, label = _line("report: {units: {pressure: psi}}")
    assert "psi" in label
    peak = y[np.argmin(np.abs(x - 360))]
    assert peak == pytest.approx(50e5 / 6894.757293168361, rel=1e-9)    # 50 bar in psi


def test_without_a_report_unit_the_diagram_keeps_the_load_unit():
    x, y, label = _line("")
    assert "bar" in label
    assert y[np.argmin(np.abs(x - 360))] == pytest.approx(50, rel=1e-12)


def test_the_pressure_caption_names_the_unit_drawn():
    from mechreport.report.model import build_model
    m = build_model(mechreport.analyse(ENGINE.replace("REPORT", "report: {units: {pressure: "
                                                                "psi}}")), animation=False)
    caption = m.figures["pressure"].caption
    assert caption.endswith("in psi.") and "bar" not in caption
