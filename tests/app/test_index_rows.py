"""The index tells a mixed batch apart (issue 30, item 6): counts that add up, the reason on
every FAIL row, and the spec's path (relative to where the build ran) on every row."""
from __future__ import annotations

import json
import os
from pathlib import Path

import pytest

from mechreport.app.cli import main

ROOT = Path(__file__).resolve().parents[2]


@pytest.mark.slow
def test_a_mixed_batch_counts_and_explains_every_row(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "a.yaml").write_text((ROOT / "specs" / "four_bar.yaml").read_text())
    text = (ROOT / "specs" / "slider_crank.yaml").read_text()
    assert "value: 151.4924}" in text
    (tmp_path / "b.yaml").write_text(text.replace("value: 151.4924}", "value: 150}"))
    (tmp_path / "c.yaml").write_text("name: broken\n")
    assert main(["build", "a.yaml", "b.yaml", str(tmp_path / "c.yaml"), "-o", "out",
                 "-q"]) == 1
    md = (tmp_path / "out" / "index.md").read_text()
    assert ("3 spec(s): 1 passed their check, 1 failed it, 1 could not be built." in md)
    rows = {r["folder"]: r for r in json.loads((tmp_path / "out" / "index.json")
                                                .read_text())["specs"]}
    assert rows["a"]["message"] == "" and rows["a"]["status"] == "PASS"
    assert "expectation(s) failed: driver.torque at 45 deg" in rows["b"]["message"]
    assert "missing required key" in rows["c"]["message"]
    assert [rows[k]["spec"] for k in "abc"] == ["a.yaml", "b.yaml", "c.yaml"]
    assert not any(os.path.isabs(r["spec"]) for r in rows.values())
    for line in md.splitlines():
        if "| FAIL" in line:
            assert "failed:" in line or "missing required key" in line, line
    assert "(a.yaml)" in md and "(b.yaml)" in md
