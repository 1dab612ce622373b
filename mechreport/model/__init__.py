"""Stage 2: the mechanism model: joint graph, dyads (Assur groups) and loops (contours)."""
from __future__ import annotations

from dataclasses import dataclass

from ..spec import GROUND, Joint, Spec
from .dyads import Dyad
from .graph import Loop, all_loops, cycle_basis
from .groups import Group, decompose_groups


@dataclass(frozen=True)
class Mechanism:
    """A validated spec with its structure: Assur groups in solving order (the driver's
    first), independent loops, and every simple cycle (``cycles``, shortest first: the
    contour method's candidates)."""

    spec: Spec
    groups: tuple[Group, ...]
    loops: tuple[Loop, ...]
    cycles: tuple[Loop, ...]

    @property
    def dyads(self) -> tuple[Dyad, ...]:
        """The groups that are dyads (closed forms), in solving order."""
        return tuple(g.dyad for g in self.groups if g.dyad is not None)

    def joints_of(self, link: str) -> list[Joint]:
        return [j for j in self.spec.joints if link in j.links]

    def with_spec(self, spec: Spec) -> "Mechanism":
        """The same structure over ``spec`` (the same links and joints by name, other
        numbers): every group, dyad and loop then refers to ``spec``'s own joints, whose lines
        may differ (a study's variants, or all of them stacked)."""
        own = {j.name: j for j in spec.joints}

        def rebind(joints):
            return tuple(own[j.name] for j in joints)

        def dyad(d: Dyad | None) -> Dyad | None:
            if d is None:
                return None
            return Dyad(d.links, rebind(d.outer), own[d.inner.name])
        groups = tuple(Group(g.links, rebind(g.joints), g.driver, dyad(g.dyad))
                       for g in self.groups)
        return Mechanism(spec, groups, tuple(Loop(l.links, rebind(l.joints)) for l in self.loops),
                         tuple(Loop(l.links, rebind(l.joints)) for l in self.cycles))


# The structure of the last few topologies met, bound to the first spec of each: a batch or a
# study analyses many specs of one topology, whose structure is found once (it depends on the
# names, types and links of the joints, the links' order and the driver joint, nothing else).
_STRUCTURES: dict[tuple, Mechanism] = {}
_STRUCTURES_KEPT = 64


def topology(spec: Spec) -> tuple:
    """What the structure of ``spec``'s mechanism depends on (hashable): the links' order,
    the joints' names, types and links, and the driver joint."""
    return (tuple(l.name for l in spec.links),
            tuple((j.name, j.type, j.links) for j in spec.joints), spec.driver.joint)


def build_mechanism(spec: Spec) -> Mechanism:
    """Raises ``UnsupportedMechanism`` when the links do not form Assur groups."""
    key = topology(spec)
    known = _STRUCTURES.get(key)
    if known is None:
        known = Mechanism(spec, decompose_groups(spec), cycle_basis(spec), all_loops(spec))
        if len(_STRUCTURES) >= _STRUCTURES_KEPT:
            _STRUCTURES.clear()
        _STRUCTURES[key] = known
    return known if known.spec is spec else known.with_spec(spec)


__all__ = ["Mechanism", "build_mechanism", "topology", "Dyad", "Group", "Loop", "GROUND", "all_loops"]
