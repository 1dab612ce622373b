"""Design studies: many variants of one spec, their cycle quantities in one table.

    mechreport study SPEC [-o OUT] [--method M] [--scheduler ADDRESS] [--jobs N]
                          [--reports K] [--cross-check N] [--chunk N]

One module per step: :mod:`.plan` (the ``study:`` section -> the variants: grid, random,
Latin hypercube), :mod:`.variants` (the spec's data tree with the varied leaves replaced,
validated by the loader), :mod:`.evaluate` (THE SEAM: a chunk of variants -> one row each),
:mod:`.methods` (which force method), :mod:`.table` (the rows as columns, ranking, Pareto front),
:mod:`.outputs` (study.parquet, study.csv), :mod:`.report` and
:mod:`.document` (study.md, study.pdf), :mod:`.cross_check`; :mod:`.run` (chunks of variants
run by the executor, and ``run_study``, the Python entry point), :mod:`.executor` (a local
process pool with retries of lost chunks, partial results, stop checks; ``mechreport build``
uses it too) and :mod:`.cluster` (the same on a Dask cluster). The command's messages,
progress and output folder are :mod:`mechreport.app.study`'s.
"""
from .evaluate import Row, evaluate_chunk
from .plan import Plan, plan_of
from .variants import BaseSpec, base_of, load_base, variant_spec

__all__ = ["Row", "evaluate_chunk", "Plan", "plan_of", "BaseSpec", "base_of",
           "load_base", "variant_spec"]
