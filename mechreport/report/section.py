"""What every section of the report model shares: a :class:`Figure`, the display units of
an analysis, the driver's effort and coordinate, the joints' colours (their reaction
symbols are :func:`mechreport.post.records.reaction_symbols`)."""
from __future__ import annotations

from dataclasses import dataclass

from ..units import Display
from ..post.records import reaction_symbols
from .mpl import PALETTE
from .spec_items import effort_of
from .text import spec_display

__all__ = ["Figure", "display_of", "effort_of", "joint_colors", "reaction_symbols"]


@dataclass
class Figure:
    """A figure ``figures/<stem>.svg`` (vector: the PDF and the Markdown report show the same
    file), with its caption."""

    stem: str
    caption: str
    kind: str                     # drawing|torque|reactions|polar|shaking|flywheel|...

    @property
    def svg(self) -> str:
        return f"figures/{self.stem}.svg"

    @property
    def path(self) -> str:
        return self.svg


def display_of(analysis) -> Display:
    """The spec's display units with the scales [SI] of this analysis (round-off rule)."""
    return spec_display(analysis.spec, analysis.scales())


def joint_colors(spec) -> dict[str, str]:
    """One colour per joint, in spec order, across every figure (:data:`PALETTE`)."""
    return {name: PALETTE[i % len(PALETTE)]
            for i, name in enumerate(spec.reported_reactions())}
