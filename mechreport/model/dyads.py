"""Split a mechanism into its driver and Assur groups of class II (dyads).

A dyad is two links i, j and three joints: ``outer[0]`` joins i to an already-known link,
``inner`` joins i and j, ``outer[1]`` joins j to an already-known link (textbook 4.4). Dyads
are listed in solving order: each one's outer joints attach to ground, the driver or earlier
dyads. The force-analysis dyad method walks this list backwards.
"""
from __future__ import annotations

from dataclasses import dataclass

from ..errors import UnsupportedMechanism
from ..spec import GROUND, Joint, Spec


@dataclass(frozen=True)
class Dyad:
    links: tuple[str, str]
    outer: tuple[Joint, Joint]
    inner: Joint

    @property
    def kind(self) -> str:
        """Joint types along the group, e.g. ``RRT`` or ``RTR``."""
        return self.outer[0].type + self.inner.type + self.outer[1].type

    @property
    def label(self) -> str:
        """Textbook-style name from its joints, e.g. ``B_R C_R C_T``."""
        def tag(j: Joint) -> str:
            return j.name if j.name.endswith("_" + j.type) else f"{j.name}_{j.type}"
        return " ".join(tag(j) for j in (self.outer[0], self.inner, self.outer[1]))

    def known_link(self, k: int) -> str:
        """The already-known link that outer joint ``k`` attaches dyad link ``k`` to."""
        a, b = self.outer[k].links
        return b if a == self.links[k] else a


def decompose(spec: Spec) -> tuple[Dyad, ...]:
    """Dyads in solving order; raises ``UnsupportedMechanism`` naming links it cannot group."""
    known = {GROUND, spec.driver.link}
    remaining = [l.name for l in spec.links if l.name not in known]
    used = {spec.driver.joint}
    dyads: list[Dyad] = []

    def joints_between(a: str, bs: set[str]) -> list[Joint]:
        return [j for j in spec.joints if j.name not in used and
                ((j.links[0] == a and j.links[1] in bs) or (j.links[1] == a and j.links[0] in bs))]

    while remaining:
        found = None
        for i in remaining:
            outer_i = joints_between(i, known)
            if len(outer_i) != 1:
                continue
            for inner in joints_between(i, set(remaining) - {i}):
                j = inner.links[1] if inner.links[0] == i else inner.links[0]
                outer_j = joints_between(j, known)
                if len(outer_j) != 1 or len(joints_between(i, {j})) != 1:
                    continue
                found = Dyad((i, j), (outer_i[0], outer_j[0]), inner)
                break
            if found:
                break
        if found is None:
            raise UnsupportedMechanism(
                f"{spec.file}: links {', '.join(remaining)} do not split into dyads (groups of "
                "two links and three joints attached to known links); this mechanism is not "
                "supported")
        if found.kind == "TTT":
            raise UnsupportedMechanism(
                f"{spec.file}: links {', '.join(found.links)} form a TTT group, which fixes no "
                "link orientation; this mechanism is not supported")
        dyads.append(found)
        used.update(j.name for j in (*found.outer, found.inner))
        known.update(found.links)
        remaining = [l for l in remaining if l not in found.links]

    leftover = [j.name for j in spec.joints if j.name not in used]
    if leftover:
        raise UnsupportedMechanism(
            f"{spec.file}: joints {', '.join(leftover)} are not part of any dyad; this "
            "mechanism is not supported")
    return tuple(dyads)
