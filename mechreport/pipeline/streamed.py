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

import numpy as np

from .dynamics import simulated, steady_rates
from .analysis import (DEFAULT_TOL, Analysis, Checked, analyse, no_angle_error,
                       solve_trusted, sweep_angles_left)
from ..checks import Agreement, ExpectationResult, Residual, residuals
from ..checks.agreement import finish, merge, spreads
from ..checks.trust import bounds, inputs_of, judged
from ..checks.expectations import at_angle, check_cycle, judge, left_out
from ..forces import METHODS, PROBES, ForceContext, sweep_choices
from ..forces.power import resolvable_effort
from ..forces.result import slider_point
from ..kinematics import Flag
from ..kinematics.result import friction_notes, jam_note, reversal_note
from ..kinematics.stream import kinematic_chunks, streamable
from ..model import build_mechanism
from ..quantities import split as split_quantity
from ..post import Traces, Verdict, design_review_from, reference_method, traces_of, verdicts
from ..post.verdicts import undefined_reasons
from ..post.strength import merge_parts, review_of_parts, strength_parts
from ..quantities import DYNAMICS_INSTANT, is_member
from ..post.transmission import instant_quantities
from ..spec import Spec

STREAM_ANGLES = 100_000   # analysed angles beyond which `check` streams the sweep
CHUNK = 8192              # angles analysed together


@dataclass(frozen=True)
class SweepCheck(Checked):
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
    untrusted: dict[str, str] = field(default_factory=dict)   # by method: see checks.trust
    members: dict[str, float] | None = None   # the members' quantities (links with a section)

    def notes(self) -> list[str]:
        return list(self.kinematic_notes)


def check_sweep(spec: Spec, methods=None, tol: float = DEFAULT_TOL,
                chunk: int = CHUNK, between_phases=None) -> SweepCheck | Analysis:
    """The check of ``spec``'s sweep, ``chunk`` angles at a time (an in-memory
    :class:`Analysis` for mechanisms that cannot be streamed). ``between_phases()``, if
    given, is called where one phase's working set has been freed and the next allocates
    afresh (the command line gives the free heap back to the system there, which bounds the
    peak memory of a million-angle check)."""
    between_phases = between_phases or (lambda: None)
    mech = build_mechanism(spec)
    if not streamable(mech):
        return analyse(spec, methods, tol)
    names = list(METHODS) if methods is None else list(methods)
    chunks = kinematic_chunks(mech, chunk)
    between_phases()              # pass 1's working set: freed, but kept by the allocator
    # the contour method's equations, chosen once over the whole sweep
    memo = sweep_choices(chunks.probes(PROBES), names) if "contour" in names else {}
    flags: list[Flag] = []
    parts: dict = {}
    worst: dict[str, list[float]] = {}
    found: dict[int, list] = {}       # expect index -> its results (or a slider's inputs)
    top: dict[tuple[str, str], float] = {}   # (method, T joint) -> largest force component
    traces: Traces | None = None          # every chunk's, one after the other
    trust: dict = {}                      # (method, kind) -> checks.trust.Bound
    reversed_at: list[float] = []         # where friction alone reverses the effort
    n = 0
    timed = [(i, e) for i, e in enumerate(spec.expect) if e.angle is not None
             and e.quantity not in DYNAMICS_INSTANT]      # those: from the simulation
    strength = None                       # the members' extremes, merged chunk by chunk
    off_sweep, swept = spec.off_sweep_angles(), False    # a sweep angle is left (not only `at`)
    effort = 0.0                          # the driver effort's resolvable scale (agreement)
    for kin in chunks:
        if kin.n:
            kin, ctx, forces = solve_trusted(kin, names, memo)
        flags += kin.flags
        if not kin.n:
            continue
        n += kin.n
        swept = swept or sweep_angles_left(kin.angles, off_sweep)
        reversed_at += kin.reversed_by_friction
        parts = merge(parts, spreads(forces))
        effort = max(effort, resolvable_effort(ctx))
        for r in residuals(ctx, forces):
            w = worst.setdefault(r.method, [0.0, 0.0])
            w[0], w[1] = max(w[0], r.force), max(w[1], r.moment)
        inputs = inputs_of(ctx)
        for name, res in forces.items():     # each method's rounding, for one-method checks
            for kind, b in bounds(res, inputs).items():
                trust[name, kind] = b.merged(trust[name, kind]) if (name, kind) in trust else b
        for name, res in forces.items():     # slider points are judged against these
            for j, r in res.reactions.items():
                if r.moment is not None:
                    top[name, j] = max(top.get((name, j), 0.0),
                                       float(np.max(np.abs(r.fx))), float(np.max(np.abs(r.fy))))
        for i, e in timed:
            k = kin.index_of(e.angle)
            if k is None:
                continue
            if _slider_point(e):
                found[i] = _slider_inputs(e, ctx, forces, k)
            else:
                found[i] = at_angle(e, kin, forces, k, instant_quantities(kin)
                                    if e.quantity == "transmission_angle" else None)
        if any(link.strength for link in spec.links) and \
                forces[reference_method(forces)].reactions:
            strength = merge_parts(strength, strength_parts(
                ctx, forces[reference_method(forces)], keep=False))
        part = traces_of(kin, forces, ctx.loads)
        if traces is None:
            traces = part.allocate(len(chunks.angles))
        traces.write(part, n - kin.n)
        del kin, ctx, forces, part     # nothing of a chunk outlives it
    flags = sorted(flags, key=lambda f: f.angle)
    if n == 0 or not swept:
        raise no_angle_error(spec, flags)
    between_phases()              # the last chunks' working set, before the review's own
    rev, why = design_review_from(traces.head(n), spec, chunks.motion.full,
                                  chunks.turn_problem, jam_note(flags, spec))
    values = rev.values if rev is not None else None
    if spec.dynamics is not None:       # the steady turn's quantities, from the simulation
        _, sim, steady = simulated(mech)
        values = {**(values or {}), **steady}
        for i, e in enumerate(spec.expect):
            if e.angle is not None and e.quantity in DYNAMICS_INSTANT:
                got = steady_rates(sim, np.array([e.angle])).get(e.quantity)
                found[i] = judge(e, {"kinematics": float("nan") if got is None
                                     else float(got[0])}, spec)
    del rev, traces
    members = (review_of_parts(strength, "").values if strength else None)
    expectations: list[ExpectationResult] = []
    for i, e in enumerate(spec.expect):
        if is_member(e.quantity):
            expectations.append(check_cycle(e, members or {}, ""))
        elif e.angle is None:
            expectations.append(check_cycle(e, values, why))
        elif i not in found:
            expectations += left_out(e, spec, flags)
        elif _slider_point(e):
            expectations += _judge_slider(e, spec, found[i], top)
        else:
            expectations += found[i]
    found: dict[str, dict] = {}
    for (name, kind), b in trust.items():
        found.setdefault(name, {})[kind] = b
    untrusted = {name: judged(b, tol, name, spec.axis_unit) for name, b in found.items()}
    return SweepCheck(spec, n, tuple(flags), finish(parts, spec.size, effort),
                      [Residual(m, f, mo) for m, (f, mo) in worst.items()], expectations, tol,
                      values, why, tuple(verdicts(spec.design, values, why, members,
                                         undefined_reasons(spec))),
                      chunks.notes() + ([reversal_note(reversed_at, spec)] if reversed_at
                                        else []) + friction_notes(flags, spec),
                      untrusted, members)


def _slider_point(e) -> bool:
    """Whether expectation ``e`` is on a T joint's point of application (joint.J.px or py):
    defined against the largest force over the whole sweep, so judged at the end."""
    parts = split_quantity(e.quantity)
    return parts is not None and parts[0] == "joint" and parts[2] in ("px", "py")


def _slider_inputs(e, ctx: ForceContext, forces, k: int) -> dict:
    """What each method's slider point at row ``k`` is made of: (context at that angle, fx,
    fy, m); the point is computed when the sweep's largest force is known."""
    joint = split_quantity(e.quantity)[1]
    one = ForceContext(ctx.kin.take([k], ()))
    out = {}
    for name, res in forces.items():
        r = res.reactions.get(joint)
        if r is not None and r.moment is not None:
            out[name] = (one, r.fx[k:k + 1], r.fy[k:k + 1], r.moment[k:k + 1])
    return out


def _judge_slider(e, spec: Spec, inputs: dict, top: dict) -> list[ExpectationResult]:
    _, joint, axis = split_quantity(e.quantity)
    sources = {}
    for name, (one, fx, fy, m) in inputs.items():
        px, py = slider_point(one, spec.joint(joint), fx, fy, m, top[name, joint])
        sources[name] = float((px if axis == "px" else py)[0])
    return judge(e, sources, spec)
