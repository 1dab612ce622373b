"""Split a mechanism into Assur groups of any class, from the driver outward.

A group is a smallest set S of not-yet-known links whose joints (those with one end in S and
the other in S or among the known links) fix them: 3 |S| equations of constraint, 2 per pin or
slider and 3 for the driver joint, whose coordinate is prescribed (a weld at the driven angle or
stroke). The driver's own group comes first (a crank on ground is one link); then dyads (two
links, three joints: class II), triads (four links, six joints, one of them joined to the three
others: class III), and larger groups, each attached to links already known. Dyads keep their
closed forms; other groups are solved by Newton-Raphson (kinematics). Links are searched in the
order the spec writes them (the textbook's dyad labels follow it); nothing else depends on it.
"""
from __future__ import annotations

from dataclasses import dataclass
from itertools import combinations

from ..errors import UnsupportedMechanism
from ..spec import GROUND, Joint, Spec
from .dyads import Dyad


@dataclass(frozen=True)
class Group:
    """``links`` solved together; ``joints`` every joint that ties them to each other or to
    links known before (the driver joint among them for the driver's group); ``dyad`` the
    closed-form dyad when the group is one."""

    links: tuple[str, ...]
    joints: tuple[Joint, ...]
    driver: str | None = None       # the driver joint's name, in the driver's group
    dyad: Dyad | None = None

    @property
    def label(self) -> str:
        """Its joints' names as the spec writes them, e.g. ``B C C_T``."""
        if self.dyad is not None:
            return self.dyad.label
        return " ".join(j.written for j in self.joints)

    @property
    def kind(self) -> str:
        """``driver``, ``dyad``, ``triad`` or ``group``."""
        if self.driver is not None:
            return "driver"
        if self.dyad is not None:
            return "dyad"
        return "triad" if self.is_triad else "group"

    @property
    def is_triad(self) -> bool:
        """Four links, one of them joined to each of the three others (class III)."""
        if len(self.links) != 4:
            return False
        inner = [set(j.links) for j in self.joints if set(j.links) <= set(self.links)]
        return any(sum(1 for pair in inner if l in pair) == 3 for l in self.links)

    @property
    def class_name(self) -> str:
        """How a report names it: ``driver``, ``dyad (class II)``, ``triad (class III)``,
        ``class IV group`` ..."""
        if self.driver is not None:
            return "driver" if len(self.links) == 1 else f"driver group of {len(self.links)} links"
        if self.dyad is not None:
            return "dyad (class II)"
        if self.is_triad:
            return "triad (class III)"
        return "class IV group" if len(self.links) == 4 else f"group of {len(self.links)} links"


def constraints(joint: Joint, driver: str) -> int:
    """Equations of constraint a joint adds: 2, or 3 for the driver (its coordinate is set)."""
    return 3 if joint.name == driver else 2


def decompose_groups(spec: Spec) -> tuple[Group, ...]:
    """Groups in solving order; raises ``UnsupportedMechanism`` naming links that no group
    closes (the mechanism is not assembled from Assur groups, e.g. redundant constraints)."""
    driver = spec.driver.joint
    known = {GROUND}
    remaining = [l.name for l in spec.links]
    used: set[str] = set()
    groups: list[Group] = []
    while remaining:
        found = None
        for k in range(1, len(remaining) + 1):
            for subset in combinations(remaining, k):
                s = set(subset)
                joints = [j for j in spec.joints if j.name not in used
                          and set(j.links) & s and set(j.links) <= s | known]
                if sum(constraints(j, driver) for j in joints) != 3 * k:
                    continue
                if not _connected(subset, joints):
                    continue
                found = (subset, joints)
                break
            if found:
                break
        if found is None:
            raise UnsupportedMechanism(
                f"{spec.file}: links {', '.join(remaining)} do not form Assur groups (no set of "
                "them is fixed by its joints to the links already known); check the joints")
        subset, joints = found
        has_driver = driver if any(j.name == driver for j in joints) else None
        dyad = _as_dyad(subset, joints) if len(subset) == 2 and not has_driver else None
        if dyad is not None and dyad.kind == "TTT":
            raise UnsupportedMechanism(
                f"{spec.file}: links {', '.join(dyad.links)} form a TTT group, which fixes no "
                "link orientation; this mechanism is not supported")
        groups.append(Group(tuple(subset), tuple(joints), has_driver, dyad))
        used.update(j.name for j in joints)
        known.update(subset)
        remaining = [l for l in remaining if l not in subset]
    leftover = [j.name for j in spec.joints if j.name not in used]
    if leftover:
        raise UnsupportedMechanism(
            f"{spec.file}: joints {', '.join(leftover)} are not part of any Assur group; this "
            "mechanism is not supported")
    return tuple(groups)


def _connected(links: tuple[str, ...], joints: list[Joint]) -> bool:
    """The links of a candidate group hang together through the group's own joints."""
    if len(links) == 1:
        return True
    seen, todo = {links[0]}, [links[0]]
    inside = [j.links for j in joints if set(j.links) <= set(links)]
    while todo:
        here = todo.pop()
        for a, b in inside:
            other = b if a == here else a if b == here else None
            if other is not None and other not in seen:
                seen.add(other)
                todo.append(other)
    return len(seen) == len(links)


def _as_dyad(links: tuple[str, ...], joints: list[Joint]) -> Dyad | None:
    """Two links, each with one outer joint and one interior joint between them: a dyad."""
    i, j = links
    inner = [jt for jt in joints if set(jt.links) == {i, j}]
    outer_i = [jt for jt in joints if i in jt.links and j not in jt.links]
    outer_j = [jt for jt in joints if j in jt.links and i not in jt.links]
    if len(inner) != 1 or len(outer_i) != 1 or len(outer_j) != 1:
        return None
    return Dyad((i, j), (outer_i[0], outer_j[0]), inner[0])
