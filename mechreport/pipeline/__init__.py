"""The pipeline: a spec in, every result out, the checks judged.

:mod:`.analysis` (one spec in memory: :func:`analyse`), :mod:`.streamed` (a long sweep
checked chunk by chunk in bounded memory), :mod:`.batch` (many variants of one spec solved
as one stacked batch, for studies). Everything above (report, study, the command line) reads
the records these return.
"""
from .analysis import DEFAULT_TOL, Analysis, analyse

__all__ = ["Analysis", "analyse", "DEFAULT_TOL"]
