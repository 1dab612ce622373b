"""``mechreport optimize SPEC``: load, search, prove, write the outputs.

Exit status: 0 when a feasible optimum was found and proven (its files written); 1 when none
was (the files are written all the same: history.csv, optimize.md/.pdf naming the least
violating design and what it misses, optimum.yaml with that design's values), or when the
optimisation cannot run (the spec or its optimize section is invalid, the scheduler cannot
be used, the output folder cannot be written); 130 when interrupted (nothing is written).

The files, written into ``OUT/<spec>/`` safely (as ``mechreport study`` writes its own: a
private folder swapped in whole, a report built there by ``mechreport build`` carried over):

    OUT/<spec>/optimum.yaml                   the spec with the optimal values written in
    OUT/<spec>/history.csv                    every evaluation
    OUT/<spec>/optimize.md, optimize.pdf      the optimisation report
    OUT/<spec>/optimize-figures/*.svg         its figures
    OUT/<spec>/optimum/                       the optimum's full report (as mechreport build)
"""
from __future__ import annotations

import os
import sys
import time
from pathlib import Path

from . import outdir as od


def optimize_command(path, out="out", scheduler: str | None = None, jobs: int | None = None,
                     budget: int | None = None, seed: int | None = None,
                     wait: float = 120.0, stream=None) -> int:
    """Run the optimisation of the spec at ``path`` into ``out``; the exit status (see the
    module docstring). Raises ``SpecError``/``MechreportError`` when it cannot run and
    KeyboardInterrupt when interrupted."""
    from functools import partial

    from ..study.optimize import load_optimize_base, problem_of, run_optimize
    from .process import check_stop, stop_requests
    from .progress import StudyProgress, duration
    from .runs import cluster_client, placement, stop_said
    from .workers import worker_init

    err = stream or sys.stderr
    path = Path(path)
    base = load_optimize_base(path)
    opt = base.spec.optimize
    total = int(budget if budget is not None else opt.budget)
    out = od.prepare(Path(out))
    name = od.safe_stem(path)
    with stop_requests():
        prepared = problem_of(base)
        problem = prepared[0]
        with cluster_client(scheduler, err) as client:
            workers, _size, where = placement(client, scheduler, 10**6, jobs, None, err)
            sense = "maximize" if opt.maximize else "minimize"
            print(f"optimize {path}: {sense} {opt.objective} over {len(opt.vary)} key(s), "
                  f"{len(problem.constraints)} constraint(s); budget {total} evaluations; "
                  f"method {problem.method} (with the trust test), every method for the "
                  f"proof; on {where}", file=err, flush=True)
            progress = StudyProgress(total, err, items="evaluations", bad="infeasible")

            def tick(done: int, infeasible: int, _total: int) -> None:
                progress.update(done, infeasible)

            with stop_said(err, lambda: f"interrupted after {progress.done} evaluation(s); "
                                        "nothing was written", progress.close):
                result = run_optimize(base, jobs=workers if client is None else 1,
                                      client=client, budget=budget, seed=seed,
                                      progress=tick, notify=progress.say, stop_check=check_stop,
                                      setup=partial(worker_init, os.getpid()),
                                      prepared=prepared)
                progress.close()
        result.where = where
        print(f"{result.history.n} evaluation(s) in {duration(result.seconds)}; "
              f"{int(result.history.feasible().sum())} feasible", file=err, flush=True)
        print(f"writing {out / name}/ ...", file=err, flush=True)
        with stop_said(err, lambda: f"interrupted while writing; {out / name} was left as it "
                                    "was"):
            final = write_optimize(result, path, out, name, wait, err)
    return report_lines(result, final, err)


def report_lines(result, final: Path, err) -> int:
    """The result on stdout (stderr for the misses); the exit status."""
    from ..study.optimize import value_change
    from ..units import fmt
    p = result.problem
    if result.feasible:
        j = result.judged
        print(f"{p.base.spec.file}: optimum {p.objective} = {fmt(j.objective)} "
              f"(original {fmt(result.original.objective)}); written to {final}/ "
              "(optimum.yaml, history.csv, optimize.md, optimize.pdf, optimum/)")
        for k, v in result.values.items():
            print(f"  {value_change(k, v, result.start[k])}")
        active = [c.name for c, _ in result.active()] + result.at_box()
        print(f"  active: {', '.join(active) if active else 'none'}")
        return 0
    print(f"{p.base.spec.file}: no feasible design in {result.history.n} evaluation(s); "
          f"written to {final}/")
    j = result.judged
    if j is not None:
        print("error: the least violating design "
              + ", ".join(f"{k} = {v:.10g}" for k, v in result.values.items())
              + " misses:", file=err)
        for line in j.missed(p):
            print(f"  {line}", file=err)
    return 1


def write_optimize(result, path: Path, out: Path, name: str, wait: float = 120.0,
                   err=None) -> Path:
    """Write every file of ``result`` into ``OUT/name``; the folder."""
    from ..report.build import write_report_folder
    from ..report.files import atomic_write_text
    from ..report.provenance import build_time, spec_sha256
    from ..report.pdf import compile_typst
    from ..report.write_markdown import markdown
    from ..report.write_typst import typst
    from ..study.optimize import profiles
    from ..study.optimize_report import FIGURES, build_document, write_figures, write_history
    err = err or sys.stderr
    profs = profiles(result)

    def write(tmp: Path) -> None:
        write_history(result, tmp / "history.csv")
        report = ""
        if result.text:
            atomic_write_text(tmp / "optimum.yaml", result.text)
        if result.feasible:
            where = od.inside(tmp, tmp / "optimum")
            where.mkdir(parents=True)
            atomic_write_text(where / "optimum.yaml", result.text)
            print("report: the optimum", file=err, flush=True)
            write_report_folder(_described(result), where, "optimum/optimum.yaml",
                                spec_sha256(where / "optimum.yaml"))
            report = "optimum/report.pdf"
        figures = write_figures(result, tmp / FIGURES, profs)
        doc = build_document(result, figures, sha256=spec_sha256(path),
                             date=build_time().strftime("%Y-%m-%d %H:%M UTC"), report=report)
        atomic_write_text(tmp / "optimize.md", markdown(doc))
        compile_typst(typst(doc), tmp / "optimize.pdf", tmp)

    with od.writing(out, wait) as out:
        return od.write_folder(out, name, write, carry=od.all_but(od.OPTIMIZE_ENTRIES))


def _described(result):
    """The optimum's analysis, its report's description saying what it is first (the spec's
    own description follows, whose numbers are the original design's)."""
    from dataclasses import replace
    a = result.analysis
    from ..study.optimize import value_change
    changed = ", ".join(value_change(k, v, result.start[k]) for k, v in result.values.items())
    sense = "maximize" if result.problem.maximize else "minimize"
    about = (f"The optimum found by mechreport optimize ({sense} {result.problem.objective}): "
             f"{changed}. The spec's own description follows; its numbers are the original "
             "design's.")
    text = about + ("\n\n" + a.spec.description if a.spec.description else "")
    return replace(a, spec=replace(a.spec, description=text))
