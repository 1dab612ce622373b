"""Stage 2: the mechanism model: joint graph, dyads (Assur groups) and loops (contours)."""
from __future__ import annotations

from dataclasses import dataclass

from ..spec import GROUND, Joint, Spec
from .dyads import Dyad, decompose
from .graph import Loop, all_loops, cycle_basis


@dataclass(frozen=True)
class Mechanism:
    """A validated spec with its structure: dyads in solving order and independent loops."""

    spec: Spec
    dyads: tuple[Dyad, ...]
    loops: tuple[Loop, ...]

    def joints_of(self, link: str) -> list[Joint]:
        return [j for j in self.spec.joints if link in j.links]


def build_mechanism(spec: Spec) -> Mechanism:
    """Raises ``UnsupportedMechanism`` when the links do not split into dyads."""
    return Mechanism(spec, decompose(spec), cycle_basis(spec))


__all__ = ["Mechanism", "build_mechanism", "Dyad", "Loop", "GROUND", "all_loops"]
