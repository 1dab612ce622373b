"""A closed pipe ends a command quietly (issue 40, point 8): `mechreport kin SPEC | head -2`
stops with exit status 141 (128 + SIGPIPE, as a shell reports a Unix tool that met a closed
pipe) and nothing on stderr: no "BrokenPipeError", no "Exception ignored", no traceback."""
from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
SPEC = str(ROOT / "specs" / "four_bar.yaml")


def _into_a_closed_pipe(*args: str) -> subprocess.CompletedProcess:
    """``mechreport ARGS`` with stdout a pipe whose reader has already gone (`| head -0`)."""
    read, write = os.pipe()
    os.close(read)
    try:
        return subprocess.run([sys.executable, "-m", "mechreport", *args], stdout=write,
                              stderr=subprocess.PIPE, text=True, cwd=ROOT, timeout=300)
    finally:
        os.close(write)


@pytest.mark.parametrize("args", [("kin", SPEC), ("validate", SPEC), ("schema",)],
                         ids=["kin", "validate", "schema"])
def test_a_closed_pipe_ends_the_command_quietly(args):
    proc = _into_a_closed_pipe(*args)
    assert (proc.returncode, proc.stderr) == (141, "")


def test_help_into_a_closed_pipe_says_nothing():
    proc = _into_a_closed_pipe("--help")       # argparse itself ignores the failed write
    assert proc.returncode in (0, 141) and proc.stderr == ""


def test_a_closed_stderr_ends_a_build_quietly(tmp_path):
    read, write = os.pipe()
    os.close(read)
    try:
        proc = subprocess.run([sys.executable, "-m", "mechreport", "validate", SPEC,
                               str(tmp_path / "missing.yaml")], stdout=subprocess.PIPE,
                              stderr=write, text=True, cwd=ROOT, timeout=300)
    finally:
        os.close(write)
    assert proc.returncode == 141


def test_a_broken_pipe_that_is_not_stdout_is_an_internal_error(monkeypatch, capsys):
    from mechreport.app import kin
    from mechreport.app.cli import main

    def command(path, angles):
        raise BrokenPipeError(32, "Broken pipe")          # a worker's pipe, say
    monkeypatch.setattr(kin, "kin_command", command)
    assert main(["kin", SPEC]) == 1
    assert "internal error: BrokenPipeError" in capsys.readouterr().err
