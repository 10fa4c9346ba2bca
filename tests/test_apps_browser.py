"""The five explorer apps in a real browser: Voila serving each app as `python -m paperlib explore` does,
driven by Playwright against Debian's Chromium (DESIGN.md, "The notebook contract"; issue 22 item 2).

For every app: the panel renders (its figure, a PNG image widget, is shown), changing one control
changes the figure's bytes, and the page logs no console error (a failed fetch, a widget that fails
to render, an exception in the page). On the Barla 2006 and Simhon 2001 apps a mouse stroke drawn on
the canvas must produce a synthesis (the figure changes again and the status says it used the
drawing). Screenshots go to build/browser/ (CI keeps them as artefacts).

Playwright's own browser download is not available here: the test uses the system Chromium
(`.ci/run` installs Debian's `chromium`) and skips, saying so, only where none is installed.
"""

from __future__ import annotations

import math
import socket
import subprocess
import time
from pathlib import Path

import pytest
from browser_support import chromium_executable

from paperlib import apps

pytestmark = pytest.mark.browser

SCREENSHOTS = Path(__file__).resolve().parents[1] / "build" / "browser"
#: First render of an app: the kernel starts, imports paperlib and builds the panel; with an empty numba
#: cache that compiles the kernels it uses (about a minute on a loaded 2-core machine).
FIRST_RENDER_MS = 420_000
#: One update after a control changes (a synthesis at the paper's T = 1e5 steps is the slowest).
UPDATE_S = 180

#: Per app: the control changed (by its label: a dropdown gets its next option, a number box a new value),
#: and a text the status shows after a canvas stroke.
CONTROL = {"hurtut2009": "density", "barla2006": "exemplar", "kim2009": "image", "alvarez2015": "geometry seed",
           "simhon2001": "preset"}
CANVAS = {"barla2006": "drawn", "simhon2001": "drawn"}

IMAGE_DIGEST = """async (img) => {
    const bytes = await (await fetch(img.src)).arrayBuffer();
    const digest = await crypto.subtle.digest("SHA-256", bytes);
    return Array.from(new Uint8Array(digest), (b) => b.toString(16).padStart(2, "0")).join("");
}"""


def _free_port() -> int:
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        return probe.getsockname()[1]


def _wait_for_port(port: int, process: subprocess.Popen, timeout: float = 120.0) -> None:
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if process.poll() is not None:
            raise RuntimeError(f"voila exited with status {process.returncode}")
        try:
            socket.create_connection(("127.0.0.1", port), timeout=0.5).close()
            return
        except OSError:
            time.sleep(0.2)
    raise TimeoutError(f"voila did not listen on port {port} within {timeout:.0f} s")


@pytest.fixture(scope="module")
def browser():
    playwright_api = pytest.importorskip("playwright.sync_api", reason="playwright is in the test extra")
    executable = chromium_executable("run the browser tests")
    with playwright_api.sync_playwright() as playwright:
        # --no-sandbox: CI runs as root, where Chromium refuses its sandbox
        launched = playwright.chromium.launch(executable_path=executable, args=["--no-sandbox"])
        yield launched
        launched.close()


@pytest.fixture
def served(request, tmp_path):
    """``(url, file_root, log)`` of the app ``request.param`` served by Voila as `explore` serves it."""
    method, port = request.param, _free_port()
    log_path = tmp_path / "voila.log"
    with open(log_path, "w") as log:
        process = subprocess.Popen(apps.voila_command(method, port=port), env=apps.voila_environment(tmp_path),
                                   stdout=log, stderr=subprocess.STDOUT)
    try:
        _wait_for_port(port, process)
        yield f"http://127.0.0.1:{port}/", tmp_path, log_path
    finally:
        process.terminate()
        try:
            process.wait(timeout=20)
        except subprocess.TimeoutExpired:
            process.kill()


def _figure_digest(page) -> str:
    return page.locator("img.widget-image").evaluate(IMAGE_DIGEST)


def _wait_for_new_figure(page, before: str, what: str) -> str:
    deadline = time.monotonic() + UPDATE_S
    while time.monotonic() < deadline:
        digest = _figure_digest(page)
        if digest != before:
            return digest
        page.wait_for_timeout(250)
    raise AssertionError(f"the figure did not change within {UPDATE_S} s after {what}")


def _change_control(page, label: str) -> str:
    """Give the control labelled ``label`` another value, as a user would; the value chosen."""
    control = page.get_by_label(label, exact=True)
    if control.evaluate("(element) => element.tagName") == "SELECT":
        options = control.locator("option").evaluate_all("(options) => options.map((o) => o.value)")
        current = control.input_value()
        choice = next(value for value in options if value != current)
        control.select_option(choice)
        return choice
    choice = str(int(control.input_value()) + 1)
    control.fill(choice)
    control.press("Enter")
    return choice


def _draw_loop(page) -> None:
    """A closed, slightly irregular loop drawn with the mouse on the app's canvas (press, 48 moves, release)."""
    box = page.locator("canvas").first.bounding_box()
    cx, cy = box["x"] + box["width"] / 2, box["y"] + box["height"] / 2
    rx, ry = 0.32 * box["width"], 0.32 * box["height"]
    points = [(cx + rx * (1 + 0.15 * math.sin(3 * a)) * math.cos(a), cy + ry * math.sin(a))
              for a in (2 * math.pi * i / 48 for i in range(49))]
    page.mouse.move(*points[0])
    page.mouse.down()
    for point in points[1:]:
        page.mouse.move(*point, steps=2)
    page.mouse.up()


@pytest.mark.parametrize("served", list(apps.APPS), indirect=True)
def test_app_renders_responds_and_logs_no_error(browser, served, request):
    url, _, log_path = served
    method = request.node.callspec.params["served"]
    SCREENSHOTS.mkdir(parents=True, exist_ok=True)
    page = browser.new_page(viewport={"width": 1300, "height": 1100})
    errors: list[str] = []
    page.on("console", lambda message: errors.append(message.text) if message.type == "error" else None)
    page.on("pageerror", lambda error: errors.append(f"page error: {error}"))
    try:
        page.goto(url, timeout=FIRST_RENDER_MS)
        page.locator("img.widget-image").wait_for(state="visible", timeout=FIRST_RENDER_MS)
        page.screenshot(path=SCREENSHOTS / f"{method}_opened.png")
        first = _figure_digest(page)

        choice = _change_control(page, CONTROL[method])
        changed = _wait_for_new_figure(page, first, f"choosing {choice!r} in {CONTROL[method]!r}")
        page.screenshot(path=SCREENSHOTS / f"{method}_control.png")

        if method in CANVAS:
            _draw_loop(page)
            _wait_for_new_figure(page, changed, "a stroke drawn on the canvas")
            page.screenshot(path=SCREENSHOTS / f"{method}_drawn.png")
            status = page.locator(".widget-html").last.inner_text()
            assert CANVAS[method] in status, f"the status does not mention the drawing: {status!r}"
    finally:
        page.close()
    assert not errors, f"console errors in the {method} app: {errors}; voila log: {log_path.read_text()[-2000:]}"
