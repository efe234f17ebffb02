"""Comparison and league reports: rendering entry points and atomic writing.

Markdown lives in :mod:`batcert.reports.compare_markdown`, the styled HTML in
:mod:`batcert.reports.compare_html`; this module names the files and writes them (every format is
rendered before the first file is written, each file is replaced atomically).
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

from batcert.compare import ComparisonResult
from batcert.league import LeagueResult
from batcert.reports.compare_html import render_comparison_html, render_league_html
from batcert.reports.compare_markdown import (  # noqa: F401
    VERDICT_TEXT,
    limit_text,
    margin_text,
    metric_text,
    render_comparison_markdown,
    render_league_markdown,
    rule_value_text,
)

# ---------------------------------------------------------------- writing


def _slug(text: str) -> str:
    from batcert.reports.write import slugify
    return slugify(text)


def comparison_stem(result: ComparisonResult) -> str:
    """``compare--<study>`` or ``compare--<protocol ids>``, then the bats' file stems."""
    what = result.study or "+".join(p.protocol for p in result.protocols)
    bats = "+".join(Path(b.path).stem for b in result.bats)
    return _stem("compare", what, bats)


def league_stem(result: LeagueResult) -> str:
    return _stem("league", result.league, "+".join(Path(b.path).stem for b in result.bats))


def _stem(kind: str, what: str, bats: str) -> str:
    stem = f"{kind}--{_slug(what)}--{_slug(bats)}"
    if len(stem) > 120:  # keep file names short; the hash keeps different inputs apart
        import hashlib
        stem = stem[:100] + "-" + hashlib.sha256(stem.encode()).hexdigest()[:10]
    return stem


def _write(result, out_dir: Path, formats: Sequence[str], stem: str, markdown, html) -> list[Path]:
    """Render every format first, then write them together (:func:`write.write_texts`)."""
    from batcert.reports.write import FORMATS, write_texts
    render = {"md": markdown, "html": html, "json": lambda r: r.to_json() + "\n"}
    return write_texts({Path(out_dir) / f"{stem}{FORMATS[f][0]}": render[f](result)
                        for f in dict.fromkeys(formats)})


def write_comparison_reports(result: ComparisonResult, out_dir: Path,
                             formats: Sequence[str] = ("md", "html", "json")) -> list[Path]:
    return _write(result, out_dir, formats, comparison_stem(result), render_comparison_markdown,
                  render_comparison_html)


def write_league_reports(result: LeagueResult, out_dir: Path,
                         formats: Sequence[str] = ("md", "html", "json")) -> list[Path]:
    return _write(result, out_dir, formats, league_stem(result), render_league_markdown,
                  render_league_html)
