"""Many variants of one mechanism analysed as one batch: what a design study runs.

The variants' numbers are stacked with the angles (rows = variants x angles, see
:mod:`mechreport.spec.stack`); the kinematics and one force method are solved for every row
at once, with the same equations and the same batched solver as a single analysis. Then each
variant's cycle quantities and design verdicts are taken from its own rows.

A variant is analysed alone, by :func:`mechreport.analysis.analyse`, when its sweep is not
clean (an angle that cannot close, is unreachable, singular or near-singular for the
kinematics or the method, or a value that is not finite) or when the batch cannot be stacked
(variants that differ in more than numbers, Newton groups): its result, flags and reasons are
then exactly a single analysis'. Either way each variant's outcome equals ``analyse(spec,
methods=[method])`` to rounding.
"""
from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from ..checks.trust import inputs_of, untrusted
from .analysis import DEFAULT_TOL, Analysis, analyse, strength_of, trusted
from .streamed import STREAM_ANGLES, check_sweep
from ..forces import METHODS, ForceContext
from ..forces.contour import ContourPlans
from ..forces.loads import undefined_directions
from ..kinematics.stacked import solve_stacked, variant_kinematics
from ..model import build_mechanism
from ..post import Review, Verdict, design_review, verdicts
from ..post.verdicts import undefined_reasons
from ..spec import Spec


@dataclass(frozen=True)
class Outcome:
    """One variant's result: ``review`` (cycle quantities, or None and ``review_problem``),
    its design ``verdicts``, and ``exception`` when it could not be analysed at all (what a
    single analysis raises). ``batched``: solved in the batch (False: analysed alone).
    ``untrusted``: why its one method's numbers cannot be trusted ("" when they can; see
    :mod:`mechreport.checks.trust`): there is no second method to disagree with. A variant
    whose sweep is longer than ``STREAM_ANGLES`` is checked chunk by chunk in bounded memory
    (as `check` does): it has no ``review`` object, only its ``streamed`` cycle quantities."""

    spec: Spec
    review: Review | None = None
    review_problem: str = ""
    verdicts: tuple[Verdict, ...] = ()
    exception: BaseException | None = None
    batched: bool = False
    untrusted: str = ""
    streamed: dict[str, float] | None = None
    members: dict[str, float] | None = None   # the members' quantities (links with a section)
    left_out: tuple[float, ...] = ()    # the angles left out (flagged) [deg or length unit]
    branches: tuple = ()                # the assembly branch choices (``Kinematics.branches``)
    locked: str = ""                    # why part of the sweep is out of reach ("" if none)

    @property
    def cycle_values(self) -> dict[str, float] | None:
        """The cycle quantities by name (None when undefined: ``review_problem`` says why)."""
        return self.review.values if self.review is not None else self.streamed

    @property
    def error(self) -> str | None:
        """The failure's message for users (None when the variant was analysed)."""
        if self.exception is None:
            return None
        from ..errors import describe_failure
        return describe_failure(self.exception)


ROWS = 16384    # variants x angles solved together (bounds the working memory)


def analyse_variants(specs: list[Spec], method: str, plans=None) -> list[Outcome]:
    """The outcome of every variant in ``specs`` (variants of one spec) with ``method``.
    ``plans``: contour plans to share (default: one for this batch; see
    :class:`~mechreport.forces.contour.ContourPlans`)."""
    plans = ContourPlans() if plans is None else plans
    out: list[Outcome | None] = [None] * len(specs)
    groups: dict[tuple, list[int]] = {}      # variants that can stack: same sense, same sweep
    for i, s in enumerate(specs):
        if len(s.analysed_angles()) > STREAM_ANGLES:     # bounded memory: streamed alone
            out[i] = _streamed(s, method)
            continue
        if s.friction or s.dynamics:    # friction solved with its own forces, a motion of
            continue                    # its own: alone
        groups.setdefault((np.sign(s.driver.omega), s.sweep, tuple(s.at)), []).append(i)
    for members in groups.values():
        per = len(specs[members[0]].analysed_angles())
        size = max(1, ROWS // max(per, 1))
        for start in range(0, len(members), size):
            idx = members[start:start + size]
            part = [specs[i] for i in idx]
            try:
                mech = build_mechanism(part[0])
                with np.errstate(all="ignore"):
                    stacked = solve_stacked(mech, part)
                if stacked is not None:
                    for i, o in zip(idx, _batched(stacked, mech, part, method, plans)):
                        out[i] = o
            except Exception:   # noqa: BLE001 - each variant is then analysed alone
                pass
    return [o if o is not None else _alone(s, method, plans) for o, s in zip(out, specs)]


def _batched(stacked, mech, specs: list[Spec], method: str, plans) -> list[Outcome | None]:
    """The outcomes of the clean variants of the stacked batch (None for the others)."""
    out: list[Outcome | None] = [None] * len(specs)
    kin = stacked.kin
    with np.errstate(all="ignore"):
        ctx = ForceContext(kin)
        ctx.plans = plans
        res = METHODS[method].solve(ctx)
        ok = trusted(kin, res)
        for values in res.values().values():
            ok &= np.isfinite(values)
        for _, bad in undefined_directions(kin):    # a spring whose ends meet: alone
            ok &= ~bad
    clean = stacked.clean & ok.reshape(len(specs), stacked.per).all(axis=1)
    index = {id(ld): k for k, ld in enumerate(ctx.spec.loads)}
    inputs = inputs_of(ctx)
    for v in np.flatnonzero(clean):
        spec = specs[v]
        rows = stacked.rows(v)
        kin_v = variant_kinematics(stacked, v, mech.with_spec(spec))
        forces = {method: res.take(rows, None)}
        loads = [replace(ld, load=spec.loads[index[id(ld.load)]],
                         force=None if ld.force is None else ld.force[rows],
                         moment=None if ld.moment is None else ld.moment[rows])
                 for ld in ctx.loads]
        rev, why = design_review(kin_v, forces, loads)
        values = rev.values if rev is not None else None
        members = _members(kin_v, forces)
        out[v] = Outcome(spec, rev, why, tuple(verdicts(spec.design, values, why, members,
                                         undefined_reasons(spec))),
                         batched=True, untrusted=untrusted(forces[method], DEFAULT_TOL,
                                                            spec.axis_unit, inputs.take(rows)),
                         members=members, branches=kin_v.branches)
    return out


def _members(kin, forces) -> dict[str, float] | None:
    """A variant's members' quantities (None when no link has a section), from its own
    kinematics and reactions."""
    if not any(link.strength for link in kin.mechanism.spec.links):
        return None
    st = strength_of(ForceContext(kin), forces)
    return st.values if st is not None else None


def _streamed(spec: Spec, method: str) -> Outcome:
    """A variant of a long sweep checked chunk by chunk (:func:`~.streamed.check_sweep`); a
    failure is its message, never an exception."""
    try:
        c = check_sweep(spec, methods=[method])
    except Exception as exc:     # noqa: BLE001 - a failed variant is a row with its reason
        return Outcome(spec, exception=exc)
    if isinstance(c, Analysis):  # not streamable: analysed in memory after all
        return Outcome(spec, c.review, c.review_problem, c.verdicts,
                       untrusted=untrusted(c.forces[method], c.tol, spec.axis_unit,
                                           c.trust_inputs()),
                       members=c.strength.values if c.strength is not None else None)
    return Outcome(spec, None, c.review_problem, c.verdicts, streamed=c.values,
                   untrusted=c.untrusted.get(method, ""), members=c.members)


def _alone(spec: Spec, method: str, plans) -> Outcome:
    """A variant analysed by itself; a failure is its message, never an exception."""
    try:
        a = analyse(spec, methods=[method], plans=plans)
    except Exception as exc:     # noqa: BLE001 - a failed variant is a row with its reason
        return Outcome(spec, exception=exc)
    return Outcome(spec, a.review, a.review_problem, a.verdicts,
                   untrusted=untrusted(a.forces[method], a.tol, spec.axis_unit,
                                       a.trust_inputs()),
                   members=a.strength.values if a.strength is not None else None,
                   left_out=tuple(f.angle for f in a.kinematics.flags),
                   branches=a.kinematics.branches, locked=locked_text(a.kinematics))


def locked_text(kin) -> str:
    """Why part of the sweep of ``kin`` (Kinematics) is out of reach, the mechanism locking
    ("" when the driver covers it all)."""
    motion = kin.motion
    if motion is None or motion.full:
        return ""
    return motion.describe() or "part of the sweep is out of reach (the mechanism locks)"


__all__ = ["Outcome", "analyse_variants", "locked_text"]
