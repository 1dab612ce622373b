"""Write a solution sheet and its problem version: solution.md / solution.pdf (the answer
key) and problem.md / problem.pdf (statement, data, figures, what to find), beside the
figures they show (figures/sheet-*.svg).

The problem sheet is a document (:mod:`.problem_doc`) written by the document writers.
Templates: ``templates/solution.{md,typ}.j2``, through
the reports' one Jinja2 environment (:func:`mechreport.report.render.environment`) with the
sheets' math filters: ``mtex`` / ``mtyp`` render an atom, expression or equation (or rich
text: a list of strings and math) as LaTeX or Typst math."""
from __future__ import annotations

from pathlib import Path

from ..files import atomic_write_text
from ..markdown import md_inline
from ..pdf import compile_typst, typst_escape
from ..render import environment
from .expr import Equation, fmt, math, round_off
from .model import SheetOptions, build_problem, build_sheet
from .problem_doc import problem_document
from .symbols import rich_label


def _rich(segments, how: str) -> str:
    """Text with inline math: strings escaped for the target, math between dollars."""
    out = []
    for seg in segments:
        if isinstance(seg, str):
            if how == "tex":             # md_inline trims; math needs the spaces around it
                core = seg.strip()
                lead, trail = seg[:len(seg) - len(seg.lstrip())], seg[len(seg.rstrip()):]
                out.append((" " if lead else "") + (md_inline(core) if core else "")
                           + (" " if trail and core else ""))
            else:
                out.append(typst_escape(seg))
        else:
            out.append("$" + math(seg, how) + "$")
    return "".join(out)


def _env():
    env = environment()
    if "mtex" not in env.filters:
        env.filters["mtex"] = lambda x: math(x, "tex")
        env.filters["mtyp"] = lambda x: math(x, "typ")
        env.filters["rich_md"] = lambda segs: _rich(segs, "tex")
        env.filters["rich_typ"] = lambda segs: _rich(segs, "typ")
        env.filters["num"] = fmt
        env.filters["label_md"] = lambda s: _rich(rich_label(str(s)), "tex")
        env.filters["label_typ"] = lambda s: _rich(rich_label(str(s)), "typ")
        env.tests["equation"] = lambda x: isinstance(x, Equation)
        env.tests["mathlist"] = lambda x: isinstance(x, (list, tuple))
    return env


def render_markdown(model) -> str:
    with round_off(model.zero):
        return _env().get_template("solution.md.j2").render(sheet=model)


def render_typst(model) -> str:
    with round_off(model.zero):
        return _env().get_template("solution.typ.j2").render(sheet=model)


def render_problem_markdown(model) -> str:
    """problem.md of the :class:`.model.ProblemModel` ``model``."""
    with round_off(model.zero):
        return problem_document(model).markdown()


def render_problem_typst(model) -> str:
    """The Typst source of problem.pdf."""
    with round_off(model.zero):
        return problem_document(model).typst()


def write_sheet(analysis, outdir: Path, options: SheetOptions | None = None) -> list[Path]:
    """Write the answer key and the problem version of ``analysis`` into ``outdir``, with
    their figures; returns [solution.md, solution.pdf, problem.md, problem.pdf]."""
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
    return out
