"""A real run (ash bat, proposed protocol, rigid engine) written in every format."""

from __future__ import annotations

import hashlib
import json
import re
import xml.etree.ElementTree as ET
from html import unescape
from pathlib import Path

import pytest

from batcert.commands.inputs import load_bat_any, load_protocol_any
from batcert.commands.run import run
from batcert.reports.markdown import md_text
from batcert.reports.write import write_reports
from batcert.results.run import RunResult

REPO = Path(__file__).resolve().parents[2]
NS = "{http://www.w3.org/2000/svg}"


@pytest.fixture(scope="module")
def result() -> RunResult:
    with pytest.MonkeyPatch.context() as mp:
        mp.chdir(REPO)
        bat = load_bat_any("bats/ash-34.yaml")
        protocol = load_protocol_any("proposed")
        [res] = run(bat, [protocol], "rigid")
    return res


@pytest.fixture(scope="module")
def written(result, tmp_path_factory) -> dict[str, Path]:
    out = tmp_path_factory.mktemp("e2e") / "reports"
    paths = write_reports(result, out, ("md", "html", "json"))
    return {p.suffix[1:]: p for p in paths}


def test_files_written(written):
    assert set(written) == {"md", "html", "json"}
    out = written["md"].parent
    assert sorted(p.name for p in out.glob("[!.]*")) == sorted(p.name for p in written.values())
    for path in written.values():
        assert path.stem == "ash-34-in-smith-2001--proposed"
        assert path.stat().st_size > 1000


def test_json_round_trips(result, written):
    data = json.loads(written["json"].read_text(encoding="utf-8"))
    assert RunResult.from_dict(data) == result
    assert data["protocol"] == "proposed" and data["metric"] == "bpf"
    assert data["limit"] is None and data["verdict"] is None  # the proposal sets no limit
    assert [c["name"] for c in data["conditions"]] == \
        ["stationary-bat", "stationary-ball", "pitched-and-swung"]


def test_input_hashes_match_files(result, written):
    html = written["html"].read_text(encoding="utf-8")
    md = written["md"].read_text(encoding="utf-8")
    assert {f.role for f in result.inputs} == {"bat", "protocol", "ball"}
    for f in result.inputs:
        # shipped inputs are named as shipped:<folder>/<file>, user files by their path
        path = (REPO / f.path.removeprefix("shipped:") if f.path.startswith("shipped:")
                else Path(f.path) if Path(f.path).is_absolute() else REPO / f.path)
        assert f.sha256 == hashlib.sha256(path.read_bytes()).hexdigest()
        assert f"<code>{f.sha256}</code>" in html
        assert f"`{f.sha256}`" in md


def test_html_plot_has_one_series_per_condition(result, written):
    html = written["html"].read_text(encoding="utf-8")
    assert "NO LIMIT" in html and "<link" not in html and "<script" not in html
    charts = [ET.fromstring(s) for s in re.findall(r"<svg\b.*?</svg>", html, re.S)]
    assert len(charts) == 2  # exit speed, and BPF
    names = [c.name for c in result.conditions]
    for chart in charts:
        polylines = chart.findall(f"{NS}polyline")
        strokes = {p.get("stroke") for p in polylines}
        assert len(strokes) == len(names)
        assert len(polylines) == len(names)  # the sweeps are all finite: one unbroken line each
        texts = [t.text for t in chart.iter(f"{NS}text")]
        # each condition in the legend; a curve under another's says so: "(same as ...)"
        assert all(any(t == n or (t or "").startswith(f"{n} (same as ") for t in texts)
                   for n in names)
        impact = [c for c in chart.findall(f"{NS}circle") if c.get("fill") == "#ffffff"
                  and c.get("r") == "4.5"]
        assert len(impact) >= len(names)  # one impact point per condition (+ the legend's)
        # tick labels are distinguishable, even for BPF = 1 by construction (rounding noise)
        left = [t.text for t in chart.iter(f"{NS}text") if t.get("text-anchor") == "end"
                and t.get("font-size") == "11" and float(t.get("x")) < 66]
        assert len(left) >= 2 and len(set(left)) == len(left), left
    first = charts[0]
    for p, c in zip(first.findall(f"{NS}polyline"), result.conditions, strict=True):
        assert len(p.get("points").split()) == len(c.sweep.impact_location)


def test_warnings_in_reports(result, written):
    assert result.warnings
    html = unescape(written["html"].read_text(encoding="utf-8"))
    md = written["md"].read_text(encoding="utf-8")
    for w in result.warnings:
        assert w in html
        assert f"> **\u26a0 Warning:** {md_text(w)}" in md
    assert "use the flexible engine for a meaningful BPF" in md


def test_markdown_has_a_row_per_condition(result, written):
    md = written["md"].read_text(encoding="utf-8")
    for c in result.conditions:
        assert sum(line.startswith(f"| {c.name} |") for line in md.splitlines()) == 3
