"""report.html and index.html in a real browser (headless chromium driven by selenium):
opened from disk, no script error or policy violation logged, no request leaving the
folder, the slider at the peak bearing load showing results.csv's value, the index sorting
by a column and filtering, a hostile spec name shown as text.

Needs Debian's ``chromium`` and ``chromium-driver`` packages and ``selenium`` (the test
extra); .ci/run installs the packages. Elsewhere these tests skip, saying what to install.
One browser for the module; the reports are written without their PDF and figures (the page
needs neither to run)."""
from __future__ import annotations

import csv
import json
import math
import shutil
from pathlib import Path

import pytest

import mechreport
from helpers import tiny_spec

ROOT = Path(__file__).resolve().parents[2]
CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")
DRIVER = shutil.which("chromedriver")
HOSTILE = "<script>alert(1)</script> & <b>bold</b>"

webdriver = pytest.importorskip(
    "selenium.webdriver", reason="the browser tests need selenium: pip install -e '.[test]'")
pytestmark = pytest.mark.slow          # a browser session and two analyses: about 9 s
if not (CHROMIUM and DRIVER):
    pytest.skip("the browser tests need chromium and chromedriver: "
                "apt-get install chromium chromium-driver (Debian)", allow_module_level=True)


def _write(spec: Path, out: Path, name: str | None = None) -> dict:
    """``out/<stem>/report.html`` and results.csv of ``spec``; its index row."""
    from mechreport.report.html_page import write_html_report
    from mechreport.report.model import build_model
    from mechreport.report.render import csv_text
    a = mechreport.analyse(spec)
    m = build_model(a, f"specs/{spec.name}")
    folder = out / spec.stem
    folder.mkdir(parents=True)
    write_html_report(a, m, folder)
    (folder / "results.csv").write_text(csv_text(m.csv_header, m.csv_rows), encoding="utf-8")
    return dict(m.index_row, stem=spec.stem, summary=m.summary)


@pytest.fixture(scope="module")
def site(tmp_path_factory):
    from mechreport.report.index_doc import index_document
    from mechreport.report.render import write_index_html
    out = tmp_path_factory.mktemp("html") / "out"
    rows = [_write(ROOT / "specs" / "four_bar.yaml", out),
            _write(tiny_spec(tmp_path_factory.mktemp("spec") / "hostile.yaml", HOSTILE), out)]
    for r in rows:
        r.update(report_html=f"{r['stem']}/report.html", sheets=[])
    write_index_html(index_document(rows, "batch", "test", "today"), out)
    return out, rows


@pytest.fixture(scope="module")
def browser():
    from selenium.webdriver.chrome.service import Service
    opts = webdriver.ChromeOptions()
    opts.binary_location = CHROMIUM
    for arg in ("--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage",
                "--window-size=1200,900", "--no-first-run", "--disable-extensions"):
        opts.add_argument(arg)
    opts.set_capability("goog:loggingPrefs", {"browser": "ALL", "performance": "ALL"})
    driver = webdriver.Chrome(service=Service(DRIVER), options=opts)
    yield driver
    driver.quit()


def _open(browser, path: Path) -> list[dict]:
    """Open ``path`` from disk; the browser log's errors and warnings while it loaded (but
    for the figures inside the output folder, which these tests do not write)."""
    browser.get_log("browser")                                   # drop earlier entries
    browser.get_log("performance")
    browser.get(path.as_uri())
    browser.execute_script("return document.readyState")
    folder = path.parent.parent.as_uri() + "/"
    return [e for e in browser.get_log("browser") if e["level"] in ("SEVERE", "WARNING")
            and not (e["message"].startswith(folder) and "ERR_FILE_NOT_FOUND" in e["message"])]


def _requests(browser) -> list[str]:
    """The URLs the page requested since it was opened (the DevTools network events: a page
    from disk records no resource timing)."""
    urls = []
    for entry in browser.get_log("performance"):
        event = json.loads(entry["message"])["message"]
        if event["method"] == "Network.requestWillBeSent":
            urls.append(event["params"]["request"]["url"])
    return urls


def test_the_report_runs_offline_without_errors(site, browser):
    out, _ = site
    assert _open(browser, out / "four_bar" / "report.html") == []
    urls = _requests(browser)
    assert any(u.endswith("/.mechreport-html/report.js") for u in urls)
    assert all(u.startswith(out.as_uri() + "/") for u in urls), urls
    # the script ran: the mechanism is drawn, one plot per sweep quantity with its cursor
    assert browser.execute_script("return document.querySelectorAll('#mech line').length") > 0
    assert browser.execute_script("return document.querySelectorAll('#charts line.cursor')"
                                  ".length") == 3


def _shown(browser, css: str) -> float:
    text = browser.find_element("css selector", css).text
    return float(text.replace("−", "-"))


def test_the_slider_at_the_peak_bearing_load_shows_results_csv_s_value(site, browser):
    out, rows = site
    summary = rows[0]["summary"]
    big, ref = summary["largest_bearing_load"], summary["reference_method"]
    _open(browser, out / "four_bar" / "report.html")
    slider = browser.find_element("id", "angle")
    angles = browser.execute_script(
        "return JSON.parse(document.getElementById('mr-data').textContent).angles")
    k = angles.index(big["angle_deg"])
    browser.execute_script("arguments[0].value = arguments[1];"
                           "arguments[0].dispatchEvent(new Event('input'))", slider, k)
    assert browser.find_element("id", "angle-out").text == f"crank angle {big['angle_deg']:g}°"
    with open(out / "four_bar" / "results.csv", encoding="utf-8") as fh:
        row = next(r for r in csv.DictReader(fh)
                   if float(r["crank_angle [deg]"]) == big["angle_deg"])
    fx = float(row[f"{ref}.joint.{big['joint']}.fx [N]"])
    fy = float(row[f"{ref}.joint.{big['joint']}.fy [N]"])
    cell = f"#values tr[data-joint='{big['joint']}']"
    for shown, value in ((_shown(browser, cell + " td.f"), math.hypot(fx, fy)),
                         (_shown(browser, cell + " td.fx"), fx),
                         (_shown(browser, cell + " td.fy"), fy)):
        # as the report prints it: 4 significant digits
        assert shown == pytest.approx(value, rel=5e-4, abs=1e-9)
    assert _shown(browser, cell + " td.f") == pytest.approx(big["value"], rel=5e-4)
    # the play button moves it
    browser.find_element("id", "play").click()
    browser.implicitly_wait(0)
    moved = browser.execute_script(
        "return new Promise(r => setTimeout(() => r(document.getElementById('angle').value),"
        " 300))")
    browser.find_element("id", "play").click()
    assert int(moved) != k


def test_a_hostile_spec_name_is_text(site, browser):
    out, _ = site
    assert _open(browser, out / "hostile" / "report.html") == []
    assert browser.find_element("tag name", "h1").text == HOSTILE
    assert browser.execute_script("return document.querySelectorAll('main b').length") == 0


def test_the_index_sorts_and_filters(site, browser):
    out, _ = site
    assert _open(browser, out / "index.html") == []
    assert all(u.startswith(out.as_uri() + "/") for u in _requests(browser))

    def first_column():
        return [r.text.split("\n")[0] for r in browser.find_elements(
            "css selector", "main table tbody tr") if r.is_displayed()]

    heads = browser.find_elements("css selector", "main table thead th")
    names = first_column()
    assert any(n.startswith(HOSTILE) for n in names)        # the hostile name is text
    assert browser.execute_script("return document.querySelectorAll('main b').length") == 0
    heads[0].click()
    assert first_column() == sorted(names, key=str.casefold)
    heads[0].click()
    assert first_column() == sorted(names, key=str.casefold, reverse=True)
    heads[5].click()                                  # the largest bearing load: by number
    loads = [float(r.find_elements("css selector", "td")[5].text.split()[0]) for r in
             browser.find_elements("css selector", "main table tbody tr")]
    assert loads == sorted(loads) and len(set(loads)) == 2
    links = browser.find_elements("link text", "html")
    assert {a.get_attribute("href") for a in links} == {
        (out / s / "report.html").as_uri() for s in ("four_bar", "hostile")}
    box = browser.find_element("css selector", "input.filter")
    box.send_keys("four")
    assert first_column() == [n for n in names if "four" in n.lower()] != names


def test_the_plots_zoom_show_values_on_hover_and_move_the_slider(site, browser):
    from selenium.webdriver.common.action_chains import ActionChains
    out, _ = site
    _open(browser, out / "four_bar" / "report.html")
    chart = browser.find_elements("css selector", "#charts svg")[1]
    width = chart.size["width"]

    def ticks():
        return [t.text for t in chart.find_elements("css selector", "text")
                if t.get_attribute("text-anchor") == "middle" and t.text.isdigit()]

    def tip():
        return chart.find_element("css selector", "text.tip").text

    whole = ticks()
    ActionChains(browser).move_to_element_with_offset(chart, int(-0.25 * width), 0) \
        .click_and_hold().move_by_offset(int(0.3 * width), 0).release().perform()
    zoomed = ticks()
    assert zoomed != whole and int(zoomed[0]) > int(whole[0])
    ActionChains(browser).double_click(chart).perform()
    assert ticks() == whole
    before = tip()
    ActionChains(browser).move_to_element_with_offset(chart, int(0.3 * width), 0).perform()
    assert tip() != before and tip().endswith(" N")
    ActionChains(browser).click().perform()                 # a click moves the slider there
    assert browser.find_element("id", "angle").get_attribute("value") != "0"
    assert _errors(browser) == []


def _errors(browser) -> list[dict]:
    return [e for e in browser.get_log("browser") if e["level"] == "SEVERE"]
