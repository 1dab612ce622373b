"""The batch: parallel build, index, one corrupted spec that fails alone, exit code."""
from __future__ import annotations

import json
import shutil

import pytest

from mechreport.app.build import build_files
from mechreport.app.progress import Progress

pytestmark = pytest.mark.slow      # builds reports, starts processes or fuzzes: not in the fast tier


@pytest.fixture(scope="module")
def batch(tmp_path_factory, textbook_specs):
    specs = tmp_path_factory.mktemp("specs")
    good = shutil.copy(textbook_specs["4.6"], specs / "slider_crank.yaml")
    bad = specs / "broken.yaml"
    bad.write_text(textbook_specs["4.6"].read_text().replace("mass: 1\n", "mass: -1\n", 1))
    out = tmp_path_factory.mktemp("out")
    code = build_files([bad, good], out, jobs=2)
    return code, out, bad


def test_exit_code_says_a_spec_failed(batch):
    code, _, _ = batch
    assert code == 1


def test_index_has_a_fail_row_with_the_message(batch):
    _, out, bad = batch
    index = (out / "index.md").read_text(encoding="utf-8")
    row = next(line for line in index.splitlines() if str(bad) in line)
    assert "| FAIL: could not be built |" in row
    assert "mass" in row.lower()                 # the SpecError's message is carried
    assert "1 passed their check, 0 failed it, 1 could not be built" in index
    good = next(line for line in index.splitlines() if line.startswith("| R-RRT slider-crank"))
    assert "crank.yaml)" in good                 # the spec path tells same names apart
    assert "| PASS |" in good and "[pdf](slider_crank/report.pdf)" in good
    assert "200.6 N·m at 85°" in good           # peak driver torque of the slider-crank
    assert (out / "index.pdf").stat().st_size > 0


def test_the_other_report_is_complete(batch):
    _, out, _ = batch
    folder = out / "slider_crank"
    for name in ("report.md", "report.pdf", "results.csv", "summary.json"):
        assert (folder / name).stat().st_size > 0
    assert json.loads((folder / "summary.json").read_text())["status"] == "PASS"
    assert not (out / "broken").exists()


def test_failure_is_reported_on_stderr(tmp_path, capsys):
    bad = tmp_path / "nope.yaml"
    bad.write_text("mechreport: 1\nname: [unclosed\n")
    assert build_files([bad], tmp_path / "out", jobs=1) == 1
    err = capsys.readouterr().err
    assert f"FAIL {bad}" in err


def test_progress_plain_lines_off_a_terminal(capsys):
    import sys
    p = Progress(2, sys.stderr)
    p.update({"spec": "specs/x.yaml", "ok": True, "seconds": 1.23})
    p.close()
    assert "built specs/x.yaml (1.2 s)" in capsys.readouterr().err


def test_no_specs_is_an_error(tmp_path):
    assert build_files([], tmp_path) == 1


def test_the_report_embeds_its_animation_and_the_index_links_it(batch):
    _, out, _ = batch
    folder = out / "slider_crank"
    assert (folder / "animation.gif").read_bytes()[:6] == b"GIF89a"
    assert "![The mechanism moving over the sweep with its forces](animation.gif)" in \
        (folder / "report.md").read_text(encoding="utf-8")
    assert "[animation](slider_crank/animation.gif)" in \
        (out / "index.md").read_text(encoding="utf-8")
    assert list((folder / "figures").glob("frame_*.svg"))       # the PDF's filmstrip


def test_no_animation_leaves_it_out_and_rebuilds_what_had_one(tmp_path):
    from helpers import tiny_spec
    spec = tiny_spec(tmp_path / "tiny.yaml")
    out = tmp_path / "out"
    assert build_files([spec], out, jobs=1, quiet=True) == 0
    assert (out / "tiny" / "animation.gif").is_file()
    assert build_files([spec], out, jobs=1, quiet=True, animation=False) == 0
    folder = out / "tiny"
    assert not (folder / "animation.gif").exists()
    assert not list((folder / "figures").glob("frame_*.svg"))
    assert "animation.gif" not in (folder / "report.md").read_text(encoding="utf-8")
    assert json.loads((folder / "summary.json").read_text())["build"]["animation"] is False
    assert "[animation]" not in (out / "index.md").read_text(encoding="utf-8")


# ------------------------------------------------- the executor's retries (issue 42, item 4)

def _dies_once(options, i, path, name):
    """The build's task, whose worker process dies on the first try of spec ``i == 0``."""
    import os
    from pathlib import Path

    from mechreport.app import build
    tries = Path(os.environ["BUILD_FAULTS"]) / f"tries-{i}"
    with open(tries, "a", encoding="utf-8") as fh:
        fh.write("try\n")
    if i == 0 and len(tries.read_text(encoding="utf-8").splitlines()) == 1:
        os._exit(1)
    return build._build_task(options, i, path, name)


def test_a_worker_that_dies_while_building_a_spec_costs_only_a_retry(tmp_path, monkeypatch,
                                                                       capsys,
                                                                       textbook_specs):
    from mechreport.app import build
    faults = tmp_path / "faults"
    faults.mkdir()
    monkeypatch.setenv("BUILD_FAULTS", str(faults))
    monkeypatch.setattr(build, "_build_task", _dies_once)
    specs = [shutil.copy(textbook_specs["4.6"], tmp_path / f"s{k}.yaml") for k in (1, 2)]
    code = build_files(specs, tmp_path / "out", jobs=2, animation=False)
    err = capsys.readouterr().err
    assert code == 0, err
    assert sorted(p.name for p in faults.iterdir()) == ["tries-0", "tries-1"]
    assert len((faults / "tries-0").read_text().splitlines()) == 2
    assert "a worker process died" in err and "computing them again (try 2 of 3)" in err
    for k in (1, 2):
        assert (tmp_path / "out" / f"s{k}" / "report.pdf").is_file()


def test_the_report_and_index_pages_and_their_shared_script(batch):
    _, out, _ = batch
    page = (out / "slider_crank" / "report.html").read_text(encoding="utf-8")
    assert "../.mechreport-html/report.js" in page and "R-RRT slider-crank" in page
    index = (out / "index.html").read_text(encoding="utf-8")
    assert 'href="slider_crank/report.html"' in index and "could not be built" in index
    assert "[html](slider_crank/report.html)" in (out / "index.md").read_text(encoding="utf-8")
    assert {p.name for p in (out / ".mechreport-html").iterdir()} == {"report.js", "report.css"}


def test_report_html_false_writes_no_page(tmp_path):
    from helpers import tiny_spec
    spec = tiny_spec(tmp_path / "tiny.yaml")
    spec.write_text(spec.read_text(encoding="utf-8") + "report: {html: false}\n",
                    encoding="utf-8")
    assert build_files([spec], tmp_path / "out", jobs=1) == 0
    assert (tmp_path / "out" / "tiny" / "report.md").is_file()
    assert not (tmp_path / "out" / "tiny" / "report.html").exists()
    assert not (tmp_path / "out" / "index.html").exists()
    assert not (tmp_path / "out" / ".mechreport-html").exists()
