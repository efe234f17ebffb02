"""What a lab needs to file a report: honest margins at a limit, units, the basis of the values,
print headers and page numbers, and reports that are byte-identical between runs but for the
date (issue: a tool a lab can leave running)."""

from __future__ import annotations

import re
from html import unescape

import pytest

from batcert.reports.format import margin_text, rule_margin
from batcert.reports.html import css_string

ASH = "ash-34"


@pytest.mark.parametrize("margin, digits, shown", [
    (0.0, 4, "0 (at the limit)"),  # exactly at the limit
    (3e-5, 4, "+<0.0001"),  # passes by less than the shown resolution: never "+0.0000"
    (-3e-5, 4, "\u2212<0.0001"),
    (-0.0405, 4, "\u22120.0405"),
    (0.26, 1, "+0.3"),
])
def test_margin_is_honest_at_the_limit(margin, digits, shown):
    assert margin_text(margin, digits) == shown


def test_length_margin_at_the_limit():
    # a 2.625 in barrel against a 2 5/8 in limit: not "+0.0 mm" beside "2.62 in"
    assert rule_margin(0.0, "m").si == "0 mm (at the limit)"
    assert rule_margin(2.0e-5, "m").si == "+<0.1 mm"


def test_css_string_cannot_escape_its_string():
    text = css_string('Bat "X" </style><script>')
    assert '"' not in text and "<" not in text and ">" not in text


def _reports(batcert_cli, out, *args):
    result = batcert_cli("run", ASH, "-p", "ncaa-bbcor", "--engine", "rigid", "--out", out, *args)
    assert result.exit_code in (0, 1), result.stderr
    return {p.name: p.read_text(encoding="utf-8") for p in sorted(out.iterdir()) if p.is_file()}


def test_reports_are_identical_between_runs_but_for_the_date(batcert_cli, tmp_path):
    first, second = _reports(batcert_cli, tmp_path / "a"), _reports(batcert_cli, tmp_path / "b")
    assert first.keys() == second.keys() and len(first) == 3
    date = re.compile(r"\d{4}-\d\d-\d\d[ T]\d\d:\d\d:\d\d(\+00:00| UTC)")
    for name in first:
        assert date.sub("DATE", first[name]) == date.sub("DATE", second[name]), name


def test_certificate_states_basis_print_header_and_page_numbers(batcert_cli, tmp_path):
    reports = _reports(batcert_cli, tmp_path / "r")
    html = next(v for k, v in reports.items() if k.endswith(".html"))
    md = next(v for k, v in reports.items() if k.endswith(".md"))
    for text in (unescape(html), md):
        assert "A model prediction, not a certificate: values computed by batcert's rigid " \
               "model of the bat from its specification, not measured on a bench" in text
        # the metric's known offset (docs/validation.md), from the metrics registry
        assert "Known offset of the model: wood bats sit at the NCAA's wood level" in text
    assert 'content: "page " counter(page) " of " counter(pages)' in html
    assert "@top-left" in html and "ncaa\\2d bbcor" in html  # the certificate's header
    assert "| Correction | Value | Unit |" in md
    assert "| Setting or diagnostic | Value | Unit |" in md
