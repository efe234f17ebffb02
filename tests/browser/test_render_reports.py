"""Render every kind of HTML report (run, compare, league, sweep, design, lab) in real headless
Chromium: the screenshot is not blank, and at a narrow window no table cell's content spills
over its box into a neighbour's (issue: report quality). Skipped only where no Chromium is
installed; .ci/run installs Debian's chromium package so CI runs these."""

from __future__ import annotations

import json
import re
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).parent))
from pngread import read_png  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")

pytestmark = [pytest.mark.browser,
              pytest.mark.skipif(CHROMIUM is None, reason="chromium is not installed "
                                 "(apt-get install chromium); .ci/run installs it")]


def batcert(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "batcert.cli", *args], cwd=ROOT,
                          capture_output=True, text=True, timeout=300)


def screenshot(html: Path, tmp_path: Path) -> np.ndarray:
    png = tmp_path / (html.stem + ".png")
    profile = tmp_path / "profile"
    subprocess.run([CHROMIUM, "--headless", "--no-sandbox", "--disable-gpu", "--no-first-run",
                    "--disable-background-networking", "--disable-component-update",
                    "--disable-sync", f"--user-data-dir={profile}", f"--screenshot={png}",
                    "--window-size=1200,1600", html.as_uri()],
                   capture_output=True, timeout=120, check=False)
    assert png.is_file(), f"chromium wrote no screenshot of {html.name}"
    return read_png(png.read_bytes())


def assert_not_blank(img: np.ndarray) -> None:
    rgb = img[..., :3].astype(int)
    # A blank page is one colour; a rendered report has text, tables and plot lines: a few
    # per cent of pixels differ from white and there are many distinct colours.
    non_white = np.mean(rgb.sum(axis=2) < 3 * 240)
    colours = len(np.unique(rgb.reshape(-1, 3)[::7], axis=0))
    assert non_white > 0.02, f"only {non_white:.1%} of the screenshot is not white"
    assert colours > 20, f"only {colours} distinct colours in the screenshot"


COMMANDS = {
    "run": ["run", "bats/aluminium-34.yaml", "--protocol", "proposed"],
    "compare": ["compare", "bats/ash-34.yaml", "bats/aluminium-34.yaml", "--protocol", "proposed"],
    "league": ["league", "ncaa", "bats/ash-34.yaml", "bats/bbcor-alloy-34.yaml"],
    "sweep": ["sweep", "aluminium-34", "-p", "ncaa-bbcor", "--vary",
              "pitch_speed=50m/s:70m/s:3", "--vary", "bat_angular_speed=0rad/s:40rad/s:9"],
    "design": ["design", "ash-34", "-p", "ncaa-bbcor", "--solve", "pitch_speed", "--range",
               "40m/s:75m/s", "--points", "5"],
    "lab": ["reduce", "examples/lab/synthetic-scatter.yaml", "-p", "ncaa-bbcor"],
}


def report_of(kind: str, tmp_path: Path) -> Path:
    out = tmp_path / "reports"
    proc = batcert(*COMMANDS[kind], "--engine", "rigid", "--out", str(out), "--format", "html")
    assert proc.returncode in (0, 1), proc.stderr
    pages = sorted(out.glob("*.html"))
    assert len(pages) == 1, proc.stdout + proc.stderr
    return pages[0]


# Run in a copy of the page: every table cell whose content is wider than its box (it spills
# into the next cell), by its text, written into the page for --dump-dom to show.
_PROBE = """<script>
const spilt = [];
for (const c of document.querySelectorAll("td, th")) {
  if (c.scrollWidth > c.clientWidth + 1) spilt.push(c.textContent.trim().slice(0, 80));
}
document.body.setAttribute("data-spilt", JSON.stringify(spilt));
</script>"""


def spilt_cells(html: Path, tmp_path: Path, width: int) -> list[str]:
    page = html.read_text(encoding="utf-8")
    page = re.sub(r'<meta http-equiv="Content-Security-Policy"[^>]*>', "", page)
    probe = tmp_path / ("probe-" + html.name)
    probe.write_text(page.replace("</body>", _PROBE + "</body>"), encoding="utf-8")
    proc = subprocess.run([CHROMIUM, "--headless", "--no-sandbox", "--disable-gpu",
                           "--no-first-run", f"--user-data-dir={tmp_path / 'profile-dom'}",
                           f"--window-size={width},1600", "--dump-dom", probe.as_uri()],
                          capture_output=True, text=True, timeout=120, check=False)
    found = re.search(r'data-spilt="([^"]*)"', proc.stdout)
    assert found, "the probe did not run: " + proc.stderr[-300:]
    return json.loads(found.group(1).replace("&quot;", '"').replace("&amp;", "&"))


@pytest.mark.parametrize("kind", sorted(COMMANDS))
def test_report_renders_in_chromium(kind, tmp_path):
    page = report_of(kind, tmp_path)
    assert_not_blank(screenshot(page, tmp_path))
    # a laptop's half screen: the narrowest window a report is read in side by side
    spilt = spilt_cells(page, tmp_path, 800)
    assert spilt == [], spilt


def test_a_spilt_cell_is_detected(tmp_path):
    page = tmp_path / "spill.html"
    page.write_text('<!doctype html><html><body><table style="table-layout: fixed; width: 200px">'
                    '<tr><td style="white-space: nowrap">' + "x" * 200 + "</td><td>y</td></tr>"
                    "</table></body></html>", encoding="utf-8")
    assert spilt_cells(page, tmp_path, 800) == ["x" * 80]


def test_blank_page_is_detected(tmp_path):
    page = tmp_path / "blank.html"
    page.write_text("<!doctype html><html><body></body></html>", encoding="utf-8")
    with pytest.raises(AssertionError):
        assert_not_blank(screenshot(page, tmp_path))
