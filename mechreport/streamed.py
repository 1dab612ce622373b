"""A long sweep checked in bounded memory: what `mechreport check` runs on sweeps of more than
``STREAM_ANGLES`` analysed angles.

The same pipeline as :func:`mechreport.analysis.analyse`, a chunk of angles at a time
(:func:`mechreport.kinematics.stream.kinematic_chunks`): each chunk's kinematics, every
method's forces, the angles a method cannot trust, then what the check keeps of it: the
methods' largest spreads (:func:`checks.agreement.spreads`, merged chunk by chunk), the
largest residuals, the expectations at the chunk's angles, and the few traces the cycle review
reads (:class:`post.Traces`: 10 to 20 numbers per angle). The contour method's equations are
chosen once, on probe angles spread over the whole sweep, as for one analysis. Nothing else of
a chunk outlives it.

The result, :class:`SweepCheck`, answers what `check` asks of an :class:`Analysis` (flags,
agreement, residuals, expectations, verdicts, notes, PASS or FAIL), and the numbers equal the
in-memory analysis' (tests/test_streamed.py). Mechanisms with a group that has no closed form
(Newton groups) are analysed in memory.
"""
from __future__ import annotations

from dataclasses import dataclass, field

from .analysis import DEFAULT_TOL, Analysis, analyse, no_angle_error, passes, solve_trusted
from .checks import Agreement, ExpectationResult, Residual, residuals
from .checks.agreement import finish, merge, spreads
from .checks.expectations import at_angle, check_cycle, left_out
from .forces import METHODS, ForceContext, contour
from .kinematics import Flag
from .kinematics.stream import kinematic_chunks, streamable
from .model import build_mechanism
from .post import Traces, Verdict, design_review_from, traces_of, verdicts
from .spec import Spec

STREAM_ANGLES = 100_000   # analysed angles beyond which `check` streams the sweep
CHUNK = 8192              # angles analysed together


@dataclass(frozen=True)
class SweepCheck:
    """What a check of one spec found, without the per-angle results: ``n`` angles analysed,
    ``flags`` those left out, the agreement table (worst first), each method's largest
    residuals, the expectations, the design review's cycle quantities ``values`` (None when
    undefined, because ``review_problem``) and verdicts, and the kinematics' ``notes``."""

    spec: Spec
    n: int
    flags: tuple[Flag, ...]
    agreement: list[Agreement]
    residuals: list[Residual]
    expectations: list[ExpectationResult]
    tol: float
    values: dict[str, float] | None
    review_problem: str
    verdicts: tuple[Verdict, ...]
    kinematic_notes: list[str] = field(default_factory=list)

    @property
    def worst(self) -> Agreement | None:
        return self.agreement[0] if self.agreement else None

    @property
    def passed(self) -> bool:
        return passes(self)

    def notes(self) -> list[str]:
        return list(self.kinematic_notes)


def check_sweep(spec: Spec, methods=None, tol: float = DEFAULT_TOL,
                chunk: int = CHUNK) -> SweepCheck | Analysis:
    """The check of ``spec``'s sweep, ``chunk`` angles at a time (an in-memory
    :class:`Analysis` for mechanisms that cannot be streamed)."""
    mech = build_mechanism(spec)
    if not streamable(mech):
        return analyse(spec, methods, tol)
    names = list(METHODS) if methods is None else list(methods)
    chunks = kinematic_chunks(mech, chunk)
    memo: dict = {}
    if contour.NAME in names:   # the contour method's equations, chosen over the whole sweep
        probe = ForceContext(chunks.probes(contour.PROBES))
        if probe.n:
            contour.plan(probe)
            memo = probe.memo
    flags: list[Flag] = []
    parts: dict = {}
    worst: dict[str, list[float]] = {}
    found: dict[int, list[ExpectationResult]] = {}
    traces: Traces | None = None          # every chunk's, one after the other
    n = 0
    timed = [(i, e) for i, e in enumerate(spec.expect) if e.angle is not None]
    for kin in chunks:
        if kin.n:
            kin, ctx, forces = solve_trusted(kin, names, memo)
        flags += kin.flags
        if not kin.n:
            continue
        n += kin.n
        parts = merge(parts, spreads(forces))
        for r in residuals(ctx, forces):
            w = worst.setdefault(r.method, [0.0, 0.0])
            w[0], w[1] = max(w[0], r.force), max(w[1], r.moment)
        for i, e in timed:
            k = kin.index_of(e.angle)
            if k is not None:
                found[i] = at_angle(e, kin, forces, k)
        part = traces_of(kin, forces, ctx.loads)
        if traces is None:
            traces = part.allocate(len(chunks.angles))
        traces.write(part, n - kin.n)
        del kin, ctx, forces, part     # nothing of a chunk outlives it
    flags = sorted(flags, key=lambda f: f.angle)
    if n == 0:
        raise no_angle_error(spec, flags)
    rev, why = design_review_from(traces.head(n), spec, chunks.motion.full,
                                  chunks.turn_problem)
    values = rev.values if rev is not None else None
    del rev, traces
    expectations: list[ExpectationResult] = []
    for i, e in enumerate(spec.expect):
        if e.angle is None:
            expectations.append(check_cycle(e, values, why))
        else:
            expectations += found.get(i) or left_out(e, spec, flags)
    return SweepCheck(spec, n, tuple(flags), finish(parts),
                      [Residual(m, f, mo) for m, (f, mo) in worst.items()], expectations, tol,
                      values, why, tuple(verdicts(spec.design, values, why)), chunks.notes())
