"""The HTML report: one self-contained, well-formed document with the verdict, tables and plots."""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET
from html import unescape
from html.parser import HTMLParser

import pytest
from sample import sample_result

from batcert.reports.html import run_html as render_html
from batcert.reports.write import render

VOID = {"area", "base", "br", "col", "embed", "hr", "img", "input", "link", "meta", "param",
        "source", "track", "wbr"}
SVG_NS = "{http://www.w3.org/2000/svg}"
VALUE = f"{sample_result().value:.4f}"  # the mean BPF of the sample, as the report rounds it


def signed(v: float) -> str:
    """A signed metric as reports show it: 4 decimals, typographic minus."""
    return f"{v:+.4f}".replace("-", "\u2212")


class TagChecker(HTMLParser):
    """Records unbalanced tags and the text of the document (outside <style>)."""

    def __init__(self) -> None:
        super().__init__(convert_charrefs=True)
        self.stack: list[tuple[str, tuple[int, int]]] = []
        self.errors: list[str] = []
        self.text: list[str] = []
        self.tags: list[tuple[str, dict[str, str | None]]] = []

    def handle_starttag(self, tag, attrs):
        self.tags.append((tag, dict(attrs)))
        if tag not in VOID:
            self.stack.append((tag, self.getpos()))

    def handle_startendtag(self, tag, attrs):
        self.tags.append((tag, dict(attrs)))  # <line/> in SVG: opened and closed at once

    def handle_endtag(self, tag):
        if tag in VOID:
            self.errors.append(f"end tag of void element </{tag}> at {self.getpos()}")
        elif not self.stack:
            self.errors.append(f"</{tag}> at {self.getpos()} closes nothing")
        elif self.stack[-1][0] != tag:
            self.errors.append(f"</{tag}> at {self.getpos()} closes <{self.stack[-1][0]}> "
                               f"opened at {self.stack[-1][1]}")
        else:
            self.stack.pop()

    def handle_data(self, data):
        if not self.stack or self.stack[-1][0] != "style":
            self.text.append(data)


def check_tags(html: str) -> TagChecker:
    checker = TagChecker()
    checker.feed(html)
    checker.close()
    assert checker.errors == []
    assert checker.stack == [], f"unclosed: {checker.stack}"
    return checker


def visible_text(html: str) -> str:
    return " ".join(" ".join(check_tags(html).text).split())


def style_of(html: str) -> str:
    [css] = re.findall(r"<style>(.*?)</style>", html, re.S)
    return css


def svgs_of(html: str) -> list[ET.Element]:
    return [ET.fromstring(s) for s in re.findall(r"<svg\b.*?</svg>", html, re.S)]


@pytest.fixture(scope="module")
def passing() -> str:
    return render_html(sample_result(limit=1.05))


@pytest.fixture(scope="module")
def failing() -> str:
    return render_html(sample_result(limit=0.95))


@pytest.fixture(scope="module")
def no_limit() -> str:
    return render_html(sample_result(limit=None))


# ---- the checker itself ----


def test_tag_checker_catches_unbalanced_markup():
    for bad in ["<div><p>x</div>", "<table><tr><td>x</td></table>", "<p>open", "</span>",
                "<br></br>"]:
        checker = TagChecker()
        checker.feed(bad)
        checker.close()
        assert checker.errors or checker.stack, bad
    check_tags('<p>a<br><img src="x.png"><svg><line x1="0"/></svg></p>')


# ---- document structure ----


@pytest.mark.parametrize("variant", ["passing", "failing", "no_limit"])
def test_document_head_and_balance(variant, request):
    html = request.getfixturevalue(variant)
    assert html.startswith("<!DOCTYPE html>")
    assert re.search(r'<html lang="en">', html)
    assert '<meta charset="utf-8">' in html.lower()
    assert html.lower().index("<meta charset") < 1024  # within the first 1024 bytes
    [title] = re.findall(r"<title>(.*?)</title>", html.split("</head>")[0], re.S)
    assert "Ash 34 in (Smith 2001)" in unescape(title) and "proposed" in title
    assert '<meta name="viewport"' in html
    check_tags(html)
    assert html.rstrip().endswith("</html>")


@pytest.mark.parametrize("variant", ["passing", "failing", "no_limit"])
def test_self_contained(variant, request):
    html = request.getfixturevalue(variant)
    lower = html.lower()
    assert "<link" not in lower
    assert "<script" not in lower
    assert "@import" not in lower
    assert not re.search(r"url\(", lower)
    assert not re.search(r"""\b(src|href|srcset|data|poster|action)\s*=\s*["']?\s*(https?:)?//""",
                         lower)
    assert "<iframe" not in lower and "<img" not in lower and "<object" not in lower
    # CSS inline in the head, with print styles
    css = style_of(html)
    assert "<style>" in html.split("</head>")[0]
    assert "@media print" in css
    assert "@page" in css
    assert ".verdict-pass" in css and ".verdict-fail" in css
    # CSS is not HTML-escaped by the autoescaping of the page (quotes in content: "(")
    assert "&#34;" not in css and "&quot;" not in css and "&#39;" not in css
    assert 'content: "("' in css


def test_pass_verdict(passing):
    text = visible_text(passing)
    # a run's report is a model prediction, and says so: never a bare PASS (issue 24)
    assert '<div class="verdict verdict-pass" role="status">PREDICTED PASS</div>' in passing
    assert "Predicted bat performance (model prediction, not a certificate)" in text
    assert "FAIL" not in text
    assert unescape(re.search(r"<title>(.*?)</title>", passing).group(1)).startswith(
        "PREDICTED PASS")
    margin = signed(sample_result(limit=1.05).margin)
    assert f"Predicted BPF {VALUE} \u2264 limit 1.0500 + tolerance 0.0050; margin {margin}." in text
    for label, value in [("BPF", VALUE), ("Limit", "1.0500"), ("Tolerance", "0.0050"),
                         ("Margin", margin)]:
        assert re.search(rf"<dt>{label}</dt><dd><span class=\"si\">{re.escape(value)}</span>",
                         passing), label


def test_fail_verdict(failing):
    text = visible_text(failing)
    assert '<div class="verdict verdict-fail" role="status">PREDICTED FAIL</div>' in failing
    assert "PASS" not in text
    result = sample_result(limit=0.95)
    assert result.verdict == "fail"
    assert f"> limit 0.9500 + tolerance 0.0050; margin {signed(result.margin)}." in text
    assert result.margin < 0
    assert f"<dt>Margin</dt><dd><span class=\"si\">{signed(result.margin)}</span>" in failing


def test_no_limit(no_limit):
    text = visible_text(no_limit)
    assert '<div class="verdict verdict-none" role="status">NO LIMIT</div>' in no_limit
    assert "PASS" not in text and "FAIL" not in text
    assert f"Predicted BPF {VALUE}; the protocol sets no limit." in text
    assert "<dt>Limit</dt>" not in no_limit and "<dt>Margin</dt>" not in no_limit


def test_exit_speed_metric_in_si_and_us():
    result = sample_result(metric="exit-speed", limit=50.0)
    html = render_html(result)
    text = visible_text(html)
    check_tags(html)
    v = result.value
    assert f"Exit speed {v:.2f} m/s ({v / 0.44704:.1f} mph) \u2264 limit 50.00 m/s (111.8 mph)" \
        in text
    assert re.search(r"<dt>Margin</dt><dd><span class=\"si\">\+\d+\.\d\d m/s</span>"
                     r"<span class=\"us\">\+\d+\.\d mph</span>", html)
    assert len(svgs_of(html)) == 1  # the metric is the exit speed: no second plot


def test_facts_and_inputs(passing):
    result = sample_result()
    text = visible_text(passing)
    for item in ["Ash 34 in (Smith 2001)", "collegiate baseball",
                 "proposed \u2014 Matched relative speed at the sweet spot", "version 1.0",
                 "Sports Engineering 4 (2001) 205-214", "BPF, mean of 3 conditions",
                 "sweet spot (maximum exit speed)", "flexible, bat pinned at the pivot",
                 "2025-03-14 09:26:53 UTC", "batcert 0.1.0"]:
        assert item in text, item
    for f in result.inputs:
        assert len(f.sha256) == 64
        row = re.search(rf"<tr><td>{f.role}</td><td>{re.escape(f.name)}</td>"
                        rf"<td class=\"path\">{re.escape(f.path)}</td>"
                        rf"<td class=\"hash\"><code>([0-9a-f]+)</code></td></tr>", passing)
        assert row and row.group(1) == f.sha256


def table_rows(html: str, caption: str) -> list[str]:
    """The body rows of the table with this caption, as lists of visible cell texts."""
    [table] = re.findall(rf"<caption>{re.escape(caption)}</caption>(.*?)</table>", html, re.S)
    body = table.split("<tbody>")[1]
    return [re.sub(r"<[^>]+>", " ", row) for row in re.findall(r"<tr>(.*?)</tr>", body, re.S)]


def test_row_per_condition(passing):
    result = sample_result()
    names = [c.name for c in result.conditions]
    for caption in ("Speeds and impact location", "Performance measures"):
        rows = table_rows(passing, caption)
        assert len(rows) == len(names)
        for row, c in zip(rows, result.conditions, strict=True):
            assert row.split()[:len(c.name.split())] == c.name.split()
    speeds = table_rows(passing, "Speeds and impact location")
    c = result.conditions[1]
    assert f"{c.exit_speed:.2f} m/s" in speeds[1]
    assert f"{c.exit_speed / 0.44704:.1f} mph" in speeds[1]
    assert f"{c.impact_location:.3f} m from pivot" in speeds[1]
    perf = table_rows(passing, "Performance measures")
    assert f"{c.bpf:.4f}" in perf[1] and f"{c.besr:.4f}" in perf[1]
    # the locations table (no caption) has a row per condition too
    section = passing.split("<h2>Centre of percussion and sweet spot</h2>")[1].split("</table>")[0]
    assert section.count('<tr><th scope="row">') == len(names)


def test_si_and_us_units(passing):
    text = visible_text(passing)
    for si, us in [("m/s", "mph"), ("rad/s", "rpm"), ("kg", "oz"), ("m from pivot", "in from tip"),
                   ("kg m\u00b2", "oz*in^2")]:
        assert si in text and us in text, (si, us)
    assert '<span class="si">0.860 m</span><span class="us">33.86 in</span>' in passing
    assert "from the knob" in text


def test_plots(passing):
    result = sample_result()
    charts = svgs_of(passing)
    assert len(charts) == 2  # exit speed, and the metric (BPF) since it is not the exit speed
    assert passing.count("<figure>") == 2
    for chart in charts:
        texts = [t.text for t in chart.iter(f"{SVG_NS}text")]
        for c in result.conditions:
            assert c.name in texts
        assert "Impact location from the pivot [m]" in texts
        lines = chart.findall(f"{SVG_NS}polyline")
        assert len({p.get("stroke") for p in lines}) == len(result.conditions)
        assert len(chart.findall(f"{SVG_NS}circle")) >= len(result.conditions)
        assert "COP" in texts
    texts = [t.text for t in charts[0].iter(f"{SVG_NS}text")]
    assert "Exit speed [m/s]" in texts and "Exit speed [mph]" in texts
    assert "BPF [-]" in [t.text for t in charts[1].iter(f"{SVG_NS}text")]


def test_warnings_shown_and_escaped():
    html = render_html(sample_result(warnings=[
        "stationary bat: the impact point lies on the search window's edge",
        "rigid engine: <b>BPF</b> is 1 & meaningless"]))
    check_tags(html)
    assert '<section class="warnings" aria-label="Warnings">' in html
    text = visible_text(html)
    assert "stationary bat: the impact point lies on the search window's edge" in text
    assert "rigid engine: <b>BPF</b> is 1 & meaningless" in text
    assert "&lt;b&gt;BPF&lt;/b&gt; is 1 &amp; meaningless" in html
    assert "<b>" not in html


def test_no_warnings_section_without_warnings(passing):
    assert 'class="warnings"' not in passing


def test_engine_diagnostics_from_extras():
    html = render_html(sample_result(extras={
        "modes_hz": [172.4, 571.9], "mode_nodes": [[0.17, 0.68], [0.07, 0.39, 0.72]],
        "contact_time_ms": 0.7123456,
        "barrel": {"hoop_frequency_hz": 1234.5678, "model": "<hollow>"}, "flag": True}))
    check_tags(html)
    section = html.split("<h2>Engine</h2>")[1]
    rows = {re.sub(r"<[^>]+>", "", k): [re.sub(r"<[^>]+>", "", c) for c in cells] for k, *cells
            in re.findall(r"<tr><th scope=\"row\">(.*?)</th><td>(.*?)</td><td>(.*?)</td></tr>",
                          section)}
    assert rows["engine"] == ["flexible", ""] and rows["support"] == ["pinned", ""]
    assert "engine" in rows and section.count(">engine<") == 1  # the engine row once
    assert rows["modes"] == ["18", ""] and rows["time_step"] == ["5e-06", "s"]
    assert rows["contact_time_ms"] == ["0.71235", ""]
    assert rows["barrel.hoop_frequency_hz"] == ["1234.6", "Hz"]
    assert rows["barrel.model"] == ["&lt;hollow&gt;", ""]
    assert rows["flag"] == ["true", ""]
    # each mode with its own nodes, in their own table
    modes = re.findall(r"<tr><th scope=\"row\">(\d)</th><td class=\"num\">(\d+)</td><td>(.*?)</td>",
                       section)
    assert modes == [("1", "172", "17.0, 68.0"), ("2", "572", "7.0, 39.0, 72.0")]


def test_names_are_escaped_everywhere():
    result = sample_result()
    result.bat = 'Bat <script>alert("x")</script> & co'
    result.conditions[0].name = "cond <i>&</i>"
    html = render_html(result)
    check_tags(html)
    assert "<script" not in html and "<i>" not in html
    text = visible_text(html)
    assert 'Bat <script>alert("x")</script> & co' in text
    assert "cond <i>&</i>" in text
    for chart in svgs_of(html):  # parses, so the SVG text is escaped as well
        assert "cond <i>&</i>" in [t.text for t in chart.iter(f"{SVG_NS}text")]


def test_render_dispatch_matches(passing):
    assert render(sample_result(limit=1.05), "html") == passing
