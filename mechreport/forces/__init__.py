"""Stage 4: joint reactions and driver torque by the textbook's four methods plus a power
balance. Every method module has ``NAME``, ``TITLE``, ``SECTION``,
``build_steps(ctx: ForceContext)`` (its labelled systems) and
``solve(ctx: ForceContext) -> ForceResult``; they are registered here by name.
:func:`solve_forces` solves every method's steps together (``result.run_methods``), the
numbers each method's ``solve`` gives alone."""
from __future__ import annotations

from types import ModuleType

from ..kinematics import Kinematics
from . import contour, dalembert, dyad, newton_euler, power
from .context import ForceContext
from .equations import Equation, Step, Term, prepare_blocks
from .result import ForceResult, JointReaction, chain, method_steps, run_methods

METHODS: dict[str, ModuleType] = {m.NAME: m for m in (newton_euler, dalembert, dyad, contour,
                                                      power)}


CHUNK = 8192    # angles solved together: bounds the equation objects' memory on long sweeps


def solve_forces(kin: Kinematics, methods=None,
                 ctx: ForceContext | None = None) -> dict[str, ForceResult]:
    """Run the named methods (default: all) on one kinematics; results by method name.
    ``ctx``: the kinematics' ForceContext, if the caller has built it already.

    Sweeps longer than ``CHUNK`` angles are solved chunk by chunk. The results keep the
    numbers, not the equation objects (:func:`worked_steps` builds them again)."""
    names = list(METHODS) if methods is None else list(methods)
    unknown = [m for m in names if m not in METHODS]
    if unknown:
        raise ValueError(f"unknown method(s) {', '.join(unknown)}; valid: {', '.join(METHODS)}")
    ctx = ForceContext(kin) if ctx is None else ctx
    if kin.n <= CHUNK:
        return _solve_all(ctx, names)
    if contour.NAME in names:
        contour.plan(ctx)         # chosen once, over the whole sweep's probe angles
    parts: dict[str, list[ForceResult]] = {name: [] for name in names}
    for a in range(0, kin.n, CHUNK):    # one chunk's context at a time: all methods, then gone
        c = ForceContext(kin.take(slice(a, a + CHUNK), kin.flags))
        c.memo = ctx.memo
        for name, res in _solve_all(c, names).items():
            parts[name].append(res)
        del c
    return {name: ForceResult.join(parts[name], ctx) for name in names}


def _solve_all(ctx: ForceContext, names: list[str]) -> dict[str, ForceResult]:
    """The named methods over ``ctx``. Every method's
    blocks are prepared together (``equations.prepare_blocks``: the same numbers, one pass
    of numpy calls for those of one size, a block that several methods share prepared
    once), then solved together level by level of their chains (``chains.solve_chains``);
    a method that cannot build its equations says so, the first in ``names`` order."""
    steps = {name: method_steps(ctx, name, METHODS[name].build_steps) for name in names}
    prepared = prepare_blocks([chain(ctx, s) for s in steps.values()], ctx.n)
    return run_methods(steps, ctx, prepared)


#: angles at which a method that chooses its equations once per sweep (the contour method)
#: judges them: a long sweep's are spread over the whole of it (see :func:`sweep_choices`)
PROBES = contour.PROBES


def sweep_choices(probes: Kinematics, methods) -> dict:
    """The choices the named ``methods`` make once for a whole sweep (the contour method's
    equations), made over ``probes``, the kinematics at up to ``PROBES`` angles spread over
    it: give them to each chunk's solve (:func:`solve_forces` ``memo``) so that every chunk
    solves the same equations."""
    if contour.NAME not in methods or not probes.n:
        return {}
    probe = ForceContext(probes)
    contour.plan(probe)
    return probe.memo


def worked_steps(ctx: ForceContext, method: str) -> tuple[Step, ...]:
    """The labelled systems ``method`` solves over ``ctx``, in order: the equation objects
    the numbers came from (for the solution sheets and the split by source)."""
    return tuple(METHODS[method].build_steps(ctx))


__all__ = ["METHODS", "PROBES", "solve_forces", "sweep_choices", "worked_steps", "ForceContext", "ForceResult", "JointReaction",
           "Equation", "Step", "Term"]
