"""`mechreport check`: one line per spec, expectations with expected vs got, exit codes."""
from __future__ import annotations

import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def run(*args, cwd=ROOT):
    return subprocess.run([sys.executable, "-m", "mechreport.app.cli", *args], cwd=cwd,
                          capture_output=True, text=True)


def test_check_passes_textbook_spec():
    out = run("check", "specs/slider_crank.yaml")
    assert out.returncode == 0, out.stdout + out.stderr
    line = out.stdout.strip()
    assert line.startswith("PASS specs/slider_crank.yaml: 14 expectation(s)")
    assert "worst disagreement" in line and "2 angle(s) left out" in line


def test_check_reports_failed_expectation_and_exits_1(tmp_path):
    text = (ROOT / "specs" / "slider_crank.yaml").read_text()
    bad = tmp_path / "bad.yaml"
    bad.write_text(text.replace("value: 151.4924}", "value: 150.0}"))
    good = tmp_path / "good.yaml"
    good.write_text(text)
    out = run("check", str(bad), str(good))
    assert out.returncode == 1
    lines = out.stdout.splitlines()
    assert lines[0].startswith(f"FAIL {bad}")
    # each failed expectation once (not once per method), with expected, computed,
    # difference, tolerance and the methods
    failed = [l for l in lines if "expectation failed: driver.torque at 45 deg" in l]
    assert len(failed) == 1, lines
    assert ("expected 150 N·m, computed 151.49 N·m, difference 1.49 N·m, tolerance "
            "±0.015 N·m (Newton-Euler, D'Alembert, Dyad (Assur groups), Contour, Power "
            "balance)") in failed[0]
    assert any(l.startswith(f"PASS {good}") for l in lines)   # the batch goes on


def test_check_expectation_at_singular_angle_says_so(tmp_path):
    text = (ROOT / "specs" / "slider_crank.yaml").read_text()
    spec = tmp_path / "s.yaml"
    spec.write_text(text.replace("expect:\n", "expect:\n  - {angle: 90, quantity: "
                                             "driver.torque, value: 1}\n"))
    out = run("check", str(spec))
    assert out.returncode == 1
    assert "crank angle 90 deg is left out: dyad B C C_T: velocity equations singular" \
        in out.stdout


def test_check_bad_spec_is_a_fail_line_not_a_traceback(tmp_path):
    spec = tmp_path / "broken.yaml"
    spec.write_text("mechreport: 1\nname: x\nlinks: {a: {points: {A: [0, 0]}, mass: heavy}}\n")
    out = run("check", str(spec))
    assert out.returncode == 1
    assert "Traceback" not in out.stdout + out.stderr
    assert f"FAIL {spec}" in out.stdout and "links.a.mass: must be a positive number" in \
        out.stdout
