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

SUFFIX = {"md": ".md", "html": ".html", "json": ".json"}


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


def _write(texts: dict[Path, str]) -> list[Path]:
    """Write every rendered text atomically (all are rendered before the first write)."""
    from batcert.reports.write import atomic_write_text
    for path, text in texts.items():
        path.parent.mkdir(parents=True, exist_ok=True)
        atomic_write_text(path, text)
    return list(texts)


def write_comparison_reports(result: ComparisonResult, out_dir: Path,
                             formats: Sequence[str] = ("md", "html", "json")) -> list[Path]:
    render = {"md": render_comparison_markdown, "html": render_comparison_html,
              "json": lambda r: r.to_json() + "\n"}
    stem = comparison_stem(result)
    return _write({Path(out_dir) / f"{stem}{SUFFIX[f]}": render[f](result)
                   for f in dict.fromkeys(formats)})


def write_league_reports(result: LeagueResult, out_dir: Path,
                         formats: Sequence[str] = ("md", "html", "json")) -> list[Path]:
    render = {"md": render_league_markdown, "html": render_league_html,
              "json": lambda r: r.to_json() + "\n"}
    stem = league_stem(result)
    return _write({Path(out_dir) / f"{stem}{SUFFIX[f]}": render[f](result)
                   for f in dict.fromkeys(formats)})
