"""Write a solution sheet and its problem version: solution.md / solution.pdf (the answer
key) and problem.md / problem.pdf (statement, data, figures, what to find), beside the
figures they show (figures/sheet-*.svg).

Both are documents (:mod:`.solution_doc`, :mod:`.problem_doc`: blocks of
:mod:`mechreport.report.document`) written by the one Markdown and the one Typst writer; their
math (atoms, expressions, equations of :mod:`.expr`) is TeX in Markdown, Typst math in print."""
from __future__ import annotations

from pathlib import Path

from ..files import atomic_write_text
from ..pdf import compile_typst
from .expr import round_off
from .model import SheetOptions, build_problem, build_sheet
from .problem_doc import problem_document
from .solution_doc import solution_document
from ..write_markdown import markdown
from ..write_typst import typst


def render_markdown(model) -> str:
    """solution.md of the :class:`.model.SheetModel` ``model``."""
    with round_off(model.zero):
        return markdown(solution_document(model))


def render_typst(model) -> str:
    """The Typst source of solution.pdf."""
    with round_off(model.zero):
        return typst(solution_document(model))


def render_problem_markdown(model) -> str:
    """problem.md of the :class:`.model.ProblemModel` ``model``."""
    with round_off(model.zero):
        return markdown(problem_document(model))


def render_problem_typst(model) -> str:
    """The Typst source of problem.pdf."""
    with round_off(model.zero):
        return typst(problem_document(model))


def write_sheet(analysis, outdir: Path, options: SheetOptions | None = None,
                models: bool = False):
    """Write the answer key and the problem version of ``analysis`` into ``outdir``, with
    their figures; returns [solution.md, solution.pdf, problem.md, problem.pdf] (with
    ``models``: the sheet's and the problem's models instead)."""
    outdir = Path(outdir)
    sheet = build_sheet(analysis, options)
    (outdir / "figures").mkdir(parents=True, exist_ok=True)
    with round_off(sheet.zero):
        for fig in sheet.figures():
            fig.draw(outdir / fig.path)
    problem = build_problem(analysis, options, sheet)
    out = [atomic_write_text(outdir / "solution.md", render_markdown(sheet))]
    out.append(compile_typst(render_typst(sheet), outdir / "solution.pdf", outdir))
    out.append(atomic_write_text(outdir / "problem.md", render_problem_markdown(problem)))
    out.append(compile_typst(render_problem_typst(problem), outdir / "problem.pdf", outdir))
    return (sheet, problem) if models else out
