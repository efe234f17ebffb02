"""``--figures DIR`` of `batcert run` and `batcert compare`: one SVG, PDF and PNG per figure of
the report, named ``<report stem>--<figure>.<format>`` (the sweep's: tests/cli/test_sweep_cli.py).

Rigid engine (closed forms, fast); tests/reports/test_figures.py checks the files' content.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

pytest.importorskip("matplotlib")

FORMATS = ("pdf", "png", "svg")


def check_set(directory: Path, stem: str, figures: list[str]) -> None:
    """``directory`` holds exactly the three files of each figure, each a file of its format."""
    expected = sorted(f"{stem}--{f}.{x}" for f in figures for x in FORMATS)
    assert sorted(p.name for p in directory.iterdir()) == expected
    for p in directory.iterdir():
        data = p.read_bytes()
        if p.suffix == ".svg":
            assert ET.fromstring(data).tag == "{http://www.w3.org/2000/svg}svg", p
        else:
            assert data.startswith(b"%PDF-" if p.suffix == ".pdf" else b"\x89PNG\r\n\x1a\n"), p


def test_run_writes_its_figures(batcert_cli, tmp_path):
    out = tmp_path / "figures"
    result = batcert_cli("run", "ash-34", "-p", "proposed", "--engine", "rigid", "--no-reports",
                         "--figures", out)
    assert result.exit_code == 0, result.stderr  # the proposal sets no limit
    # the exit speed and, the metric being BPF, the metric against impact location
    check_set(out, "ash-34-in-smith-2001--proposed", ["exit-speed", "metric"])
    assert "wrote 6 figure files" in result.stderr


def test_compare_writes_its_figures(batcert_cli, tmp_path):
    out = tmp_path / "figures"
    result = batcert_cli("compare", "ash-34", "aluminium-34", "-p", "ncaa-bbcor", "--engine",
                         "rigid", "--no-reports", "--figures", out)
    # exit 0: both rigid bats are under BBCOR 0.50 (about 0.48); the figures are written
    assert result.exit_code == 0, result.stderr
    check_set(out, "compare--ncaa-bbcor--ash-34-aluminium-34",
              ["overview", "ncaa-bbcor--metric", "ncaa-bbcor--relative", "ncaa-bbcor--sweet-spot"])
    assert "wrote 12 figure files" in result.stderr


def test_figures_under_a_file_is_exit_4(batcert_cli, tmp_path):
    blocker = tmp_path / "file"
    blocker.write_text("not a directory")
    result = batcert_cli("run", "ash-34", "-p", "proposed", "--engine", "rigid", "--no-reports",
                         "--figures", blocker / "figures")
    assert result.exit_code == 4  # "the reports cannot be written (... a path that is a file)"
    assert "is not a directory" in result.stderr
    assert blocker.read_text() == "not a directory"
