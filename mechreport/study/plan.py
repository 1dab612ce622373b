"""The study section -> the variants: which value each varied key takes in each variant.

- **grid**: every combination. A ``from``/``to``/``count`` entry gives ``count`` values evenly
  spaced from ``from`` to ``to``, both included; a ``values`` entry gives its values. The first
  key varies slowest (variant 1 takes the first value of every key, variant 2 the second value
  of the last key, ...), as nested loops written in ``vary`` order would.
- **random**: ``count`` variants, each key drawn independently: uniform in [from, to], or
  uniformly among its ``values``.
- **lhs**: ``count`` variants of a Latin hypercube (``scipy.stats.qmc.LatinHypercube``): each
  key's range is cut into ``count`` equal strata and every stratum is used exactly once; a
  ``values`` key takes the value of the stratum its draw falls in (so each value is used
  equally often, to within one).

random and lhs are drawn from ``numpy.random.default_rng(seed)``: the same spec and seed give
the same variants, whatever the chunk size, the number of workers or the scheduler.
Values are in the spec's own units, as written in ``vary``.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..spec import Study, Vary

#: how the reports and the terminal name a ``sample`` method (``<name> sampling``)
SAMPLING_NAMES = {"grid": "grid", "random": "random", "lhs": "Latin hypercube"}


@dataclass(frozen=True)
class Plan:
    """The variants of a study: ``keys`` (the varied key paths, as written) and ``values``
    (n, len(keys)) [the spec's units], row i being variant i + 1."""

    keys: tuple[str, ...]
    values: np.ndarray
    sample: str
    seed: int

    @property
    def n(self) -> int:
        return int(self.values.shape[0])

    def variant(self, i: int) -> dict[str, float]:
        """Variant ``i`` (0-based) as {key: value}."""
        return {k: float(v) for k, v in zip(self.keys, self.values[i])}

    def chunk(self, start: int, stop: int) -> list[dict[str, float]]:
        """Variants ``start`` .. ``stop - 1`` as {key: value} dicts."""
        return [{k: float(v) for k, v in zip(self.keys, row)}
                for row in self.values[start:stop]]


def levels(v: Vary) -> np.ndarray:
    """The grid values of one varied key."""
    if v.values is not None:
        return np.asarray(v.values, float)
    return np.linspace(v.start, v.stop, int(v.count))


def plan_of(study: Study) -> Plan:
    """Every variant of ``study`` (see the module docstring)."""
    keys = tuple(v.key for v in study.vary)
    d = len(study.vary)
    if study.sample == "grid":
        axes = [levels(v) for v in study.vary]
        grids = np.meshgrid(*axes, indexing="ij")          # first key slowest
        values = np.stack([g.reshape(-1) for g in grids], axis=1) if d else np.zeros((1, 0))
        return Plan(keys, values, "grid", study.seed)
    n = int(study.count)
    unit = unit_samples(study.sample, n, d, study.seed)
    values = np.empty((n, d))
    for j, v in enumerate(study.vary):
        u = unit[:, j]
        if v.values is not None:
            options = np.asarray(v.values, float)
            pick = np.minimum((u * len(options)).astype(np.int64), len(options) - 1)
            values[:, j] = options[pick]
        else:
            values[:, j] = v.start + u * (v.stop - v.start)
    return Plan(keys, values, study.sample, study.seed)


def unit_samples(sample: str, n: int, d: int, seed) -> np.ndarray:
    """``n`` points (n, d) in [0, 1]^d of the ``sample`` kind (``random``, else a Latin
    hypercube) from the generator of ``seed``: a study's and a tolerance analysis's draw."""
    rng = np.random.default_rng(seed)
    return rng.random((n, d)) if sample == "random" else _latin_hypercube(d, n, rng)


def _latin_hypercube(d: int, n: int, rng: np.random.Generator) -> np.ndarray:
    """``n`` points of a Latin hypercube in [0, 1]^d drawn from ``rng`` (the one sampler of
    the study's ``lhs``, the tolerance analysis's and the optimiser's first population)."""
    from scipy.stats import qmc
    try:
        sampler = qmc.LatinHypercube(d=d, rng=rng)
    except TypeError:                           # scipy < 1.15 names it ``seed``
        sampler = qmc.LatinHypercube(d=d, seed=rng)
    return sampler.random(n)
