"""Design optimisation: the feasible design with the best objective in the box of
``optimize.vary``, found by scipy and proven before it is reported.

    from mechreport import optimize
    result = optimize("specs/four_bar_optimize.yaml", jobs=2)
    result.feasible, result.values, result.objective     # {key: value} in the spec's units

**The search.** ``scipy.optimize.differential_evolution`` over the box (each key scaled to
[0, 1]), its whole population evaluated at once per generation (``vectorized=True``): the
population is one batch of candidates computed as a study computes its variants (chunks on
the local process pool, kept running between generations, or a Dask cluster), each judged by
:mod:`.optimize_eval` (the design verdicts, the bounds, the branch, the left-out angles, the
trust test). Differential evolution needs no gradient, is not misled by the kinks of max and
min quantities, accepts infeasible candidates ranked by their violation (Deb's rule, here as
one score: :func:`~.optimize_eval.score`), and is reproducible from its seed.

**The polish.** Where the objective is smooth in the varied values (an RMS, a mean, a
bearing's cube-mean load and life, the balance quantities: integrals over the cycle, not
extremes), the best feasible design is polished by SLSQP (scipy's local method with
inequality constraints: the margins of every verdict and bound), started from it and kept
only if it is feasible and better. Extremes (``.max``, ``.min``, the flywheel inertia, the
energy fluctuation) are not polished: their gradients jump where the extreme moves from one
angle to another.

**The proof.** The best feasible design is written into the spec's own text (optimum.yaml),
read back, re-analysed by every force method and checked as ``mechreport check`` does
(methods agreeing, every verdict) and judged again. A design that fails that is not the
optimum: the next best feasible one is tried (at most ``MAX_PROOFS``).

**The budget** counts the candidates evaluated (history.csv's rows): differential evolution
gets what the polish does not reserve (``POLISH_SHARE`` of it, at most ``POLISH_MAX``); the
proofs' full analyses are not counted.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from .optimize_eval import Constraint, Judged, Problem, judge_chunk, judge_outcome, score
from .plan import _latin_hypercube
from .variants import BaseSpec, section_base

#: share of the budget kept for the polish, and its most evaluations
POLISH_SHARE = 0.15
POLISH_MAX = 300
#: feasible designs tried by the proof, best first
MAX_PROOFS = 5
#: a constraint is active at the optimum when its relative margin is at most this
ACTIVE = 1e-3
#: differential evolution's relative tolerance on the spread of the population's scores
DE_TOL = 1e-6

SMOOTH_NAMES = ("rms", "mean", "f_mean", "f_equivalent", "life_h")


def smooth(quantity: str) -> bool:
    """Whether ``quantity`` is smooth in the design's numbers (an integral over the cycle,
    not an extreme; see the module docstring)."""
    last = quantity.rpartition(".")[2]
    return (quantity.startswith("balance.") or last in SMOOTH_NAMES
            or last.endswith(("_rms", "_mean")))


@dataclass
class History:
    """Every evaluation in order: ``values`` (n, d) [spec units], ``judged``, ``phase``
    ("search" or "polish"), ``generation`` (0: the initial population)."""

    values: list[np.ndarray] = field(default_factory=list)
    judged: list[Judged] = field(default_factory=list)
    phase: list[str] = field(default_factory=list)
    generation: list[int] = field(default_factory=list)

    @property
    def n(self) -> int:
        return len(self.judged)

    def add(self, values: np.ndarray, judged: list[Judged], phase: str, gen: int) -> None:
        for v, j in zip(values, judged):
            self.values.append(np.asarray(v, float))
            self.judged.append(j)
            self.phase.append(phase)
            self.generation.append(gen)

    def feasible(self) -> np.ndarray:
        return np.array([j.feasible for j in self.judged], bool)

    def ranked(self, problem: Problem) -> list[int]:
        """Indices of the feasible evaluations, best first, each design once."""
        sign = -1.0 if problem.maximize else 1.0
        idx = [i for i, j in enumerate(self.judged) if j.feasible]
        idx.sort(key=lambda i: (sign * self.judged[i].objective, i))
        seen, out = set(), []
        for i in idx:
            k = tuple(np.round(self.values[i], 12))
            if k not in seen:
                seen.add(k)
                out.append(i)
        return out

    def least_violating(self) -> int | None:
        if not self.judged:
            return None
        return int(np.argmin([j.violation for j in self.judged]))


@dataclass
class Proof:
    """One proof attempt: the evaluation ``index``, whether it held, and why not."""

    index: int
    ok: bool
    why: str = ""


@dataclass
class OptimizeResult:
    """What ``mechreport optimize`` found (see the module docstring). ``optimum``: the
    history index of the proven optimum (None: no feasible design); ``least``: the least
    violating design when none is feasible; ``analysis``: the optimum's full analysis
    (every method) and ``text`` its spec (optimum.yaml); ``original``: the spec's own design
    judged, ``original_analysis`` its full analysis; ``start``: its values."""

    problem: Problem
    history: History
    original: Judged
    original_analysis: object
    start: dict[str, float]
    optimum: int | None = None
    least: int | None = None
    proofs: list[Proof] = field(default_factory=list)
    analysis: object = None
    text: str = ""
    seconds: float = 0.0
    where: str = "this process"
    message: str = ""
    polished: bool = False
    generations: int = 0
    budget: int | None = None
    seed: int | None = None

    @property
    def feasible(self) -> bool:
        return self.optimum is not None

    @property
    def keys(self) -> tuple[str, ...]:
        return self.problem.keys

    @property
    def best(self) -> int | None:
        """The optimum, else the least violating design."""
        return self.optimum if self.optimum is not None else self.least

    @property
    def values(self) -> dict[str, float]:
        """The optimum's (else the least violating design's) values [spec units]."""
        i = self.best
        return {} if i is None else {k: float(v) for k, v in
                                     zip(self.keys, self.history.values[i])}

    @property
    def judged(self) -> Judged | None:
        """The optimum's (else the least violating design's) judgement; a least violating
        design that the search found feasible but whose proof failed carries that failure
        as a fault (so that what it misses is told)."""
        i = self.best
        if i is None:
            return None
        j = self.history.judged[i]
        if self.optimum is None:
            why = next((p.why for p in self.proofs if p.index == i and not p.ok), None)
            if why is not None:
                from dataclasses import replace
                j = replace(j, faults=j.faults + (f"its proof failed: {why}",))
        return j

    @property
    def objective(self) -> float:
        j = self.judged
        return math.nan if j is None else j.objective

    def active(self) -> list[tuple[Constraint, float]]:
        """The constraints active at the optimum: (constraint, margin) with margin at most
        ``ACTIVE``, and the box's ends reached, as constraints on their key."""
        j = self.judged
        if j is None or self.optimum is None:
            return []
        return [(c, m) for c, m in zip(self.problem.constraints, j.margins) if m <= ACTIVE]

    def at_box(self) -> list[str]:
        """The varied keys at an end of their range at the optimum ("key = from")."""
        out = []
        if self.optimum is None:
            return out
        for v, x in zip(self.problem.base.spec.optimize.vary, self.history.values[self.optimum]):
            span = abs(v.stop - v.start)
            for end, name in ((v.start, "from"), (v.stop, "to")):
                if abs(x - end) <= ACTIVE * span:
                    out.append(f"{v.key} at its '{name}' end ({end:g})")
        return out


# ------------------------------------------------------------------------------ setup

def optimize_base(spec, src) -> BaseSpec:
    """The :class:`BaseSpec` of a validated ``spec`` (with an ``optimize`` section) read from
    ``src``: its data tree without ``study``, ``expect`` and ``optimize``, the varied paths
    those of ``optimize.vary``."""
    return section_base(spec, src, spec.optimize.vary, ("optimize",))


def load_optimize_base(spec) -> BaseSpec:
    """The :class:`BaseSpec` of a path, YAML text or BaseSpec; ``SpecError`` if the spec is
    not valid or has no ``optimize:`` section."""
    from ..errors import Problem as SpecProblem, SpecError
    from ..spec.loader import load_source, parse_source, spec_from_data
    if isinstance(spec, BaseSpec):
        return spec
    src = (parse_source(spec, "<text>") if isinstance(spec, str) and "\n" in spec
           else load_source(Path(spec)))
    s = spec_from_data(src.data, src)
    if s.optimize is None:
        raise SpecError([SpecProblem(src.filename, None, "", (
            "this spec has no 'optimize:' section; `mechreport optimize` needs one saying "
            "what to vary, what to minimize or maximize and subject to what (docs/spec.md, "
            "section 'Design optimisation')"))])
    return optimize_base(s, src)


def problem_of(base: BaseSpec, method: str | None = None):
    """(the :class:`Problem`, the original design's full analysis, why this method)."""
    from ..pipeline import analyse
    from ..spec.loader import spec_from_data
    from .methods import choose_method
    opt = base.spec.optimize
    quantities = tuple(dict.fromkeys([opt.objective] + [b.quantity for b in opt.bounds]))
    method, why = choose_method(method, quantities, base.spec.design, named="--method")
    original = spec_from_data(base.data, base.source)
    a = analyse(original)
    from .evaluate import row_of
    # the original's values of the quantities read, cycle and member quantities alike (a
    # member's stress in Pa scaled by 1 left the search's scores equal to 1e-8: it stopped)
    got = dict(zip(quantities, row_of(a, quantities).values))

    def size(q: str) -> float:
        v = got.get(q, math.nan)
        return abs(v) if math.isfinite(v) else 0.0
    constraints = [Constraint("design", v.item, v.quantity) for v in a.verdicts]
    for b in opt.bounds:
        scale = max(abs(b.low or 0.0), abs(b.high or 0.0), size(b.quantity)) or 1.0
        constraints.append(Constraint("bound", b.quantity, b.quantity, b.low, b.high, scale,
                                      b.unit))
    scale = size(opt.objective) or 1.0
    problem = Problem(base, method, opt.objective, opt.maximize, quantities,
                      tuple(constraints),
                      tuple((b.dyad, b.sign) for b in a.kinematics.branches
                            if b.rule != "unique"),
                      frozenset(round(float(f.angle), 9) for f in a.kinematics.flags),
                      len(original.analysed_angles()), scale)
    return problem, a, why


def start_values(base: BaseSpec) -> dict[str, float]:
    """The varied values as the spec has them [spec units]."""
    out = {}
    for v in base.spec.optimize.vary:
        node = base.data
        for part in v.path:
            node = node[part]
        out[v.key] = float(node)
    return out


# ----------------------------------------------------------------------------- search

class _Stop(Exception):
    """The budget is spent (raised inside scipy's loop, caught here)."""


def run_optimize(base: BaseSpec, *, method: str | None = None, jobs: int = 1, client=None,
                 budget: int | None = None, seed: int | None = None, progress=None,
                 notify=None, stop_check=None, setup=None, chunk: int | None = None,
                 prepared=None) -> OptimizeResult:
    """Search, polish and prove (see the module docstring). ``jobs``: local processes (1: in
    this process); ``client``: a connected Dask client instead; ``budget``, ``seed``: the
    spec's unless given; ``progress(done, infeasible, total)`` after each batch;
    ``notify``, ``stop_check``, ``setup``: as the study's executor; ``prepared``: the
    result of :func:`problem_of` when already computed."""
    from scipy.optimize import differential_evolution

    from .executor import stop_pools
    from .run import run_chunks
    opt = base.spec.optimize
    budget = int(budget if budget is not None else opt.budget)
    seed = int(seed if seed is not None else opt.seed)
    problem, original_analysis, _why = prepared or problem_of(base, method)
    original = judge_outcome(problem, original_analysis)
    lo = np.array([v.start for v in opt.vary])
    hi = np.array([v.stop for v in opt.vary])
    d = len(lo)
    history = History()
    state = {"gen": 0, "infeasible": 0}
    polish_budget = min(POLISH_MAX, int(POLISH_SHARE * budget)) if smooth(opt.objective) else 0
    de_budget = budget - polish_budget
    pop = max(2, min(15, de_budget // (8 * d)), math.ceil(5 / d))
    size_pop = pop * d
    init = "latinhypercube"
    if size_pop > de_budget:          # many keys, a small budget: a smaller first population
        size_pop = max(5, de_budget)
        init = _latin_hypercube(d, size_pop, np.random.default_rng([seed, 1]))
    maxiter = max(0, de_budget // size_pop - 1)
    # the spec's own design, where it lies in the box, is a member of the first population:
    # the search never reports a box as infeasible, nor an optimum worse than the original,
    # when the original is a feasible design of that box
    u_start = (np.array([start_values(base)[v.key] for v in opt.vary]) - lo) / (hi - lo)
    x0 = u_start if np.all((u_start >= 0.0) & (u_start <= 1.0)) else None
    if client is not None:
        from .cluster import dask_workers
        parts = dask_workers(client)
    else:
        parts = max(1, jobs)
    kept: list = []
    t0 = time.perf_counter()

    def evaluate(values: np.ndarray, phase: str) -> list[Judged]:
        n = len(values)
        out: list = [None] * n
        size = chunk or max(1, math.ceil(n / parts))      # one chunk per worker

        def on_done(_chunk, result):
            start, rows = result
            out[start:start + len(rows)] = rows

        def args_of(c):
            return c[0], values[c[0]:c[1]]

        def on_lost(a, b, reason):
            from .optimize_eval import failed
            out[a:b] = [failed(problem, reason)] * (b - a)
        run_chunks(judge_chunk, problem, n, size, args_of, on_done,
                   jobs=jobs if client is None else 0, client=client, on_lost=on_lost,
                   notify=notify, stop_check=stop_check, setup=setup, kept=kept)
        history.add(values, out, phase, state["gen"])
        state["infeasible"] += sum(not j.feasible for j in out)
        if progress is not None:
            progress(history.n, state["infeasible"], budget)
        return out

    def population(u: np.ndarray) -> np.ndarray:
        u = np.atleast_2d(u.T if u.ndim == 2 else u[:, None].T)
        if history.n + len(u) > de_budget and history.n:
            raise _Stop()                     # the search's share of the budget is spent
        values = lo + np.clip(u, 0.0, 1.0) * (hi - lo)
        judged = evaluate(values, "search")
        state["gen"] += 1
        return np.array([score(problem, j) for j in judged])

    message = "the search's share of the budget is spent"
    polished = False
    try:
        try:
            how = dict(popsize=pop, maxiter=maxiter, tol=DE_TOL, polish=False,
                       vectorized=True, updating="deferred", init=init, x0=x0)
            try:
                res = differential_evolution(population, [(0.0, 1.0)] * d,
                                             rng=np.random.default_rng(seed), **how)
            except TypeError:               # scipy < 1.15 names it ``seed``
                if history.n:
                    raise
                res = differential_evolution(population, [(0.0, 1.0)] * d,
                                             seed=np.random.default_rng(seed), **how)
            message = str(res.message)
        except _Stop:
            pass
        if polish_budget and history.ranked(problem):
            polished = _polish(problem, history, lo, hi, polish_budget, evaluate)
    finally:
        stop_pools(kept)
    result = OptimizeResult(problem, history, original, original_analysis,
                            start_values(base), message=message, polished=polished,
                            generations=state["gen"], budget=budget, seed=seed)
    prove(result)
    result.seconds = time.perf_counter() - t0
    return result


def _polish(problem: Problem, history: History, lo, hi, budget: int, evaluate) -> bool:
    """SLSQP from the best feasible design (see the module docstring), evaluations one at a
    time in this process' executor call; whether it found a better feasible design."""
    from scipy.optimize import minimize
    best = history.ranked(problem)[0]
    u0 = (history.values[best] - lo) / (hi - lo)
    cache: dict[tuple, Judged] = {}
    spent = {"n": 0}
    sign = -1.0 if problem.maximize else 1.0

    def judged(u) -> Judged:
        u = np.clip(np.asarray(u, float), 0.0, 1.0)
        key = tuple(u)
        if key not in cache:
            if spent["n"] >= budget:
                raise _Stop()
            spent["n"] += 1
            cache[key] = evaluate((lo + u * (hi - lo))[None, :], "polish")[0]
        return cache[key]

    def fun(u) -> float:
        j = judged(u)
        return sign * j.objective / problem.scale if math.isfinite(j.objective) else 1e6

    def margins(u) -> np.ndarray:
        j = judged(u)
        m = np.nan_to_num(np.asarray(j.margins, float), nan=-1.0)
        structural = -1.0 if j.faults else 0.0
        return np.append(m, structural)

    try:
        minimize(fun, u0, method="SLSQP", bounds=[(0.0, 1.0)] * len(u0),
                 constraints=[{"type": "ineq", "fun": margins}],
                 options={"maxiter": 100, "ftol": 1e-12, "eps": 1e-7})
    except _Stop:
        pass
    return bool(history.ranked(problem)) and history.ranked(problem)[0] != best


# ------------------------------------------------------------------------------ proof

def value_change(key: str, value: float, start: float) -> str:
    """``ground.D.0 = 183.3340996 (was 200)``: a varied key's value and the spec's own, in
    the spec's units, as the terminal, the optimum's report and optimum.yaml's header say
    it."""
    return f"{key} = {value:.10g} (was {start:.10g})"


def header_of(result: OptimizeResult, index: int, optimum: bool = True) -> str:
    """optimum.yaml's header: where its values come from (``optimum`` False: the least
    violating design of a search that found no feasible one, and what it misses)."""
    base = result.problem.base
    sense = (f"{'maximize' if result.problem.maximize else 'minimize'} "
             f"{result.problem.objective}")
    if optimum:
        lines = [f"The optimum of {Path(base.file).name} found by mechreport optimize "
                 f"({sense}):"]
    else:
        lines = [f"NOT an optimum: mechreport optimize found no feasible design of "
                 f"{Path(base.file).name} ({sense}). These are the values of the least "
                 "violating design, which misses:"]
        j = result.judged
        lines += [f"  {line}" for line in (j.missed(result.problem) if j is not None else [])]
        lines.append("Its values:")
    for k, v in zip(result.keys, result.history.values[index]):
        lines.append(f"  {value_change(k, v, result.start[k])}")
    return "\n".join(lines)


def text_of(result: OptimizeResult, index: int, optimum: bool = True) -> str:
    """The spec text of evaluation ``index``: the user's text with its values written in
    (:mod:`.optimize_yaml`), checked to read back as that design (``optimum``: see
    :func:`header_of`)."""
    from .optimize_yaml import check_text_gives, optimum_text
    from .variants import replaced, _plain
    base = result.problem.base
    values = dict(zip(result.keys, result.history.values[index]))
    text = optimum_text(base.source.text, base.paths, values,
                        header_of(result, index, optimum))
    data = replaced(base.source.data, {base.paths[k]: _plain(v) for k, v in values.items()})
    check_text_gives(text, data, base.file)
    return text


def prove(result: OptimizeResult) -> None:
    """Try the feasible designs best first (at most ``MAX_PROOFS``): the first whose spec
    text, read back, passes every method's analysis and the check is the optimum. Without
    one, ``least`` is the least violating design."""
    from ..pipeline import analyse
    from ..report.check_text import problems
    from ..spec import parse_spec
    problem, history = result.problem, result.history
    for i in history.ranked(problem)[:MAX_PROOFS]:
        try:
            text = text_of(result, i)
            a = analyse(parse_spec(text, "optimum.yaml"))
            j = judge_outcome(problem, a)
        except Exception as exc:  # noqa: BLE001 - a design that cannot be proven is not it
            from .evaluate import reason_of
            result.proofs.append(Proof(i, False, reason_of(exc, "optimum.yaml")))
            continue
        if a.passed and j.feasible:
            result.proofs.append(Proof(i, True))
            result.optimum, result.analysis, result.text = i, a, text
            return
        why = "; ".join(problems(a, a.tol)[:3] + j.missed(problem)[:3]) or "the check fails"
        result.proofs.append(Proof(i, False, why))
    # without a proven optimum: the best design the search found feasible whose proof failed
    # (it misses only its proof, which says why), else the least violating one
    refused = [p.index for p in result.proofs if not p.ok]
    result.least = None if result.optimum is not None else (
        refused[0] if refused else history.least_violating())
    if result.optimum is None and result.least is not None:
        try:
            result.text = text_of(result, result.least, optimum=False)
        except Exception:  # noqa: BLE001 - the least violating design's text is a courtesy
            result.text = ""


def optimize(spec, *, jobs: int | None = None, scheduler: str | None = None,
             budget: int | None = None, seed: int | None = None,
             method: str | None = None, progress=None) -> OptimizeResult:
    """Run the optimisation of ``spec`` (a path, YAML text or BaseSpec with an ``optimize:``
    section) as ``mechreport optimize`` does and return its :class:`OptimizeResult`:
    ``feasible``, ``values`` (the optimum's, in the spec's units), ``objective`` [SI],
    ``text`` (optimum.yaml), ``history``. ``jobs``: local processes (default 1: in this
    process); ``scheduler``: a Dask scheduler address instead; ``budget``, ``seed``: the
    spec's unless given. Nothing is printed or written."""
    from .cluster import close_client, connect
    base = load_optimize_base(spec)
    client = connect(scheduler) if scheduler is not None else None
    try:
        return run_optimize(base, method=method, jobs=jobs or 1, client=client,
                            budget=budget, seed=seed, progress=progress)
    finally:
        if client is not None:
            close_client(client)


# ---------------------------------------------------------------------------- profiles

#: points of each profile, and its half-width as a share of the key's range
PROFILE_POINTS = 25
PROFILE_WINDOW = 0.2


@dataclass(frozen=True)
class Profile:
    """The objective along one varied ``key`` through the design at ``index``, the other
    keys held: ``x`` [spec units], ``objective`` [SI] and ``feasible`` at each point."""

    key: str
    x: np.ndarray
    objective: np.ndarray
    feasible: np.ndarray


def profiles(result: OptimizeResult, points: int = PROFILE_POINTS,
             window: float = PROFILE_WINDOW) -> list[Profile]:
    """The objective along each varied key through the optimum (else the least violating
    design), over ``window`` of the key's range on either side (clipped to the box), the
    other keys at their optimal values; computed as one batch in this process (not part of
    the budget or the history)."""
    i = result.best
    if i is None:
        return []
    centre = result.history.values[i]
    rows, spans = [], []
    for k, v in enumerate(result.problem.base.spec.optimize.vary):
        lo, hi = min(v.start, v.stop), max(v.start, v.stop)
        half = window * (hi - lo)
        x = np.unique(np.append(np.linspace(max(lo, centre[k] - half),
                                            min(hi, centre[k] + half), points), centre[k]))
        spans.append((v.key, x))
        for xv in x:
            row = centre.copy()
            row[k] = xv
            rows.append(row)
    _, judged = judge_chunk(result.problem, 0, np.array(rows))
    out, at = [], 0
    for key, x in spans:
        part = judged[at:at + len(x)]
        at += len(x)
        out.append(Profile(key, x, np.array([j.objective for j in part]),
                           np.array([j.feasible for j in part])))
    return out
