"""Moved to :mod:`mechreport.study.run` (the executor: :mod:`mechreport.study.executor` and
:mod:`mechreport.study.cluster`). This name remains only for tests outside the study's that
still import ``run_variants`` from here (tests/dynamics, tests/report); import it from
:mod:`mechreport.study.run` instead."""
from __future__ import annotations

from ..study.run import run_variants

__all__ = ["run_variants"]
