"""Spec texts that tests in several folders write (tests/ is on the path: see conftest)."""
from __future__ import annotations

import json
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def tiny_spec(path: Path, name: str = "tiny", expect_torque: float | None = None) -> Path:
    """specs/slider_crank.yaml on a 30-degree sweep, without a solution sheet; with
    ``expect_torque`` its only expectation is the driver torque at 45 deg."""
    text = (ROOT / "specs" / "slider_crank.yaml").read_text(encoding="utf-8")
    text = text[:text.index("# Textbook 4.6")]
    text = text.replace("sweep: {start: 0, stop: 360, step: 1}",
                        "sweep: {start: 0, stop: 360, step: 30}")
    text = text.replace("sheet: true ", "sheet: false")
    text = text.replace("name: R-RRT slider-crank", f"name: {json.dumps(name)}")
    if expect_torque is not None:
        text += f"expect:\n  - {{angle: 45, quantity: driver.torque, value: {expect_torque}}}\n"
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text, encoding="utf-8")
    return path
