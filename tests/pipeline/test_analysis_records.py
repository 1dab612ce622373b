"""results.csv and summary.json are written from the pipeline's records (issue 42, item 3):
built once per analysis, read by the report as they are; the effort without friction is the
friction solve's own (Kinematics.frictionless), not the report's subtraction."""
from __future__ import annotations

from pathlib import Path

import numpy as np

import mechreport
from mechreport.report.model import build_model

ROOT = Path(__file__).resolve().parents[2]


def test_the_report_writes_the_analysis_records_it_was_given():
    analysis = mechreport.analyse(ROOT / "specs" / "four_bar.yaml")
    record = analysis.summary_record()
    assert analysis.summary_record() is record                 # built once
    model = build_model(analysis)
    for key, value in record.items():                          # read, not rebuilt
        assert model.summary[key] is value, key
    assert list(model.summary)[:2] == ["mechreport_version", "spec"]
    assert (model.csv_header, model.csv_rows) == analysis.results_table()


def test_the_frictionless_effort_is_the_split_s_effort_without_its_friction_source():
    analysis = mechreport.analyse(ROOT / "specs" / "crank_press_friction.yaml")
    kin = analysis.kinematics
    assert kin.frictionless is not None and kin.frictionless.shape == (kin.n,)
    res = analysis.forces[analysis.sweep_summary().method]
    part = analysis.by_source(res.method)["friction"][res.driver_quantity]
    scale = np.max(np.abs(res.driver_torque))
    assert np.max(np.abs(res.driver_torque - part - kin.frictionless)) <= 1e-6 * scale
    assert not np.allclose(kin.frictionless, res.driver_torque)   # friction changes it


def test_a_spec_without_friction_has_no_frictionless_effort():
    assert mechreport.analyse(ROOT / "specs" / "four_bar.yaml").kinematics.frictionless is None
