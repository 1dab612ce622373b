"""Where a report comes from: its build time (``SOURCE_DATE_EPOCH`` for reproducible
builds), the spec file's SHA-256 and the title block (:class:`Meta`)."""
from __future__ import annotations

import datetime as _dt
import hashlib
import os
from dataclasses import dataclass
from pathlib import Path


@dataclass
class Meta:
    """Traceability and the spec's ``report`` metadata, as printed."""

    title: str
    project: str
    author: str
    revision: str
    date: str
    version: str
    sha256: str
    units: str

    def rows(self) -> list[list[str]]:
        """(label, value) rows for the first page; empty metadata left out."""
        rows = [["Project", self.project], ["Revision", self.revision],
                ["Author", self.author]]
        rows = [r for r in rows if r[1]]
        return rows + [["Date", self.date], ["mechreport", self.version],
                       ["Spec SHA-256", self.sha256], ["Units", self.units]]


def build_time() -> _dt.datetime:
    """Now, or ``SOURCE_DATE_EPOCH`` (reproducible builds) when it is set, in UTC."""
    epoch = os.environ.get("SOURCE_DATE_EPOCH", "").strip()
    if epoch:
        try:
            return _dt.datetime.fromtimestamp(int(epoch), _dt.timezone.utc)
        except (ValueError, OverflowError, OSError):
            pass
    return _dt.datetime.now(_dt.timezone.utc).replace(microsecond=0)


def spec_sha256(path) -> str:
    """SHA-256 of the spec file's bytes ("" when there is no file)."""
    try:
        return hashlib.sha256(Path(path).read_bytes()).hexdigest()
    except (OSError, ValueError, TypeError):
        return ""
