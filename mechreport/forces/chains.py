"""Every method's chain of blocks solved together, level by level.

A block of a chain (:func:`mechreport.forces.result.chain`) needs the unknowns that some
blocks before it found (``Step.needs``, read from the block triangular form), and only
those: its level is one past the latest level among them (0 if it needs none), so that
d'Alembert's seventeen unknowns, in ten blocks, take six levels, and the contour method's
nine blocks two. The blocks of a level, of every method, are solved once the levels before
it are. Each block's right-hand side is its own
(:func:`~mechreport.forces.equations.step_rhs`); what a level does at once is solve its 1x1
blocks, then its 2x2 blocks: those :func:`~mechreport.forces.equations.prepare_blocks`
prepared together are slices of one joined system, and every step of their solve is per
angle, so the level's slices are gathered and solved by one pass of numpy calls
(:meth:`mechreport.linalg._SmallGroup.solve_at`) instead of one pass each: R-RTR-RTR's 27
such blocks in 5 passes and 5 single solves. Larger blocks are solved one by one.

The numbers are those of :func:`~mechreport.forces.equations.solve_chain` run chain by
chain, bit for bit (tests/test_core_speed.py checks every spec).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..linalg import SINGULAR_COND, SmallSystem, solve_cond
from .equations import Step, prepare_blocks, step_matrix, step_rhs


@dataclass(frozen=True)
class ChainSolution:
    """One chain's unknowns' values (n,) by name; the product of its blocks' condition
    numbers (n,), in chain order (NaN where a system was not finite); where any of its
    blocks was singular (n,) bool."""

    values: dict[str, np.ndarray]
    cond: np.ndarray
    singular: np.ndarray


def solve_chains(chains: list[list[Step]], n: int, prepared: dict | None = None,
                 ) -> list[ChainSolution]:
    """Solve every chain of ``chains`` (each a list of square blocks, each block with the
    values found by the blocks before it in its chain), all chains level by level (see the
    module's docstring). ``prepared``: the blocks' systems by ``id`` of the block
    (:func:`~mechreport.forces.equations.prepare_blocks`); those missing are prepared here."""
    prepared = {} if prepared is None else prepared
    missing = [blk for blocks in chains for blk in blocks
               if blk.unknowns and id(blk) not in prepared]
    if missing:
        prepared = {**prepared, **prepare_blocks([missing], n)}
    todo: dict[int, list[tuple[int, int, Step]]] = {}     # level -> (chain, index, block)
    for c, blocks in enumerate(chains):
        for i, (level, blk) in enumerate(zip(_levels(blocks), blocks)):
            todo.setdefault(level, []).append((c, i, blk))
    where: list[dict[str, np.ndarray]] = [{} for _ in chains]   # chain -> unknown -> values
    conds: list[list] = [[None] * len(blocks) for blocks in chains]   # in chain order
    for level in sorted(todo):
        for group in _groups(todo[level], prepared):
            rhs = [step_rhs(blk, where[c], n)[:, 0] for c, _, blk in group]   # (m, n) each
            if len(group) > 1:
                x, found = _solve_small(group, prepared, rhs, n)
            else:
                (c, _, blk), = group
                system = prepared.get(id(blk))
                b = rhs[0].T
                xt, c_blk = system.solve_cond(b) if system is not None else solve_cond(
                    step_matrix(blk, n), b)
                x, found = [xt.T], (c_blk,)
            for (c, i, blk), xk, ck in zip(group, x, found):
                where[c].update(zip(blk.unknowns, xk))
                conds[c][i] = ck
    out = []
    with np.errstate(over="ignore", invalid="ignore"):
        for c, found in enumerate(conds):
            if not found:
                out.append(ChainSolution({}, np.ones(n), np.zeros(n, bool)))
                continue
            each = np.array(found)                  # (blocks, n)
            # in chain order from the first (1 c is c): the product run_steps formed
            product = np.multiply.reduce(each, axis=0)
            out.append(ChainSolution(where[c], product, ~(each < SINGULAR_COND).all(axis=0)))
    return out


def _levels(blocks: list[Step]) -> list[int]:
    """The level of each block of a chain: one past the latest level of the blocks before
    it that found the unknowns it needs (``Step.needs``), 0 if none. A chain whose blocks
    do not all say what they need, need an unknown no block before them found, or find one
    twice, is taken in turn, one block per level: as
    :func:`~mechreport.forces.equations.solve_chain` does, errors included."""
    found: dict[str, int] = {}
    out = []
    for blk in blocks:
        needs = blk.needs
        if needs is None:
            return list(range(len(blocks)))
        level = 0
        for u in needs:
            before = found.get(u)
            if before is None:
                return list(range(len(blocks)))
            if before >= level:
                level = before + 1
        for u in blk.unknowns:
            if u in found:
                return list(range(len(blocks)))
            found[u] = level
        out.append(level)
    return out


def _groups(blocks: list[tuple[int, int, Step]], prepared: dict) -> list[list]:
    """The level's blocks (chain, index, block) as the groups solved at once: prepared 1x1
    or 2x2 systems of one joined group together, every other block alone. The blocks of a
    level need nothing of each other, so any order gives the same numbers; the smallest go
    first (measured: 0.3 million instructions fewer per analysis than the larger first)."""
    groups: dict[int, list] = {}
    for item in blocks:
        system = prepared.get(id(item[2]))
        key = id(system.group) if isinstance(system, SmallSystem) else id(item[2])
        groups.setdefault(key, []).append(item)
    return sorted(groups.values(), key=lambda g: len(g[0][2].unknowns))


def _solve_small(group: list[tuple[int, int, Step]], prepared: dict, rhs: list[np.ndarray],
                 n: int) -> tuple[np.ndarray, np.ndarray]:
    """The k prepared m x m systems of ``group`` (slices of one joined group) for their
    right-hand sides ``rhs`` ((m, n) each): solutions (k, m, n) and condition numbers
    (k, n)."""
    k = len(group)
    systems = [prepared[id(blk)] for _, _, blk in group]
    at = (np.array([s.part.start for s in systems])[:, None] + np.arange(n)).ravel()
    bt = np.concatenate(rhs, axis=1)                      # (m, k n): block after block
    x, conds = systems[0].group.solve_at(at, bt)          # (m, k n), (k n,)
    m = len(bt)
    return x.reshape(m, k, n).transpose(1, 0, 2), conds.reshape(k, n)
