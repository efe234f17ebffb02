"""The Markdown report: verdict, figures, a table row per condition, input hashes, warnings."""

from __future__ import annotations

import re

import pytest
from sample import sample_result

from batcert.reports.markdown import md_cell, md_table, md_text
from batcert.reports.markdown import run_markdown as render_markdown
from batcert.reports.write import render

VALUE = f"{sample_result().value:.4f}"  # the mean BPF of the sample, as the report rounds it


def signed(v: float) -> str:
    """A signed metric as reports show it: 4 decimals, typographic minus."""
    return f"{v:+.4f}".replace("-", "\u2212")


def cells(line: str) -> list[str]:
    """Cells of a GFM table row, honouring escaped pipes."""
    assert line.startswith("| ") and line.endswith(" |"), line
    return [c.strip() for c in re.split(r"(?<!\\)\|", line[1:-1])]


def table_after(md: str, header_start: str) -> tuple[list[str], list[list[str]]]:
    """The table whose header row starts with ``header_start``: (headers, body rows)."""
    lines = md.splitlines()
    i = next(k for k, line in enumerate(lines) if line.startswith(header_start))
    headers = cells(lines[i])
    assert re.fullmatch(r"\|(:---|---:)(\|(:---|---:))*\|", lines[i + 1])
    assert lines[i + 1].count("|") == len(headers) + 1
    body = []
    for line in lines[i + 2:]:
        if not line.startswith("|"):
            break
        body.append(cells(line))
    assert all(len(row) == len(headers) for row in body)
    return headers, body


@pytest.fixture(scope="module")
def md() -> str:
    return render_markdown(sample_result(limit=1.05, warnings=["watch the window edge"]))


def test_title_and_verdict_pass(md):
    # a model prediction, titled as one (issue 24); a certificate is reduce's, from hits
    assert md.startswith("# Predicted bat performance: Ash 34 in (Smith 2001)\n")
    assert "A model prediction, not a certificate" in md
    margin = sample_result(limit=1.05).margin
    assert f"**Verdict: PREDICTED PASS** \u2014 Predicted BPF {VALUE} \u2264 limit 1.0500 + tolerance 0.0050; " \
           f"margin {signed(margin)}." in md


def test_verdict_fail():
    result = sample_result(limit=0.95)
    md = render_markdown(result)
    # ">" is escaped so that it cannot start HTML; it renders as ">"
    assert f"**Verdict: PREDICTED FAIL** \u2014 Predicted BPF {VALUE} \\> limit 0.9500 + tolerance 0.0050; " \
           f"margin {signed(result.margin)}." in md
    assert "PASS" not in md


def test_verdict_no_limit():
    md = render_markdown(sample_result(limit=None))
    assert f"**Verdict: NO LIMIT** \u2014 Predicted BPF {VALUE}; the protocol sets no limit." \
        in md
    assert "PASS" not in md and "FAIL" not in md
    assert "margin" not in md


def test_exit_speed_metric_with_units():
    result = sample_result(metric="exit-speed", limit=50.0)
    md = render_markdown(result)
    v = result.value
    assert (f"Exit speed {v:.2f} m/s ({v / 0.44704:.1f} mph) \u2264 limit 50.00 m/s (111.8 mph) "
            f"+ tolerance 0.01 m/s (0.0 mph); margin +{result.margin:.2f} m/s") in md
    assert "Plots of exit speed against impact location are in the HTML report." in md


def test_header_table(md):
    headers, rows = table_after(md, "| Item | Value |")
    facts = dict(rows)
    assert facts["Metric"] == "BPF, mean of 3 conditions"
    assert facts["Protocol"] == "proposed \u2014 Matched relative speed at the sweet spot"
    assert facts["Ball"] == "collegiate baseball"
    assert facts["Date"] == "2025-03-14 09:26:53 UTC"


def test_row_per_condition(md):
    result = sample_result()
    headers, rows = table_after(md, "| Condition | Set-up |")
    assert [r[0] for r in rows] == [c.name for c in result.conditions]
    assert [r[1] for r in rows] == [c.setup for c in result.conditions]
    c = result.conditions[2]
    row = dict(zip(headers, rows[2], strict=True))
    assert row["Exit speed"] == f"{c.exit_speed:.2f} m/s ({c.exit_speed / 0.44704:.1f} mph)"
    assert row["Pitch speed (toward bat)"] == "30.0 m/s (67.1 mph)"

    headers, rows = table_after(md, "| Condition | COR e |")
    assert headers[-1] == "Metric: BPF"
    assert [r[0] for r in rows] == [c.name for c in result.conditions]
    bpf = headers.index("BPF")  # the metric columns follow the metric registry's order
    for row, c in zip(rows, result.conditions, strict=True):
        assert row[bpf] == f"{c.bpf:.4f}" and row[-1] == f"{c.metric_value:.4f}"

    headers, rows = table_after(md, "| Condition | Centre of percussion |")
    assert len(rows) == len(result.conditions)


def test_input_hashes(md):
    for f in sample_result().inputs:
        assert f"- {f.role} `{f.name}`: `{f.sha256}` ({f.path})" in md


def test_warnings(md):
    assert "## Warnings" in md
    assert "> **\u26a0 Warning:** watch the window edge" in md


def test_no_warnings_section():
    assert "## Warnings" not in render_markdown(sample_result())


def test_several_warnings_stay_in_one_quote():
    md = render_markdown(sample_result(warnings=["first\nline two", "second <b>"]))
    block = md.split("## Warnings\n\n")[1].split("\n\n")[0].splitlines()
    assert block == ["> **\u26a0 Warning:** first line two", ">",
                     "> **\u26a0 Warning:** second \\<b\\>"]


def test_engine_extras(md):
    headers, rows = table_after(md, "| Setting or diagnostic | Value | Unit |")
    diag = {k: (v, unit) for k, v, unit in rows}
    assert "modes_hz" not in diag  # the modes have their own table, with their nodes
    assert diag["barrel.model"] == ("solid", "")
    assert diag["barrel.hoop_frequency_hz"] == ("\u2014", "Hz")  # None
    headers, rows = table_after(md, "| Mode | Frequency \\[Hz\\] | Nodes \\[cm from knob\\] |")
    assert [r[1] for r in rows] == ["172", "572", "1181", "1851"]


def test_special_characters_do_not_break_tables():
    result = sample_result()
    result.conditions[0].name = "a | b *c* `d`"
    result.bat = "# not a heading <b>"
    md = render_markdown(result)
    headers, rows = table_after(md, "| Condition | Set-up |")
    assert rows[0][0] == r"a \| b \*c\* \`d\`"
    assert md.startswith("# Predicted bat performance: \\# not a heading \\<b\\>\n")


def test_helpers():
    assert md_text("# heading") == "\\# heading"
    assert md_text("a  \n b") == "a b"
    assert md_cell("x|y") == "x\\|y"
    assert md_cell("") == " "
    assert md_cell("snake_case") == "snake_case"
    assert md_cell("_emph_") == "\\_emph\\_"


def test_md_table_alignment():
    from batcert.reports.table import Table
    text = md_table(Table(["A", "B"], [["x", "1"]], numeric=[False, True]))
    assert text.splitlines() == ["| A | B |", "|:---|---:|", "| x | 1 |"]


def test_render_dispatch_matches(md):
    assert render(sample_result(limit=1.05, warnings=["watch the window edge"]), "md") == md
