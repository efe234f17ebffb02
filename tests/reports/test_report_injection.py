"""Text from the user's files reaches reports, figures and the terminal as text: a name with
line breaks cannot start a new Markdown block (raw HTML) or a new terminal line, and a name
that looks like matplotlib's mathtext is drawn as written."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
NAME = "Ash\\n\\n<script>alert(1)</script>\\n\\n# Heading $\\\\frac{1}$"


def _bat(tmp_path: Path, name: str = NAME) -> Path:
    text = (REPO / "bats" / "ash-34.yaml").read_text(encoding="utf-8")
    bat = tmp_path / "bat.yaml"
    text = re.sub(r"(?m)^name: .*$", lambda _: f'name: "{name}"', text, count=1)
    bat.write_text(text, encoding="utf-8")
    return bat


def test_a_name_with_blank_lines_injects_nothing_into_markdown_or_the_terminal(batcert_cli,
                                                                              tmp_path):
    res = batcert_cli("run", _bat(tmp_path), "-p", "ncaa-bbcor", "--engine", "rigid", "--out",
                      tmp_path / "out")
    assert res.exit_code == 0  # rigid ash: BBCOR about 0.48, a predicted pass
    [md] = (tmp_path / "out").glob("*.md")
    for line in md.read_text(encoding="utf-8").splitlines():
        assert not line.startswith("<script>"), line  # no raw HTML block
        assert not line.startswith("# Heading"), line  # no heading of the user's
    first = res.stdout.splitlines()[0]
    assert "Ash <script>alert(1)</script> # Heading" in first  # the name on its one line


def test_a_bidirectional_override_in_a_name_is_refused(batcert_cli, tmp_path):
    res = batcert_cli("validate", _bat(tmp_path, "Ash \\u202egnp.exe"))
    assert res.exit_code == 3
    assert "bat.yaml:" in res.stderr and "name" in res.stderr and "U+202E" in res.stderr


@pytest.mark.parametrize("command", ["run", "compare"])
def test_mathtext_in_a_name_is_drawn_as_text_in_figures(batcert_cli, tmp_path, command):
    bat = _bat(tmp_path, "Ash $\\\\frac{1}$ x")
    extra = ["ash-34"] if command == "compare" else []
    res = batcert_cli(command, bat, *extra, "-p", "ncaa-bbcor", "--engine", "rigid",
                      "--no-reports", "--figures", tmp_path / "figs")
    assert res.exit_code in (0, 1), res.stderr
    svgs = list((tmp_path / "figs").glob("*.svg"))
    assert svgs
