"""``mechreport tolerance SPEC``: its files, the tolerance.* quantities in tolerance.json and
in a report's summary.json, what it says on stdout and stderr, and its refusals."""
from __future__ import annotations

import csv
import json
from pathlib import Path

import pytest

from mechreport.app.cli import main
from mechreport.app.tolerance import with_tolerance

ROOT = Path(__file__).resolve().parents[2]
SPEC = (ROOT / "specs" / "four_bar.yaml").read_text(encoding="utf-8").replace(
    "sweep: {start: 0, stop: 360, step: 1}", "sweep: {start: 0, stop: 360, step: 6}") + """
tolerances:
  vary:
    - {key: links.coupler.points.C.0, tol: 0.3}
    - {key: links.coupler.mass, sigma: 8}
  count: 24
  seed: 3
  keep: [cycle.torque.rms, joint.B.f_max]
"""


@pytest.mark.slow                   # the PDF and the figures: several seconds
def test_the_command_writes_every_file_and_keeps_the_report(tmp_path, capsys):
    spec = tmp_path / "four_bar.yaml"
    spec.write_text(SPEC, encoding="utf-8")
    out = tmp_path / "out"
    folder = out / "four_bar"
    folder.mkdir(parents=True)             # a report there, as `mechreport build` leaves it
    from mechreport.report.provenance import spec_sha256
    (folder / "summary.json").write_text(json.dumps(
        {"status": "PASS", "spec_sha256": spec_sha256(spec),
         "quantities": {"cycle.torque.rms": {"value": 2.3, "unit": "N·m"},
                        "tolerance.old.p95": {"value": 1, "unit": ""}}}),
        encoding="utf-8")
    (folder / "report.md").write_text("the report", encoding="utf-8")
    assert main(["tolerance", str(spec), "-o", str(out), "--jobs", "1"]) == 0
    said = capsys.readouterr()
    # the probabilities as tolerance.md prints them
    assert "24 sample(s): assembles 100 % (95 % interval " in said.out
    assert "Probability that the mechanism assembles: 100 % (95 % interval " in \
        (folder / "tolerance.md").read_text(encoding="utf-8")
    assert "24/24 samples" in said.err
    for name in ("tolerance.csv", "tolerance.parquet", "tolerance.md", "tolerance.pdf",
                 "tolerance.json", "tolerance-figures/histogram-1.svg",
                 "tolerance-figures/histogram-2.svg", "report.md"):
        assert (folder / name).exists(), name
    with open(folder / "tolerance.csv", encoding="utf-8") as fh:
        rows = list(csv.DictReader(fh))
    assert len(rows) == 24
    assert list(rows[0])[:5] == ["sample", "links.coupler.points.C.0", "links.coupler.mass",
                                 "cycle.torque.rms [N·m]", "joint.B.f_max [N]"]
    assert {"design_pass", "verdict.limits.joint_force", "status", "reason"} <= set(rows[0])
    assert all(r["status"] == "ok" and r["design_pass"] == "true" for r in rows)
    import pyarrow.parquet as pq
    table = pq.read_table(folder / "tolerance.parquet")
    assert table.num_rows == 24 and table.column_names == list(rows[0])
    record = json.loads((folder / "tolerance.json").read_text(encoding="utf-8"))["quantities"]
    summary = json.loads((folder / "summary.json").read_text(encoding="utf-8"))
    assert summary["status"] == "PASS"                        # the report's own fields stay
    assert summary["quantities"]["cycle.torque.rms"]["value"] == 2.3
    assert "tolerance.old.p95" not in summary["quantities"]   # the earlier run's replaced
    for name in ("tolerance.cycle.torque.rms.p95", "tolerance.joint.B.f_max.std",
                 "tolerance.limits.joint_force.p_pass", "tolerance.design.p_pass_low",
                 "tolerance.assembly.p", "tolerance.samples"):
        assert summary["quantities"][name] == record[name], name
    assert record["tolerance.joint.B.f_max.p95"]["unit"] == "N"
    assert record["tolerance.samples"]["value"] == 24
    text = (folder / "tolerance.md").read_text(encoding="utf-8")
    for heading in ("Kept quantities", "Design verdicts", "Which tolerance matters",
                    "Distributions", "Worst sample", "Samples without a result"):
        assert f"## {heading}" in text


def test_a_spec_without_tolerances_is_refused(tmp_path, capsys):
    spec = tmp_path / "plain.yaml"
    spec.write_text((ROOT / "specs" / "four_bar.yaml").read_text(encoding="utf-8"),
                    encoding="utf-8")
    assert main(["tolerance", str(spec), "-o", str(tmp_path / "out")]) == 1
    assert "no 'tolerances:' section" in capsys.readouterr().err
    assert not (tmp_path / "out" / "plain").exists()


def test_with_tolerance_replaces_only_the_tolerance_quantities():
    old = {"a": 1, "quantities": {"x": {"value": 1}, "tolerance.y.p5": {"value": 2}}}
    new = with_tolerance(old, {"tolerance.z.p5": {"value": 3}})
    assert new == {"a": 1, "quantities": {"x": {"value": 1}, "tolerance.z.p5": {"value": 3}}}
    assert old["quantities"]["tolerance.y.p5"] == {"value": 2}       # not modified


@pytest.mark.parametrize("args", [["--jobs", "0"], ["--chunk", "-1"]])
def test_bad_options_are_usage_errors(tmp_path, args, capsys):
    with pytest.raises(SystemExit) as info:
        main(["tolerance", "x.yaml", *args])
    assert info.value.code == 2


def test_a_rebuild_keeps_the_tolerance_quantities_of_the_same_spec_only(tmp_path):
    from mechreport.app.tolerance import carry_into_report
    summary = tmp_path / "summary.json"
    record = tmp_path / "tolerance.json"
    record.write_text(json.dumps({"spec_sha256": "abc", "quantities": {
        "tolerance.cycle.torque.rms.p95": {"value": 2.5, "unit": "N·m"}}}), encoding="utf-8")
    summary.write_text(json.dumps({"quantities": {"x": {"value": 1, "unit": ""}}}),
                       encoding="utf-8")
    carry_into_report(summary, record, "other")            # the spec changed: not carried
    assert json.loads(summary.read_text(encoding="utf-8"))["quantities"] == {
        "x": {"value": 1, "unit": ""}}
    carry_into_report(summary, record, "abc")
    assert json.loads(summary.read_text(encoding="utf-8"))["quantities"][
        "tolerance.cycle.torque.rms.p95"] == {"value": 2.5, "unit": "N·m"}
    record.write_text("not json", encoding="utf-8")        # unreadable: left alone
    carry_into_report(summary, record, "abc")
    carry_into_report(summary, tmp_path / "missing.json", "abc")



def test_a_report_of_another_spec_does_not_get_the_tolerance_quantities(tmp_path):
    """OUT/<name>/summary.json of another spec of the same file name (or of this spec before
    an edit) got this analysis's tolerance.* figures: numbers of one design in the record of
    another. Only a report whose spec_sha256 is this spec's gets them."""
    from mechreport.app.tolerance import report_summary
    report = tmp_path / "summary.json"
    report.write_text(json.dumps({"status": "PASS", "spec_sha256": "0" * 64, "quantities": {
        "cycle.torque.rms": {"value": 2.3, "unit": "N·m"}}}), encoding="utf-8")
    quantities = {"tolerance.samples": {"value": 24, "unit": ""}}
    assert report_summary(report, quantities, "1" * 64) is None
    assert report_summary(report, quantities, "") is None
    assert report_summary(tmp_path / "none.json", quantities, "0" * 64) is None
    merged = report_summary(report, quantities, "0" * 64)
    assert merged["quantities"]["tolerance.samples"] == {"value": 24, "unit": ""}
    assert merged["quantities"]["cycle.torque.rms"]["value"] == 2.3
