"""Assur groups of class II (dyads): the groups whose positions have closed forms.

A dyad is two links i, j and three joints: ``outer[0]`` joins i to an already-known link,
``inner`` joins i and j, ``outer[1]`` joins j to an already-known link (textbook 4.4). The
split of a mechanism into groups, dyads among them, is :func:`.groups.decompose_groups`.
"""
from __future__ import annotations

from dataclasses import dataclass

from ..spec import Joint


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
        """Its joints' names as the spec writes them, outer, inner, outer: ``B C C_T`` (the
        kind, RRT, says which are pins and which sliders)."""
        return " ".join(j.written for j in (self.outer[0], self.inner, self.outer[1]))

    def known_link(self, k: int) -> str:
        """The already-known link that outer joint ``k`` attaches dyad link ``k`` to."""
        a, b = self.outer[k].links
        return b if a == self.links[k] else a
