"""The documentation site (issue 23): `make docs`'s build, with warnings as errors, and the built pages in Chromium.

The site is built once per module (``sphinx-build -E -W --keep-going``, as `make docs` does, into a temporary
folder): a broken reference, a missing figure, a docstring reST cannot read or a notebook without a page fails
the build. Then: every notebook of ``notebooks/`` and every paper has a page; every notebook page names the
quality and seed of its figures (from ``figures/<notebook>/stats.json``) and shows each of them; no page loads a
script, stylesheet or image from outside the machine; and, in headless Chromium (Debian's, as in
``tests/test_apps_browser.py``; skipped, saying so, without one), the index and a notebook page load every
image (``naturalWidth > 0``) without any request leaving ``file://``. Nothing is executed: the pages come from
``build/notebooks/`` (`make reproduce`'s executed copies) when they match the committed figures, and from the
notebook sources otherwise; :func:`test_a_page_without_executed_copy_says_so` checks the second case directly.
"""

from __future__ import annotations

import json
import subprocess
import sys
from html.parser import HTMLParser
from pathlib import Path

import nbformat
import pytest
from browser_support import chromium_executable

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"
NOTEBOOKS = sorted(path.stem for path in (ROOT / "notebooks").glob("*.ipynb"))
PAPERS = ("hurtut2009", "barla2006", "kim2009", "alvarez2015", "simhon2001")
#: The notebook page opened in the browser: one that saves several figures.
BROWSED = "hurtut2009_ripley_L"
SCREENSHOTS = ROOT / "build" / "browser"

pytest.importorskip("sphinx", reason="the docs extra: pip install -e '.[docs]'")
pytest.importorskip("myst_nb", reason="the docs extra: pip install -e '.[docs]'")


class _Assets(HTMLParser):
    """The URLs a page loads (script src, link href, img src) and the images it shows (their alt texts)."""

    def __init__(self):
        super().__init__()
        self.loaded: list[str] = []
        self.images: list[str] = []
        self.problematic = 0

    def handle_starttag(self, tag, attrs):
        attrs = dict(attrs)
        if tag in ("script", "img", "iframe", "source") and attrs.get("src"):
            self.loaded.append(attrs["src"])
        if tag == "link" and attrs.get("href") and attrs.get("rel") not in ("canonical",):
            self.loaded.append(attrs["href"])
        if tag == "img":
            self.images.append(attrs.get("alt", ""))
        if "problematic" in (attrs.get("class") or "").split():
            self.problematic += 1


def _assets(page: Path) -> _Assets:
    parser = _Assets()
    parser.feed(page.read_text(encoding="utf-8"))
    return parser


@pytest.fixture(scope="module")
def site(tmp_path_factory) -> Path:
    """The site built as `make docs` builds it; the build log is shown when it fails."""
    out = tmp_path_factory.mktemp("docs")
    command = [sys.executable, "-m", "sphinx", "-E", "-W", "--keep-going", "-j", "2", "-b", "html",
               "-d", str(out / "doctrees"), str(DOCS), str(out / "html")]
    done = subprocess.run(command, cwd=ROOT, capture_output=True, text=True, timeout=900)
    assert done.returncode == 0, "sphinx-build -W failed:\n" + (done.stdout + done.stderr)[-6000:]
    return out / "html"


def test_every_notebook_and_paper_has_a_page(site):
    missing = [stem for stem in NOTEBOOKS if not (site / "_generated" / "notebooks" / f"{stem}.html").is_file()]
    assert not missing, f"notebooks without a page: {missing}"
    missing = [paper for paper in PAPERS if not (site / "papers" / f"{paper}.html").is_file()]
    assert not missing, f"papers without a page: {missing}"
    for page in ("index", "getting_started", "explore", "scale_out", "statistics", "_generated/api/index"):
        assert (site / f"{page}.html").is_file(), page
    modules = {"hurtut2009": "arrangement", "barla2006": "strokepattern", "kim2009": "stipple", "alvarez2015": "mlts",
               "simhon2001": "sketch"}
    for paper in PAPERS:
        text = (site / "papers" / f"{paper}.html").read_text(encoding="utf-8")
        assert f"paperlib.{modules[paper]}" in text, paper
        assert "Notebooks" in text and "Claims ledger" in text and "Verdicts: reproduced" in text, paper


def test_api_reference_covers_the_public_modules(site):
    sys.path.insert(0, str(DOCS))
    try:
        import generate
    finally:
        sys.path.remove(str(DOCS))
    for module in generate.public_modules(ROOT):
        page = site / "_generated" / "api" / f"{module}.html"
        assert page.is_file(), module
        assert f'id="module-{module}"' in page.read_text(encoding="utf-8"), f"{module}: autodoc found nothing"


def test_notebook_pages_show_quality_seed_figures_and_statistics(site):
    for stem in NOTEBOOKS:
        page = site / "_generated" / "notebooks" / f"{stem}.html"
        text = page.read_text(encoding="utf-8")
        stats_file = ROOT / "figures" / stem / "stats.json"
        if stats_file.is_file():
            stats = json.loads(stats_file.read_text(encoding="utf-8"))
            assert f"Figures of quality <code class=\"docutils literal notranslate\"><span class=\"pre\">" \
                   f"{stats['quality']}</span></code>, seed <code class=\"docutils literal notranslate\">" \
                   f"<span class=\"pre\">{stats['seed']}</span></code>" in text, stem
        assert "Recorded statistics" in text, stem
        assert ("executed copy" in text) or ("notebook source" in text), stem
        figures = {p.stem for p in (ROOT / "figures" / stem).glob("*.png")} | \
            {p.stem for p in (ROOT / "figures" / stem).glob("*.svg")}
        shown = set(_assets(page).images)  # the generator's alt text is the figure's name
        assert figures <= shown, f"{stem}: figures not shown: {sorted(figures - shown)}"


def test_no_page_loads_anything_from_outside(site):
    outside, problematic = {}, {}
    for page in site.rglob("*.html"):
        assets = _assets(page)
        external = [url for url in assets.loaded if url.startswith(("http:", "https:", "//"))]
        if external:
            outside[str(page.relative_to(site))] = external
        if assets.problematic:
            problematic[str(page.relative_to(site))] = assets.problematic
    assert not outside, f"pages that load from other hosts: {outside}"
    assert not problematic, f"pages with unresolved reST (substitutions, references): {problematic}"


def test_a_page_without_executed_copy_says_so(tmp_path):
    """The fresh-clone case: no executed copy, so the page is the source's markdown cells and the figures."""
    sys.path.insert(0, str(DOCS))
    try:
        import generate
    finally:
        sys.path.remove(str(DOCS))
    generator = generate.Generator(tmp_path / "_generated", ROOT, executed=tmp_path / "no-executed-copies")
    page = nbformat.read(generator.notebook_page(BROWSED), as_version=4)
    source = nbformat.read(ROOT / "notebooks" / f"{BROWSED}.ipynb", as_version=4)
    assert {cell.cell_type for cell in page.cells} == {"markdown"}
    text = "\n".join(cell.source for cell in page.cells)
    assert "notebook source" in text and "no executed copy" in text
    lines = set(text.split("\n"))
    for cell in source.cells:
        if cell.cell_type == "markdown":
            assert all(line in lines for line in cell.source.split("\n")), cell.source[:80]
    for figure in (ROOT / "figures" / BROWSED).glob("*.png"):
        assert f"../figures/{BROWSED}/{figure.name}" in text
        assert (tmp_path / "_generated" / "figures" / BROWSED / figure.name).is_file()


@pytest.mark.browser
@pytest.mark.parametrize("page", ["index.html", f"_generated/notebooks/{BROWSED}.html"])
def test_pages_load_their_figures_in_chromium(site, page):
    playwright_api = pytest.importorskip("playwright.sync_api", reason="playwright is in the test extra")
    executable = chromium_executable("open the built site in a browser")
    requests, errors = [], []
    with playwright_api.sync_playwright() as playwright:
        # --no-sandbox: CI runs as root, where Chromium refuses its sandbox
        browser = playwright.chromium.launch(executable_path=executable, args=["--no-sandbox"])
        try:
            tab = browser.new_page(viewport={"width": 1400, "height": 1000})
            tab.on("request", lambda request: requests.append(request.url))
            tab.on("console", lambda message: errors.append(message.text) if message.type == "error" else None)
            tab.on("pageerror", lambda error: errors.append(str(error)))
            tab.goto((site / page).as_uri(), wait_until="load")
            images = tab.locator("img").evaluate_all(
                "(images) => images.map((img) => [img.getAttribute('src'), img.complete, img.naturalWidth])")
            SCREENSHOTS.mkdir(parents=True, exist_ok=True)
            tab.screenshot(path=str(SCREENSHOTS / f"docs_{Path(page).stem}.png"), full_page=False)
        finally:
            browser.close()
    if page != "index.html":
        assert len(images) >= len(list((ROOT / "figures" / BROWSED).glob("*.png"))) > 0
    broken = [src for src, complete, width in images if not complete or width == 0]
    assert not broken, f"{page}: images that did not load: {broken}"
    outside = [url for url in requests if not url.startswith(("file:", "data:", "blob:"))]
    assert not outside, f"{page}: requests leaving the machine: {outside}"
    assert not errors, f"{page}: console errors: {errors}"
