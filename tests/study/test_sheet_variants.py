"""Problem variants for a class (issue 46, ``sheet.variants``): the answers are those of the
data as printed on each variant's problem sheet, the seed reproduces the set, the variants
are distinct, and a ``require`` no variant meets is a bounded, clear error."""
from __future__ import annotations

import csv
import re
from pathlib import Path

import pytest

from mechreport.errors import SpecError
from mechreport.pipeline import analyse
from mechreport.report.sheet.variants_out import answers_csv, write_variants
from mechreport.spec.loader import load_source
from mechreport.study.sheet_variants import (ANSWER_DIGITS, answers_of, make_variants,
                                             round_sig, sheet_base)
from mechreport.study.variants import variant_spec

ROOT = Path(__file__).resolve().parents[2]
VARIANTS = """sheet:
  variants:
    vary:
      - {key: loads.0.value.0, from: 50, to: 200, step: 10}
      - {key: links.slider.mass, from: 0.5, to: 3}
      - {key: driver.rpm, values: [10, 20, 30]}
    count: 3
    seed: 7
    digits: 3
    require: {transmission_angle_min: 30}
"""


def class_spec(tmp_path: Path, extra: str = VARIANTS, name: str = "class.yaml") -> Path:
    text = (ROOT / "specs" / "slider_crank.yaml").read_text(encoding="utf-8")
    text = re.sub(r"(?m)^sheet: true.*$", "", text)
    path = tmp_path / name
    path.write_text(text + extra, encoding="utf-8")
    return path


@pytest.fixture(scope="module")
def written(tmp_path_factory):
    d = tmp_path_factory.mktemp("class")
    path = class_spec(d)
    variants = make_variants(path)
    write_variants(variants, d / "out", name="R-RRT slider-crank")
    return path, variants, d / "out" / "variants"


def printed_data(problem_md: str) -> dict:
    """The varied data read back from a variant's problem.md as a student reads them."""
    force = re.search(r"a force \(([-\d.e+]+), 0\) N on link 3 \(slider\)", problem_md)
    mass = re.search(r"\| 3 \| slider \|[^|]*\|[^|]*\|[^|]*\| ([\d.e+-]+) \|", problem_md)
    rpm = re.search(r"\(([\d.]+) rpm\)", problem_md)
    return {"loads.0.value.0": float(force.group(1)), "links.slider.mass": float(mass.group(1)),
            "driver.rpm": float(rpm.group(1))}


def test_answers_are_those_of_the_printed_data(written):
    path, variants, out = written
    _, base = sheet_base(load_source(path))
    rows = list(csv.DictReader((out / "answers.csv").open(encoding="utf-8")))
    assert len(rows) == sum(len(v.answers) for v in variants) > 0
    for v in variants:
        md = (out / f"{v.number:02d}" / "problem.md").read_text(encoding="utf-8")
        data = printed_data(md)
        assert data == v.values                        # what is printed is what was analysed
        again = answers_of(analyse(variant_spec(base, data)), [45.0])
        key = {r["quantity"]: float(r["value"]) for r in rows if int(r["variant"]) == v.number}
        assert len(key) == len(again)
        for a in again:
            assert key[f"{a.quantity}@45"] == round_sig(a.value, ANSWER_DIGITS)


def test_the_printed_data_are_rounded_to_digits(written):
    _, variants, _ = written
    for v in variants:
        for x in v.values.values():
            assert x == round_sig(x, 3)


def test_variants_are_distinct_and_feasible(written):
    _, variants, _ = written
    assert [v.number for v in variants] == [1, 2, 3]
    assert len({tuple(sorted(v.values.items())) for v in variants}) == 3
    assert len({tuple(a.value for a in v.answers) for v in variants}) == 3
    for v in variants:
        assert v.analysis.kinematics.index_of(45.0) is not None
        assert not [f for f in v.analysis.flags if abs(f.angle - 45) < 1e-9]
        assert v.spec.name.endswith(f"variant {v.number:02d}")


def test_the_same_seed_gives_the_same_answers_csv(written, tmp_path):
    path, variants, out = written
    again = make_variants(path)
    assert answers_csv(again) == (out / "answers.csv").read_text(encoding="utf-8")
    other = make_variants(path, seed=8)
    assert answers_csv(other) != answers_csv(again)


def test_count_overrides_the_spec(written):
    path, _, _ = written
    assert len(make_variants(path, count=1)) == 1


def test_a_require_no_variant_meets_is_a_bounded_clear_error(tmp_path):
    path = class_spec(tmp_path, VARIANTS.replace("transmission_angle_min: 30",
                                                 "transmission_angle_min: 89.9"))
    with pytest.raises(SpecError) as err:
        make_variants(path)
    text = str(err.value)
    assert "sheet.variants" in text and "transmission_angle_min" in text
    assert "0 of 3 variants" in text


def test_a_bad_key_path_is_a_spec_error(tmp_path):
    path = class_spec(tmp_path, VARIANTS.replace("links.slider.mass", "links.slider.mas"))
    with pytest.raises(SpecError, match=r"sheet\.variants\.vary\[1\]\.key"):
        make_variants(path)


@pytest.mark.slow
def test_build_writes_the_class_files(tmp_path):
    """`mechreport build --sheet --variants 2`: every file the contract names, per variant
    and for the class; --seed changes the set."""
    import subprocess
    import sys
    path = class_spec(tmp_path)
    out = tmp_path / "out"
    cmd = [sys.executable, "-m", "mechreport", "build", str(path), "--sheet", "--no-animation",
           "-q", "-o", str(out), "--variants", "2"]
    subprocess.run(cmd, check=True, cwd=ROOT)
    root = out / "class" / "variants"
    for n in ("01", "02"):
        for f in ("problem.pdf", "solution.pdf", "problem.md", "solution.md"):
            assert (root / n / f).is_file()
    assert not (root / "03").exists()
    for f in ("answers.csv", "answers.pdf", "moodle.xml"):
        assert (root / f).is_file()
    first = (root / "answers.csv").read_text(encoding="utf-8")
    subprocess.run(cmd + ["--seed", "99", "--force"], check=True, cwd=ROOT)
    assert (root / "answers.csv").read_text(encoding="utf-8") != first
