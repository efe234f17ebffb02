"""The comparison and league HTML pages: self-contained, valid HTML5, styled like the run report
(status badges, print CSS), generated from real runs with the fast rigid engine."""

from __future__ import annotations

import json
import re
from html.parser import HTMLParser
from importlib import resources
from pathlib import Path

import pytest

from batcert.commands.compare import run_comparison
from batcert.commands.league import run_league
from batcert.reports.html import comparison_html as render_comparison_html
from batcert.reports.html import league_html as render_league_html
from batcert.reports.markdown import comparison_markdown as render_comparison_markdown
from batcert.reports.write import write_reports
from batcert.results.compare import ComparisonResult
from batcert.results.league import LeagueResult

REPO = Path(__file__).resolve().parents[2]
ASH, ALU, R161 = (str(REPO / "bats" / f) for f in ("ash-34.yaml", "aluminium-34.yaml",
                                                    "r161.yaml"))
VOID = {"area", "base", "br", "col", "embed", "hr", "img", "input", "link", "meta", "source",
        "track", "wbr"}


class TagChecker(HTMLParser):
    """Checks that every element is closed in order and records what the page would load."""

    def __init__(self) -> None:
        super().__init__(convert_charrefs=True)
        self.stack: list[str] = []
        self.errors: list[str] = []
        self.starts: list[tuple[str, dict[str, str | None]]] = []
        self.doctype = ""
        self.styles: list[str] = []
        self._in_style = False

    def handle_decl(self, decl: str) -> None:
        self.doctype = decl

    def handle_starttag(self, tag, attrs):
        self.starts.append((tag, dict(attrs)))
        if tag not in VOID:
            self.stack.append(tag)
        self._in_style = tag == "style"

    def handle_startendtag(self, tag, attrs):  # <rect .../> in SVG: opened and closed
        self.starts.append((tag, dict(attrs)))

    def handle_endtag(self, tag):
        self._in_style = False
        if tag in VOID:
            self.errors.append(f"end tag for void element <{tag}>")
        elif not self.stack or self.stack[-1] != tag:
            self.errors.append(f"</{tag}> closes <{self.stack[-1] if self.stack else None}>")
        else:
            self.stack.pop()

    def handle_data(self, data):
        if self._in_style:
            self.styles.append(data)


def check_page(html: str) -> TagChecker:
    """Valid-looking HTML5 that fetches nothing: asserts and returns the parse."""
    p = TagChecker()
    p.feed(html)
    p.close()
    assert p.doctype.lower() == "doctype html"
    assert not p.errors, p.errors[:5]
    assert not p.stack, f"unclosed: {p.stack}"
    tags = [t for t, _ in p.starts]
    assert tags[0] == "html" and p.starts[0][1].get("lang") == "en"
    assert ("meta", {"charset": "utf-8"}) in p.starts
    assert tags.count("title") >= 1 and tags.count("body") == 1 and tags.count("main") == 1
    assert "link" not in tags and "script" not in tags and "iframe" not in tags
    assert "img" not in tags  # charts are inline SVG
    for tag, attrs in p.starts:
        for name in ("src", "href", "xlink:href", "action", "data"):
            value = (attrs.get(name) or "").strip().lower()
            assert not re.match(r"(https?:)?//", value), f"<{tag} {name}={value}> loads"
            if name == "href" and value:
                assert value.startswith("#"), f"<{tag} href={value}> leaves the page"
    css = "\n".join(p.styles)
    assert "@media print" in css
    assert "url(" not in css and "@import" not in css
    return p


def badges(html: str) -> list[tuple[str, str]]:
    """(colour class, text) of every status badge on the page."""
    return re.findall(r'<span class="badge badge-(\w+)">([^<]+)</span>', html)


@pytest.fixture(scope="module")
def study(tmp_path_factory) -> tuple[ComparisonResult, Path]:
    out = tmp_path_factory.mktemp("compare")
    result = run_comparison([ASH, ALU], [], study="smith2001", engine="rigid")
    paths = write_reports(result, out)
    return result, next(p for p in paths if p.suffix == ".html")


@pytest.fixture(scope="module")
def limited(tmp_path_factory) -> tuple[ComparisonResult, str]:
    """Three bats under a protocol with a limit (rigid BBCOR is about 0.48 < 0.500 with the ball
    lot calibrated on a wood bat's 0.490 on the flexible engine: all pass)."""
    result = run_comparison([ASH, ALU, R161], ["ncaa-bbcor", "stationary-ball"], engine="rigid")
    return result, render_comparison_html(result)


@pytest.fixture(scope="module")
def league(tmp_path_factory) -> tuple[LeagueResult, Path]:
    out = tmp_path_factory.mktemp("league")
    result = run_league("ncaa", [ASH, ALU, R161], engine="rigid")
    paths = write_reports(result, out)
    return result, next(p for p in paths if p.suffix == ".html")


def test_templates_ship_inside_the_package():
    templates = resources.files("batcert.reports") / "templates"
    for name in ("compare.html.j2", "league.html.j2", "style.css.j2"):
        assert (templates / name).is_file()


def test_comparison_page_is_valid_and_self_contained(study):
    result, path = study
    html = path.read_text(encoding="utf-8")
    page = check_page(html)
    tags = [t for t, _ in page.starts]
    assert tags.count("svg") >= 2 * len(result.protocols)  # metric and sweet-spot charts
    assert "<svg" in html and "xmlns=\"http://www.w3.org/2000/svg\"" in html  # a namespace only
    assert tags.count("section") >= len(result.protocols)
    assert "overflow-wrap: anywhere" in html


def test_comparison_page_header_and_findings(study):
    result, path = study
    html = path.read_text(encoding="utf-8")
    assert 'class="certificate"' in html
    for text in ("smith2001", result.reference, "rigid", result.batcert_version,
                 "What the model finds", "The study's claims against the model"):
        assert text in html, text
    for item in result.inputs:  # input files with their hashes
        assert item["sha256"] in html
    for finding in result.findings[:3]:
        assert finding.replace("'", "&#39;") in html
    assert html.index("What the model finds") < html.index("claims against the model") \
        < html.index("Protocol " + result.protocols[0].protocol)


def test_comparison_claim_badges(study):
    result, path = study
    found = badges(path.read_text(encoding="utf-8"))
    colour = {"supported": "pass", "not supported": "fail", "not testable": "warn"}
    for claim in result.claims:
        text = claim.status.replace("-", " ")
        assert (colour[text], text) in found, claim.id
    assert len(result.claims) >= 3


def test_comparison_values_carry_units(study):
    result, path = study
    html = path.read_text(encoding="utf-8")
    p = result.protocols[0]
    assert "mean of P across conditions" in html and "std of P (population)" in html
    assert f"{p.conditions[0].bats[result.reference].cop:.3f} m" in html  # SI ...
    assert "in from tip" in html  # ... with inches below
    assert re.search(r"[+\u2212]\d+\.\d cm</span><span class=\"us\">[+\u2212]\d+\.\d\d in", html)
    assert "0.150 m (5.91 in) from the knob" in html  # pivot in SI and US
    assert re.search(r"\d\.\d{4} kg m²</span><span class=\"us\">[\d,]+ oz\*in\^2", html)  # MOI


def test_comparison_limit_verdicts_and_speeds(limited):
    result, html = limited
    check_page(html)
    found = badges(html)
    bbcor = result.protocol("ncaa-bbcor")
    assert all(v and v.lower() == "pass" for v in bbcor.verdicts.values())
    assert found.count(("pass", "predicted PASS")) == len(result.bats)  # the model's verdict
    assert "limit 0.500" in html  # the limit line on the BBCOR chart
    assert "on edge: not located" in html  # rigid sweet spots on the window edge are flagged
    for b in result.bats:
        assert b.label in html


def test_comparison_exit_speed_in_si_and_us(tmp_path):
    result = run_comparison([ASH, ALU], ["proposed"], engine="rigid")
    result.protocols[0].metric = "exit-speed"  # show a speed metric with the same numbers
    html = render_comparison_html(result)
    check_page(html)
    assert re.search(r"\d+\.\d\d m/s</span><span class=\"us\">\d+\.\d mph", html)


def test_comparison_html_escapes_text_and_rerenders_from_json(study):
    result, path = study
    again = ComparisonResult.from_dict(json.loads(result.to_json()))
    assert render_comparison_html(again) == path.read_text(encoding="utf-8")
    again.title = "<b>A & B</b>"
    again.findings = ["x < y"]
    html = render_comparison_html(again)
    check_page(html)
    assert "&lt;b&gt;A &amp; B&lt;/b&gt;" in html and "x &lt; y" in html


def test_comparison_markdown_unchanged_by_html(study):
    result, _ = study
    md = render_comparison_markdown(result)
    assert md.startswith("# Bat comparison: ") and "<" not in md.split("\n", 1)[0]
    assert "What the model finds" in md and "mean of P across conditions" in md


def test_league_page_is_valid_and_self_contained(league):
    result, path = league
    html = path.read_text(encoding="utf-8")
    check_page(html)
    # the source column wraps long URLs instead of widening the page
    assert re.search(r"table\.rules td[^{]*\{[^}]*overflow-wrap: anywhere", html)
    assert 'class="source"' in html
    assert "https://www.on3.com/" in html  # URLs are shown as text, never fetched


def test_league_verdict_badges(league):
    result, path = league
    html = path.read_text(encoding="utf-8")
    found = badges(html)
    from batcert.reports.league_view import rests_on_model
    colour = {"pass": ("pass", "PASS"), "fail": ("fail", "FAIL"),
              "incomplete": ("warn", "INCOMPLETE")}
    # summary row and section heading; a verdict the model decides is "predicted" (a FAIL only
    # when no rule of the bat file's own numbers fails)
    for b in result.bats:
        kind, word = colour[b.verdict]
        by_model = rests_on_model(b.rules, b.verdict) and b.verdict != "incomplete"
        word = f"predicted {word}" if by_model else word
        assert found.count((kind, word)) >= 2
    verdicts = {r.verdict for b in result.bats for r in b.rules}
    assert {"pass", "fail", "not-modelled", "not-applicable"} <= verdicts
    assert ("warn", "NOT MODELLED") in found and ("na", "not applicable") in found
    assert 'class="verdict verdict-fail"' in html  # headline: a bat fails
    n_rules = sum(len(b.rules) for b in result.bats)
    assert len(found) == n_rules + 2 * len(result.bats)


def test_league_not_modelled_rules_show_their_reason(league):
    result, path = league
    html = path.read_text(encoding="utf-8")
    nm = [(b, r) for b in result.bats for r in b.rules if r.verdict == "not-modelled"]
    assert nm
    assert html.count('<tr class="not-modelled">') == len(nm)
    assert 'class="nm-box"' in html
    for _, r in nm:
        assert r.note and r.note.replace("'", "&#39;") in html
        assert "Not modelled:" in html


def test_league_values_limits_and_margins_in_si_and_us(league):
    result, path = league
    html = path.read_text(encoding="utf-8")
    assert "914.4 mm</span><span class=\"us\">36.000 in" in html  # limit
    assert re.search(r"\+\d+\.\d mm</span><span class=\"us\">\+\d+\.\d{3} in", html)  # margin
    assert "\u22120.42" in html  # a failing drop margin with a real minus sign
    assert result.sha256 in html and all(b.sha256 in html for b in result.bats)


def test_league_incomplete_headline(tmp_path):
    result = run_league("usa-baseball", [ASH, ALU], engine="rigid")
    assert {b.verdict for b in result.bats} == {"pass", "incomplete"}
    html = render_league_html(result)
    check_page(html)
    assert 'class="verdict verdict-warn"' in html and ">INCOMPLETE<" in html
    assert ("warn", "INCOMPLETE") in badges(html)
