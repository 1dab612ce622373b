"""mechreport: dynamic force analysis reports for planar linkages, from YAML specs.

    import mechreport
    a = mechreport.analyse("specs/slider_crank.yaml")     # a path, or the YAML text
    a.forces["dyad"].reactions["B"].fx                     # (n,) [N] over a.angles [deg]

The pipeline, one package per stage, data flowing one way: ``spec`` (load, validate) ->
``model`` (graph, dyads, loops) -> ``kinematics`` -> ``forces`` (one module per method) ->
``checks`` and ``post`` (pure functions of the results) -> ``pipeline`` (analyse, streamed,
batch) -> ``report`` -> ``study``; ``app`` (the command line) sits on top. Importing the
package loads nothing else and changes nothing in the process: ``analyse`` is imported on
first use.
"""
from .version import __version__

__all__ = ["analyse", "Analysis", "__version__"]


def __getattr__(name: str):
    # PEP 562: the pipeline (numpy, scipy) is imported when first asked for, so that the
    # command line can set up the process (BLAS threads) before numpy loads.
    if name in ("analyse", "Analysis"):
        from . import pipeline
        return getattr(pipeline, name)
    raise AttributeError(f"module 'mechreport' has no attribute {name!r}")
