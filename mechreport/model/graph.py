"""The joint graph: links are nodes (ground included), joints are edges.

``cycle_basis`` gives the independent loops (contours) used by the contour method: the
shortest cycles that are independent over GF(2), so a two-loop linkage gets its two natural
loops (textbook 4.7: 0-1-2-3-0 and 0-3-4-5-0) rather than one long detour.
"""
from __future__ import annotations

from dataclasses import dataclass

from ..spec import GROUND, Joint, Spec


@dataclass(frozen=True)
class Loop:
    """A closed contour: ``links[k]`` and ``links[k+1]`` are joined by ``joints[k]``;
    ``joints[-1]`` closes it back to ``links[0]``."""

    links: tuple[str, ...]
    joints: tuple[Joint, ...]

    def label(self, spec: Spec) -> str:
        nums = [str(spec.number(l)) for l in self.links]
        return "-".join(nums + nums[:1])


def _simple_cycles(spec: Spec) -> list[Loop]:
    """Every simple cycle of the (small) joint multigraph, each once."""
    nodes = [GROUND] + [l.name for l in spec.links]
    order = {n: i for i, n in enumerate(nodes)}
    edges_at: dict[str, list[Joint]] = {n: [] for n in nodes}
    for j in spec.joints:
        edges_at[j.links[0]].append(j)
        edges_at[j.links[1]].append(j)
    found: dict[frozenset, Loop] = {}

    def other(j: Joint, n: str) -> str:
        return j.links[1] if j.links[0] == n else j.links[0]

    for start in nodes:  # cycles whose lowest node is `start`
        stack = [(start, [start], [])]
        while stack:
            node, path, jpath = stack.pop()
            for j in edges_at[node]:
                if jpath and j is jpath[-1]:
                    continue
                nxt = other(j, node)
                if nxt == start and len(jpath) >= 1 and (len(jpath) >= 2 or j is not jpath[0]):
                    key = frozenset(x.name for x in jpath + [j])
                    found.setdefault(key, Loop(tuple(path), tuple(jpath + [j])))
                elif order[nxt] > order[start] and nxt not in path:
                    stack.append((nxt, path + [nxt], jpath + [j]))
    return list(found.values())


def _canonical(loop: Loop) -> tuple:
    return len(loop.joints), sorted(j.name for j in loop.joints)


def all_loops(spec: Spec) -> tuple[Loop, ...]:
    """Every simple cycle, ground first in each, shortest first, ties by joint names."""
    return tuple(_rooted(c) for c in sorted(_simple_cycles(spec), key=_canonical))


def cycle_basis(spec: Spec) -> tuple[Loop, ...]:
    """Shortest independent loops, ground first in each loop, in a stable order (by length,
    then joint names: never by the order the spec was written in)."""
    names = [j.name for j in spec.joints]
    cycles = sorted(_simple_cycles(spec), key=_canonical)
    basis: list[Loop] = []
    rows: list[int] = []  # GF(2) row echelon over joint bitmasks
    for cyc in cycles:
        vec = 0
        for j in cyc.joints:
            vec ^= 1 << names.index(j.name)
        for r in rows:
            vec = min(vec, vec ^ r)
        if vec:
            rows.append(vec)
            basis.append(_rooted(cyc))
    return tuple(basis)


def _rooted(loop: Loop) -> Loop:
    """The loop in a canonical form: starting at ground when it passes through ground (else at
    the link first by name), walked so that the first joint's name sorts before the last's
    (textbook 4.6: 0-1-2-3-0 through A, B, C, C_T). Never depends on the spec's order."""
    links, joints = list(loop.links), list(loop.joints)
    start = links.index(GROUND) if GROUND in links else links.index(min(links))
    links, joints = links[start:] + links[:start], joints[start:] + joints[:start]
    if len(joints) > 1 and joints[0].name > joints[-1].name:
        # reverse the walk: links[0], links[-1], ..., links[1]; joints[k] joins links[k], k+1
        links = links[:1] + links[1:][::-1]
        joints = joints[::-1]
    return Loop(tuple(links), tuple(joints))
