"""The statistics of a tolerance analysis, from its samples (:mod:`.tolerance`): what the
report, the files and summary.json say, each computed once here.

- **Kept quantities**, over the ``ok`` samples: mean, standard deviation (``ddof=1``), the
  5th, 95th and 99th percentiles (``numpy.percentile``, linear interpolation between order
  statistics), smallest and largest; the nominal value is the spec as written.
- **Probabilities** (each design verdict, every verdict together, assembly): the fraction
  of all samples, with a 95 % Clopper-Pearson interval (exact binomial: its coverage is at
  least 95 % for every true probability and sample size, and it stays inside [0, 1] when no
  or every sample passes). A sample that is not ``ok`` counts as not passing (a machine whose
  numbers cannot be trusted is not known to pass). For a Latin hypercube the binomial
  interval is conservative (stratified samples vary less than independent ones).
- **Ranking**, per kept quantity: the share of its variance each tolerance explains, by
  squared standardised regression coefficients: ``y`` regressed linearly on every varied
  value (least squares, with an intercept, over the ``ok`` samples), ``SRC_i = b_i s_i /
  s_y``, share ``SRC_i^2`` (scaled so that the shares add up to R^2 exactly: the sampled
  values are independent only to within their sampling correlations). Tolerances are small next to the dimensions, so a quantity is
  close to linear in them over the tolerance box; then ``SRC_i^2`` is tolerance i's
  first-order variance share, the shares add up to the regression's R^2 (reported: how much
  of the variance the linear ranking accounts for) and the estimate converges at the rate of
  a regression, not of a histogram, so a few hundred samples rank them.
"""
from __future__ import annotations

import math
import re
from collections import Counter
from dataclasses import dataclass, field
from fnmatch import fnmatchcase

import numpy as np

from ..quantities import unit_of
from .table import badness

CONFIDENCE = 0.95
_NUMBER = re.compile(r"\d+(?:\.\d+)?(?:[eE][-+]?\d+)?")
_DIFFER = "; its numbers differ from sample to sample)"
#: a sample's status (see :mod:`.tolerance`)
STATUSES = ("ok", "invalid", "no assembly", "untrusted", "failed")
PERCENTILES = (5, 95, 99)
#: a quantity whose standard deviation is below this fraction of its magnitude does not vary
#: with the tolerances (its spread is round-off): it is not ranked
VARIES_RTOL = 1e-9

__all__ = ["ToleranceResult", "QuantityStats", "Probability", "Ranking", "analyse_samples",
           "clopper_pearson", "src_shares", "CONFIDENCE"]


@dataclass(frozen=True)
class QuantityStats:
    """One kept quantity over the ok samples [SI, ``unit``]; ``limit`` the design limit
    judged on it (None if none; ``at_least`` for a lower limit, ``item`` its design key)."""

    quantity: str
    unit: str
    nominal: float
    n: int
    mean: float
    std: float
    p5: float
    p95: float
    p99: float
    low: float
    high: float
    limit: float | None = None
    at_least: bool = False
    item: str = ""


@dataclass(frozen=True)
class Probability:
    """``k`` of ``n`` samples: ``p`` with its 95 % Clopper-Pearson interval ``low`` ..
    ``high``. ``name``: a design item, ``design`` (every verdict) or ``assembly``;
    ``nominal``: whether the spec as written passes (None for assembly)."""

    name: str
    k: int
    n: int
    p: float
    low: float
    high: float
    nominal: bool | None = None
    quantity: str = ""
    limit: float | None = None
    unit: str = ""


@dataclass(frozen=True)
class Ranking:
    """The tolerances ranked for one quantity: ``shares`` ((key, share), largest first),
    ``r2`` the linear regression's R^2 (None when the quantity does not vary or there are
    too few samples), ``n`` the samples used."""

    quantity: str
    shares: tuple[tuple[str, float], ...]
    r2: float | None
    n: int


@dataclass
class ToleranceResult:
    """Everything a tolerance analysis says (see the module docstring)."""

    base: object
    table: object
    nominal: object
    nominal_verdicts: list
    method: str
    method_why: str
    seconds: float
    lost: list = field(default_factory=list)
    quantities: list[QuantityStats] = field(default_factory=list)
    verdicts: list[Probability] = field(default_factory=list)
    design: Probability | None = None
    assembly: Probability | None = None
    ranking: list[Ranking] = field(default_factory=list)
    counts: dict[str, int] = field(default_factory=dict)
    reasons: list[tuple[str, str, int, list[int]]] = field(default_factory=list)
    worst: int | None = None
    worst_why: str = ""

    @property
    def plan(self):
        return self.table.plan

    @property
    def spec(self):
        return self.base.spec

    def summary(self) -> dict[str, dict]:
        """summary.json's ``tolerance.*`` quantities: name -> {value, unit} (SI)."""
        return summary_quantities(self)


# --------------------------------------------------------------------------- estimators

def clopper_pearson(k: int, n: int, confidence: float = CONFIDENCE) -> tuple[float, float]:
    """The exact (Clopper-Pearson) two-sided interval of a binomial proportion ``k / n``."""
    from scipy.stats import beta
    if n <= 0:
        return 0.0, 1.0
    a = (1.0 - confidence) / 2.0
    low = 0.0 if k <= 0 else float(beta.ppf(a, k, n - k + 1))
    high = 1.0 if k >= n else float(beta.ppf(1.0 - a, k + 1, n - k))
    return low, high


def src_shares(x: np.ndarray, y: np.ndarray) -> tuple[np.ndarray, float | None]:
    """Squared standardised regression coefficients of ``y`` (m,) on the columns of ``x``
    (m, d), and the regression's R^2; zeros and None when ``y`` does not vary or there are
    fewer than d + 2 samples. A column that does not vary gets 0."""
    m, d = x.shape
    out = np.zeros(d)
    sy = float(np.std(y, ddof=1)) if m > 1 else 0.0
    if m < d + 2 or not varies(sy, y):
        return out, None
    sx = np.std(x, axis=0, ddof=1)
    use = sx > 0
    xs = (x[:, use] - x[:, use].mean(axis=0)) / sx[use]
    ys = (y - y.mean()) / sy
    coef, *_ = np.linalg.lstsq(xs, ys, rcond=None)
    resid = ys - xs @ coef
    r2 = max(0.0, min(1.0, 1.0 - float(resid @ resid) / float(ys @ ys)))
    src2 = coef ** 2
    total = float(src2.sum())
    # the sampled values are independent only to within sampling correlations (of order
    # 1/sqrt(m)), so the raw SRC^2 add up to R^2 only nearly: scaled to add up to it exactly
    out[use] = src2 * (r2 / total) if total > 0 else src2
    return out, r2


def varies(std: float, values: np.ndarray) -> bool:
    """Whether values with standard deviation ``std`` vary by more than round-off (1e-9 of
    their magnitude)."""
    scale = float(np.max(np.abs(values))) if len(values) else 0.0
    return std > VARIES_RTOL * scale and std > 0


def limit_of(quantity: str, verdicts) -> tuple[float | None, bool, str]:
    """(limit, at_least, item) of the design verdict judged on ``quantity`` (a verdict on
    ``joint.*.f_max`` judges every joint's), (None, False, "") when none is."""
    for v in verdicts:
        if v.quantity == quantity or ("*" in v.quantity and fnmatchcase(quantity, v.quantity)):
            return float(v.limit), bool(v.at_least), v.item
    return None, False, ""


def _probability(name: str, k: int, n: int, **kw) -> Probability:
    low, high = clopper_pearson(k, n)
    return Probability(name, int(k), int(n), k / n if n else math.nan, low, high, **kw)


# ------------------------------------------------------------------------------ analyse

def analyse_samples(base, table, nominal, verdicts, method: str, why: str, seconds: float,
                    lost=()) -> ToleranceResult:
    """The :class:`ToleranceResult` of a filled sample table."""
    r = ToleranceResult(base, table, nominal, list(verdicts), method, why, seconds, list(lost))
    ok = table.ok
    n = table.n
    for j, q in enumerate(table.keep):
        col = table.values[ok, j]
        col = col[np.isfinite(col)]
        limit, at_least, item = limit_of(q, verdicts)
        if len(col):
            p5, p95, p99 = (float(x) for x in np.percentile(col, PERCENTILES))
            # one ok sample has no spread to measure: undefined (never a 0 that says the
            # tolerances do not move the quantity)
            std = float(np.std(col, ddof=1)) if len(col) > 1 else math.nan
            stats = (float(np.mean(col)), std, p5, p95, p99, float(col.min()), float(col.max()))
        else:
            stats = (math.nan,) * 7
        r.quantities.append(QuantityStats(q, unit_of(q) or "", float(nominal.values[j]),
                                          int(len(col)), *stats, limit, at_least, item))
    for k, v in enumerate(verdicts):
        passed = int(np.count_nonzero(ok & (table.passes[:, k] == 1))) if n else 0
        r.verdicts.append(_probability(v.item, passed, n, nominal=bool(v.passed),
                                       quantity=v.quantity, limit=float(v.limit), unit=v.unit))
    design = table.design_pass
    r.design = _probability("design", int(np.count_nonzero(design == 1)), n,
                            nominal=all(v.passed for v in verdicts))
    # known to assemble: a sample lost with its worker, or whose analysis stopped with an
    # error, is not (as a verdict it is not known to pass, it is not known to assemble)
    built = int(np.count_nonzero(table.assembled))
    r.assembly = _probability("assembly", built, n)
    x = table.plan.values
    for j, q in enumerate(table.keep):
        sel = ok & np.isfinite(table.values[:, j])
        shares, r2 = src_shares(x[sel], table.values[sel, j])
        order = np.argsort(-shares, kind="stable")
        r.ranking.append(Ranking(q, tuple((table.plan.keys[i], float(shares[i])) for i in order),
                                 r2, int(np.count_nonzero(sel))))
    r.counts = {s: int(np.count_nonzero(table.has(s))) for s in STATUSES}
    r.reasons = _reasons(table)
    r.worst, r.worst_why = _worst(table, verdicts)
    return r


def _reasons(table) -> list[tuple[str, str, int, list[int]]]:
    """(status, reason, count, first three sample numbers) for every sample not ok, the most
    frequent first."""
    groups: Counter = Counter()
    first: dict[tuple[str, str], list[int]] = {}
    text: dict[tuple[str, str], str] = {}
    for i, (s, why) in enumerate(zip(table.status, table.reason)):
        if s == "ok":
            continue
        key = (s, _NUMBER.sub("#", why))    # one reason per kind, whatever the values drawn
        groups[key] += 1
        lst = first.setdefault(key, [])
        if len(lst) < 3:
            lst.append(i + 1)
        if key not in text:
            text[key] = why
        elif text[key] != why and not text[key].endswith(_DIFFER):
            text[key] = f"{text[key]} (sample {lst[0]}{_DIFFER}"
    return [(key[0], text[key], c, first[key]) for key, c in groups.most_common()]


def _worst(table, verdicts) -> tuple[int | None, str]:
    """The worst ok sample: the smallest margin over the design verdicts (the one that fails
    by most, or passes by least); without verdicts, the worst first kept quantity."""
    ok = np.flatnonzero(table.ok)
    if not len(ok):
        return None, ""
    if len(verdicts):
        m = table.margins[ok]
        has = np.isfinite(m).any(axis=1)
        if has.any():
            least = np.where(np.isfinite(m), m, np.inf).min(axis=1)
            least[~has] = np.inf
            k = int(np.argmin(least))
            j = int(np.nanargmin(np.where(np.isfinite(m[k]), m[k], np.inf)))
            return int(ok[k]), (f"the smallest margin of any design verdict: "
                                f"{verdicts[j].item} {least[k]:+.1%} of its limit")
    q = table.keep[0]
    bad = badness(q, table.values[ok, 0])
    if not np.isfinite(bad).any():
        return None, ""
    k = int(np.nanargmax(bad))
    return int(ok[k]), f"the worst {q}"


# ---------------------------------------------------------------------------- summary

def summary_quantities(r: ToleranceResult) -> dict[str, dict]:
    """``tolerance.<quantity>.nominal|mean|std|p5|p95|p99`` (the quantity's SI unit),
    ``tolerance.<design item>.p_pass|p_pass_low|p_pass_high``,
    ``tolerance.design.p_pass...`` (every verdict), ``tolerance.assembly.p|p_low|p_high`` and
    ``tolerance.samples``, ``tolerance.samples_ok``: name -> {value, unit}."""
    out: dict[str, dict] = {}

    def put(name: str, value, unit: str = "") -> None:
        if value is None or (isinstance(value, float) and not math.isfinite(value)):
            return
        out[name] = {"value": value, "unit": unit}

    put("tolerance.samples", int(r.table.n))
    put("tolerance.samples_ok", int(r.counts.get("ok", 0)))
    for s in r.quantities:
        base = f"tolerance.{s.quantity}"
        for attr in ("nominal", "mean", "std", "p5", "p95", "p99"):
            put(f"{base}.{attr}", float(getattr(s, attr)), s.unit)
    for p in r.verdicts + ([r.design] if r.design is not None and r.verdicts else []):
        put(f"tolerance.{p.name}.p_pass", p.p)
        put(f"tolerance.{p.name}.p_pass_low", p.low)
        put(f"tolerance.{p.name}.p_pass_high", p.high)
    if r.assembly is not None:
        put("tolerance.assembly.p", r.assembly.p)
        put("tolerance.assembly.p_low", r.assembly.low)
        put("tolerance.assembly.p_high", r.assembly.high)
    return out
