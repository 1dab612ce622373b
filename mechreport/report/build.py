"""One spec's report folder from its analysis: the one way a report is written.

    folder/report.md, report.pdf, results.csv, summary.json, figures/*.svg
    folder/report.html, ../.mechreport-html/*       (report.html, default true)
    folder/dynamics.csv, dynamics.parquet           (with dynamics:)
    folder/animation.gif                            (report.animation, unless left out)
    folder/mechanism.dxf                            (report.dxf)
    folder/solution.md, .pdf, problem.md, .pdf      (with sheets)

``mechreport build`` (:mod:`mechreport.app.build`) and a study's best-variant reports both
call :func:`write_report_folder`; the output folders, workers and index are theirs.
"""
from __future__ import annotations

from pathlib import Path


def write_report_folder(analysis, folder: Path, source: str | Path, sha256: str, *,
                        name: str | None = None, build_key: dict | None = None,
                        sheet: bool = False, sheet_options=None, sheet_source=None,
                        stage=None, animation: bool = True) -> dict:
    """Write the report of ``analysis`` (an :class:`~mechreport.pipeline.Analysis`) into
    ``folder``; its index row. ``source`` is the spec's path as shown in the report,
    ``sha256`` its bytes' hash; ``name`` the report folder's name in the index (default: the
    spec file's stem); ``build_key`` what decided the build (kept in summary.json);
    ``sheet``: also the solution and problem sheets (with ``sheet_options``, a
    :class:`~mechreport.report.sheet.SheetOptions`), worked from ``sheet_source`` (default:
    ``analysis``; the analysis of :func:`~mechreport.report.sheet.sheet_spec` where the sheet
    asks for angles the sweep does not have). ``stage(i, n, what)`` is called before
    each stage after the analysis (stage 1). ``animation`` False: no animation.gif even where
    the spec's ``report.animation`` asks for one."""
    from .animation import write_animation
    from .drawing import write_drawings
    from .dynamics import write_histories
    from .dynamics_plots import write_dynamics_plot
    from .dxf import write_dxf
    from .model import build_model, index_row
    from .plots import write_plots
    from .render import write_report

    stage = stage or (lambda i, n, what: None)
    folder = Path(folder)
    n = 4 if sheet else 3
    model = build_model(analysis, source, sha256=sha256, animation=animation)
    if build_key is not None:
        model.summary["build"] = build_key
    if name is not None:
        model.stem, model.index_row = name, index_row(model.summary, name)
    stage(2, n, "figures" + (" and animation" if model.animation is not None else ""))
    write_plots(model, folder / "figures")
    write_drawings(model, folder / "figures")
    write_dynamics_plot(model, folder / "figures")
    write_animation(model, folder)
    write_dxf(model, folder)
    stage(3, n, "report (Markdown, PDF, CSV, JSON)")
    write_report(model, folder)
    if analysis.spec.report.html:
        from .html_page import write_html_report
        write_html_report(analysis, model, folder)
    if model.dynamics is not None:
        write_histories(model.dynamics.histories, folder)
    if sheet:
        from .sheet import SheetOptions, sheet_analysis, write_sheet
        stage(4, n, "solution sheet and problem")
        options = sheet_options or SheetOptions()
        write_sheet(sheet_analysis(sheet_source or analysis, options), folder, options)
    return model.index_row
