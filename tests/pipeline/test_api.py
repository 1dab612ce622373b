"""The Python API a notebook user reaches for: mechreport.analyse on a path or YAML text,
and every result as a DataFrame that agrees with results.csv cell for cell."""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

import mechreport
from mechreport.report.model import build_model

ROOT = Path(__file__).resolve().parents[2]
SPECS = sorted((ROOT / "specs").glob("*.yaml"))


def test_analyse_takes_a_path_or_the_yaml_text():
    path = ROOT / "specs" / "four_bar.yaml"
    by_path = mechreport.analyse(path)
    by_text = mechreport.analyse(path.read_text(encoding="utf-8"))
    assert by_text.spec.file == "<text>" and by_path.spec.file == str(path)
    np.testing.assert_array_equal(by_text.forces["dyad"].driver_torque,
                                  by_path.forces["dyad"].driver_torque)


def test_analyse_of_bad_text_names_the_problems_not_a_file():
    from mechreport.errors import SpecError
    with pytest.raises(SpecError) as exc:
        mechreport.analyse("name: x\nlinks: 3\n")
    assert "<text>" in str(exc.value) and "links" in str(exc.value)


@pytest.mark.parametrize("path", SPECS, ids=lambda p: p.stem)
def test_dataframe_agrees_with_results_csv(path):
    pd = pytest.importorskip("pandas")
    a = mechreport.analyse(path)
    df = a.to_dataframe()
    model = build_model(a)
    header, rows = model.csv_header, model.csv_rows
    assert [df.index.name, *df.columns] == header
    assert len(df) == len(rows)
    for (angle, row), csv_row in zip(df.iterrows(), rows):
        assert f"{angle:g}" == csv_row[0].replace("-0", "0") or float(csv_row[0]) == angle
        assert row["flag"] == csv_row[1]
        for value, cell in zip(row.iloc[1:], csv_row[2:]):
            shown = f"{value:.10g}" if isinstance(value, float) and math.isfinite(value) else ""
            assert shown == cell
    assert isinstance(df, pd.DataFrame)
    flagged = df[df["flag"] != ""]
    assert len(flagged) == len(a.flags) and flagged.drop(columns="flag").isna().all().all()
