"""A spec that stops building is a change (issue 40, point 7): a failed rebuild marks the
earlier report out of date (FAILED.json), the index keeps saying FAIL, `diff` lists it as
"no longer builds: <reason>" with exit 1, and the next good build clears the mark."""
from __future__ import annotations

import json
import shutil
from pathlib import Path

import pytest

from mechreport.app import outdir as od
from mechreport.app.build import build_files
from mechreport.app.cli import main

from helpers import tiny_spec

pytestmark = pytest.mark.slow     # several builds each: the slow tier

REPORT = ("report.md", "report.pdf", "results.csv", "summary.json")


def _build(spec: Path, out: Path) -> int:
    return build_files([spec], out, jobs=1, quiet=True, animation=False)


def _break(spec: Path) -> None:
    text = spec.read_text()
    assert text.count("    mass: 1\n") == 3
    spec.write_text(text.replace("    mass: 1\n", "    mass: heavy\n", 1))


def _index(out: Path) -> dict:
    return {r["folder"]: r for r in json.loads((out / "index.json").read_text())["specs"]}


def _diff(capsys, old: Path, new: Path) -> tuple[int, str]:
    capsys.readouterr()
    code = main(["diff", str(old), str(new)])
    captured = capsys.readouterr()
    assert "Traceback" not in captured.err and "internal error" not in captured.err
    return code, captured.out


def test_diff_reports_a_spec_that_no_longer_builds(tmp_path, capsys):
    spec = tiny_spec(tmp_path / "tiny.yaml")
    old, new = tmp_path / "old", tmp_path / "new"
    assert _build(spec, old) == 0
    shutil.copytree(old, new, symlinks=True)
    before = {f: (new / "tiny" / f).read_bytes() for f in REPORT}
    _break(spec)
    assert _build(spec, new) == 1
    assert {f: (new / "tiny" / f).read_bytes() for f in REPORT} == before   # left as it was
    assert "links.crank.mass" in od.failure_of(new / "tiny")
    assert _index(new)["tiny"]["status"] == "FAIL"

    code, out = _diff(capsys, old, new)
    assert code == 1
    assert "| tiny | build | PASS | does not build | no longer builds: " in out
    assert "links.crank.mass: must be a positive number" in out
    code, out = _diff(capsys, new, old)
    assert code == 1 and "| tiny | build | does not build | PASS | builds again |" in out
    (new / "tiny" / od.FAILED).unlink()            # as if it could not be written: the index
    code, out = _diff(capsys, old, new)
    assert code == 1 and "no longer builds: " in out and "still in tiny/" in out


def test_an_out_of_date_report_stays_marked_until_its_spec_builds_again(tmp_path, capsys):
    spec = tiny_spec(tmp_path / "tiny.yaml")
    other = tiny_spec(tmp_path / "other.yaml", "other")
    out = tmp_path / "out"
    assert _build(spec, out) == 0
    good = spec.read_text()
    _break(spec)
    assert _build(spec, out) == 1
    assert _build(other, out) == 0                 # a later build of another spec only
    row = _index(out)["tiny"]
    assert row["status"] == "FAIL"
    assert row["message"].startswith("the latest build failed: ")
    assert "still in tiny/" in row["message"]
    spec.write_text(good)                          # the same bytes as the report's build
    assert _build(spec, out) == 0                  # rebuilt, not taken as unchanged
    assert od.failure_of(out / "tiny") is None
    assert _index(out)["tiny"]["status"] == "PASS"


def test_diff_reports_a_spec_whose_check_now_fails(tmp_path, capsys):
    old, new = tmp_path / "old", tmp_path / "new"
    assert _build(tiny_spec(tmp_path / "a" / "tiny.yaml"), old) == 0
    assert _build(tiny_spec(tmp_path / "b" / "tiny.yaml", expect_torque=1e6), new) == 1
    code, out = _diff(capsys, old, new)
    assert code == 1 and "| tiny | check status | PASS | FAIL | changed |" in out


def test_diff_reports_a_spec_missing_or_failing_in_a_fresh_build(tmp_path, capsys):
    spec = tiny_spec(tmp_path / "tiny.yaml")
    old, fresh, gone = tmp_path / "old", tmp_path / "fresh", tmp_path / "gone"
    assert _build(spec, old) == 0
    shutil.copytree(old, gone)
    shutil.rmtree(gone / "tiny")
    (gone / "index.json").unlink()
    (gone / "x").mkdir()
    (gone / "x" / "summary.json").write_text((old / "tiny" / "summary.json").read_text())
    code, out = _diff(capsys, old, gone)
    assert code == 1 and "| tiny | spec | PASS | — | removed |" in out

    _break(spec)
    assert _build(spec, fresh) == 1                # no earlier report: only the index says so
    assert not (fresh / "tiny").exists()
    code, out = _diff(capsys, old, fresh)
    assert code == 1 and "| tiny | build | PASS | does not build | no longer builds: " in out


def test_diff_refuses_a_malformed_index_and_reads_an_unreadable_mark_as_failed(tmp_path,
                                                                                 capsys):
    spec = tiny_spec(tmp_path / "tiny.yaml")
    old, new = tmp_path / "old", tmp_path / "new"
    assert _build(spec, old) == 0
    shutil.copytree(old, new)
    (new / "tiny" / od.FAILED).mkdir()             # not a file: still out of date
    code, out = _diff(capsys, old, new)
    assert code == 1 and f"no longer builds: {od.FAILED} could not be read" in out
    (new / "index.json").write_text('{"specs": [{"folder": 3}]}')
    capsys.readouterr()
    assert main(["diff", str(old), str(new)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "index.json: not a mechreport index: specs[0].folder" in err


def test_the_out_of_date_mark_is_never_written_through_a_link(tmp_path):
    out = tmp_path / "out"
    (out / "tiny").mkdir(parents=True)
    (out / "tiny" / "summary.json").write_text("{}")
    target = tmp_path / "elsewhere.txt"
    target.write_text("mine")
    (out / "tiny" / od.FAILED).symlink_to(target)
    assert od.mark_failed(out, "tiny", "tiny.yaml", "it broke")
    assert target.read_text() == "mine"
    assert od.failure_of(out / "tiny") == "it broke"
    (out / "mine").mkdir()
    (out / "mine" / "notes.txt").write_text("x")   # not a report: never marked
    assert not od.mark_failed(out, "mine", "mine.yaml", "it broke")
    assert not (out / "mine" / od.FAILED).exists()
