"""Opens a sightline report.html in headless Chromium, as an assessor's browser
would, checks that it works offline, saves a full-page screenshot and prints
what the end-to-end test compares with results.json, as JSON.

Usage: python check_report.py REPORT.html SCREENSHOT.png [--pdf REPORT.pdf] [--falsify] [--chromium PATH]

It fails (exit 1, one line per reason on stderr) when the page does not load,
logs a console error or warning, throws, requests anything but itself and
data: URIs, or lacks the document-control table (#document-control), the
verdict banner (#verdict) or, but for the report of `sightline falsify`
(--falsify), the traceability table (#traceability). Otherwise it prints
(exit 0): the document title, the heading, the document-control rows, the
banner's verdict and text, the traceability table's rows as cell texts, the
scenario appendix's text content (null without one), the number of script elements and of elements with an inline event handler, and
the globals the page defines beyond a blank page's (a script that ran would
leave some). Chromium is Debian's, driven by Playwright, started
without a sandbox and without its own background traffic; nothing is
downloaded.

With --pdf it also prints the page to PDF as Chromium's print does (the paper
size the page's `@page` rule names: A4 unless the scenario asks for Letter),
reads the PDF's text back with pypdf and fails when a column head of any
table is missing from it, or when a table is wider than the printed page
(clipped); it then adds the PDF's page count to what it prints.
"""

import argparse
import json
import pathlib
import re
import sys
import tempfile
import unicodedata

from playwright.sync_api import Error as PlaywrightError
from playwright.sync_api import sync_playwright

# Playwright starts Chromium headless; no sandbox (CI runs as root), and none of
# the connections Chromium makes on its own (updates, sync, field trials): a
# closed network refuses them, and they are not the page's requests anyway.
CHROMIUM_ARGS = [
    "--no-sandbox",
    "--disable-gpu",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--disable-quic",
    "--no-first-run",
]

# What the page shows, read in the page.
READ_PAGE = """() => {
  const banner = document.getElementById("verdict");
  const table = document.getElementById("traceability");
  const control = document.getElementById("document-control");
  const text = (element) => element.innerText.trim();
  return {
    title: document.title,
    heading: document.querySelector("h1")?.innerText.trim() ?? null,
    control: control && control.checkVisibility()
      ? Array.from(control.rows, (row) => Array.from(row.cells, text))
      : null,
    verdict: banner && banner.dataset.verdict,
    banner: banner && banner.checkVisibility() ? text(banner) : null,
    traceability: table && table.checkVisibility()
      ? Array.from(table.tBodies[0].rows, (row) => Array.from(row.cells, text))
      : null,
    appendix: document.querySelector("pre.scenario")?.textContent ?? null,
    scripts: document.scripts.length,
    handlers: Array.from(document.querySelectorAll("*"))
      .filter((element) => Array.from(element.attributes).some((a) => a.name.startsWith("on")))
      .length,
    globals: Object.keys(window),
  };
}"""


# Under print media at the printed width: every table's column heads, and the
# tables wider than the page (their right edge beyond it: clipped on paper).
READ_PRINT = """() => {
  const width = document.documentElement.clientWidth;
  const tables = Array.from(document.querySelectorAll("table"));
  return {
    width,
    heads: tables.flatMap((t) => Array.from(t.querySelectorAll("th"), (th) => th.innerText)),
    clipped: tables
      .filter((t) => t.getBoundingClientRect().right > width + 1)
      .map((t) => (t.caption ? t.caption.innerText : t.id) || t.rows[0].innerText.slice(0, 60)),
  };
}"""

# The printable width of A4 and Letter under the report's @page margins (12 mm
# each side), CSS pixels at 96 per inch.
PRINT_WIDTH = {"A4": round((210 - 24) / 25.4 * 96), "Letter": round((215.9 - 24) / 25.4 * 96)}


def squeezed(text):
    """Text without whitespace or soft breaks, ligatures spelt out (NFKC: a
    printed `ﬁ` is `fi`), to compare a wrapped head."""
    return re.sub(r"[\s\u00ad\u200b]+", "", unicodedata.normalize("NFKC", text))


def print_pdf(page, pdf):
    """Prints `page` to `pdf`; returns (what the print shows, problems)."""
    from pypdf import PdfReader

    paper = "Letter" if "size: letter" in page.content() else "A4"
    page.emulate_media(media="print")
    page.set_viewport_size({"width": PRINT_WIDTH[paper], "height": 1000})
    shown = page.evaluate(READ_PRINT)
    page.pdf(path=str(pdf), prefer_css_page_size=True, print_background=True)
    reader = PdfReader(str(pdf))
    text = squeezed("".join(p.extract_text() or "" for p in reader.pages))
    missing = sorted({h for h in shown["heads"] if squeezed(h) not in text})
    problems = [f"the PDF lacks the column head {h!r}" for h in missing]
    problems += [f"a table is wider than the printed page: {t!r}" for t in shown["clipped"]]
    return {"paper": paper, "pages": len(reader.pages), "heads": len(shown["heads"])}, problems


def allowed(url, page_url):
    """Whether the page may request `url`: only itself and inline data."""
    return url == page_url or url.startswith("data:")


def check(report, screenshot, chromium, pdf=None, falsify=False):
    """Opens `report`, saves `screenshot`; returns (what the page shows, problems)."""
    page_url = report.resolve().as_uri()
    problems = []
    with sync_playwright() as playwright, tempfile.TemporaryDirectory() as scratch:
        browser = playwright.chromium.launch(executable_path=chromium, args=CHROMIUM_ARGS)
        page = browser.new_page(offline=True)
        # The globals of an empty page from a file, as the report is.
        blank = pathlib.Path(scratch, "blank.html")
        blank.write_text("<!DOCTYPE html><title>blank</title>")
        page.goto(blank.as_uri())
        builtins = page.evaluate("Object.keys(window)")
        page.on(
            "console",
            lambda m: m.type in ("error", "warning") and problems.append(f"console {m.type}: {m.text}"),
        )
        page.on("pageerror", lambda e: problems.append(f"uncaught exception: {e}"))
        page.on(
            "request",
            lambda r: allowed(r.url, page_url) or problems.append(f"request to {r.url}"),
        )
        page.on("requestfailed", lambda r: problems.append(f"request failed: {r.url} ({r.failure})"))
        try:
            response = page.goto(page_url, wait_until="load")
        except PlaywrightError as error:
            problems.append(f"the page did not load: {error.message}")
            browser.close()
            return None, problems
        if response is not None and not response.ok:
            problems.append(f"the page did not load: status {response.status}")
        shown = page.evaluate(READ_PAGE)
        shown["globals"] = sorted(set(shown["globals"]) - set(builtins))
        page.screenshot(path=str(screenshot), full_page=True)
        if pdf is not None:
            shown["pdf"], printed = print_pdf(page, pdf)
            problems.extend(printed)
        browser.close()
    if shown["control"] is None:
        problems.append("no visible document-control table (#document-control)")
    if shown["banner"] is None:
        problems.append("no visible verdict banner (#verdict)")
    if falsify:
        pass
    elif shown["traceability"] is None:
        problems.append("no visible traceability table (#traceability)")
    elif not shown["traceability"]:
        problems.append("the traceability table has no rows")
    return shown, problems


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("report", type=pathlib.Path, help="the report.html to open")
    parser.add_argument("screenshot", type=pathlib.Path, help="where to save a full-page PNG")
    parser.add_argument("--pdf", type=pathlib.Path, help="also print the page to this PDF and check it")
    parser.add_argument("--falsify", action="store_true", help="the report of `sightline falsify` (no traceability)")
    parser.add_argument("--chromium", default="/usr/bin/chromium", help="the Chromium to drive")
    options = parser.parse_args()
    if not options.report.is_file():
        parser.error(f"{options.report}: no such file")
    shown, problems = check(options.report, options.screenshot, options.chromium, options.pdf, options.falsify)
    if problems:
        for problem in problems:
            print(f"{options.report}: error: {problem}", file=sys.stderr)
        return 1
    json.dump(shown, sys.stdout, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
