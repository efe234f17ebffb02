"""A study's ``figures:`` and the claims that read them, as `batcert validate` checks them
(batcert.specs.study._check_figures and batcert.sweeps.study_figures.check_figures).

Each bad file is the shipped smith2001 study with one thing changed; its protocol files are
given by absolute path so that the copy in tmp_path resolves them (a relative path resolves
against the study's own folder). Every problem must name the file, the line and the field.
"""

from __future__ import annotations

from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
STUDIES = REPO / "protocols" / "studies"
SHIPPED = (STUDIES / "smith2001.yaml").read_text(encoding="utf-8")


def _text() -> str:
    """smith2001.yaml with its protocol files by absolute path (line numbers unchanged)."""
    text = SHIPPED.replace("\n  - smith2001-", f"\n  - {STUDIES}/smith2001-")
    assert text.count(str(STUDIES)) == 4  # the four study protocols (the fifth is `proposed`)
    return text


def _write(tmp_path: Path, old: str, new: str, *more: tuple[str, str]) -> tuple[Path, str]:
    """The study with ``old`` replaced by ``new`` (and each further pair), each found once."""
    text = _text()
    for a, b in ((old, new), *more):
        assert text.count(a) == 1, a
        text = text.replace(a, b)
    path = tmp_path / "study.yaml"
    path.write_text(text, encoding="utf-8")
    return path, text


def _line(text: str, needle: str) -> int:
    """The 1-based number of the one line holding ``needle``."""
    hits = [i for i, line in enumerate(text.splitlines(), 1) if needle in line]
    assert len(hits) == 1, (needle, hits)
    return hits[0]


def test_the_shipped_study_and_its_copy_validate(batcert_cli, tmp_path):
    assert batcert_cli("validate", STUDIES / "smith2001.yaml").exit_code == 0
    path, _ = _write(tmp_path, "bats: compared", "bats: compared")  # the unchanged copy
    result = batcert_cli("validate", path)
    assert result.exit_code == 0, result.stderr


# (what is changed, into what, the field blamed, words of the message, the line blamed)
BAD = {
    "unknown-parameter": (
        "vary: wall=60%:140%:9", "vary: wal=60%:140%:9", "figures[0].vary",
        "unknown parameter 'wal'", "vary: wal="),
    "second-figure-parameter": (
        "vary: bat_angular_speed=", "vary: bat_angular_sped=", "figures[1].vary",
        "did you mean 'bat_angular_speed'", "vary: bat_angular_sped="),
    "not-a-condition": (
        "condition: pitched-and-swung\n    vary: wall", "condition: pitched-and-swang\n    vary: wall",
        "figures[0].condition",
        "protocol 'smith2001-bpf-sweet-spot' has no condition 'pitched-and-swang'",
        "condition: pitched-and-swang"),
    "not-a-protocol-of-the-study": (
        "protocol: smith2001-bpf-sweet-spot\n    condition: pitched-and-swung\n    vary: wall",
        "protocol: ncaa-bbcor\n    condition: pitched-and-swung\n    vary: wall",
        "figures[0].protocol", "'ncaa-bbcor' is not a protocol of this study", "protocol: ncaa-bbcor"),
    "unknown-quantity": (  # the swing-speed figure: no claim reads its quantities' names
        "metrics: [sweet_spot, rigid_sweet_spot, cop]",
        "metrics: [sweet_spot, rigid_sweet_spot, cops]",
        "figures[1].metrics", "unknown quantity 'cops'",
        "metrics: [sweet_spot, rigid_sweet_spot, cops]"),
    "unknown-bats-choice": (
        "bats: compared", "bats: compare", "figures[0].bats", "did you mean 'compared'",
        "bats: compare"),
}


@pytest.mark.parametrize("old, new, field, message, at", BAD.values(), ids=BAD)
def test_a_bad_figure_is_invalid_input_at_its_line(batcert_cli, tmp_path, old, new, field,
                                                   message, at):
    path, text = _write(tmp_path, old, new)
    result = batcert_cli("validate", path)
    assert result.exit_code == 3
    out = " ".join(result.stderr.split())
    assert f"{path}:{_line(text, at)}: {field}: " in out
    assert message in out


# a figure claim: (what is changed, into what, the field blamed, words of the message, the
# claim's first line); the problem may be shown at the claim or at its `figure:` line
CLAIMS = {
    "figure-not-of-the-study": (
        "    figure: wall-thickness\n", "    figure: wall-thicknes\n", "claims[8].figure",
        "the opposite-trends check needs `figure:`, the id of one of the study's figures "
        "(wall-thickness, sweet-spot-swing-speed)", "- id: thin-wall-opposite-trends"),
    "figure-missing": (
        "    figure: sweet-spot-swing-speed\n", "", "claims[9].figure",
        "the figure-sweet-spot-less-than-rigid check needs `figure:`",
        "- id: sweet-spot-swing-speed-less-than-rigid"),
    "opposite-trends-without-metrics": (
        "    figure: wall-thickness\n    metrics: [bpf, besr]\n", "    figure: wall-thickness\n",
        "claims[8].metrics", "opposite-trends needs the two `metrics:` to compare",
        "- id: thin-wall-opposite-trends"),
}


@pytest.mark.parametrize("old, new, field, message, claim", CLAIMS.values(), ids=CLAIMS)
def test_a_bad_figure_claim_is_invalid_input_at_its_line(batcert_cli, tmp_path, old, new, field,
                                                         message, claim):
    path, text = _write(tmp_path, old, new)
    result = batcert_cli("validate", path)
    assert result.exit_code == 3
    out = " ".join(result.stderr.split())
    lines = [_line(text, claim)] + ([_line(text, new.strip())] if new.strip() else [])
    assert any(f"{path}:{n}: {field}: " in out for n in lines), out
    assert message in out


def test_every_figure_problem_is_reported_at_once(batcert_cli, tmp_path):
    path, text = _write(tmp_path, "vary: wall=60%:140%:9", "vary: wal=60%:140%:9",
                        ("metrics: [sweet_spot, rigid_sweet_spot, cop]",
                         "metrics: [sweet_spot, rigid_sweet_spot, COP]"))
    result = batcert_cli("validate", path)
    assert result.exit_code == 3
    assert f"{path}:{_line(text, 'vary: wal=')}: figures[0].vary: " in result.stderr
    assert f"{path}:{_line(text, 'COP]')}: figures[1].metrics: unknown quantity 'COP'" \
        in " ".join(result.stderr.split())
    assert "2 problems in" in result.stderr


def test_compare_refuses_a_bad_figure_before_running(batcert_cli, tmp_path):
    # load_study_any checks the figures' parameters as validate does: exit 3 at the line
    path, text = _write(tmp_path, "vary: wall=60%:140%:9", "vary: wal=60%:140%:9")
    result = batcert_cli("compare", "--study", path, "--engine", "rigid", "--no-reports")
    assert result.exit_code == 3
    assert f"{path}:{_line(text, 'vary: wal=')}: figures[0].vary: " in result.stderr


# ---------------------------------------------------------------- known problems


@pytest.mark.parametrize("old, new", [
    ("vary: wall=60%:140%:9", "vary: wall=60%:140%"),
    ("vary: bat_angular_speed=0rad/s:60rad/s:13", "vary: bat_angular_speed=0m/s:60m/s:13"),
], ids=["no-count", "wrong-unit"])
def test_an_unreadable_range_is_invalid_input(batcert_cli, tmp_path, old, new):
    path, text = _write(tmp_path, old, new)
    result = batcert_cli("validate", path)
    assert result.exit_code == 3
    index = 0 if "wall" in old else 1
    assert f"{path}:{_line(text, new)}: figures[{index}].vary: " in result.stderr


def test_claim_metrics_must_be_plotted_by_its_figure(batcert_cli, tmp_path):
    old = "    figure: wall-thickness\n    metrics: [bpf, besr]\n"
    path, _ = _write(tmp_path, old, old.replace("besr", "bbcor"))
    result = batcert_cli("validate", path)
    assert result.exit_code == 3
    assert "claims[8].metrics" in result.stderr


def test_compare_with_a_claim_metric_the_figure_lacks_is_invalid_input(batcert_cli, tmp_path):
    path = tmp_path / "small.yaml"  # one protocol, one figure of two points: fast to compare
    path.write_text(f"""id: small
title: t
reference: r
version: "1"
bats: [ash-34, aluminium-34]
protocols: [{STUDIES / 'smith2001-bpf-sweet-spot.yaml'}]
figures:
  - id: wall
    title: t
    protocol: smith2001-bpf-sweet-spot
    condition: pitched-and-swung
    vary: wall=60%:100%:2
    metrics: [bpf, besr]
    bats: compared
claims:
  - id: c
    statement: s
    check: opposite-trends
    figure: wall
    metrics: [bpf, bbcor]
    protocols: [smith2001-bpf-sweet-spot]
""", encoding="utf-8")
    result = batcert_cli("compare", "--study", path, "--engine", "rigid", "--no-reports")
    assert result.exit_code == 3


def test_figure_ids_are_distinct(batcert_cli, tmp_path):
    path, _ = _write(tmp_path, "  - id: sweet-spot-swing-speed\n", "  - id: wall-thickness\n",
                     ("figure: sweet-spot-swing-speed", "figure: wall-thickness"))
    result = batcert_cli("validate", path)
    assert result.exit_code == 3
    assert "figures[1].id" in result.stderr
