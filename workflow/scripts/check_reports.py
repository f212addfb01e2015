#!/usr/bin/env python
"""Check the rendered HTML reports in a real browser (headless Chromium, via Playwright).

The reports (``reports/{paper,sweep,verification}.html``) are rendered by nbconvert and
read in a browser, so what matters is what a browser shows, not what the HTML says. A
table wider than its output box, for instance, is valid HTML; nbconvert wraps every
output in a box with ``overflow-x: auto``, so the browser simply hides the columns that
do not fit, and nobody notices. This script opens each report as a ``file://`` URL in
Chromium, at a window 1400 px wide, and reports:

* **width**: every ``table``, ``img``, ``pre``, ``svg`` and output box (nbconvert's
  ``.jp-OutputArea-output``) whose rendered width exceeds the page's content width
  (``document.documentElement.clientWidth``) or that lies (partly) outside it; and every
  ``table``, ``pre``, ``img`` or ``svg`` that is clipped by its nearest ancestor with
  ``overflow-x`` ``auto``, ``scroll``, ``hidden`` or ``clip`` (the element, or its
  content, is wider than the ancestor's visible box: part of it is hidden, or only
  shown by scrolling sideways);
* **page width**: the page itself scrolls horizontally;
* **images**: an ``img`` that did not load (``!img.complete || img.naturalWidth == 0``);
* **self-containment**: any request other than for the report file itself or a
  ``data:`` URL (every such request is also aborted, so nothing leaves the machine), and
  any error printed on the browser console or raised by a script of the page;
* **table text**: a header cell (``th``) that reads like a code identifier (an
  underscore between letters, e.g. ``tangential_force_outer``), and any cell that shows
  ``<NA>``, ``NaN``, ``nan`` or ``None``;
* **finding first**: the report opens with its finding: an element of class
  ``lsbg-finding`` whose top edge lies on the first screen (the first 900 px) and whose
  text contains a number.

Each problem is one line that names the report, the element (by its caption, "Table 8",
"Figure 3", or else a short excerpt of its text) and what was measured, in px. With
``--screenshots DIR`` the script also saves ``<report>-full.png`` (the whole page) and
``<report>-first-screen.png`` (1400 x 900, what a reader sees first) for each report.

Run it as::

    python workflow/scripts/check_reports.py reports/*.html --screenshots DIR

It prints the problems of each report and one summary line per report, and exits 1 if
there is any problem, 0 if there is none and 2 on bad usage (a missing report, no
browser). It is also a module: :func:`check_report` checks one report and returns its
problems. Chromium is ``/usr/bin/chromium`` unless the environment variable
``LSBG_CHROMIUM`` names another executable; Playwright's own browser download is never
used.
"""

from __future__ import annotations

import argparse
import contextlib
import os
import shutil
import sys
import time
from pathlib import Path

#: The Chromium executable by default; the environment variable LSBG_CHROMIUM overrides it.
CHROMIUM = "/usr/bin/chromium"

#: Chromium's command-line flags (headless comes from Playwright's own option): no
#: sandbox (we run as root), no GPU, and no background traffic of the browser's own.
CHROMIUM_FLAGS = ["--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
                  "--disable-background-networking", "--disable-component-update",
                  "--disable-sync"]

#: What the page tells about itself, measured in the browser (returns plain data).
_MEASURE = r"""
() => {
  const root = document.documentElement;
  const pageWidth = root.clientWidth;
  const px = (x) => Math.round(x);
  const tag = (el) => el.tagName.toLowerCase();
  const excerpt = (text, n = 40) => {
    text = (text || '').replace(/\s+/g, ' ').trim();
    return text.length > n ? text.slice(0, n - 1) + '…' : text;
  };
  const CLIPS = ['auto', 'scroll', 'hidden', 'clip'];
  const overflowX = (el) => getComputedStyle(el).overflowX;

  // Captions: a paragraph (or caption) that starts with "Table n." or "Figure n.".
  const capRe = /^(Table|Figure)\s+(\d+)\./;
  const captions = [];
  for (const el of document.querySelectorAll('p, caption, figcaption')) {
    const m = el.textContent.trim().match(capRe);
    if (m && !el.closest('td, th')) captions.push({el, kind: m[1], label: `${m[1]} ${m[2]}`});
  }
  const before = (a, b) => !!(a.compareDocumentPosition(b) & Node.DOCUMENT_POSITION_FOLLOWING);
  const preceding = (el, kind) => {
    let found = null;
    for (const c of captions) if ((!kind || c.kind === kind) && before(c.el, el)) found = c;
    return found;
  };
  const cellOf = (el) => el.closest('.jp-Cell, .cell') || document.body;
  const following = (el, kind) => captions.find(
    (c) => c.kind === kind && before(el, c.el) && cellOf(c.el) === cellOf(el));
  const tables = [...document.querySelectorAll('table')];

  // An element's name: its caption (a table's precedes it, a figure's follows the image
  // in the same notebook cell), else a short excerpt of its text.
  const label = (el) => {
    const t = tag(el);
    if (t === 'table') {
      const own = el.querySelector(':scope > caption');
      const m = own && own.textContent.trim().match(capRe);
      if (m) return `${m[1]} ${m[2]}`;
      const c = preceding(el, 'Table');
      // the caption names this table only if no other table stands between them
      const between = (o) => o !== el && !o.contains(el) && !el.contains(o)
        && before(c.el, o) && before(o, el);
      if (c && !tables.some(between)) return c.label;
      return `table "${excerpt(el.innerText)}"`;
    }
    if (t === 'img' || t === 'svg') {
      const c = following(el, 'Figure') || preceding(el, 'Figure');
      if (c) return c.label;
      const text = t === 'img' ? el.getAttribute('alt') || el.getAttribute('src') : el.textContent;
      return `${t} "${excerpt(text)}"`;
    }
    const kind = t === 'pre' ? 'pre' : 'output';  // name it by what it holds
    const inner = el.querySelector('table, img, svg');
    if (inner) return `${kind} of ${label(inner)}`;
    const c = preceding(el, null);
    return `${kind} "${excerpt(el.innerText)}"` + (c ? ` after ${c.label}` : '');
  };
  const visible = (el, r) => (r.width > 0 || r.height > 0)
    && getComputedStyle(el).display !== 'none';
  const clipper = (el) => {  // the nearest ancestor that hides or scrolls what overflows
    for (let a = el.parentElement; a && a !== root; a = a.parentElement)
      if (CLIPS.includes(overflowX(a))) return a;
    return null;
  };

  const elements = [];
  const selector = 'table, img, pre, svg, .jp-OutputArea-output, .output_subarea';
  for (const el of document.querySelectorAll(selector)) {
    const r = el.getBoundingClientRect();
    if (!visible(el, r) || (tag(el) === 'svg' && el.parentElement.closest('svg'))) continue;
    const issues = [];
    const left = r.left + window.scrollX, right = r.right + window.scrollX;
    if (r.width > pageWidth + 0.5)
      issues.push(`${px(r.width)} px wide, wider than the page's ${pageWidth} px`);
    else if (right > pageWidth + 0.5)
      issues.push(`right edge at ${px(right)} px, beyond the page's ${pageWidth} px`);
    if (left < -0.5) issues.push(`left edge at ${px(left)} px, left of the page`);
    if (['table', 'pre', 'img', 'svg'].includes(tag(el))) {
      const box = clipper(el);
      if (box) {
        const visibleRight = box.getBoundingClientRect().left + box.clientLeft + box.clientWidth;
        const need = Math.max(r.width, el.scrollWidth);
        if (need > box.clientWidth + 1 || r.right > visibleRight + 1) {
          const hidden = px(Math.max(need - box.clientWidth, r.right - visibleRight));
          const mode = overflowX(box);
          const how = ['hidden', 'clip'].includes(mode) ? 'cut off'
            : 'hidden unless scrolled sideways';
          issues.push(`${px(need)} px wide in a box (overflow-x: ${mode}) `
                      + `${box.clientWidth} px wide: ${hidden} px ${how}`);
        }
      }
      if (tag(el) === 'pre' && el.scrollWidth > el.clientWidth + 1 && CLIPS.includes(overflowX(el)))
        issues.push(`its text is ${el.scrollWidth} px wide in a box ${el.clientWidth} px wide`);
    }
    if (issues.length) elements.push({label: label(el), issues});
  }

  // The page scrolls sideways: name the element that reaches furthest right.
  let page = null;
  if (root.scrollWidth > root.clientWidth) {
    let widest = null, widestRight = -Infinity;
    for (const el of document.body.querySelectorAll('*')) {
      const r = el.getBoundingClientRect();
      if (r.width > 0 && r.right > widestRight) { widest = el; widestRight = r.right; }
    }
    const text = widest
      ? widest.innerText || widest.textContent || widest.getAttribute('alt') || '' : '';
    page = {scrollWidth: root.scrollWidth, clientWidth: root.clientWidth,
            widest: widest ? `${tag(widest)} "${excerpt(text)}"` : 'nothing'};
  }

  const images = [];
  for (const img of document.images) {
    if (!img.complete || img.naturalWidth === 0) {
      const src = img.getAttribute('src') || '';
      images.push({label: label(img), src: src.startsWith('data:') ? excerpt(src, 30) : src});
    }
  }

  // Table text: headers that read like code, cells that show a missing value.
  const codeRe = /[A-Za-z]_[A-Za-z]/;
  const missing = new Set(['<NA>', 'NaN', 'nan', 'None']);
  const texts = [];
  for (const table of tables) {
    const headers = [...new Set([...table.querySelectorAll('th')]
      .map((th) => th.textContent.trim()).filter((text) => codeRe.test(text)))];
    const head = table.tHead && table.tHead.rows.length
      ? [...table.tHead.rows[table.tHead.rows.length - 1].cells].map((c) => c.textContent.trim())
      : [];
    const cells = [];
    let number = 0;
    for (const row of table.rows) {
      if (row.parentElement.tagName === 'THEAD') continue;
      number += 1;
      [...row.cells].forEach((cell, i) => {
        const text = cell.textContent.trim();
        if (missing.has(text))
          cells.push({text, row: `${number} ("${excerpt(row.cells[0].textContent, 30)}")`,
                      column: excerpt(head[i] || `column ${i + 1}`, 30)});
      });
    }
    if (headers.length || cells.length) texts.push({label: label(table), headers, cells});
  }

  const findings = [...document.querySelectorAll('.lsbg-finding')].map((el) => {
    const r = el.getBoundingClientRect();
    return {top: px(r.top + window.scrollY), visible: visible(el, r),
            digit: /\d/.test(el.innerText || ''), text: excerpt(el.innerText, 60)};
  });

  return {pageWidth, elements, page, images, tables: texts, findings};
}
"""


def chromium_executable():
    """The Chromium to run: ``$LSBG_CHROMIUM`` if set, else :data:`CHROMIUM`.

    Returns
    -------
    str
        The path of the executable (a command name is looked up on ``PATH``).
    """
    executable = os.environ.get("LSBG_CHROMIUM") or CHROMIUM
    if os.sep not in executable:  # a command name: Playwright needs the path
        executable = shutil.which(executable) or executable
    return executable


def browser_unavailable():
    """Why no browser can be started here, or None if one can.

    Returns
    -------
    str or None
        A sentence naming what is missing (the ``playwright`` package or the Chromium
        executable), or None when both are there.
    """
    try:
        import playwright.sync_api  # noqa: F401
    except ImportError:
        return "the Python package playwright is not installed (see environment-pip.txt)"
    executable = chromium_executable()
    if not os.path.isfile(executable) or not os.access(executable, os.X_OK):
        return (f"no Chromium at {executable} (install Debian's chromium, or set "
                "LSBG_CHROMIUM to a Chromium executable)")
    return None


@contextlib.contextmanager
def open_browser():
    """Start headless Chromium for :func:`check_report`; close it on leaving.

    Yields
    ------
    playwright.sync_api.Browser
        One browser, to pass as ``browser=`` to any number of :func:`check_report` calls.

    Raises
    ------
    RuntimeError
        If Playwright or Chromium is missing (the message says which).
    """
    reason = browser_unavailable()
    if reason:
        raise RuntimeError(reason)
    from playwright.sync_api import sync_playwright

    executable = chromium_executable()
    with sync_playwright() as playwright:
        browser = playwright.chromium.launch(executable_path=executable, headless=True,
                                             args=CHROMIUM_FLAGS)
        try:
            yield browser
        finally:
            browser.close()


def check_report(path, screenshot_dir=None, width=1400, first_screen=900, *, browser=None):
    """Open one report in Chromium and return what is wrong with how it shows.

    Parameters
    ----------
    path : str or os.PathLike
        The HTML report, opened as a ``file://`` URL.
    screenshot_dir : str or os.PathLike, optional
        If given, save ``<name>-full.png`` (the whole page) and ``<name>-first-screen.png``
        (``width`` x ``first_screen`` px, the top of the page) there, ``<name>`` being the
        report's file name without its suffix. The folder is created if needed.
    width : int, default 1400
        Width of the browser window, px.
    first_screen : int, default 900
        Height of the first screen, px: the finding box (class ``lsbg-finding``) must
        start above it. Also the window's height.
    browser : playwright.sync_api.Browser, optional
        A browser from :func:`open_browser`, to check many reports with one browser; by
        default one is started and closed for this report.

    Returns
    -------
    list of str
        One line per problem, each starting with the report's file name; empty when the
        report shows well. The checks are listed in the module's docstring.

    Raises
    ------
    FileNotFoundError
        If ``path`` is not a file.
    RuntimeError
        If no browser can be started (see :func:`browser_unavailable`).
    """
    path = Path(path).resolve()
    if not path.is_file():
        raise FileNotFoundError(f"no such report: {path}")
    if browser is None:
        with open_browser() as own:
            return check_report(path, screenshot_dir, width, first_screen, browser=own)

    name = path.name
    url = path.as_uri()
    requests, blocked, errors = [], [], []

    def allowed(request_url):
        return request_url.split("#", 1)[0] == url or request_url.startswith("data:")

    def on_request(request):
        requests.append(request.url)

    def on_route(route, request):
        if allowed(request.url):
            route.continue_()
        else:
            blocked.append(request.url)
            route.abort()

    def on_console(message):
        if message.type == "error":
            errors.append((message.text, (message.location or {}).get("url", "")))

    context = browser.new_context(viewport={"width": width, "height": first_screen},
                                  accept_downloads=False, service_workers="block")
    try:
        page = context.new_page()
        page.on("request", on_request)
        page.on("console", on_console)
        page.on("pageerror", lambda error: errors.append((f"uncaught {error}", "")))
        page.route("**/*", on_route)
        page.goto(url, wait_until="load")
        measured = page.evaluate(_MEASURE)
        if screenshot_dir is not None:
            folder = Path(screenshot_dir)
            folder.mkdir(parents=True, exist_ok=True)
            page.evaluate("window.scrollTo(0, 0)")
            page.screenshot(path=folder / f"{path.stem}-first-screen.png")
            page.screenshot(path=folder / f"{path.stem}-full.png", full_page=True)
    finally:
        context.close()
    outside = [u for u in dict.fromkeys(requests + blocked) if not allowed(u)]
    return _problems(name, measured, outside, blocked, errors, first_screen)


def _problems(name, measured, outside, blocked, errors, first_screen):
    """The problem lines of one report from what was measured and recorded."""
    problems = []
    for element in measured["elements"]:
        problems.append(f"{name}: {element['label']}: " + "; ".join(element["issues"]))
    page = measured["page"]
    if page:
        problems.append(
            f"{name}: the page scrolls sideways: it is {page['scrollWidth']} px wide in a "
            f"window whose content is {page['clientWidth']} px wide (furthest right: "
            f"{page['widest']})")
    for image in measured["images"]:
        problems.append(f"{name}: {image['label']}: the image did not load (src {image['src']})")

    for request_url in outside:
        problems.append(f"{name}: request for {request_url} (blocked): a report must be "
                        "self-contained")
    for text, where in dict.fromkeys(errors):
        if where in blocked and text.startswith("Failed to load resource"):
            continue  # the blocked request, reported above
        problems.append(f"{name}: console error: {text}" + (f" ({where})" if where else ""))

    for table in measured["tables"]:
        if table["headers"]:
            listed = ", ".join(table["headers"])
            problems.append(f"{name}: {table['label']}: header cells read like code "
                            f"identifiers: {listed}")
        if table["cells"]:
            cells = table["cells"]
            shown = "; ".join(f"{c['text']} in row {c['row']}, column \"{c['column']}\""
                              for c in cells[:5])
            more = f" and {len(cells) - 5} more" if len(cells) > 5 else ""
            problems.append(f"{name}: {table['label']}: {len(cells)} cell(s) show a missing "
                            f"value: {shown}{more}")

    findings = measured["findings"]
    if not any(f["visible"] and f["top"] < first_screen and f["digit"] for f in findings):
        if not findings:
            problems.append(f"{name}: no finding box: the report must open with an element "
                            f"of class lsbg-finding, on the first screen ({first_screen} px), "
                            "that states the finding with its number")
        else:
            box = findings[0]
            issues = []
            if not box["visible"]:
                issues.append("it is not shown")
            elif box["top"] >= first_screen:
                issues.append(f"it starts at {box['top']} px, below the first screen "
                              f"({first_screen} px)")
            if not box["digit"]:
                issues.append("its text has no number")
            problems.append(f"{name}: finding box \"{box['text']}\": " + "; ".join(issues))
    return problems


def main(argv=None):
    """Check reports from the command line: print the problems, one summary line each.

    Parameters
    ----------
    argv : list of str, optional
        The arguments (default ``sys.argv[1:]``): report files, and optionally
        ``--screenshots DIR``, ``--width PX``, ``--first-screen PX``.

    Returns
    -------
    int
        0 if no report has a problem, 1 if any has, 2 if no browser can be started.
        Bad usage (such as a missing report) exits with status 2 through argparse.
    """
    parser = argparse.ArgumentParser(
        prog="check_reports.py",
        description="Check the rendered HTML reports in headless Chromium: widths, "
                    "images, requests, table text and the finding on the first screen.")
    parser.add_argument("reports", nargs="+", type=Path, help="HTML reports to check")
    parser.add_argument("--screenshots", type=Path, metavar="DIR",
                        help="save <report>-full.png and <report>-first-screen.png here")
    parser.add_argument("--width", type=int, default=1400, help="window width, px (1400)")
    parser.add_argument("--first-screen", type=int, default=900,
                        help="height of the first screen, px (900)")
    args = parser.parse_args(argv)
    missing = [str(p) for p in args.reports if not p.is_file()]
    if missing:
        parser.error("no such report: " + ", ".join(missing))
    if args.width <= 0 or args.first_screen <= 0:
        parser.error("--width and --first-screen must be positive")
    reason = browser_unavailable()
    if reason:
        print(f"check_reports.py: error: {reason}", file=sys.stderr)
        return 2

    failed = False
    with open_browser() as browser:
        for report in args.reports:
            start = time.perf_counter()
            problems = check_report(report, args.screenshots, args.width, args.first_screen,
                                    browser=browser)
            seconds = time.perf_counter() - start
            for problem in problems:
                print(problem)
            verdict = f"{len(problems)} problem(s)" if problems else "OK"
            print(f"{report.name}: {verdict} ({seconds:.1f} s)", flush=True)
            failed = failed or bool(problems)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
