"""Stage 2: the mechanism model: joint graph, dyads (Assur groups) and loops (contours)."""
from __future__ import annotations

from dataclasses import dataclass, replace

from ..spec import GROUND, Joint, Spec
from .dyads import Dyad
from .graph import Loop, all_loops, cycle_basis
from .groups import Group, decompose_groups


@dataclass(frozen=True)
class Mechanism:
    """A validated spec with its structure: Assur groups in solving order (the driver's
    first) and independent loops."""

    spec: Spec
    groups: tuple[Group, ...]
    loops: tuple[Loop, ...]

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
            return replace(d, outer=rebind(d.outer), inner=own[d.inner.name])
        groups = tuple(replace(g, joints=rebind(g.joints), dyad=dyad(g.dyad)) for g in self.groups)
        loops = tuple(replace(l, joints=rebind(l.joints)) for l in self.loops)
        return Mechanism(spec, groups, loops)


def build_mechanism(spec: Spec) -> Mechanism:
    """Raises ``UnsupportedMechanism`` when the links do not form Assur groups."""
    return Mechanism(spec, decompose_groups(spec), cycle_basis(spec))


__all__ = ["Mechanism", "build_mechanism", "Dyad", "Group", "Loop", "GROUND", "all_loops"]
