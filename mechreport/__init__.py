"""mechreport: dynamic force analysis reports for planar linkages, from YAML specs.

    import mechreport
    a = mechreport.analyse("specs/slider_crank.yaml")     # a path, or the YAML text
    a.forces["dyad"].reactions["B"].fx                     # (n,) [N] over a.angles [deg]
    t = mechreport.run_study("specs/four_bar.yaml")        # its study: section, as a Table
    r = mechreport.tolerance("spec.yaml")                  # its tolerances: section
    o = mechreport.optimize("specs/four_bar_optimize.yaml")  # its optimize: section, proven

The pipeline, one package per stage, data flowing one way: ``spec`` (load, validate) ->
``model`` (graph, dyads, loops) -> ``kinematics`` -> ``forces`` (one module per method) ->
``checks`` and ``post`` (pure functions of the results) -> ``pipeline`` (analyse, streamed,
batch) -> ``report`` -> ``study``; ``app`` (the command line) sits on top. Importing the
package loads nothing else and changes nothing in the process: ``analyse`` and
``run_study`` (:func:`mechreport.study.run.run_study`: the rows ``mechreport study`` writes)
are imported on first use.
"""
from .version import __version__

__all__ = ["analyse", "Analysis", "run_study", "tolerance", "optimize", "__version__"]


def __getattr__(name: str):
    # PEP 562: the pipeline (numpy, scipy) is imported when first asked for, so that the
    # command line can set up the process (BLAS threads) before numpy loads.
    if name in ("analyse", "Analysis"):
        from . import pipeline
        return getattr(pipeline, name)
    if name == "run_study":
        from .study.run import run_study
        return run_study
    if name == "tolerance":
        from .study.tolerance import run_tolerance
        return run_tolerance
    if name == "optimize":
        from .study.optimize import optimize
        return optimize
    raise AttributeError(f"module 'mechreport' has no attribute {name!r}")
