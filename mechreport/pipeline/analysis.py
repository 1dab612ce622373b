"""The public pipeline: spec -> model -> kinematics -> forces -> checks, in one call.

    from mechreport import analyse
    result = analyse("specs/slider_crank.yaml")
    result.forces["dyad"].reactions["B"].fx        # (n,) [N] over result.angles

Angles where the kinematics or any method's equations are singular are flagged and left out
of every result, so all arrays share one angle axis.
"""
from __future__ import annotations

from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np

from ..checks import (Agreement, ExpectationResult, Residual, agreement, check_expectations,
                     residuals)
from ..checks.agreement import DEFAULT_TOL
from ..checks.trust import Inputs, inputs_of
from ..errors import AnalysisError
from ..forces import METHODS, ForceContext, ForceResult, Step, solve_forces, worked_steps
from ..forces.friction import with_friction
from ..forces.context import LinkState
from ..forces.equations import Action
from ..forces.loads import undefined_directions
from ..forces.power import resolvable_effort
from ..kinematics import EPS, TRUST_RTOL, Flag, Kinematics, solve_kinematics
from ..kinematics.frames import scaled
from ..linalg import SINGULAR_COND
from ..model import Mechanism, build_mechanism
from ..post import Review, Verdict, design_review, reference_method, verdicts
from ..post.verdicts import undefined_reasons
from ..post.strength import StrengthReview, strength_review
from ..post.columns import Column, result_columns, scales, sweep_rows
from ..post.transmission import instant_quantities
from ..quantities import MECHANISM_UNITS
from ..post.sweep import SweepSummary, sweep_summary
from ..spec import Spec, load_spec, parse_spec
from .dynamics import run_dynamics, steady_rates

class Checked:
    """The check's verdict on a result with ``agreement`` (worst first), ``expectations``,
    ``verdicts``, ``tol`` and ``n`` angles analysed: an Analysis or a streamed sweep's check."""

    @property
    def worst(self) -> Agreement | None:
        return self.agreement[0] if self.agreement else None

    @property
    def passed(self) -> bool:
        """Every expectation and design verdict met, the methods agreeing within ``tol``, at
        least one angle analysed."""
        worst = self.worst
        return (all(e.ok for e in self.expectations)
                and all(v.passed for v in self.verdicts)
                and (worst is None or worst.relative <= self.tol)
                and self.n > 0)


@dataclass(frozen=True)
class Analysis(Checked):
    """Everything known about one spec. ``forces`` by method name; ``flags`` the angles left
    out (kinematic or force singularities) with reasons. What the force methods worked with
    (free bodies, their actions, the equations) is asked of the analysis
    (:meth:`worked_steps`, :meth:`free_body_actions` ...): the solver's own context stays
    inside it."""

    spec: Spec
    mechanism: Mechanism
    kinematics: Kinematics
    _context: ForceContext = field(repr=False, compare=False)
    forces: dict[str, ForceResult]
    flags: tuple[Flag, ...]
    agreement: list[Agreement]
    residuals: list[Residual]
    expectations: list[ExpectationResult]
    tol: float = DEFAULT_TOL
    review: Review | None = None      # cycle quantities (whole-turn sweeps of a full-turn crank)
    review_problem: str = ""          # why there is no review
    verdicts: tuple[Verdict, ...] = ()
    strength: StrengthReview | None = None   # the members of links with a section
    # machine dynamics (a spec with ``dynamics:``): the motion the motor gives, and the
    # steady turn's own analysis (a :class:`mechreport.pipeline.dynamics.DynamicsResult`)
    dynamics: object | None = None
    # each derived result computed once (see _once): the summary, the scales, the worked steps
    _derived: dict = field(default_factory=dict, repr=False, compare=False)

    def _once(self, key: tuple, build):
        """``build()``'s result, computed at the first request of ``key`` and kept: every
        output (report, sheets, summary.json) reads one value of a derived result."""
        if key not in self._derived:
            self._derived[key] = build()
        return self._derived[key]

    @property
    def passed(self) -> bool:
        """As :attr:`Checked.passed`, and the methods agreeing over a machine-dynamics steady
        turn too (its forces are reported beside the sweep's)."""
        steady = getattr(self.dynamics, "steady", None)
        worst = steady.worst if steady is not None else None
        return super().passed and (worst is None or worst.relative <= self.tol)

    @property
    def angles(self) -> np.ndarray:
        return self.kinematics.angles

    @property
    def loads(self):
        """The applied loads evaluated over ``angles`` (AppliedLoad: force (n, 2) [N] or
        moment (n,) [N m])."""
        return self._context.loads

    def joint_points(self) -> dict[str, np.ndarray]:
        """Where each joint's reaction acts, (n, 2) [m] by joint name: the pin, or the
        slider's point."""
        return self._context.joint_points

    def free_body_actions(self, links, inertia: bool = True) -> list[Action]:
        """Every action on the free body of ``links`` (names) over ``angles``: reactions of
        the joints cut (their unknowns named), loads, weights and, with ``inertia``, the
        d'Alembert inertia forces and couples."""
        return self._context.actions_on(list(links), inertia=inertia)

    def inertia_actions(self, link: str) -> list[Action]:
        """Link ``link``'s d'Alembert inertia force -m a_C at its centre of mass and couple
        -I alpha."""
        return self._context.inertia_actions(link)

    def gravity_action(self, link: str) -> Action:
        """Link ``link``'s weight m g at its centre of mass."""
        return self._context.gravity_action(link)

    def strength_context(self) -> ForceContext:
        """What the members' internal forces are computed from (the loads, points and
        actions of the force methods): for the solution sheet's cuts
        (:mod:`mechreport.report.sheet.strength`)."""
        return self._context

    def trust_inputs(self) -> Inputs:
        """The largest input of each kind at each angle (loads, m a_C, m g, I alpha) and the
        mechanism's span: what bounds one method's rounding (:mod:`mechreport.checks.trust`)."""
        return inputs_of(self._context)

    def link_state(self, link: str) -> LinkState:
        """Link ``link``'s mass, inertia and its centre of mass's motion over ``angles``."""
        return self._context.links[link]

    def by_source(self, method: str | None = None) -> dict[str, dict[str, np.ndarray]]:
        """Every unknown of ``method`` (default: the reference method) split by source:
        ``{"inertia" | "gravity" | load name: {unknown: (n,)}}``; the parts sum to the
        method's values (one extra solve with one right-hand side per source)."""
        from ..forces.sources import split_by_source
        from ..post import reference_method
        method = method or reference_method(self.forces)
        return self._once(("by_source", method), lambda: split_by_source(
            self._context, self.worked_steps(method)))

    def cycle_torque_by_source(self) -> dict[str, np.ndarray]:
        """The driver torque over the design review's cycle grid (``review.cycle.angles``,
        left-out angles filled in) split by source (see :meth:`by_source`), (N,) [N m] each;
        empty without a review."""
        rev = self.review
        if rev is None:
            return {}
        return {src: rev.cycle.sample(v["driver.torque"], self.angles)
                for src, v in self.by_source(rev.method).items()}

    def worked_steps(self, method: str) -> tuple[Step, ...]:
        """The labelled systems ``method`` solved, in order, over ``angles``: the equation
        objects its numbers came from (built at the first request, then kept: they hold
        every coefficient at every angle)."""
        return self._once(("worked_steps", method), lambda: worked_steps(self._context, method))

    @property
    def n(self) -> int:
        """Angles analysed (those left out are in ``flags``)."""
        return self.kinematics.n

    def sweep_summary(self) -> SweepSummary:
        """What the sweep's results come to (effort statistics, each joint's peak and RMS
        load, the frame load, bearing traces, the power balance's agreement): see
        :mod:`mechreport.post.sweep`."""
        return self._once(("sweep_summary",), lambda: sweep_summary(
            self.kinematics, self.forces, self.loads, self.flags,
            self.review.values if self.review is not None else None))

    def scales(self) -> dict[str, float]:
        """The largest magnitude [SI] of each kind of quantity (length, force, moment ...):
        a value below 1e-9 of it is round-off (see :func:`mechreport.post.columns.scales`)."""
        return self._once(("scales",), lambda: scales(self.kinematics, self.forces, self.loads))

    def columns(self) -> list[Column]:
        """Every result as a named column over ``angles`` (what results.csv holds, see
        :mod:`mechreport.post.columns`)."""
        return self._once(("columns",), lambda: result_columns(self.kinematics, self.forces,
                                                              self.scales()))

    def results_table(self) -> tuple[list[str], list[list[str]]]:
        """results.csv's header and rows (see :func:`mechreport.pipeline.records.results_table`)."""
        from .records import results_table
        return self._once(("results_table",), lambda: results_table(self))

    def summary_record(self) -> dict:
        """summary.json's results, SI with units (see
        :func:`mechreport.pipeline.records.summary_record`): read, never changed."""
        from .records import summary_record
        return self._once(("summary_record",), lambda: summary_record(self))

    def to_dataframe(self):
        """Every result as a pandas DataFrame (``pip install 'mechreport[pandas]'``): one
        row per angle of the sweep, indexed by the sweep coordinate
        (``crank_angle [deg]``, or a T driver's ``stroke [mm]``), a ``flag`` column giving why an angle was left out (its
        row is NaN then), and one column per quantity named with its SI unit, as in
        results.csv: ``crank.omega [rad/s]``, ``dyad.joint.B.fx [N]``,
        ``newton_euler.driver.torque [N·m]`` ..."""
        try:
            import pandas as pd
        except ImportError:
            raise ImportError("to_dataframe needs pandas: pip install "
                              "'mechreport[pandas]'") from None
        columns = self.columns()
        angles, index, reasons = sweep_rows(self.angles, self.flags)
        rows = np.array([-1 if k is None else k for k in index], int)
        data = {"flag": reasons}
        for c in columns:
            values = np.full(len(angles), np.nan)
            values[rows >= 0] = c.values[rows[rows >= 0]]
            data[c.name] = values
        index = pd.Index(np.array(angles, float), name=self.spec.axis_column)
        return pd.DataFrame(data, index=index)

    def notes(self) -> list[str]:
        """What a reader must know before the numbers (see ``Kinematics.notes``)."""
        return self.kinematics.notes()



def analyse(spec: Spec | str | Path, methods=None, tol: float = DEFAULT_TOL,
            plans=None) -> Analysis:
    """Load ``spec`` (a :class:`Spec`, a file's path, or YAML text: a string of more than one
    line), solve every method and run the checks.
    ``methods``: the force methods' names (default: all); ``tol``: the largest relative
    disagreement between methods that passes; ``plans``: a
    :class:`~mechreport.forces.contour.ContourPlans` shared with other analyses of the same
    structure (a batch's), whose contour search it may reuse.

    Angles where any method's result could not be trusted to ``TRUST_RTOL`` are flagged and
    left out of every result. Raises ``AnalysisError`` when no angle is left, or when a value
    in any result is not finite (never reported as a number)."""
    if isinstance(spec, str) and "\n" in spec:      # the YAML text itself
        spec = parse_spec(spec, "<text>")
    elif not isinstance(spec, Spec):
        spec = load_spec(spec)
    with np.errstate(all="ignore"):    # what is not finite is flagged or refused below, never a warning
        mech = build_mechanism(spec)
        kin = solve_kinematics(mech)
        dynamics = None
        if spec.dynamics is not None:       # the steady turn takes the sweep's poses
            dynamics = run_dynamics(mech, analysis_of, methods, tol, plans, kin)
        return analysis_of(mech, kin, methods, tol, plans, dynamics)


def analysis_of(mech: Mechanism, kin: Kinematics, methods=None, tol: float = DEFAULT_TOL,
                plans=None, dynamics=None, extra: dict[str, float] | None = None
                ) -> Analysis:
    """The :class:`Analysis` of ``mech`` over the kinematics ``kin`` (a sweep's, or a machine-
    dynamics turn's with the crank's true speed at each angle): every method, the checks, the
    design review. ``dynamics``: the spec's machine-dynamics result, whose ``dynamics.*``
    quantities join the cycle quantities (expectations and verdicts read them), as
    ``extra`` quantities do."""
    spec = mech.spec
    with np.errstate(all="ignore"):
        kin, ctx, forces = solve_trusted(_require_angles(kin), methods, plans=plans)
        kin = _require_angles(kin)
        rev, why = design_review(kin, forces, ctx.loads)
        extra = {**(extra or {}), **(dynamics.values if dynamics is not None else {})}
        if extra and rev is not None:    # cycle quantities too: every output lists them
            rev = replace(rev, values={**rev.values, **extra})
        values = rev.values if rev is not None else (extra or None)
        res = residuals(ctx, forces)
        effort = resolvable_effort(ctx)
        strength = strength_of(ctx, forces)
    members = strength.values if strength is not None else None
    ctx.cache.clear()   # the actions and equations the methods shared: rebuilt if asked for
    return Analysis(spec, mech, kin, ctx, forces, kin.flags, agreement(forces, spec.size, effort), res,
                    check_expectations(kin, forces, kin.flags, values, why,
                                       _instant(spec, kin, dynamics), members), tol, rev, why,
                    tuple(verdicts(spec.design, values, why, members,
                                         undefined_reasons(spec))), strength, dynamics)


def strength_of(ctx: ForceContext, forces: dict[str, ForceResult]) -> StrengthReview | None:
    """The members' internal forces and safety factors (links with a ``section``), from the
    reference method's reactions; None when no link has a section, or when no method solved
    the reactions (the power balance alone)."""
    res = forces[reference_method(forces)]
    if not any(link.strength for link in ctx.spec.links) or not res.reactions:
        return None
    return strength_review(ctx, res)


def _instant(spec: Spec, kin: Kinematics, dynamics=None) -> dict[str, np.ndarray] | None:
    """The mechanism's own quantities at each angle, where an expectation asks for one (the
    steady cycle's speed and acceleration from ``dynamics``, when it has one)."""
    if any(e.quantity in MECHANISM_UNITS for e in spec.expect):
        out = instant_quantities(kin)
        if dynamics is not None:
            out.update(steady_rates(dynamics.simulation, kin.angles))
        return out
    return None


def solve_trusted(kin: Kinematics, methods=None, memo: dict | None = None, plans=None,
                  ) -> tuple[Kinematics, ForceContext, dict[str, ForceResult]]:
    """Every method's forces over ``kin``, with the angles where a method cannot be trusted
    flagged and left out of the kinematics and of every result (see :func:`_force_flags`).
    Raises ``AnalysisError`` where an input or a result is not a finite number. ``memo``:
    choices shared with other parts of the same sweep (the contour method's plan); ``plans``:
    contour plans shared with other specs (see :func:`analyse`). Where friction leaves no
    angle (it self-locks at every one), the kinematics come back empty with their flags,
    no context and no result: the caller says so (no angle at all, or one chunk of a long
    sweep)."""
    if kin.mechanism.spec.friction:         # the friction every method then includes
        kin = with_friction(kin)[0]
        if not kin.n:
            return kin, None, {}
    ctx = ForceContext(kin)                 # one per kinematics: its loads evaluated once
    ctx.plans = plans
    if memo is not None:
        ctx.memo = memo
    _require_finite_inputs(ctx)
    forces = solve_forces(kin, methods, ctx)
    extra = _force_flags(kin, forces)
    if extra:
        bad = np.isin(np.round(kin.angles, 9), np.round([f.angle for f in extra], 9))
        kin = kin.take(~bad, tuple(sorted(kin.flags + tuple(extra), key=lambda f: f.angle)))
        memo, ctx = ctx.memo, ForceContext(kin)
        ctx.memo, ctx.plans = memo, plans   # the same equations as the numbers came from
        forces = {name: res.take(~bad, ctx) for name, res in forces.items()}
    _require_finite(kin, forces)
    return kin, ctx, forces


def _force_flags(kin: Kinematics, forces: dict[str, ForceResult]) -> list[Flag]:
    """Angles where a spring's or damper's ends coincide (its force has no direction:
    :func:`~mechreport.forces.loads.undefined_directions`), where a method's equations are
    singular, or where its rounding error bound (eps x condition number) added to the
    kinematics' own error exceeds ``TRUST_RTOL``.

    The kinematic error already covers the physical singularities (Newton-Euler's matrix is
    the transpose of the constraint Jacobian); the force systems add their own rounding."""
    worst = np.ones(kin.n)
    singular = np.zeros(kin.n, bool)
    doubtful = {}
    for name, res in forces.items():
        cond = res.cond if res.cond is not None else np.ones(kin.n)
        if np.isnan(cond).any():
            k = int(np.flatnonzero(np.isnan(cond))[0])
            raise AnalysisError(
                f"{kin.mechanism.spec.file}: the {name} equations are not finite numbers at "
                f"{kin.angles[k]:g} {kin.mechanism.spec.axis_unit}: the inputs are beyond what "
                "double precision can "
                "represent (check masses, lengths, speeds, gravity and loads)")
        doubtful[name] = ~trusted(kin, res)
        singular |= res.singular
        worst = np.maximum(worst, cond)     # (no NaN: raised above)
    flags = []
    undefined = undefined_directions(kin)
    for k in np.flatnonzero(np.any([bad for _, bad in undefined], axis=0)) if undefined else ():
        names = [ld.label for ld, bad in undefined if bad[k]]
        what = (f"the two ends of {names[0]} coincide: its force has" if len(names) == 1 else
                f"the two ends of each of {', '.join(names)} coincide: their forces have")
        flags.append(Flag(float(kin.angles[k]), f"{what} no direction there", "singular"))
    taken = {f.angle for f in flags}
    for k in np.flatnonzero(np.any(list(doubtful.values()), axis=0)):
        if float(kin.angles[k]) in taken:
            continue
        names = [name for name, bad in doubtful.items() if bad[k]]
        if singular[k] or not worst[k] < SINGULAR_COND:
            flags.append(Flag(float(kin.angles[k]),
                              f"force equations singular ({', '.join(names)})", "singular"))
        else:
            flags.append(Flag(float(kin.angles[k]),
                              f"near-singular: force equations of {', '.join(names)} "
                              f"(condition {worst[k]:.1e}); results would not be trustworthy "
                              f"to {TRUST_RTOL:g}", "near-singular"))
    return flags


def trusted(kin: Kinematics, res: ForceResult) -> np.ndarray:
    """Angles (n,) where method ``res`` is regular and its rounding error bound (eps x its
    condition number) added to the kinematics' own error is within ``TRUST_RTOL``."""
    inputs = kin.error if kin.error is not None else np.zeros(kin.n)
    cond = res.cond if res.cond is not None else np.ones(kin.n)
    with np.errstate(over="ignore", invalid="ignore"):
        return ~res.singular & (inputs + EPS * cond <= TRUST_RTOL)


def _require_angles(kin: Kinematics) -> Kinematics:
    """``kin`` if it has at least one angle of the sweep; else an error saying why every
    angle of the sweep was lost (a reference angle outside the sweep does not stand in for
    a sweep with nothing trustworthy left)."""
    spec = kin.mechanism.spec
    if sweep_angles_left(kin.angles, spec.off_sweep_angles()):
        return kin
    raise no_angle_error(spec, kin.flags)


def sweep_angles_left(angles: np.ndarray, off_sweep: np.ndarray) -> bool:
    """Whether any of the analysed ``angles`` [deg] is an angle of the sweep, not one of the
    reference or expectation angles outside it, ``off_sweep`` (``Spec.off_sweep_angles``)."""
    return bool(np.any(~np.isin(np.round(angles, 9), off_sweep)))


def no_angle_error(spec: Spec, flags) -> AnalysisError:
    """The error of a sweep that lost every angle, saying why (the first three reasons)."""
    kinds: dict[str, list[float]] = {}
    for f in flags:
        kinds.setdefault(f.reason, []).append(f.angle)
    why = "; ".join(f"{reason} ({_angles(a, spec.axis_unit)})"
                    for reason, a in list(kinds.items())[:3])
    more = f"; and {len(kinds) - 3} more reason(s)" if len(kinds) > 3 else ""
    return AnalysisError(f"{spec.file}: no angle of the sweep can be analysed: {why}{more}")


def _angles(angles: list[float], unit: str = "deg") -> str:
    shown = ", ".join(f"{a:g}" for a in angles[:4])
    return f"{shown} {unit}" + (f" and {len(angles) - 4} more" if len(angles) > 4 else "")


def _require_finite_inputs(ctx: ForceContext) -> None:
    """Raise ``AnalysisError`` where an inertia force or couple, a weight or a load overflows
    double precision (the loader bounds each input; products of several can still overflow)."""
    file = ctx.spec.file
    with np.errstate(over="ignore", invalid="ignore"):
        arrays = [(f"{what} of link {name}", value) for name, s in ctx.links.items()
                  for what, value in (("m a_C", scaled(s.mass, s.a)),
                                      ("I_C alpha", s.inertia * s.alpha),
                                      ("weight m g", scaled(s.mass, ctx.gravity)
                                       * np.ones((ctx.n, 1))))]
        arrays += [(f"load {ld.symbol}", ld.force if ld.force is not None else ld.moment)
                   for ld in ctx.loads]
    if _all_finite([np.asarray(v).reshape(-1) for _, v in arrays]):
        return                      # as a rule: nothing to name
    for what, values in arrays:
        ok = np.isfinite(values).reshape(ctx.n, -1).all(axis=1)
        if not ok.all():
            k = int(np.flatnonzero(~ok)[0])
            raise AnalysisError(
                f"{file}: {what} is not a finite number at {ctx.kin.angles[k]:g} "
                f"{ctx.spec.axis_unit}: the "
                "inputs are beyond what double precision can represent (check masses, "
                "lengths, speeds, gravity and loads)")


def _all_finite(arrays: list[np.ndarray]) -> bool:
    """Whether every value of ``arrays`` (1-D) is finite: at once for short sweeps (one
    numpy call instead of one per array), array by array where joining them would take
    memory."""
    if sum([v.size for v in arrays]) <= 1 << 20:
        return bool(np.isfinite(np.concatenate(arrays)).all())
    return all(np.isfinite(v).all() for v in arrays)


def _require_finite(kin: Kinematics, forces: dict[str, ForceResult]) -> None:
    """Raise ``AnalysisError`` naming the first non-finite value of any result (quantity,
    method, angle): a NaN must never reach a check or a report as a number."""
    spec = kin.mechanism.spec
    results = [(name, res.values()) for name, res in forces.items()]
    whole = [kin.r, kin.theta, kin.v, kin.omega, kin.a, kin.alpha]
    if _all_finite([w.reshape(-1) for w in whole]
                   + [v for _, values in results for v in values.values()]):
        return                      # as a rule: nothing to name (the ground's zeros included)
    arrays = [(f"kinematics {what} of link {link.name}", getattr(kin, what)[:, link.number])
              for link in spec.links for what in ("r", "theta", "v", "omega", "a", "alpha")]
    arrays += [(f"{q} ({name})", v) for name, values in results for q, v in values.items()]
    for what, values in arrays:
        ok = np.isfinite(values)
        if not ok.all():
            k = int(np.flatnonzero(~ok.reshape(len(kin.angles), -1).all(axis=1))[0])
            raise AnalysisError(
                f"{spec.file}: {what} is not a finite number at {kin.angles[k]:g} "
                f"{spec.axis_unit}: the "
                "inputs are beyond what double precision can represent (check masses, "
                "lengths, speeds, gravity and loads)")


__all__ = ["Analysis", "analyse", "METHODS", "DEFAULT_TOL"]
