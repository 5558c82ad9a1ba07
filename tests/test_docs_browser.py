"""The docs site as a reader sees it: built with MkDocs from the repository's
generated mkdocs.yml, served on 127.0.0.1 and opened page by page in Debian's
headless Chromium, driven by playwright (its own browser downloads are not
used). Every state diagram must be drawn as SVG, no page may log an error, and
no request may leave the machine: the site must work offline.

Chromium is installed by scripts/install-toolchains; without it (or playwright)
the test skips on a developer's machine and fails in CI.
"""
from __future__ import annotations

import functools
import os
import re
import shutil
import subprocess
import sys
import threading
from http.server import SimpleHTTPRequestHandler, ThreadingHTTPServer
from pathlib import Path
from urllib.parse import urlsplit

import pytest

from conftest import PROTOCOLS, ROOT

CHROMIUM = shutil.which("chromium") or "/usr/bin/chromium"
LOCAL_HOSTS = {"127.0.0.1", "localhost"}
LOCAL_SCHEMES = {"data", "blob", "about"}
WIDTH = 1280
# Material draws each diagram into a closed shadow root; opening them lets the test see the SVG.
OPEN_SHADOW_ROOTS = """
const attach = Element.prototype.attachShadow;
Element.prototype.attachShadow = function (init) { return attach.call(this, {...init, mode: "open"}); };
"""
DIAGRAMS_DRAWN = """() => document.querySelectorAll("pre.mermaid").length === 0 &&
    [...document.querySelectorAll("div.mermaid")].every(d => d.shadowRoot && d.shadowRoot.querySelector("svg"))"""
DIAGRAMS = """() => [...document.querySelectorAll("div.mermaid")].map(d => {
    const svg = d.shadowRoot.querySelector("svg"), box = svg.getBoundingClientRect();
    return {text: svg.textContent, width: box.width, height: box.height};
})"""
# bit layouts are the tables whose first header cell is empty; each in Material's scrolling wrapper
OVERFLOWING_LAYOUTS = """() => [...document.querySelectorAll(".md-typeset table")]
    .filter(t => t.querySelector("th") && t.querySelector("th").textContent.trim() === "")
    .map(t => t.closest(".md-typeset__scrollwrap") || t)
    .filter(w => w.scrollWidth > w.clientWidth + 1)
    .map(w => w.querySelector("th:nth-child(2)").textContent)"""


def needs(what: str) -> None:
    if os.environ.get("CI"):
        pytest.fail(f"{what} is missing; scripts/install-toolchains and scripts/setup install it")
    pytest.skip(f"{what} is not installed")


def is_local(url: str) -> bool:
    parts = urlsplit(url)
    return parts.scheme in LOCAL_SCHEMES or parts.scheme == "file" or parts.hostname in LOCAL_HOSTS


@pytest.fixture(scope="module")
def site(tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("site")
    proc = subprocess.run([sys.executable, "-m", "mkdocs", "build", "--strict", "--site-dir", str(out)],
                          cwd=ROOT, capture_output=True, text=True, timeout=600)
    assert proc.returncode == 0, proc.stderr
    return out


@pytest.fixture(scope="module")
def server(site):
    class Quiet(SimpleHTTPRequestHandler):
        def log_message(self, *args):
            pass
    httpd = ThreadingHTTPServer(("127.0.0.1", 0), functools.partial(Quiet, directory=str(site)))
    thread = threading.Thread(target=httpd.serve_forever, daemon=True)
    thread.start()
    yield f"http://127.0.0.1:{httpd.server_port}"
    httpd.shutdown()
    thread.join()


@pytest.fixture(scope="module")
def browser():
    if not Path(CHROMIUM).is_file():
        needs("Debian's chromium")
    try:
        from playwright.sync_api import sync_playwright
    except ImportError:
        needs("playwright (the test extra)")
    with sync_playwright() as playwright:
        # a host other than this machine's resolves nowhere, should a request slip past the route below
        chromium = playwright.chromium.launch(executable_path=CHROMIUM, args=[
            "--host-resolver-rules=MAP * ~NOTFOUND, EXCLUDE 127.0.0.1, EXCLUDE localhost"])
        yield chromium
        chromium.close()


class Visit:
    """One page, opened as a reader would, with what it asked for and what it logged."""

    def __init__(self, browser, url: str):
        self.requests: list[str] = []
        self.errors: list[str] = []
        self.context = browser.new_context(viewport={"width": WIDTH, "height": 900})
        self.context.add_init_script(OPEN_SHADOW_ROOTS)
        self.context.on("request", lambda request: self.requests.append(request.url))
        self.context.route("**/*", lambda route: route.continue_() if is_local(route.request.url) else route.abort())
        self.page = self.context.new_page()
        self.page.on("console", lambda message: message.type == "error" and self.errors.append(message.text))
        self.page.on("pageerror", lambda error: self.errors.append(str(error)))
        self.page.goto(url)
        self.page.wait_for_function(DIAGRAMS_DRAWN, timeout=30_000)
        self.page.wait_for_load_state("networkidle")

    def close(self) -> None:
        self.context.close()


def pages(site: Path) -> list[str]:
    return sorted(p.relative_to(site).as_posix() for p in site.rglob("*.html") if p.name != "404.html")


def diagram_states(page: str) -> list[list[str]]:
    """The states each ```mermaid fence of the page's Markdown source declares (`name: description`)."""
    source = (ROOT / "generated" / "docs" / page.replace(".html", ".md")).read_text(encoding="utf-8")
    fences = re.findall(r"^```mermaid\n(.*?)^```", source, flags=re.M | re.S)
    return [re.findall(r"^ +(\w+): ", fence, flags=re.M) for fence in fences]


def test_every_page_renders_offline_with_its_diagrams_drawn(site, server, browser):
    opened = pages(site)
    assert {f"{name}.html" for name in PROTOCOLS} | {"index.html", "examples/index.html"} <= set(opened)
    drawn = 0
    for page in opened:
        visit = Visit(browser, f"{server}/{page}")
        try:
            assert [url for url in visit.requests if not is_local(url)] == [], page
            assert visit.errors == [], page
            diagrams = visit.page.evaluate(DIAGRAMS)
            states = diagram_states(page)
            assert len(diagrams) == len(states), page
            for diagram, names in zip(diagrams, states):
                assert diagram["width"] > 100 and diagram["height"] > 100, (page, diagram)
                assert names and all(name in diagram["text"] for name in names), (page, names, diagram["text"])
            drawn += len(diagrams)
        finally:
            visit.close()
    assert drawn >= 2  # tr24's master and slave machines


@pytest.mark.parametrize("name", PROTOCOLS)
def test_bit_layouts_fit_a_1280_pixel_window(site, server, browser, name):
    visit = Visit(browser, f"{server}/{name}.html")
    try:
        assert visit.page.evaluate(OVERFLOWING_LAYOUTS) == []
    finally:
        visit.close()


IMPORTED_PAGE = """() => {
    let el = document.getElementById("msg-attitude").parentElement.nextElementSibling;
    const heading = el.textContent, tables = [];
    for (el = el.nextElementSibling; el && el.tagName !== "H2"; el = el.nextElementSibling) {
        const t = el.tagName === "TABLE" ? el : el.querySelector("table");
        if (t) tables.push(t);
    }
    const table = tables.find(t => t.querySelector("th").textContent.trim() === "field");
    table.setAttribute("data-shot", "attitude");
    const wrap = table.closest(".md-typeset__scrollwrap") || table;
    const row = [...table.querySelectorAll("tr")].find(r => r.cells[0].textContent.trim() === "roll");
    const box = wrap.getBoundingClientRect();
    return {heading: heading, cells: [...row.cells].map(c => c.textContent.trim()),
            left: box.left, right: box.right,
            enum_link: !!document.querySelector('a[href="#enum-mav-type"]'),
            enum_entry: !!document.getElementById("enum-mav-type")};
}"""


def test_an_imported_mavlink_dialect_reads_well_in_a_browser(tmp_path, browser):
    """MAVLink's common.xml imported and its site built as a user builds it (`codeword
    build` writes mkdocs.yml; `mkdocs build --strict`): ATTITUDE's field table, seen in
    Chromium at 1280 pixels, gives each field its unit, its description and its type
    (its floats may be NaN), fields name their enums by link to an entry of the page, and
    a screenshot of the table shows it drawn (a PNG of the table's size, not blank)."""
    from codeword.cli import main as codeword

    pymavlink = pytest.importorskip("pymavlink")
    common = Path(pymavlink.__file__).parent / "dialects" / "v20" / "common.xml"
    assert codeword(["import", "mavlink", str(common), "--out", str(tmp_path / "schemas")]) == 0
    cwd = os.getcwd()
    try:
        os.chdir(tmp_path)
        assert codeword(["build", "--targets", "docs"]) == 0
    finally:
        os.chdir(cwd)
    site = tmp_path / "site"
    proc = subprocess.run([sys.executable, "-m", "mkdocs", "build", "--strict", "--site-dir", str(site)],
                          cwd=tmp_path, capture_output=True, text=True, timeout=600)
    assert proc.returncode == 0, proc.stderr
    httpd = ThreadingHTTPServer(("127.0.0.1", 0), functools.partial(SimpleHTTPRequestHandler, directory=str(site)))
    threading.Thread(target=httpd.serve_forever, daemon=True).start()
    visit = Visit(browser, f"http://127.0.0.1:{httpd.server_port}/common.html#msg-attitude")
    try:
        assert [url for url in visit.requests if not is_local(url)] == [] and visit.errors == []
        seen = visit.page.evaluate(IMPORTED_PAGE)
        assert seen["heading"].startswith("attitude")
        assert seen["cells"][0] == "roll" and seen["cells"][4] == "f32 LE" and seen["cells"][6] == "rad"
        assert "NaN" in seen["cells"][5] and seen["cells"][8] == "Roll angle (-pi..+pi)"
        assert seen["enum_link"] and seen["enum_entry"]
        assert 0 <= seen["left"] and seen["right"] <= WIDTH  # the table scrolls within the page, never past it
        table = visit.page.locator('table[data-shot="attitude"]')
        # the site's header stays at the top of the window: hidden, so that it covers no row
        shot = table.screenshot(path=str(tmp_path / "attitude.png"), style=".md-header { visibility: hidden }")
        width, height = int.from_bytes(shot[16:20], "big"), int.from_bytes(shot[20:24], "big")  # the PNG header
        box = table.bounding_box()
        assert shot[:8] == b"\x89PNG\r\n\x1a\n" and (width, height) == (round(box["width"]), round(box["height"]))
        assert height > 200 and len(set(shot[64:])) > 200  # rows drawn: compressed pixels of many values
    finally:
        visit.close()
        httpd.shutdown()
