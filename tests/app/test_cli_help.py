"""Every command describes itself in `--help`, wrapped for a terminal (issue 41, point 10:
`kin` had no description; `study`'s ran on one 200-character line)."""
from __future__ import annotations

import pytest

from mechreport.app.cli import main

COMMANDS = ["validate", "kin", "check", "build", "diff", "dynamics", "study", "schema"]


@pytest.mark.parametrize("command", COMMANDS)
def test_every_command_describes_itself_in_lines_a_terminal_shows(command, capsys,
                                                                  monkeypatch):
    monkeypatch.setenv("COLUMNS", "80")
    with pytest.raises(SystemExit) as done:
        main([command, "--help"])
    assert done.value.code == 0
    text = capsys.readouterr().out
    blocks = text.split("\n\n")
    assert blocks[0].startswith(f"usage: mechreport {command}")
    description = blocks[1]
    assert not description.startswith(("positional arguments", "options")), command
    assert len(description.split()) >= 5, command
    assert max(len(line) for line in text.splitlines()) <= 80, command


def test_check_s_stated_default_tolerance_is_the_agreement_check_s(capsys, monkeypatch):
    """``check --tol`` defaults to the one owner of the tolerance (the parser does not import
    it: no numpy on --help), and its help says that number."""
    import re

    from mechreport.checks.agreement import DEFAULT_TOL
    monkeypatch.setenv("COLUMNS", "200")
    with pytest.raises(SystemExit):
        main(["check", "--help"])
    stated = re.search(r"--tol TOL\s+.*\(default ([0-9.e+-]+)\)", capsys.readouterr().out)
    assert stated and float(stated.group(1)) == DEFAULT_TOL


def test_diff_s_stated_default_tolerance_is_the_trust_tolerance(capsys, monkeypatch):
    """``diff --rtol`` defaults to what every printed value promises, the one owner of it."""
    import re

    from mechreport.kinematics import TRUST_RTOL
    monkeypatch.setenv("COLUMNS", "200")
    with pytest.raises(SystemExit):
        main(["diff", "--help"])
    stated = re.search(r"--rtol RTOL\s+.*\(default ([0-9.e+-]+):", capsys.readouterr().out)
    assert stated and float(stated.group(1)) == TRUST_RTOL
