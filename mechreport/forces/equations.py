"""Labelled linear equations over named unknowns, and the one batched solver all methods share.

An ``Equation`` is a list of ``Term``s; each term is one action (a force or a couple) as it
enters that equation: its coefficients on the unknowns it carries (joint reaction components,
T-joint couples, the driver torque) and its known constant part. The equation reads
``sum(rhs terms) - sum(lhs terms) = 0`` (Newton-Euler writes ``m a_C`` on the left; every other
method has only right-hand terms, ``... = 0``). Arrays carry the angle axis first: coefficients
(n, k), constants (n,).

A ``Step`` is one square system solved at once (a method may chain several, e.g. dyad by
dyad). Unknowns solved by earlier steps are substituted as known values. The same objects feed
the worked solution sheets, so each term keeps its symbol, application point and lever arm.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from functools import lru_cache

import numpy as np

from ..linalg import (SINGULAR_COND, Equilibrated, SmallSystem, prepare_joined, prepare_large,
                      solve_cond)


@lru_cache(maxsize=4)
def no_constant(n: int) -> np.ndarray:
    """The constant part (n,) of a term that has none: zeros, read-only and shared by every
    such term over n angles (which lets the solver pass it over)."""
    zero = np.zeros(n)
    zero.setflags(write=False)
    return zero


@lru_cache(maxsize=4)
def no_coefficients(n: int) -> np.ndarray:
    """The coefficients (n, 0) of a term on no unknown: read-only and shared."""
    none = np.zeros((n, 0))
    none.setflags(write=False)
    return none


@dataclass(frozen=True, slots=True)
class Action:
    """A force or couple acting on a link.

    ``symbol`` follows the textbook (F12 = force of link 1 on link 2, Fin2, G2, Min2, M).
    Forces: ``at`` (n, 2) is the application point [m], named ``at_name``. Unknown actions carry
    ``unknowns`` (joint.B.fx, joint.B.fy / joint.C_T.moment / driver.torque) times ``sign``; a
    force of one unknown magnitude (driver.force) acts along ``direction`` (n, 2). Known ones
    carry ``value``: (n, 2) [N] for forces, (n,) [N m] for couples.
    """

    symbol: str
    kind: str                       # "force" | "couple"
    category: str       # "reaction" | "driver" | "gravity" | "inertia" | "load" | "friction"
    link: str
    at: np.ndarray | None = None
    at_name: str | None = None
    unknowns: tuple[str, ...] = ()
    sign: float = 1.0
    value: np.ndarray | None = None
    direction: np.ndarray | None = None   # (n, 2) for a force of one unknown magnitude


#: what a term is (``Term.kind``), and the named factors each kind multiplies its action by
TERM_KINDS = {
    "projection": "a force projected on ``direction``: F . d",
    "moment": "the moment of a force about the point ``about``: r_PQ x F (``lever`` = r_PQ)",
    "couple": "a couple in a moment equation: M",
    "inertia": "Newton-Euler's left side: ``mass`` times ``accel`` . d (a force equation) or "
               "``inertia`` times ``alpha`` (a moment equation)",
    "power": "the power of an action: F . v (``rate`` = v of its point) or M omega (``rate`` = "
             "omega)",
}


@dataclass(slots=True, eq=False)
class Term:
    """One action's contribution to one equation: ``coeffs @ x[unknowns] + const``.

    ``kind`` says what the term is (see ``TERM_KINDS``) and the term carries the factors it was
    built from: ``lever`` (n, 2) is r_PQ for moment equations (Q the action's point, P the
    moment centre, named in ``factors`` as ``about``); ``direction`` (n, 2) the projection
    direction for force equations; ``rate`` what a power term works on; ``factors`` the other
    named factors (``mass``, ``accel`` (n, 2), ``inertia``, ``alpha`` (n,), ``about``), kept as
    references to arrays already computed. :func:`mechreport.forces.builders.read_term` reads
    them back as the products a worked solution prints.

    Never changed once made: equations share terms (one per action and direction or moment
    centre, per context). Not frozen only for speed: a frozen dataclass sets each field
    through ``object.__setattr__``, and hundreds of terms are made per analysis and their
    fields read thousands of times (slots read faster than an instance dict)."""

    action: Action
    coeffs: np.ndarray              # (n, len(action.unknowns))
    const: np.ndarray               # (n,)
    side: str = "rhs"
    lever: np.ndarray | None = None
    direction: np.ndarray | None = None
    rate: np.ndarray | None = None   # power terms: the velocity (n, 2) or omega (n,) it works on
    kind: str = ""                   # one of TERM_KINDS ("" only for terms built elsewhere)
    factors: tuple = ()              # ((name, value), ...): the named factors not above

    def factor(self, name: str, default=None):
        """The named factor ``name`` (see ``factors``), or ``default``."""
        for key, value in self.factors:
            if key == name:
                return value
        return default


@dataclass
class Equation:
    """A scalar equation. ``kind``: force | moment | constraint | power.

    ``label`` is how a reader names it (sum F^(2&3) . i); ``bodies`` the links of the free body;
    ``axis`` the projection (x, y, or a named sliding direction); ``about`` the moment centre."""

    label: str
    kind: str
    bodies: tuple[str, ...]
    terms: list[Term] = field(default_factory=list)
    axis: str | None = None
    about: str | None = None

    def unknown_names(self) -> list[str]:
        names: list[str] = []
        for t in self.terms:
            for u in t.action.unknowns:
                if u not in names:
                    names.append(u)
        return names

    def evaluate(self, values: dict[str, np.ndarray]) -> np.ndarray:
        """Residual sum(rhs) - sum(lhs) (n,) with every unknown taken from ``values`` (n,);
        (k, n) for values given as (k, n): k solutions at once, each summed as alone."""
        total = 0.0
        for t in self.terms:
            part = t.const
            for k, u in enumerate(t.action.unknowns):
                product = t.coeffs[:, k] * values[u]
                if part is t.const:
                    part = part + product
                else:
                    part += product
            if isinstance(total, float) or total.ndim < part.ndim:   # (n,) meets (k, n)
                total = total + part if t.side == "rhs" else total - part
            elif t.side == "rhs":
                total += part
            else:
                total -= part
        return total


@dataclass
class Step:
    """A square system: ``equations`` determine ``unknowns`` (given earlier steps' results)."""

    title: str
    unknowns: list[str]
    equations: list[Equation]
    bodies: tuple[str, ...] = ()
    # the other unknowns its equations name, found before it (set by triangular_blocks;
    # None: not known, and the step is taken to need every block before it)
    needs: tuple[str, ...] | None = field(default=None, compare=False, repr=False)


@dataclass(frozen=True)
class Solution:
    """Values (n,) per unknown; the system's estimated condition number (n,) (equilibrated,
    inf where exactly singular); where it was singular (n,) bool."""

    values: dict[str, np.ndarray]
    cond: np.ndarray

    @property
    def singular(self) -> np.ndarray:
        return ~(self.cond < SINGULAR_COND)


def step_matrix(step: Step, n: int) -> np.ndarray:
    """The step's matrix A (m, m, n), angle-last: each equation's coefficients on the step's
    own unknowns (those of earlier steps go to the right-hand side, :func:`step_rhs`)."""
    return joined_matrices([step], n)


def joined_matrices(steps: list[Step], n: int) -> np.ndarray:
    """The matrices of ``steps`` (each m x m, one m for all) joined along the angle axis,
    A (m, m, k n), step i at angles [i n, (i + 1) n): each entry the sum, in term order,
    of its coefficients (a lhs term's subtracted), from 0. One gather of every coefficient
    for all the steps instead of one numpy call per coefficient; an entry with one
    coefficient (nearly all) is written as 0 + c or 0 - c, the same bits as summing it."""
    m = len(steps[0].unknowns)
    k = len(steps)
    A = np.zeros((m * m * k, n))            # row (r m + c) k + i: A[r, c] of step i
    into: tuple[list, list] = ([], [])      # destination rows, rhs terms then lhs terms
    taken: tuple[list, list] = ([], [])     # their coefficients (n,)
    more = []                               # (row, coefficients, side) of a second one
    seen: set[int] = set()
    for i, step in enumerate(steps):
        if len(step.equations) != m or len(step.unknowns) != m:
            raise ValueError(f"{step.title}: {len(step.equations)} equations for "
                             f"{len(step.unknowns)} unknowns")
        col = {u: j for j, u in enumerate(step.unknowns)}
        for row, eq in enumerate(step.equations):
            for t in eq.terms:
                lhs = t.side != "rhs"
                for kk, u in enumerate(t.action.unknowns):
                    j = col.get(u)
                    if j is None:
                        continue
                    at = (row * m + j) * k + i
                    if at in seen:
                        more.append((at, t.coeffs[:, kk], lhs))
                    else:
                        seen.add(at)
                        into[lhs].append(at)
                        taken[lhs].append(t.coeffs[:, kk])
    if taken[0]:
        A[into[0]] = np.add(0.0, np.array(taken[0]))       # 0 + c: -0 becomes +0
    if taken[1]:
        A[into[1]] = np.subtract(0.0, np.array(taken[1]))  # a lhs term enters negated
    for at, c, lhs in more:
        (np.subtract if lhs else np.add)(A[at], c, out=A[at])
    return A.reshape(m, m, k * n)


def step_rhs(step: Step, known: dict[str, np.ndarray], n: int, columns: int = 1,
             column=None) -> np.ndarray:
    """The step's right-hand sides b (m, columns, n), angle-last: the terms' constants and
    the unknowns solved by earlier steps, ``known`` as (n,) values or (columns, n) parts. A
    term's constant goes to right-hand side ``column(term)`` (0 by default; None leaves it
    out)."""
    col = set(step.unknowns)
    zero = no_constant(n)           # b - 0 is b: terms without a constant are passed over
    b = np.zeros((len(step.equations), columns, n))
    flat = column is None and columns == 1      # (n,) values into (n,) rows: no broadcast
    subtract, add = np.subtract, np.add
    for row, eq in enumerate(step.equations):
        here = b[row]               # (columns, n), and its first column (n,)
        first = here[0]
        out = first if flat else here
        for t in eq.terms:
            sub = subtract if t.side == "rhs" else add
            if t.const is not zero:
                if column is None:
                    sub(first, t.const, first)
                elif (c := column(t)) is not None:
                    sub(here[c], t.const, here[c])
            for k, u in enumerate(t.action.unknowns):
                if u in col:
                    continue
                if u not in known:
                    raise ValueError(f"{step.title}: equation '{eq.label}' needs {u}, "
                                     "which is neither solved here nor known")
                sub(out, t.coeffs[:, k] * known[u], out)
    return b


def step_system(step: Step, known: dict[str, np.ndarray], n: int, columns: int = 1,
                column=None) -> tuple[np.ndarray, np.ndarray]:
    """The step's matrix A (m, m, n) and right-hand sides b (m, columns, n): see
    :func:`step_matrix` and :func:`step_rhs`."""
    return step_matrix(step, n), step_rhs(step, known, n, columns, column)


def solve_step(step: Step, known: dict[str, np.ndarray], n: int) -> Solution:
    """Solve one step for all angles at once (see :func:`step_system`)."""
    A, b = step_system(step, known, n)
    x, cond = solve_cond(A, b[:, 0].T)
    return Solution({u: x[:, i] for i, u in enumerate(step.unknowns)}, cond)


def solve_chain(blocks: list[Step], n: int, prepared: dict | None = None,
                ) -> tuple[dict[str, np.ndarray], list[Solution]]:
    """Solve ``blocks`` in turn, each with the values found by those before it: every
    unknown's values (n,), and each block's Solution. The same numbers as :func:`solve_step`
    block by block. The blocks' matrices do not depend on earlier values: they are prepared
    together first (:func:`prepare_blocks`), unless ``prepared`` has them already (by ``id``
    of the block). The plain form of one chain: the analysis solves every method's chains
    together (:func:`mechreport.forces.chains.solve_chains`), and the tests hold it to this."""
    prepared = {} if prepared is None else prepared
    missing = [blk for blk in blocks if blk.unknowns and id(blk) not in prepared]
    if missing:
        prepared = {**prepared, **prepare_blocks([missing], n)}
    known: dict[str, np.ndarray] = {}
    out = []
    for block in blocks:
        b = step_rhs(block, known, n)[:, 0].T
        system = prepared.get(id(block))
        x, cond = system.solve_cond(b) if system is not None else solve_cond(
            step_matrix(block, n), b)
        sol = Solution({u: x[:, i] for i, u in enumerate(block.unknowns)}, cond)
        known.update(sol.values)
        out.append(sol)
    return known, out


def prepare_blocks(chains: list[list[Step]], n: int) -> dict[int, SmallSystem | Equilibrated]:
    """The blocks of ``chains`` (several methods' blocks) ready to be solved for their
    right-hand sides, by ``id`` of the block (the caller keeps the blocks), a block of the
    same equations for the same unknowns as another (methods share equations) prepared
    once. The 1x1 and 2x2 blocks of one size are prepared all together, their matrices
    written in one pass (:func:`joined_matrices`, :func:`mechreport.linalg.prepare_joined`:
    one pass of numpy calls instead of one per block, the same numbers); larger blocks of
    one size and the same constant rows too (:func:`mechreport.linalg.prepare_large`)."""
    index: dict[tuple, int] = {}
    unique: list[Step] = []
    where: list[tuple[int, int]] = []
    for blocks in chains:
        for blk in blocks:
            if blk.unknowns:
                key = (tuple(map(id, blk.equations)), tuple(blk.unknowns))
                if key not in index:
                    index[key] = len(unique)
                    unique.append(blk)
                where.append((id(blk), index[key]))
    systems: list = [None] * len(unique)
    for m in (1, 2):
        part = [i for i, blk in enumerate(unique) if len(blk.unknowns) == m]
        if part:
            ready = prepare_joined(joined_matrices([unique[i] for i in part], n), len(part))
            for i, system in zip(part, ready):
                systems[i] = system
    large = [i for i, blk in enumerate(unique) if len(blk.unknowns) > 2]
    for i, system in zip(large, prepare_large([step_matrix(unique[i], n) for i in large])):
        systems[i] = system
    return {b: systems[i] for b, i in where}


def triangular_blocks(step: Step) -> list[Step]:
    """The step as a chain of smaller square steps, in solving order: the block triangular
    form of its sparsity pattern (Dulmage-Mendelsohn: a matching of equations to unknowns,
    then the strongly connected components of "equation i uses the unknown equation j
    determines", dependencies first). Each block uses only its own unknowns and those of the
    blocks before it, so solving the blocks in turn (each with the earlier values substituted)
    solves the whole system; a Newton-Euler system of a chain of dyads splits into the dyads'
    own systems. The pattern is structural (which unknowns each equation names), the same at
    every angle. ``[step]`` when it does not split or has no perfect matching (a structurally
    singular system is left whole, to be reported singular)."""
    key = (tuple(step.unknowns), tuple(tuple(eq.unknown_names()) for eq in step.equations))
    order = _block_order(*key)
    if len(order) <= 1:
        step.needs = order[0][2]
        return [step]
    return [Step(step.title, [step.unknowns[c] for c in cols],
                 [step.equations[r] for r in rows], step.bodies, needs)
            for rows, cols, needs in order]


class Matching:
    """A matching of equations to unknowns, grown one equation at a time: each names the
    unknown columns it uses, and :meth:`add` matches it to one of them if it can, by Kuhn's
    augmenting path (rearranging the equations matched before it), which is when it raises
    the structural rank. ``owner[c]``: the equation matched to column ``c``, or -1."""

    def __init__(self, m: int):
        self.owner = [-1] * m
        self.patterns: list[list[int]] = []

    def add(self, columns) -> bool:
        """Match the next equation, which uses ``columns``; False (and it is left out) if
        no augmenting path exists."""
        self.patterns.append(list(columns))
        if self._augment(len(self.patterns) - 1, set()):
            return True
        self.patterns.pop()
        return False

    def __len__(self) -> int:
        return len(self.patterns)

    def _augment(self, row: int, seen: set[int]) -> bool:
        for c in self.patterns[row]:
            if c not in seen:
                seen.add(c)
                if self.owner[c] < 0 or self._augment(self.owner[c], seen):
                    self.owner[c] = row
                    return True
        return False


@lru_cache(maxsize=4096)
def _block_order(unknowns: tuple[str, ...], uses: tuple[tuple[str, ...], ...]):
    """((equation rows), (unknown columns), (the other unknowns the rows name)) per block in
    solving order, once per structure; one block when the structure has no perfect
    matching."""
    m = len(unknowns)
    col = {u: j for j, u in enumerate(unknowns)}
    pattern = [sorted({col[u] for u in names if u in col}) for names in uses]
    matching = Matching(m)
    if len(uses) != m or not all(matching.add(p) for p in pattern):
        blocks = [(tuple(range(len(uses))), tuple(range(m)))]
    else:
        owner = matching.owner
        matched = {owner[c]: c for c in range(m)}       # row -> its column
        needs = [[owner[c] for c in pattern[r] if c != matched[r]] for r in range(m)]
        blocks = [(tuple(sorted(b)), tuple(sorted(matched[r] for r in b)))
                  for b in _strong_components(needs)]   # dependencies first (Tarjan)
    out = []
    for rows, cols in blocks:
        own = {unknowns[c] for c in cols}
        named = dict.fromkeys(u for r in rows for u in uses[r] if u not in own)
        out.append((rows, cols, tuple(named)))
    return tuple(out)


def _strong_components(edges: list[list[int]]) -> list[list[int]]:
    """Strongly connected components of the graph ``edges`` (node -> the nodes it needs), each
    after every component it needs (Tarjan's order). Iterative: no recursion limit."""
    index: dict[int, int] = {}
    low: dict[int, int] = {}
    stack: list[int] = []
    on_stack: set[int] = set()
    out: list[list[int]] = []
    for root in range(len(edges)):
        if root in index:
            continue
        work = [(root, 0)]
        while work:
            node, i = work.pop()
            if i == 0:
                index[node] = low[node] = len(index)
                stack.append(node)
                on_stack.add(node)
            if i < len(edges[node]):
                work.append((node, i + 1))
                nxt = edges[node][i]
                if nxt not in index:
                    work.append((nxt, 0))
                elif nxt in on_stack:
                    low[node] = min(low[node], index[nxt])
                continue
            for nxt in edges[node]:
                if nxt in on_stack:
                    low[node] = min(low[node], low[nxt])
            if low[node] == index[node]:
                comp = []
                while True:
                    w = stack.pop()
                    on_stack.discard(w)
                    comp.append(w)
                    if w == node:
                        break
                out.append(comp)
    return out
