"""`mechreport diff --html`: the same table as the Markdown, as a page of its own: user text
escaped, no script, its one inline style allowed by its hash and nothing else."""
from __future__ import annotations

import base64
import hashlib
import re
from pathlib import Path

from mechreport.app.diff import Change, html, markdown

HOSTILE = "<script>alert(1)</script>"


def test_the_diff_page_has_the_markdown_table_escaped_and_nothing_to_run():
    changes = [Change(HOSTILE, "cycle.torque.rms", "1.5 N·m", "1.6 N·m", "+6.7%"),
               Change("four_bar", "verdict motor", "PASS", "FAIL", "changed")]
    page = html(changes, Path("old"), Path(HOSTILE), 1e-6, 2)
    md = markdown(changes, Path("old"), Path("x"), 1e-6, 2)
    assert "<script" not in page and page.count("&lt;script&gt;") == 2
    cells = re.findall(r"<td[^>]*>(.*?)</td>", page)
    assert cells[:5] == ["&lt;script&gt;alert(1)&lt;/script&gt;", "cycle.torque.rms",
                         "1.5 N·m", "1.6 N·m", "+6.7%"]
    assert len(cells) == 10 == 5 * (md.count("\n| ") - 1)
    style = re.search(r"<style>(.*?)</style>", page, flags=re.S).group(1)
    digest = base64.b64encode(hashlib.sha256(style.encode()).digest()).decode()
    csp = re.search(r'http-equiv="Content-Security-Policy" content="([^"]+)"', page).group(1)
    assert csp.startswith("default-src 'none'; style-src 'sha256-" + digest + "'")
    assert "2 change(s) in 2 spec(s)" in page
    assert '<span class="badge fail">FAIL</span>' in page


def test_no_change_is_a_sentence():
    page = html([], Path("a"), Path("b"), 1e-6, 3)
    assert "nothing changed" in page and "<table" not in page
