"""Contour method (textbook 4.5, Table 4.1; worked in 4.6.4 and 4.7.3).

For each joint X of a loop, cut X (its reaction becomes the unknown) and walk the loop from X
along path I (into X's second link) and path II (into its first link). At each joint W met,
the links left behind form a free body S with d'Alembert loads; W's reaction is eliminated by
writing, for S,

- at a pin W: the moment about W of everything acting on S;
- at a slider W: the projection of everything acting on S on W's sliding direction.

A path stops before it would take in the ground. Candidates are taken alternately from paths I
and II; one is used when every unknown in it is X's (or already found) and it is independent
of those chosen (rank judged at up to 16 angles spread over the sweep: independent at every
one first, then at most of them); a T joint X also gets F . Delta = 0. The driver torque is
solved with the driver joint (4.73-4.75), so a body holding the crank is usable only then.

Loops are every simple cycle of the joint graph (model.graph), shortest first and those
without the driver before those with it. Joints are taken by name, last first, each as soon
as one of its loops gives enough equations usable with the reactions already found (4.7.3:
E, D_T, D on 0-3-4-5-0; then C, B_T, B, A). Nothing depends on the order of the spec. A
search decided by the structure alone is kept for that structure and replayed, its steps
tested again, for the next spec of it (see :func:`plan`).
"""
from __future__ import annotations

from dataclasses import dataclass
from itertools import combinations

import numpy as np

from ..errors import UnsupportedMechanism
from ..model import Loop, topology
from ..spec import GROUND, Joint
from .builders import (applied_at, force_equation, moment_equation, normal_constraint,
                       with_moment)
from .context import ForceContext, reaction_unknowns
from .equations import Equation, Matching, Step
from .result import ForceResult, method_steps, run_steps

PROBES = 16         # angles at which the rank of candidate equations is judged
SEARCH_IN_PLACE = 64   # sweeps of at most this many angles are searched without a probe context
RANK_RTOL = 1e-9    # singular values below this fraction of the largest count as zero

NAME = "contour"
TITLE = "Contour"
SECTION = "4.5, 4.6.4, 4.7.3"


def _path(loop: Loop, x: int, forward: bool):
    """Yield (W, S) along the loop from joint index ``x``: W the joint met, S the links left
    behind (in order). Stops before the ground would join S, or back at X."""
    m = len(loop.joints)
    k = (x + 1) % m if forward else x          # index of the first link entered
    body: list[str] = []
    for step in range(m - 1):
        link = loop.links[k]
        if link == GROUND:
            return
        body.append(link)
        w = loop.joints[k] if forward else loop.joints[(k - 1) % m]
        yield w, list(body)
        k = (k + 1) % m if forward else (k - 1) % m


def _equation(ctx: ForceContext, w: Joint, body: list[str]) -> Equation:
    acts = ctx.actions_on(body, inertia=True, exclude=(w.name,))
    if w.type == "R":
        return moment_equation(ctx, body, acts, w.point)
    return force_equation(ctx, body, acts, f"Delta_{w.name}", ctx.line_direction(w))


def _rows(eq: Equation, unknowns: list[str], probes: np.ndarray) -> np.ndarray:
    row = np.zeros((len(probes), len(unknowns)))
    for t in eq.terms:
        for k, u in enumerate(t.action.unknowns):
            if u in unknowns:
                row[:, unknowns.index(u)] += t.coeffs[probes, k]
    return row


def _matrix(equations: list[Equation], unknowns: list[str], probes: np.ndarray) -> np.ndarray:
    """The coefficients (P, r, k) of ``equations`` in ``unknowns`` at the probe angles, made
    dimensionless: a moment equation's coefficients on forces are lever arms (lengths) and a
    couple's unknown enters with 1, so the moment equations are divided, and the couples'
    columns multiplied, by the probe's largest lever arm L (rounded to a power of two: only
    exponents change). A mechanism 1e9 m or 1e-9 m across is then tested as one 1 m across;
    every moment row (and couple column) shares one factor, so what is round-off next to its
    neighbours stays so."""
    rows = np.stack([_rows(e, unknowns, probes) for e in equations], axis=1)
    moment_rows = np.array([e.kind == "moment" for e in equations])
    couples = np.array([u.endswith(".moment") or u == "driver.torque" for u in unknowns])
    if not moment_rows.any() or couples.all():
        return rows
    arms = np.abs(rows[:, moment_rows][:, :, ~couples]).max(axis=(1, 2))     # (P,)
    ok = np.isfinite(arms) & (arms > 0)
    _, exp = np.frexp(np.where(ok, arms, 1.0))
    scale = np.ldexp(1.0, exp)[:, None]                                       # (P, 1)
    rows[:, moment_rows] /= scale[:, :, None]
    rows[:, :, couples] *= scale[:, None]
    return rows


def _rank(rows: np.ndarray, rtol: float = RANK_RTOL) -> np.ndarray:
    """Numerical rank (P,) of each probe's matrix ``rows`` (P, r, k): its singular values
    above ``rtol`` times the largest."""
    if rows.shape[1] == 1:      # one row: its only singular value is its norm
        big = np.abs(rows[:, 0]).max(axis=1, initial=0.0)
        if ((big == 0) | ((big > 1e-290) & (big < 1e290))).all():
            return (big > 0).astype(int)    # zero, or far from the SVD's floor and overflow
    s = np.linalg.svd(rows, compute_uv=False)
    top = np.maximum(s[:, :1], 1e-300)
    return np.sum(s > rtol * top, axis=1)


def _surely_independent(rows: np.ndarray, rtol: float) -> bool:
    """Whether the square matrices ``rows`` (P, k, k) certainly have, at every probe, every
    singular value above ``rtol`` times the largest (:func:`_rank` would count k), read from
    their determinants at a fifth of an SVD's cost: |det| = s_1 ... s_k <= s_min s_max^(k-1)
    and s_max <= ||A||_F, so s_min / s_max >= |det| / ||A||_F^k. The test asks for twice
    ``rtol`` there, far above the determinant's rounding (an LU's, of order k^2 eps
    ||A||_F^k for k <= 8, growth included). False (the SVD decides) where it cannot tell: a
    ratio below that, more than 8 unknowns, or ||A||_F outside 1e-30 to 1e30, NaN included
    (within it, ||A||_F^8 and the bound stay far from overflow and underflow: an underflow
    to 0 would pass any nonzero determinant)."""
    k = rows.shape[1]
    if rows.shape[2] != k or not 1 <= k <= 8:
        return False
    with np.errstate(over="ignore", under="ignore", invalid="ignore"):
        square = np.einsum("pij,pij->p", rows, rows)          # ||A||_F^2
        if not ((square >= 1e-60) & (square <= 1e60)).all():
            return False
        return bool((np.abs(np.linalg.det(rows)) > 2.0 * rtol * square ** (k / 2)).all())


def _needs(ctx: ForceContext, w: Joint, body: list[str]) -> frozenset[str]:
    """The unknowns the equation cut at ``w`` for ``body`` names (its ``unknown_names``),
    read from the actions without building the equation."""
    acts = [a for a in ctx.actions_on(body, inertia=True, exclude=(w.name,)) if a.unknowns]
    if w.type == "R":
        acts = with_moment(ctx, acts, ctx.point_of(w.point))
    else:                                   # a projection: couples have none
        acts = [a for a in acts if a.kind == "force"]
    return frozenset(u for a in acts for u in a.unknowns)


def _candidates(ctx: ForceContext, loop: Loop, joint: Joint, unknowns: list[str],
                known: set[str], cache: dict) -> list[tuple[str, tuple[str, ...]]]:
    """The equations along ``loop`` cut at ``joint``, in the text's order (alternately along
    paths I and II), that involve ``unknowns`` and nothing else not yet known: as keys (W,
    body) for :func:`_built`, which builds only those the selection tries."""
    x = [j.name for j in loop.joints].index(joint.name)
    paths = [list(_path(loop, x, True)), list(_path(loop, x, False))]
    needs = cache.setdefault("needs", {})        # the same cuts come back joint after joint
    wanted = set(unknowns)
    usable = wanted | known
    out = []
    for w, body in (p[k] for k in range(max(map(len, paths))) for p in paths if k < len(p)):
        key = (w.name, tuple(body))
        need = needs.get(key)
        if need is None:
            need = needs[key] = _needs(ctx, w, body)
        if need & wanted and need <= usable:
            out.append(key)
    return out


def _built(ctx: ForceContext, key: tuple[str, tuple[str, ...]], cache: dict) -> Equation:
    """The equation cut at joint ``key[0]`` for the body ``key[1]``, built once per search."""
    if key not in cache:
        cache[key] = _equation(ctx, ctx.spec.joint(key[0]), list(key[1]))
        _recipes(cache)[id(cache[key])] = ("cut", *key)
    return cache[key]


def _select(unknowns: list[str], chosen: list[Equation], candidates: list, build,
            probes: np.ndarray, needs: dict, numeric: list | None = None,
            ) -> list[Equation] | None:
    """Independent equations for ``unknowns`` from ``candidates`` (keys, built by ``build``
    when taken; ``needs[key]`` the unknowns each names), after ``chosen``: a candidate is
    taken first only where it adds rank at every probe angle, then, for what is still
    missing, where it adds rank at most of them (independent except at isolated angles,
    which the solve then flags). None if there are not enough.

    The rank is judged on the structure first (:func:`_structural`), which needs no numbers.
    Too few by structure, there are not enough: any square set of them is singular at every
    angle (a structurally singular matrix), whatever its numbers. If the equations it picks
    are enough and independent at every probe angle with a margin (:func:`_verified`), they
    are exactly those the numerical selection (:func:`_select_numeric`) takes in its first
    pass: rows taken from a matrix of full row rank keep full rank (their smallest singular
    value is no smaller, their largest no larger; the margin covers the SVD's rounding of a
    small singular value, about eps relative to the largest), and a candidate that adds no
    structural rank adds none at any angle. That is one rank test instead of one per
    candidate. Otherwise (``chosen`` not independent by structure, or the picked set not
    independent enough) the numerical selection decides, and ``numeric`` (a list) is told
    so: the choice then hangs on the numbers, not on the structure alone."""
    start = [frozenset(e.unknown_names()) for e in chosen]
    keys = _structural(unknowns, start, candidates, needs)
    if keys is not None:
        if len(start) + len(keys) < len(unknowns):
            return None
        picked = list(chosen) + [build(key) for key in keys]
        if _verified(unknowns, picked, probes):
            return picked
    if numeric is not None:
        numeric.append(True)
    return _select_numeric(unknowns, chosen, candidates, build, probes)


def _verified(unknowns: list[str], equations: list[Equation], probes: np.ndarray) -> bool:
    """Whether ``equations`` (as many as ``unknowns``) are independent at every probe angle
    with a margin: singular values above twice ``RANK_RTOL`` of the largest, most often read
    from the determinants (:func:`_surely_independent`), else by the SVD."""
    rows = _matrix(equations, unknowns, probes)
    return _surely_independent(rows, 2 * RANK_RTOL) \
        or bool((_rank(rows, 2 * RANK_RTOL) == len(unknowns)).all())


def _structural(unknowns: list[str], start: list[frozenset], candidates: list,
                needs: dict) -> list | None:
    """The candidates (keys) the greedy selection takes by structural rank, after the
    equations naming ``start``: each one that can be matched to an unknown of its own
    (:class:`~mechreport.forces.equations.Matching`), until every unknown is. None if the
    ``start`` equations cannot all be matched (the numerical selection keeps them whatever
    their rank)."""
    col = {u: k for k, u in enumerate(unknowns)}
    matching = Matching(len(unknowns))
    if not all(matching.add([col[u] for u in names if u in col]) for names in start):
        return None
    taken = []
    for key in candidates:
        if len(matching) == len(unknowns):
            break
        if matching.add([col[u] for u in needs[key] if u in col]):
            taken.append(key)
    return taken


def _select_numeric(unknowns: list[str], chosen: list[Equation], candidates: list, build,
                    probes: np.ndarray) -> list[Equation] | None:
    """:func:`_select` by the numerical rank at the probe angles, candidate by candidate."""
    chosen = list(chosen)
    taken: set = set()
    rank = _rank(_matrix(chosen, unknowns, probes)) if chosen else np.zeros(len(probes), int)
    for share in (1.0, 0.5):
        for key in candidates:
            if len(chosen) == len(unknowns):
                break
            if key in taken:
                continue
            eq = build(key)
            new = _rank(_matrix(chosen + [eq], unknowns, probes))
            gain = np.count_nonzero(new > rank) / len(probes)   # the share of probes
            if gain >= share and gain > 0:
                chosen.append(eq)
                taken.add(key)
                rank = new
    return chosen if len(chosen) == len(unknowns) else None


def _unknowns(ctx: ForceContext, joints) -> list[str]:
    out = [u for j in joints for u in reaction_unknowns(j)]
    if any(j.name == ctx.spec.driver.joint for j in joints):
        out.append(ctx.driver_unknown)
    return out


def _try_joint(ctx: ForceContext, loop: Loop, joint: Joint, known: set[str],
               probes: np.ndarray, cache: dict) -> Step | None:
    """Enough independent equations along ``loop`` for ``joint``'s unknowns, or None."""
    unknowns = _unknowns(ctx, [joint])
    start = [_normal(ctx, joint, cache)] if joint.type == "T" else []
    chosen = _select(unknowns, start, _candidates(ctx, loop, joint, unknowns, known, cache),
                     lambda key: _built(ctx, key, cache), probes,
                     cache.setdefault("needs", {}), cache.setdefault("numeric", []))
    if chosen is None:
        return None
    return Step(f"Joint {joint.name} (loop {loop.label(ctx.spec)})", unknowns, chosen,
                tuple(sorted({b for e in chosen for b in e.bodies})))


def _try_joints(ctx: ForceContext, joints, loops: list[Loop], known: set[str],
                probes: np.ndarray, cache: dict) -> Step | None:
    """Several joints whose reactions no loop isolates one by one (the interior joints of a
    triad or larger Assur group), solved together from the equations along every loop cut at
    any of them."""
    unknowns = _unknowns(ctx, joints)
    start = [_normal(ctx, j, cache) for j in joints if j.type == "T"]
    candidates: list = []
    for joint in joints:
        for loop in (l for l in loops if joint.name in {j.name for j in l.joints}):
            for key in _candidates(ctx, loop, joint, unknowns, known, cache):
                if key not in candidates:
                    candidates.append(key)
    chosen = _select(unknowns, start, candidates, lambda key: _built(ctx, key, cache), probes,
                     cache.setdefault("needs", {}), cache.setdefault("numeric", []))
    if chosen is None:
        return None
    names = ", ".join(j.name for j in joints)
    return Step(f"Joints {names} (together: no loop isolates one of them)", unknowns, chosen,
                tuple(sorted({b for e in chosen for b in e.bodies})))


def _bridge_step(ctx: ForceContext, joint: Joint, known: set[str]) -> Step | None:
    """A joint on no loop cuts the mechanism in two: the part away from the ground is a free
    body whose forces (x, y) and moments about the joint determine the joint's reaction (and
    the driver torque, for the driver joint). None if the joint is on a loop after all."""
    spec = ctx.spec
    side = {l for l in joint.links if l != GROUND}
    grew = True
    while grew:
        grew = False
        for j in spec.joints:
            if j.name != joint.name and (set(j.links) & side) and not set(j.links) <= side:
                if GROUND in j.links:
                    return None
                side |= set(j.links)
                grew = True
    body = [l.name for l in spec.links if l.name in side]
    acts = ctx.actions_on(body, inertia=True)
    eqs = [force_equation(ctx, body, acts, "x"), force_equation(ctx, body, acts, "y"),
           moment_equation(ctx, body, acts, joint.point, at=ctx.joint_points[joint.name])]
    unknowns = [u for e in eqs for u in e.unknown_names() if u not in known]
    unknowns = list(dict.fromkeys(unknowns))
    if joint.type == "T":
        eqs.insert(0, normal_constraint(ctx, joint))
    if len(unknowns) != len(eqs):
        return None
    return Step(f"Joint {joint.name} (no loop: {', '.join(body)} as one free body)", unknowns,
                eqs, tuple(body))


def _probes(n: int) -> np.ndarray:
    """Up to ``PROBES`` angle indices spread evenly over the sweep."""
    return np.unique(np.linspace(0, n - 1, min(PROBES, n)).round().astype(int))


def _normal(ctx: ForceContext, joint: Joint, cache: dict) -> Equation:
    eq = normal_constraint(ctx, joint)
    _recipes(cache)[id(eq)] = ("normal", joint.name)
    return eq


def _recipes(cache: dict) -> dict[int, tuple]:
    """How each equation (or bridge step) of one search was built, by id (kept beside the
    search's equations, which keeps those ids valid)."""
    return cache.setdefault("recipes", {})


@dataclass(frozen=True)
class StepPlan:
    """A step the search chose: its title, unknowns and bodies, and each equation's recipe
    (``("cut", W, body)``, ``("normal", joint)``, or ``("bridge", joint)`` for a whole
    step), to be built again over any angles."""

    title: str
    unknowns: tuple[str, ...]
    recipes: tuple[tuple, ...]
    bodies: tuple[str, ...]


class ContourPlans:
    """The plans the search made, kept per structure (a topology and which joints'
    reactions act at which pin, see :func:`_structure`) as long as each choice it made
    followed from that structure alone, for whoever analyses many specs of one structure
    (a batch, a study's variants): pass one to each ForceContext (``ctx.plans``) and the
    next spec of a structure replays its plan instead of searching. Bit for bit the search's
    result either way; kept for the last ``KEEP`` structures at most."""

    KEEP = 64

    def __init__(self) -> None:
        self._by_structure: dict[tuple, tuple[StepPlan, ...]] = {}

    def get(self, structure: tuple) -> tuple[StepPlan, ...] | None:
        return self._by_structure.get(structure)

    def keep(self, structure: tuple, plans: tuple[StepPlan, ...]) -> None:
        if structure not in self._by_structure and len(self._by_structure) >= self.KEEP:
            self._by_structure.clear()
        self._by_structure[structure] = plans

    def __len__(self) -> int:
        return len(self._by_structure)

    def structures(self) -> list[tuple]:
        return list(self._by_structure)


def plan(ctx: ForceContext) -> tuple[StepPlan, ...]:
    """The equations the method uses, chosen once per analysis (kept in ``ctx.memo``, which
    the chunks of a long sweep share): the search judges independence at up to ``PROBES``
    angles, so it runs on a context of those angles alone.

    Where the search's every choice followed from the structure (:func:`_select`: the
    structural path, never the numerical selection), its plan is kept in ``ctx.plans`` (a
    :class:`ContourPlans`, if the caller gave one), and the next spec of the structure
    replays it (:func:`_replay`) instead of searching: every step is built again and must
    pass the same independence test at its own probe angles, which is all the search would
    ask of it; failing that, the search runs."""
    if "contour" not in ctx.memo:
        probes = _probes(ctx.n)
        # a short sweep is searched in place, and its steps kept: no second context to build
        small = ForceContext(ctx.kin.take(probes, ctx.kin.flags)) \
            if ctx.n > SEARCH_IN_PLACE else ctx
        book = ctx.plans
        structure = _structure(small) if book is not None else None
        plans = book.get(structure) if book is not None else None
        steps = _replay(small, plans) if plans is not None else None
        if steps is None:
            steps, recipes, by_structure = _search(small)
            plans = tuple(
                StepPlan(s.title, tuple(s.unknowns),
                         (recipes[id(s)],) if id(s) in recipes
                         else tuple(recipes[id(e)] for e in s.equations), tuple(s.bodies))
                for s in steps)
            if by_structure and book is not None:
                book.keep(structure, plans)
        if small is ctx:
            ctx.cache["contour steps"] = steps
        ctx.memo["contour"] = plans
    return ctx.memo["contour"]


def _structure(ctx: ForceContext) -> tuple:
    """What the search's structural choices depend on: the topology (links, joints, driver:
    the loops, the free bodies and the unknowns each names) and, for each pin a cut may take
    moments about, which joints' reactions act at it at every angle (they have no moment
    there, :func:`~mechreport.forces.builders.with_moment`, and so are not named)."""
    points = ctx.joint_points
    joints = ctx.spec.joints
    return (topology(ctx.spec), tuple(
        tuple(applied_at(ctx, points[j.name], ctx.point_of(w.point)) for j in joints)
        for w in joints if w.type == "R"))


def _replay(ctx: ForceContext, plans: tuple[StepPlan, ...]) -> tuple[Step, ...] | None:
    """The steps of ``plans``, a plan the search made from the structure alone for another
    spec of ``ctx``'s structure, built over ``ctx``'s angles: the search's own result,
    provided each step is independent at ``ctx``'s probe angles (:func:`_verified`, the
    test its selection took it by) and each bridge holds; else None (the search decides).
    Its structural choices (what each cut names, which attempts fall short) are the same
    for the same structure."""
    probes = _probes(ctx.n)
    known: set[str] = set()
    steps = []
    for p in plans:
        step = _realise(ctx, p, known)
        if step is None or list(step.unknowns) != list(p.unknowns):
            return None
        if p.recipes[0][0] != "bridge":
            usable = known.union(p.unknowns)     # (so it is, for the same structure)
            if not all(usable.issuperset(e.unknown_names()) for e in step.equations) \
                    or not _verified(step.unknowns, step.equations, probes):
                return None
        steps.append(step)
        known.update(p.unknowns)
    return tuple(steps)


def _realise(ctx: ForceContext, p: StepPlan, known: set[str]) -> Step | None:
    """The step ``p`` plans, built over ``ctx``'s angles (None: a bridge that does not hold
    there)."""
    if p.recipes[0][0] == "bridge":
        return _bridge_step(ctx, ctx.spec.joint(p.recipes[0][1]), known)
    eqs = []
    for r in p.recipes:
        if r[0] == "normal":
            eqs.append(normal_constraint(ctx, ctx.spec.joint(r[1])))
        else:
            eqs.append(_equation(ctx, ctx.spec.joint(r[1]), list(r[2])))
    return Step(p.title, list(p.unknowns), eqs, p.bodies)


def build_steps(ctx: ForceContext) -> tuple[Step, ...]:
    """The planned steps (see :func:`plan`) built over ``ctx``'s angles."""
    plans = plan(ctx)
    if "contour steps" in ctx.cache:
        return ctx.cache["contour steps"]
    known: set[str] = set()
    steps = []
    for p in plans:
        steps.append(_realise(ctx, p, known))
        known.update(p.unknowns)
    return tuple(steps)


def _search(ctx: ForceContext) -> tuple[tuple[Step, ...], dict[int, tuple], bool]:
    """Joints in a canonical order (by name, last first: the text's order for 4.6 and 4.7),
    each from the first loop through it, loops without the driver first, that gives enough
    independent equations with the reactions already found. Nothing depends on the order in
    which links and joints are written. Returns the steps, how each of their equations was
    built (:func:`_recipes`), and whether every choice followed from the structure alone
    (the numerical selection never ran)."""
    spec = ctx.spec
    drv = spec.driver.joint
    loops = sorted(ctx.mech.cycles, key=lambda l: (drv in {j.name for j in l.joints},
                                                  len(l.joints), sorted(j.name for j in l.joints)))
    probes = _probes(ctx.n)
    known: set[str] = set()
    solved: set[str] = set()
    steps: list[Step] = []
    cache: dict = {}
    order = sorted(spec.joints, key=lambda j: j.name, reverse=True)

    def take(step: Step, joints) -> None:
        steps.append(step)
        solved.update(j.name for j in joints)
        known.update(step.unknowns)

    while len(solved) < len(order):
        todo = [j for j in order if j.name not in solved]
        step = next(((s, [j]) for j in todo for loop in loops
                     if j.name in {x.name for x in loop.joints}
                     and (s := _try_joint(ctx, loop, j, known, probes, cache)) is not None),
                    None)
        for size in range(2, len(todo) + 1):
            if step is not None:
                break
            step = next(((s, list(js)) for js in combinations(todo, size)
                         if (s := _try_joints(ctx, js, loops, known, probes, cache))
                         is not None), None)
        if step is None:
            break
        take(*step)
    for joint in (j for j in order if j.name not in solved):
        step = _bridge_step(ctx, joint, known)   # a joint on no loop (a lone crank)
        if step is not None:
            _recipes(cache)[id(step)] = ("bridge", joint.name)
            steps.append(step)
            solved.add(joint.name)
            known.update(step.unknowns)
    missing = [j.name for j in spec.joints if j.name not in solved]
    if missing:
        raise UnsupportedMechanism(
            f"{spec.file}: the contour method found no independent equations for joint(s) "
            f"{', '.join(missing)} along the loops {', '.join(l.label(spec) for l in loops)}")
    return tuple(steps), _recipes(cache), not cache.get("numeric")


def solve(ctx: ForceContext) -> ForceResult:
    return run_steps(NAME, ctx, method_steps(ctx, NAME, build_steps))
