"""workflow/scripts/check_reports.py: each browser check fires on a small page made for it.

The pages are written to tmp_path and opened in headless Chromium (one browser for the
module). Without Chromium the tests skip, except on CI (CI=true), where they fail.
"""

import http.server
import importlib.util
import os
import subprocess
import sys
import threading
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
SCRIPT = REPO / "workflow" / "scripts" / "check_reports.py"


def load_script():
    """workflow/scripts/check_reports.py as a module (it is not part of the lsbg package)."""
    spec = importlib.util.spec_from_file_location("check_reports", SCRIPT)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


check_reports = load_script()

# A 1 x 1 PNG.
PIXEL = ("data:image/png;base64,iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAQAAAC1HAwCAAAAC0lEQVR42mNk"
         "YAAAAAYAAjCB0C8AAAAASUVORK5CYII=")
FINDING = '<div class="lsbg-finding">The LSBG fluctuates 12 % less than the SBG.</div>'
TABLE = ("<p><b>Table 1.</b> Speeds.</p><table><thead><tr><th>type</th><th>gear speed [deg/s]"
         "</th></tr></thead><tbody><tr><td>LSBG</td><td>1873.7</td></tr></tbody></table>")
FIGURE = (f'<img alt="a pixel" src="{PIXEL}" style="width:200px">'
          "<p><strong>Figure 1.</strong> A pixel.</p>")


def require_browser():
    """Skip when no browser can be started, but fail on CI, which must never skip."""
    reason = check_reports.browser_unavailable()
    if reason:
        if os.environ.get("CI") == "true":
            pytest.fail(f"CI needs Chromium for the report checks: {reason}")
        pytest.skip(reason)


@pytest.fixture(scope="module")
def browser():
    require_browser()
    with check_reports.open_browser() as browser:
        yield browser


@pytest.fixture
def check(tmp_path, browser):
    """check(body, finding=True, shots=False) -> the problems of a page with this body."""
    def run(body, finding=True, shots=False, name="page.html"):
        path = tmp_path / name
        path.write_text("<!DOCTYPE html><html><head><meta charset='utf-8'><title>t</title>"
                        "</head><body>" + (FINDING if finding else "") + body
                        + "</body></html>", encoding="utf-8")
        return check_reports.check_report(path, tmp_path / "shots" if shots else None,
                                          browser=browser)
    return run


def test_a_clean_page_has_no_problem(check, tmp_path):
    assert check(TABLE + FIGURE, shots=True) == []
    assert (tmp_path / "shots" / "page-full.png").stat().st_size > 0
    assert (tmp_path / "shots" / "page-first-screen.png").stat().st_size > 0


def test_a_wide_table_hidden_in_a_scrolling_box_is_reported(check):
    cells = "".join(f"<td>{i}</td>" for i in range(10))
    body = ("<p><b>Table 1.</b> Wide.</p><div style='overflow-x:auto'>"
            "<table style='width:3000px'><thead><tr>" + "<th>h</th>" * 10
            + f"</tr></thead><tbody><tr>{cells}</tr></tbody></table></div>")
    problems = check(body)
    assert problems, "the wide table was not reported"
    assert all(p.startswith("page.html: Table 1:") for p in problems), problems
    assert any("3000 px wide in a box (overflow-x: auto)" in p for p in problems), problems


def test_a_page_that_scrolls_sideways_is_reported(check):
    problems = check("<div style='width:2500px'>a very wide paragraph</div>")
    # 2500 px and the body's margin of 8 px
    assert any("scrolls sideways: it is 2508 px wide" in p for p in problems), problems


def test_a_broken_image_is_reported(check):
    problems = check('<img alt="broken" src="data:image/png;base64,AAAA">'
                     "<p><strong>Figure 1.</strong> Broken.</p>")
    assert any("Figure 1" in p and "did not load" in p for p in problems), problems


def test_an_external_request_is_reported_and_aborted(check):
    hits = []

    class Handler(http.server.BaseHTTPRequestHandler):
        def do_GET(self):
            hits.append(self.path)
            self.send_response(404)
            self.end_headers()

        def log_message(self, *args):
            pass

    server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), Handler)
    threading.Thread(target=server.serve_forever, daemon=True).start()
    try:
        local = f"http://127.0.0.1:{server.server_address[1]}/y.png"
        problems = check(f'<img src="http://example.invalid/x.png"><img src="{local}">')
    finally:
        server.shutdown()
        server.server_close()
    assert any("request for http://example.invalid/x.png (blocked)" in p
               for p in problems), problems
    assert any(f"request for {local} (blocked)" in p for p in problems), problems
    assert hits == [], "the request reached the server: it was not aborted"


def test_snake_case_headers_and_missing_values_are_reported(check):
    body = ("<p><b>Table 2.</b> Raw.</p><table><thead><tr><th>run</th>"
            "<th>tangential_force_outer</th></tr></thead><tbody><tr><td>a</td><td>NaN</td>"
            "</tr><tr><td>b</td><td>&lt;NA&gt;</td></tr></tbody></table>")
    problems = check(body)
    assert any(p.startswith("page.html: Table 2: header cells read like code identifiers: "
                            "tangential_force_outer") for p in problems), problems
    assert any("Table 2: 2 cell(s) show a missing value" in p for p in problems), problems


def test_a_missing_finding_box_is_reported(check):
    problems = check(TABLE, finding=False)
    assert len(problems) == 1 and "no finding box" in problems[0], problems


def test_a_finding_box_below_the_first_screen_is_reported(check):
    body = ("<div style='height:2000px'>intro</div>"
            '<div class="lsbg-finding">The LSBG fluctuates 12 % less.</div>')
    problems = check(body, finding=False)
    assert len(problems) == 1, problems
    # 2000 px of introduction below the body's default margin of 8 px
    assert "starts at 2008 px, below the first screen (900 px)" in problems[0], problems


def test_a_finding_box_without_a_number_is_reported(check):
    problems = check('<div class="lsbg-finding">The LSBG is better.</div>', finding=False)
    assert len(problems) == 1 and "no number" in problems[0], problems


def run_script(*args):
    return subprocess.run([sys.executable, str(SCRIPT), *map(str, args)], capture_output=True,
                          text=True, timeout=300)


def test_the_command_line(tmp_path):
    require_browser()
    good, bad = tmp_path / "good.html", tmp_path / "bad.html"
    good.write_text(f"<html><body>{FINDING}{TABLE}</body></html>", encoding="utf-8")
    bad.write_text(f"<html><body>{TABLE}</body></html>", encoding="utf-8")
    proc = run_script(good)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert proc.stdout.startswith("good.html: OK")
    proc = run_script(good, bad, "--screenshots", tmp_path / "shots")
    assert proc.returncode == 1, proc.stdout + proc.stderr
    lines = proc.stdout.splitlines()
    assert lines[0].startswith("good.html: OK")
    assert lines[1].startswith("bad.html: no finding box")
    assert lines[2].startswith("bad.html: 1 problem(s)")
    assert len(lines) == 3, lines
    for name in ("good", "bad"):
        assert (tmp_path / "shots" / f"{name}-full.png").is_file()
        assert (tmp_path / "shots" / f"{name}-first-screen.png").is_file()
    proc = run_script(good, tmp_path / "missing.html")
    assert proc.returncode == 2
    assert "no such report" in proc.stderr and "missing.html" in proc.stderr
