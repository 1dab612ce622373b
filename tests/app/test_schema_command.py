"""`mechreport schema`: prints the JSON Schema of a spec file, or writes it with --output."""
from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
PUBLISHED = ROOT / "docs" / "spec.schema.json"


def run(*args, cwd=ROOT):
    return subprocess.run([sys.executable, "-m", "mechreport.app.cli", *args], cwd=cwd,
                          capture_output=True, text=True)


def test_schema_prints_the_published_json_schema():
    out = run("schema")
    assert out.returncode == 0, out.stderr
    assert out.stderr == ""
    schema = json.loads(out.stdout)
    assert schema["$schema"] == "https://json-schema.org/draft/2020-12/schema"
    assert schema["title"] == "mechreport spec"
    assert out.stdout == PUBLISHED.read_text(encoding="utf-8")


def test_schema_output_writes_the_file_and_prints_nothing(tmp_path):
    target = tmp_path / "spec.schema.json"
    out = run("schema", "--output", str(target))
    assert out.returncode == 0, out.stderr
    assert out.stdout == ""
    assert target.read_text(encoding="utf-8") == PUBLISHED.read_text(encoding="utf-8")


def test_schema_output_that_cannot_be_written_is_an_error_without_a_traceback(tmp_path):
    out = run("schema", "-o", str(tmp_path / "missing" / "spec.schema.json"))
    assert out.returncode == 1
    assert out.stderr.startswith("error: cannot write ") and "Traceback" not in out.stderr
    assert out.stdout == ""


def test_schema_is_listed_in_the_help():
    out = run("--help")
    assert out.returncode == 0
    assert "schema" in out.stdout and "JSON Schema" in out.stdout
