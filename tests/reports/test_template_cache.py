"""The compiled-template cache (batcert.reports.templates): used when it can be, passed over in
silence when it cannot, never a cause of a failed report."""

from __future__ import annotations

import os

import pytest

from batcert.cache import cache_dir
from batcert.reports import templates


@pytest.fixture
def fresh(monkeypatch, tmp_path):
    """A fresh environment whose cache lives in ``tmp_path / "cache"``."""
    monkeypatch.setenv("BATCERT_CACHE_DIR", str(tmp_path / "cache"))
    templates.environment.cache_clear()
    yield tmp_path / "cache"
    templates.environment.cache_clear()


def render() -> str:
    """The reports' style sheet (a template without variables), through the environment."""
    return templates.environment().get_template("style.css.j2").render()


def test_a_render_leaves_the_compiled_template_in_the_cache(fresh):
    first = render()
    files = list(fresh.rglob("__jinja2_*"))
    assert len(files) == 1  # style.css.j2, compiled once
    templates.environment.cache_clear()
    stamp = files[0].stat().st_mtime_ns
    assert render() == first  # the second environment loads it and renders the same text
    assert files[0].stat().st_mtime_ns == stamp  # read, not written again


def test_an_unwritable_cache_is_passed_over(fresh, tmp_path):
    if os.geteuid() == 0:
        # root writes anywhere: make the cache's place a file instead, which no one can enter
        (tmp_path / "cache").write_text("not a directory")
    else:
        fresh.mkdir()
        fresh.chmod(0o500)
    assert cache_dir("templates") is None
    assert "font" in render()


def test_a_corrupt_cache_file_is_recompiled(fresh):
    first = render()
    (path,) = fresh.rglob("__jinja2_*")
    path.write_bytes(b"\x00garbage")
    templates.environment.cache_clear()
    assert render() == first


def test_a_cache_that_vanishes_between_runs_is_remade(fresh):
    render()
    for p in fresh.rglob("*"):
        if p.is_file():
            p.unlink()
    for p in sorted(fresh.rglob("*"), reverse=True):
        p.rmdir()
    fresh.rmdir()
    templates.environment.cache_clear()
    assert render()
    assert list(fresh.rglob("__jinja2_*"))
