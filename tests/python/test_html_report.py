"""The report that opens in a browser (issue 44 item 4: `report LOG --html`, `run --html`,
`sweep --html`), opened in a real browser: Debian's Chromium driven by Playwright (never
`playwright install`: tests/run_all.sh installs the `chromium` package where it is missing).

Goal: each page makes no request but for the file itself and logs no console error or page
error; every figure is present and not blank (a screenshot of each figure element holds more than
a few colours and a share of pixels that are not the background); the numbers in the page (their
elements' data-key, a JSON Pointer, and data-value) equal the run's `--json` document's (the
run's page: every one; the page `report` rebuilds from the log: the scenario, peaks, converged
peaks, quality and design); the time histories zoom (a wheel event narrows the axis range and
changes its ticks, a double click restores it); a `<script>` in a log's file name stays text; the
sweep's page has a chart per peak column and its numbers are the sweep's JSON rows'.
The paper scenario's run takes 0.2 s; the file about 10 s, most of it Chromium starting.
"""

from __future__ import annotations

import io
import json
import os
import shutil
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
CHROMIUM = shutil.which("chromium") or "/usr/bin/chromium"
ARGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
        "--disable-background-networking", "--disable-component-update", "--disable-sync"]
RUN_FIGURES = ["envelope-arrestor", "envelope-bridge", "h-deflection", "h-force", "h-clamp", "h-bridge"]
# A file name that is HTML: `<script>alert(1)</script>.mcap` (the `/` makes a folder of its start).
SCRIPT_FOLDER, SCRIPT_FILE = "<script>alert(1)<", "script>.mcap"


def binary() -> str:
    path = os.environ.get("BEAM_IMPACT_BIN", str(ROOT / "target" / "release" / "beam-impact"))
    assert Path(path).exists(), f"{path} not found: build with `cargo build --release` or set BEAM_IMPACT_BIN"
    return path


@pytest.fixture(scope="module")
def pages(tmp_path_factory):
    """The paper run's page, its log's page (the log under a file name that is HTML) and a sweep's
    page, with the run's --json document and the sweep's JSON rows."""
    d = tmp_path_factory.mktemp("html")
    run = subprocess.run([binary(), "run", "--mcap", str(d / "paper.mcap"), "--json", str(d / "paper.json"),
                          "--html", str(d / "run.html")], capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    (d / SCRIPT_FOLDER).mkdir()
    log = d / SCRIPT_FOLDER / SCRIPT_FILE
    shutil.copy(d / "paper.mcap", log)
    report = subprocess.run([binary(), "report", str(log), "--out", str(d / "figures"), "--html", str(d / "report.html")],
                            capture_output=True, text=True)
    assert report.returncode == 0, report.stderr
    sweep = subprocess.run([binary(), "sweep", "--vary", "drop_height=0.3,0.6,1.2", "--vary", "upper.mass=10000,14000",
                            "--set", "duration=0.5", "--out", str(d / "rows.csv"), "--json", str(d / "rows.json"),
                            "--html", str(d / "sweep.html")], capture_output=True, text=True)
    assert sweep.returncode == 0, sweep.stderr
    return {"dir": d, "run": d / "run.html", "report": d / "report.html", "sweep": d / "sweep.html",
            "doc": json.loads((d / "paper.json").read_text()), "rows": json.loads((d / "rows.json").read_text())}


@pytest.fixture(scope="module")
def browser(tmp_path_factory):
    playwright = pytest.importorskip("playwright.sync_api")
    assert Path(CHROMIUM).exists(), "chromium not installed: tests/run_all.sh installs Debian's chromium package"
    with playwright.sync_playwright() as p:
        context = p.chromium.launch_persistent_context(
            str(tmp_path_factory.mktemp("chromium-profile")), executable_path=CHROMIUM, args=ARGS, headless=True,
            viewport={"width": 1100, "height": 900})
        yield context
        context.close()


class Opened:
    """A page opened with every request, console message, page error and dialog recorded; every
    request but the file's own refused."""

    def __init__(self, context, path: Path):
        self.url = path.as_uri()
        self.requests, self.errors, self.dialogs = [], [], []
        self.page = context.new_page()
        self.page.on("console", lambda m: m.type in ("error", "warning") and self.errors.append(f"{m.type}: {m.text}"))
        self.page.on("pageerror", lambda e: self.errors.append(f"page error: {e}"))
        self.page.on("dialog", lambda d: (self.dialogs.append(d.message), d.dismiss()))

        def route(r):
            self.requests.append(r.request.url)
            return r.continue_() if r.request.url == self.url else r.abort()

        self.page.route("**/*", route)
        self.page.on("request", lambda r: r.url not in self.requests and self.requests.append(r.url))
        self.page.goto(self.url)
        self.page.wait_for_load_state("load")

    def numbers(self):
        return self.page.eval_on_selector_all(
            "[data-key]", "els => els.map(e => [e.getAttribute('data-key'), e.getAttribute('data-value')])")


def resolve(doc, pointer: str):
    for token in pointer.split("/")[1:]:
        token = token.replace("~1", "/").replace("~0", "~")
        doc = doc[int(token)] if isinstance(doc, list) else doc[token]
    return doc


def same(value, text: str) -> bool:
    if value is None:
        return text == "null"
    if isinstance(value, bool):
        return text == ("true" if value else "false")
    return float(text) == float(value)


def not_blank(png: bytes) -> tuple[int, float]:
    """Distinct colours of a screenshot and the share of its pixels that are not white."""
    from PIL import Image
    image = Image.open(io.BytesIO(png)).convert("RGB")
    colours = image.getcolors(maxcolors=1 << 24)
    white = sum(n for n, c in colours if c == (255, 255, 255))
    return len(colours), 1 - white / (image.width * image.height)


@pytest.mark.parametrize("which", ["run", "report", "sweep"])
def test_no_request_leaves_the_file_and_no_console_error(pages, browser, which):
    opened = Opened(browser, pages[which])
    assert opened.errors == []
    assert opened.dialogs == []
    assert set(opened.requests) == {opened.url}, opened.requests
    assert pages[which].stat().st_size < 5_000_000
    opened.page.close()


@pytest.mark.parametrize("which", ["run", "report"])
def test_every_figure_is_present_and_not_blank(pages, browser, which):
    opened = Opened(browser, pages[which])
    ids = opened.page.eval_on_selector_all("figure.chart", "els => els.map(e => e.id)")
    assert ids == RUN_FIGURES
    for figure in ids:
        colours, drawn = not_blank(opened.page.locator(f"#{figure} svg").screenshot())
        assert colours > 20 and drawn > 0.02, f"{figure}: {colours} colours, {drawn:.3f} of the pixels drawn"
    opened.page.close()


def test_the_run_page_numbers_are_the_run_json_documents(pages, browser):
    opened = Opened(browser, pages["run"])
    numbers = opened.numbers()
    assert len(numbers) > 300
    wrong = [(k, v, resolve(pages["doc"], k)) for k, v in numbers if not same(resolve(pages["doc"], k), v)]
    assert wrong == []
    keys = {k for k, _ in numbers}
    for key in ["/summary/peaks/lower.clamp_bending_stress", "/summary/converged_peaks/contact_force",
                "/design/utilisation/lower.clamp_bending_stress", "/quality/trusted", "/design/pass",
                "/scenario/drop_height", "/merged_contact_windows/0/end"]:
        assert key in keys, key
    opened.page.close()


def test_the_report_page_numbers_are_the_run_json_documents(pages, browser):
    opened = Opened(browser, pages["report"])
    compared = 0
    for key, value in opened.numbers():
        if key.split("/")[1] in ("scenario", "design", "quality") or key.startswith(("/summary/peaks/", "/summary/converged_peaks/")):
            assert same(resolve(pages["doc"], key), value), (key, value, resolve(pages["doc"], key))
            compared += 1
    assert compared > 80
    opened.page.close()


def test_the_time_histories_zoom_and_reset(pages, browser):
    opened = Opened(browser, pages["run"])
    page = opened.page
    svg = page.locator("#h-force svg")
    svg.scroll_into_view_if_needed()
    view = lambda: page.eval_on_selector("#h-force svg", "s => [+s.dataset.viewX0, +s.dataset.viewX1]")
    ticks = lambda: page.eval_on_selector_all("#h-force .xticks text", "ts => ts.map(t => t.textContent)")
    before, ticks_before = view(), ticks()
    box = svg.bounding_box()
    page.mouse.move(box["x"] + box["width"] * 0.3, box["y"] + box["height"] * 0.5)
    for _ in range(5):
        page.mouse.wheel(0, -200)
    page.wait_for_function("() => +document.querySelector('#h-force svg').dataset.viewX1 < 2.9")
    after = view()
    assert before[0] <= after[0] < after[1] <= before[1]
    assert after[1] - after[0] < 0.5 * (before[1] - before[0]), (before, after)
    assert ticks() != ticks_before
    page.mouse.dblclick(box["x"] + box["width"] * 0.5, box["y"] + box["height"] * 0.5)
    assert view() == before
    assert opened.errors == []
    page.close()


def test_a_script_tag_in_the_log_file_name_stays_text(pages, browser):
    opened = Opened(browser, pages["report"])
    page = opened.page
    assert f"{SCRIPT_FOLDER}/{SCRIPT_FILE}" in page.inner_text("h1")
    assert page.eval_on_selector_all("script", "s => s.length") == 1
    assert opened.dialogs == [] and opened.errors == []
    page.close()


def test_the_sweep_page_has_a_chart_per_peak_and_the_rows_numbers(pages, browser):
    opened = Opened(browser, pages["sweep"])
    page = opened.page
    ids = page.eval_on_selector_all("figure.chart", "els => els.map(e => e.id)")
    titles = page.eval_on_selector_all("figure.chart figcaption", "els => els.map(e => e.textContent)")
    assert "peak.lower.clamp_bending_stress against drop_height" in titles
    assert len(ids) >= 10, titles
    for figure in ids:
        colours, drawn = not_blank(page.locator(f"#{figure} svg").screenshot())
        assert colours > 10 and drawn > 0.01, f"{figure}: {colours} colours, {drawn:.3f} drawn"
    numbers = page.eval_on_selector_all("#rows [data-key]", "els => els.map(e => [e.getAttribute('data-key'), e.getAttribute('data-value')])")
    assert len(numbers) > 6 * 30
    assert [(k, v) for k, v in numbers if not same(resolve(pages["rows"], k), v)] == []
    page.close()
