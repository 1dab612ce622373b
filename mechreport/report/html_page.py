"""Interactive HTML pages: report.html (a report folder's) and index.html (an output
folder's), each a document written by :mod:`.write_html` inside a page that opens offline.

    OUT/index.html
    OUT/<name>/report.html
    OUT/.mechreport-html/report.js, report.css     (written once per output folder)

The script and the style ship inside the package (``html_assets/``, plain JavaScript and
CSS, no library) and are copied next to the report folders once per output folder (a hidden
folder: no spec's folder can be named so). Each page carries a Content-Security-Policy that
lets it load only files (``'self'``; a page opened from disk has no other origin) and no
inline script: the report's data is a ``<script type="application/json">`` block, which is
read as text, never run. Nothing is fetched from the network and no server is needed."""
from __future__ import annotations

import json
from importlib import resources
from pathlib import Path

from .files import atomic_write_bytes, atomic_write_text
from .write_html import esc, html_body

#: the hidden folder of an output folder that holds the pages' script and style
ASSETS = ".mechreport-html"
#: the files of ASSETS, as shipped in mechreport/report/html_assets/
ASSET_FILES = ("report.js", "report.css")
#: only the folder's own files: no inline script or style, no network, no forms, no plugins
CSP = ("default-src 'none'; script-src 'self'; style-src 'self'; img-src 'self'; "
       "base-uri 'none'; form-action 'none'; object-src 'none'")


def asset_bytes(name: str) -> bytes:
    """A shipped asset's bytes (``report.js``, ``report.css``)."""
    return resources.files("mechreport.report").joinpath("html_assets", name).read_bytes()


def write_assets(out: Path) -> list[Path]:
    """``out/.mechreport-html/*``: written where missing or different (once per output
    folder; a rebuild with the same mechreport leaves them untouched)."""
    written = []
    for name in ASSET_FILES:
        path = Path(out) / ASSETS / name
        data = asset_bytes(name)
        try:
            same = path.is_file() and not path.is_symlink() and path.read_bytes() == data
        except OSError:
            same = False
        if not same:
            written.append(atomic_write_bytes(path, data))
    return written


def json_block(data: dict, element_id: str) -> str:
    """``data`` as a non-executable JSON block (``<``, ``>`` and ``&`` as \\u escapes, so that
    no string inside it can close the element)."""
    text = json.dumps(data, ensure_ascii=False, separators=(",", ":"), allow_nan=False)
    text = text.replace("<", "\\u003c").replace(">", "\\u003e").replace("&", "\\u0026")
    return f"<script type=\"application/json\" id=\"{element_id}\">{text}</script>\n"


def page(title: str, body: str, assets: str, kind: str, data: dict | None = None) -> str:
    """A whole HTML page: ``body`` (HTML), the style and script of ``assets`` (the relative
    path of the assets folder), ``data`` as the page's JSON block; ``kind`` (report, index)
    tells the script what to do."""
    block = json_block(data, "mr-data") if data is not None else ""
    return ("<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
            f"<meta http-equiv=\"Content-Security-Policy\" content=\"{CSP}\">\n"
            "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
            "<meta name=\"generator\" content=\"mechreport\">\n"
            f"<title>{esc(title)}</title>\n"
            f"<link rel=\"stylesheet\" href=\"{assets}/report.css\">\n"
            f"</head>\n<body class=\"{kind}\">\n<main>\n{body}</main>\n{block}"
            f"<script src=\"{assets}/report.js\"></script>\n</body>\n</html>\n")


def live_section(data: dict) -> str:
    """The report's interactive part: the mechanism with its force arrows, the slider and
    play button, the values at the chosen angle and the sweep plots (filled by the script
    from the page's data)."""
    n = len(data["angles"])
    return ("<section class=\"live\" id=\"live\">\n"
            "<h2 id=\"at-any-angle\">At any angle</h2>\n"
            "<p class=\"small\">Drag the slider (or use the arrow keys, or click a plot) to "
            "move the mechanism; every value below is the reference method's at that angle. "
            "Plots: drag across to zoom, double-click to zoom out, hover to read "
            "values.</p>\n"
            "<div class=\"live-grid\">\n"
            "<div class=\"mech-box\"><svg id=\"mech\" viewBox=\"0 0 100 100\" role=\"img\" "
            "aria-label=\"the mechanism and its forces\"></svg></div>\n"
            "<div class=\"side\">\n<div class=\"controls\">"
            "<button id=\"play\" type=\"button\">▶ Play</button> "
            f"<input id=\"angle\" type=\"range\" min=\"0\" max=\"{max(n - 1, 0)}\" value=\"0\" "
            f"step=\"1\" aria-label=\"{esc(data['coord'])}\"> "
            "<output id=\"angle-out\" for=\"angle\"></output></div>\n"
            f"<table id=\"values\"><thead><tr><th>at this {esc(data['coord'])}</th>"
            "<th class=\"num\">"
            "value</th><th class=\"num\">x</th><th class=\"num\">y</th></tr></thead>"
            "<tbody></tbody></table>\n</div>\n</div>\n"
            "<div id=\"charts\"></div>\n</section>\n")


def report_html(doc, data: dict, assets: str = f"../{ASSETS}") -> str:
    """report.html of the report document ``doc`` with the interactive ``data``
    (:func:`.html_data.html_data`)."""
    body = html_body(doc, before_sections=live_section(data))
    return page(doc.title, body, assets, "report", data)


def write_html_report(analysis, model, folder: Path) -> list[Path]:
    """``folder/report.html`` of ``model`` and the output folder's assets (``folder``'s
    parent: the report folders of a build share them)."""
    from .html_data import html_data
    from .report_doc import report_document
    folder = Path(folder)
    text = report_html(report_document(model), html_data(analysis, model))
    return [atomic_write_text(folder / "report.html", text), *write_assets(folder.parent)]


def index_html(doc) -> str:
    """index.html of the index document ``doc`` (its table sorts and filters)."""
    return page(doc.title, html_body(doc), ASSETS, "index")


def table_page(doc) -> str:
    """A page of its own (``mechreport diff --html``): ``doc`` with its style inline, allowed
    by its hash in the page's CSP (the page may be saved anywhere, away from any assets)."""
    import base64
    import hashlib
    css = asset_bytes("report.css").decode("utf-8")
    digest = base64.b64encode(hashlib.sha256(css.encode("utf-8")).digest()).decode("ascii")
    csp = f"default-src 'none'; style-src 'sha256-{digest}'; base-uri 'none'; form-action 'none'"
    return ("<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
            f"<meta http-equiv=\"Content-Security-Policy\" content=\"{csp}\">\n"
            f"<title>{esc(doc.title)}</title>\n<style>{css}</style>\n</head>\n"
            f"<body class=\"table-page\">\n<main>\n{html_body(doc)}</main>\n</body>\n</html>\n")
