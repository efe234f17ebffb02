"""Render each kind of HTML report (run, compare, league) in real headless Chromium and check the
screenshot is not blank (issue: report quality). Skipped only where no Chromium is installed;
.ci/run installs Debian's chromium package so CI runs these."""

from __future__ import annotations

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


@pytest.mark.parametrize("kind", ["run", "compare", "league"])
def test_report_renders_in_chromium(kind, tmp_path):
    out = tmp_path / "reports"
    if kind == "run":
        proc = batcert("run", "bats/aluminium-34.yaml", "--protocol", "proposed", "--engine",
                       "rigid", "--out", str(out), "--format", "html")
    elif kind == "compare":
        proc = batcert("compare", "bats/ash-34.yaml", "bats/aluminium-34.yaml", "--protocol",
                       "proposed", "--engine", "rigid", "--out", str(out), "--format", "html")
    else:
        proc = batcert("league", "mlb", "bats/ash-34.yaml", "--engine", "rigid", "--out",
                       str(out), "--format", "html")
    assert proc.returncode in (0, 1), proc.stderr
    pages = sorted(out.glob("*.html"))
    assert len(pages) == 1, proc.stdout + proc.stderr
    assert_not_blank(screenshot(pages[0], tmp_path))


def test_blank_page_is_detected(tmp_path):
    page = tmp_path / "blank.html"
    page.write_text("<!doctype html><html><body></body></html>", encoding="utf-8")
    with pytest.raises(AssertionError):
        assert_not_blank(screenshot(page, tmp_path))
