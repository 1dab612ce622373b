"""Where the Jinja2 templates are: ``templates/`` beside the package in a checkout (editable
installs), or ``<prefix>/share/mechreport/templates`` when installed from a wheel."""
from __future__ import annotations

import sys
from pathlib import Path

import jinja2

from ..errors import MechreportError


def template_dir() -> Path:
    candidates = [Path(__file__).resolve().parents[2] / "templates",
                  Path(sys.prefix) / "share" / "mechreport" / "templates"]
    for path in candidates:
        if (path / "report.md.j2").is_file():
            return path
    raise MechreportError("report templates not found (looked in "
                          + ", ".join(str(p) for p in candidates) + "); reinstall mechreport")


def loader() -> jinja2.FileSystemLoader:
    return jinja2.FileSystemLoader(str(template_dir()))
