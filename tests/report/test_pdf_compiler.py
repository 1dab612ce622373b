"""The Typst compiler kept for a process (issue 48) gives what a fresh compile gives, and
sees a figure written again between two documents."""
from __future__ import annotations

import typst

from mechreport.report.pdf import compile_typst, figure_fonts, typst_compiler

SOURCE = '#image("f.svg", width: 3cm)\n\nA figure.'


def svg(colour: str) -> str:
    return ('<svg xmlns="http://www.w3.org/2000/svg" width="20" height="10">'
            f'<rect width="20" height="10" fill="{colour}"/></svg>')


def test_kept_compiler_matches_a_fresh_compile_and_reads_files_again(tmp_path, monkeypatch):
    monkeypatch.setenv("SOURCE_DATE_EPOCH", "0")
    (tmp_path / "f.svg").write_text(svg("red"))
    first = compile_typst(SOURCE, tmp_path / "a.pdf", tmp_path).read_bytes()
    (tmp_path / "f.svg").write_text(svg("blue"))
    second = compile_typst(SOURCE, tmp_path / "b.pdf", tmp_path).read_bytes()
    fresh = typst.compile(SOURCE.encode(), root=str(tmp_path), ignore_system_fonts=True,
                          font_paths=figure_fonts(), timestamp=0)
    assert first != second
    assert second == fresh
    assert typst_compiler() is typst_compiler()
