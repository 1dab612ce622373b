"""mechreport: dynamic force analysis reports for planar linkages, from YAML specs.

Pipeline (one package per stage): ``spec`` (load, validate) -> ``model`` (graph, dyads,
loops) -> ``kinematics`` -> ``forces`` (one module per method) -> ``checks`` -> ``report``.
The public entry point is ``mechreport.analysis.analyse(path)``.
"""
import os as _os

# Batched small systems are solved one by one inside LAPACK; a second BLAS thread only adds
# overhead (measured: 0.6 us vs 2-7 us per angle for 8x8). Must be set before numpy loads.
_os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

__version__ = "0.1.0"
