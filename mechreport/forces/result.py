"""The common result type of every force method."""
from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from ..quantities import split as split_quantity
from .equations import Step
from .friction_law import friction_from, joint_senses


@dataclass(frozen=True)
class JointReaction:
    """Reaction of ``links[0]`` on ``links[1]`` of joint ``joint`` over the angles (n,).

    ``fx``, ``fy`` [N], global; T joints also ``moment`` [N m], the couple about the slider's
    point, and ``px``, ``py`` [m], the equivalent application point on the sliding line (NaN
    where the force vanishes and the point is undefined; ``p_defined`` says where it is)."""

    joint: str
    type: str
    fx: np.ndarray
    fy: np.ndarray
    moment: np.ndarray | None = None
    px: np.ndarray | None = None
    py: np.ndarray | None = None
    derived: bool = False     # not an unknown: a pin's force on its hub, from the others
    friction: np.ndarray | None = None   # (n,) the joint's friction on its second link
                                         # (R: couple [N m]; T: force along the line [N])

    @property
    def f(self) -> np.ndarray:
        """Magnitude [N]."""
        return np.hypot(self.fx, self.fy)

    @property
    def p_defined(self) -> np.ndarray | None:
        return None if self.px is None else np.isfinite(self.px)

    def component(self, attr: str) -> np.ndarray | None:
        return self.f if attr == "f" else getattr(self, attr, None)


@dataclass(frozen=True)
class ForceResult:
    """One method's joint reactions and driver torque at every analysed angle.

    ``angles`` (n,) values of the sweep coordinate [deg or length unit]; ``driver_torque``
    (n,) the driver's effort named ``driver_quantity``: the torque [N m] an R driver applies
    (CCW positive), or the force [N] a T driver's first link exerts on its second along the
    line; ``reactions`` by joint name (empty for ``power``); ``singular`` (n,) bool;
    ``cond`` (n,) the product of the steps' condition numbers (later steps take earlier steps'
    results as data, so their errors multiply): relative errors of the inputs grow by at most
    about this factor; NaN where a system's coefficients were not finite (overflow).

    The labelled systems the method solved are not kept with the numbers (they hold every
    coefficient at every angle: most of an analysis' memory); an analysis builds them again
    when asked (:meth:`mechreport.pipeline.Analysis.worked_steps`)."""

    method: str
    angles: np.ndarray
    reactions: dict[str, JointReaction]
    driver_torque: np.ndarray
    singular: np.ndarray
    cond: np.ndarray | None = None
    driver_quantity: str = "driver.torque"   # "driver.force" for a T driver

    def take(self, rows: np.ndarray, source) -> "ForceResult":
        """The result at angle indices ``rows`` (index array or bool mask); ``source`` the
        ForceContext over those angles (a T joint's point is found again against them)."""
        def cut(x):
            return None if x is None else x[rows]
        reactions = {}
        for k, r in self.reactions.items():
            fx, fy, m = r.fx[rows], r.fy[rows], cut(r.moment)
            px, py = cut(r.px), cut(r.py)
            if m is not None and source is not None:   # against the kept angles' forces
                px, py = slider_point(source, source.spec.joint(k), fx, fy, m)
            reactions[k] = replace(r, fx=fx, fy=fy, moment=m, px=px, py=py,
                                   friction=cut(r.friction))
        return replace(self, angles=self.angles[rows], reactions=reactions,
                       driver_torque=self.driver_torque[rows], singular=self.singular[rows],
                       cond=cut(self.cond))

    @staticmethod
    def join(parts: list["ForceResult"], source) -> "ForceResult":
        """Results over consecutive chunks of angles, joined into one over all of them."""
        first = parts[0]
        if len(parts) == 1:
            return first

        def cat(get):
            vals = [get(p) for p in parts]
            return None if vals[0] is None else np.concatenate(vals)
        reactions = {}
        for k, r in first.reactions.items():
            fx, fy = cat(lambda p: p.reactions[k].fx), cat(lambda p: p.reactions[k].fy)
            m = cat(lambda p: p.reactions[k].moment)
            px = py = None
            if m is not None:        # defined against the whole sweep's largest force
                px, py = slider_point(source, source.spec.joint(k), fx, fy, m)
            reactions[k] = replace(r, fx=fx, fy=fy, moment=m, px=px, py=py,
                                   friction=cat(lambda p: p.reactions[k].friction))
        return replace(first, angles=cat(lambda p: p.angles), reactions=reactions,
                       driver_torque=cat(lambda p: p.driver_torque),
                       singular=cat(lambda p: p.singular), cond=cat(lambda p: p.cond))

    def quantity(self, name: str, spec=None) -> np.ndarray | None:
        """A result quantity by its ``expect`` name, e.g. ``joint.B.fx`` or ``driver.torque``
        (``driver.force`` for a T driver); with the ``spec``, also what a two-link joint
        exerts on either link (``joint.B.on.crank.fx``)."""
        if name == self.driver_quantity:
            return self.driver_torque
        parts = split_quantity(name)
        if parts is None or parts[0] != "joint":
            return None
        _, joint, attr = parts
        if joint in self.reactions:
            return self.reactions[joint].component(attr)
        terms = None if spec is None else spec.reaction_terms(joint)
        if not terms or len(terms) != 1 or terms[0][0] not in self.reactions:
            return None
        (own, sign), = terms
        values = self.reactions[own].component(attr)
        return values if attr == "f" or values is None else sign * values + 0.0

    def values(self) -> dict[str, np.ndarray]:
        """Every unknown by name (joint.J.fx/fy/moment, driver.torque; not a pin's force on
        its hub, which the others give): a new dict each time, of the result's own
        arrays."""
        out = {self.driver_quantity: self.driver_torque}
        for r in self.reactions.values():
            if r.derived:
                continue
            out[f"joint.{r.joint}.fx"] = r.fx
            out[f"joint.{r.joint}.fy"] = r.fy
            if r.moment is not None:
                out[f"joint.{r.joint}.moment"] = r.moment
        return out


def slider_point(ctx, joint, fx: np.ndarray, fy: np.ndarray, m: np.ndarray,
                 top: float | None = None):
    """Where a T joint's force (fx, fy) and couple m about the slider's point act as one force
    on the sliding line: (px, py) [m], NaN where the force vanishes (below 1e-12 of ``top``,
    the largest force component over the sweep, by default over these angles) and the point
    is undefined. (n,) each, or (k, n) for k results at once (each its own ``top``)."""
    u = ctx.line_direction(joint)
    s = u[:, 0] * fy - u[:, 1] * fx                 # u x f
    if top is None:                                 # (NaN if any component is NaN)
        top = np.maximum(np.abs(fx).max(axis=-1, initial=0.0, keepdims=True),
                         np.abs(fy).max(axis=-1, initial=0.0, keepdims=True))
    scale = np.maximum(top, 1e-300)
    with np.errstate(divide="ignore", invalid="ignore"):
        t = np.where(np.abs(s) > 1e-12 * scale, m / s, np.nan)
    p = ctx.joint_points[joint.name] + t[..., None] * u
    return p[..., 0], p[..., 1]


def make_result(method: str, ctx, values: dict[str, np.ndarray], steps, singular, cond,
                points: dict) -> ForceResult:
    """Assemble a ForceResult from solved unknowns (shared by all methods); ``points``: the
    T joints' :func:`slider_point` by joint name (:func:`_slider_points`)."""
    spec = ctx.spec
    reactions = {}
    if _has_reactions(values):
        for j in spec.joints:
            fx, fy = values[f"joint.{j.name}.fx"], values[f"joint.{j.name}.fy"]
            if j.type == "R":
                reactions[j.name] = JointReaction(j.name, "R", fx, fy)
                continue
            m = values[f"joint.{j.name}.moment"]
            px, py = points[j.name]
            reactions[j.name] = JointReaction(j.name, "T", fx, fy, m, px, py)
        reactions = _with_friction(ctx, reactions)
        reactions = _with_pin_hubs(spec, reactions)
    quantity = ctx.spec.driver.quantity
    return ForceResult(method, ctx.kin.angles, reactions, values[quantity], singular, cond,
                       quantity)


def _with_friction(ctx, reactions: dict[str, JointReaction]) -> dict[str, JointReaction]:
    """``reactions`` with each friction joint's friction by the law from the method's own
    reaction (``joint.J.friction``: equal to the friction the equations were given when the
    method is right, which the agreement between methods then shows)."""
    if ctx.kin.friction is None:
        return reactions
    sense = joint_senses(ctx)
    for fr in ctx.spec.friction:
        r = reactions[fr.joint]
        reactions[fr.joint] = replace(r, friction=friction_from(ctx, fr, sense[fr.joint],
                                                                r.fx, r.fy, r.moment))
    return reactions


def _with_pin_hubs(spec, reactions: dict[str, JointReaction]) -> dict[str, JointReaction]:
    """``reactions`` with the force each pin joining several links exerts on its hub (minus
    the sum of its forces on the other links: the pin is in equilibrium), in the order of
    ``spec.reported_reactions()``."""
    if not spec.pins:
        return reactions
    for pin in spec.pins:
        parts = [reactions[pin.joint_name(x)] for x in pin.others]
        fx = -np.sum([r.fx for r in parts], axis=0)
        fy = -np.sum([r.fy for r in parts], axis=0)
        reactions[pin.joint_name(pin.hub)] = JointReaction(pin.joint_name(pin.hub), "R",
                                                           fx + 0.0, fy + 0.0, derived=True)
    return {name: reactions[name] for name in spec.reported_reactions()}


def run_steps(method: str, ctx, steps) -> ForceResult:
    """Solve ``steps`` in order, each with the values found by those before it, block by
    block (:func:`chain`); the condition number is the product of the blocks'."""
    return run_methods({method: steps}, ctx)[method]


def run_methods(steps: dict[str, tuple], ctx, prepared: dict | None = None,
                ) -> dict[str, ForceResult]:
    """Every method's ``steps`` (by method name) solved together, level by level of their
    chains (:func:`mechreport.forces.chains.solve_chains`: the numbers each gets alone);
    ``prepared``: their blocks' systems, by ``id`` of the block, if prepared already."""
    from .chains import solve_chains
    solved = solve_chains([chain(ctx, s) for s in steps.values()], ctx.n, prepared)
    points = _slider_points(ctx, [sol.values for sol in solved])
    return {method: make_result(method, ctx, sol.values, s, sol.singular, sol.cond, pts)
            for (method, s), sol, pts in zip(steps.items(), solved, points)}


def _has_reactions(values: dict) -> bool:
    return any(k.startswith("joint.") for k in values)


def _slider_points(ctx, solved: list[dict[str, np.ndarray]]) -> list[dict]:
    """Every T joint's :func:`slider_point` for each of the results ``solved`` (unknowns by
    name) that has reactions, each joint's for all of them at once: by joint name, per
    result."""
    out: list[dict] = [{} for _ in solved]
    which = [k for k, values in enumerate(solved) if _has_reactions(values)]
    if not which:
        return out
    for j in (j for j in ctx.spec.joints if j.type == "T"):
        fx, fy, m = (np.array([solved[k][f"joint.{j.name}.{c}"] for k in which])
                     for c in ("fx", "fy", "moment"))
        px, py = slider_point(ctx, j, fx, fy, m)
        for row, k in enumerate(which):
            out[k][j.name] = (px[row], py[row])
    return out


def method_steps(ctx, method: str, build) -> tuple[Step, ...]:
    """``build(ctx)``, the steps of ``method``, once per context (what a method's ``solve``
    solves, and what :func:`mechreport.forces.solve_forces` prepares beforehand)."""
    return ctx.once(("steps", method), lambda: tuple(build(ctx)))


def chain(ctx, steps) -> list[Step]:
    """``steps`` as the chain of square blocks solved in turn (each step's
    ``triangular_blocks``), once per context and ``steps`` (kept with them: their ids stay
    theirs)."""
    from .equations import triangular_blocks
    return ctx.once(("chain", id(steps)),
                    lambda: [b for step in steps for b in triangular_blocks(step)], keep=steps)
