"""Worked solution sheets: the answer key a teacher hands out, and its problem version.

For each reference angle: the mechanism and a free-body diagram of every link, the kinematics
derivation, then each method's equations in symbols and with numbers, generated from the very
equation objects the method solved, and the answers (closed forms with ``--exact``).

Modules, in the order the data flows:

- :mod:`.symbols` the textbook's names of actions and unknowns (F12, Fin2, M03, omega_1);
- :mod:`.expr` the math atoms, expressions and equations, rendered as LaTeX, Typst, text;
- :mod:`.translate` a method's ``Equation`` objects as textbook lines (read through
  :func:`mechreport.forces.builders.read_term`);
- :mod:`.kinematics` the positions, velocities and accelerations derivation;
- :mod:`.exact` exact closed forms in the spec's own square roots;
- :mod:`.figures` the mechanism and the free-body diagrams (SVG);
- :mod:`.model` the sheet and problem models; :mod:`.render` the files.
"""
from __future__ import annotations

from .model import SheetOptions, build_problem, build_sheet, sheet_analysis, sheet_spec
from .render import (render_markdown, render_problem_markdown, render_problem_typst,
                     render_typst, write_sheet)

__all__ = ["SheetOptions", "build_sheet", "build_problem", "sheet_analysis", "sheet_spec", "write_sheet",
           "render_markdown",
           "render_typst", "render_problem_markdown", "render_problem_typst"]
