"""Spec texts of the optimisation tests: variants of specs/four_bar.yaml written in full."""
from __future__ import annotations

from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
FOUR_BAR = (ROOT / "specs" / "four_bar.yaml").read_text(encoding="utf-8")


def four_bar(step: int = 4, design: bool = False) -> str:
    """specs/four_bar.yaml at ``step`` degrees, format 1.2, with or without its design
    section (and never its expect entries: they come after it)."""
    text = FOUR_BAR if design else FOUR_BAR[:FOUR_BAR.index("# The design review")]
    if design:
        text = text[:text.index("# Kinematics at the reference angles")]
    return (text.replace("mechreport: 1\n", "mechreport: 1.2\n")
            .replace("sweep: {start: 0, stop: 360, step: 1}",
                     f"sweep: {{start: 0, stop: 360, step: {step}}}"))


#: the coupler and rocker lengths minimising the RMS torque with a transmission angle of at
#: least 40 deg, on the four-bar with a 90 mm crank (with its own 50 mm crank the bound would
#: not bind: its unconstrained optimum keeps 60 deg; with 90 mm it keeps about 39 deg). Part
#: of the box is not a crank-rocker (the crank cannot turn: no cycle quantities).
CONSTRAINED = four_bar().replace(
    """    points: {A: [0, 0], B: [50, 0]}
    density: 7850                 # kg/m^3 (always SI)
    shape: {bar: {length: 50, height: 20, depth: 10}}""",
    """    points: {A: [0, 0], B: [90, 0]}
    density: 7850                 # kg/m^3 (always SI)
    shape: {bar: {length: 90, height: 20, depth: 10}}""") + """
optimize:
  vary:
    - {key: links.coupler.points.C.0, from: 150, to: 220}
    - {key: links.rocker.points.C.0, from: 100, to: 200}
  minimize: cycle.torque.rms
  subject_to:
    - {quantity: cycle.transmission_angle.min, min: 40, unit: deg}
  budget: 600
  seed: 2
"""

#: a box holding the crossed branch (assembly hint below the frame line), whose energy
#: fluctuation is smaller than the open branch's
TRAP = four_bar(step=8) + """
optimize:
  vary:
    - {key: assembly.C.1, from: -150, to: 150}
    - {key: links.coupler.points.C.0, from: 170, to: 190}
  minimize: cycle.energy_fluctuation
  budget: 120
  seed: 1
"""

#: nothing in the box reaches a transmission angle of 85 deg
INFEASIBLE = four_bar(step=8) + """
optimize:
  vary:
    - {key: links.coupler.points.C.0, from: 170, to: 190}
  minimize: cycle.torque.rms
  subject_to:
    - {quantity: cycle.transmission_angle.min, min: 85, unit: deg}
  budget: 60
  seed: 0
"""


def crank_press(crank_mm: float, tail: str) -> str:
    """specs/crank_press_strength.yaml at 6 degree steps with a ``crank_mm`` crank, no design
    section, and ``tail`` appended: a crank longer than the 400 mm rod cannot turn (the
    in-line slider-crank locks near 0 and 180 deg)."""
    text = (ROOT / "specs" / "crank_press_strength.yaml").read_text(encoding="utf-8")
    text = text[:text.index("design:")]
    return (text.replace("mechreport: 1.1", "mechreport: 1.2")
            .replace("sheet: true", "sheet: false")
            .replace("step: 1}", "step: 6}").replace("at: [260]", "at: [90]")
            .replace("points: {A: [0, 0], B: [100, 0]}",
                     f"points: {{A: [0, 0], B: [{crank_mm}, 0]}}")) + tail

