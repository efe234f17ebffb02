"""The cache directory as a user meets it on the command line (issue 40, items 1 and 2): damaged
entries are recomputed with one warning line and the same numbers; a cache directory pointed at
a user's folder leaves every file in it as it was."""

from __future__ import annotations

import json

import pytest
from terminal_lines import items

from batcert import workspace

BAT = "bbcor-alloy-34"  # hollow: its run keeps modes, a barrel shell and ball tables on disk


def _run(batcert_cli):
    workspace.current().clear()  # the process forgets: the run reads the cache directory
    return batcert_cli("run", BAT, "-p", "ncaa-bbcor", "--json", "--no-reports")


def _numbers(result):
    (data,) = json.loads(result.stdout)["results"]
    return data["value"], [c["exit_speed"] for c in data["conditions"]]


@pytest.fixture
def cache(tmp_path, monkeypatch):
    root = tmp_path / "cache"
    monkeypatch.setenv("BATCERT_CACHE_DIR", str(root))
    return root


def test_damaged_entries_are_recomputed_with_one_warning_each(batcert_cli, cache):
    clean = _run(batcert_cli)
    entries = sorted(cache.glob("*/*.arrays"))
    assert len(entries) >= 2, entries
    for path in entries:  # one flipped bit near the end of each (inside its checksummed body)
        data = bytearray(path.read_bytes())
        data[-100] ^= 0x01
        path.write_bytes(bytes(data))
    damaged = _run(batcert_cli)
    assert damaged.exit_code == clean.exit_code, damaged.stderr
    assert _numbers(damaged) == _numbers(clean)
    said = [line for line in items(damaged.stderr) if "is damaged" in line]
    assert sorted(said) == sorted(set(said)) and len(said) == len(entries), damaged.stderr
    assert all(line.startswith("  warning: cache entry ") for line in said)
    assert "Traceback" not in damaged.stderr
    again = _run(batcert_cli)  # replaced: read without a word
    assert _numbers(again) == _numbers(clean) and "damaged" not in again.stderr


def test_a_cache_directory_set_to_a_project_folder_is_left_alone(batcert_cli, tmp_path, monkeypatch):
    project = tmp_path / "project"
    (project / "modes").mkdir(parents=True)
    mine = {project / "README.md": "# my project\n", project / "modes" / "notes.txt": "keep me"}
    for f, text in mine.items():
        f.write_text(text)
    monkeypatch.setenv("BATCERT_CACHE_DIR", str(project))
    result = _run(batcert_cli)
    assert result.exit_code in (0, 1), result.stderr
    assert "holds files batcert did not write: caching is off" in result.stderr
    assert all(f.read_text() == text for f, text in mine.items())
    assert sorted(p.relative_to(project).as_posix() for p in project.rglob("*")) == [
        "README.md", "modes", "modes/notes.txt"]


def _fill(root):
    """Two kinds of entries made by the cache itself, a user's file and a link among them."""
    import numpy as np

    from batcert.cache import ArrayStore
    for kind, key in (("modes", "a"), ("modes", "b"), ("barrels", "c")):
        ArrayStore(kind, code=("batcert.cache",)).save(key, {"x": np.arange(1000.0)})
    outside = root.parent / "outside.txt"
    outside.write_text("not batcert's")
    (root / "modes" / "notes.txt").write_text("keep me")
    (root / "modes" / ("e" * 32 + ".arrays")).symlink_to(outside)
    return outside


def test_cache_shows_folder_size_entries_and_bound(batcert_cli, cache):
    """Issue 40, item 14d: `batcert cache` (and `cache show`) says where the cache is, how
    large, its entries per kind and the bound on each."""
    empty = batcert_cli("cache")
    assert empty.exit_code == 0 and "not made yet" in empty.stdout and not cache.exists()
    _fill(cache)
    shown = batcert_cli("cache", "show")
    assert shown.exit_code == 0, shown.stderr
    assert str(cache) in shown.stdout and "256.0 MiB per kind" in shown.stdout
    assert all(len(line) <= 80 for line in shown.stdout.splitlines() if str(cache) not in line)
    (data,) = json.loads(batcert_cli("cache", "show", "--json").stdout)["results"]
    kinds = {k["kind"]: k for k in data["kinds"]}
    assert data["batcerts"] and data["entries"] == 3 and data["root"] == str(cache)
    assert (kinds["modes"]["entries"], kinds["modes"]["other_files"]) == (2, 1)
    assert kinds["barrels"]["entries"] == 1 and kinds["barrels"]["limit"] == 256 * 2**20
    assert data["bytes"] == sum(p.stat().st_size for p in cache.glob("*/*.arrays")
                                if not p.is_symlink())


def test_cache_clear_deletes_only_batcerts_own_entries(batcert_cli, cache):
    outside = _fill(cache)
    result = batcert_cli("cache", "clear")
    assert result.exit_code == 0, result.stderr
    assert result.stdout.startswith("removed 3 entries")
    assert sorted(p.relative_to(cache).as_posix() for p in cache.rglob("*")) == [
        "CACHEDIR.TAG", "barrels", "modes", "modes/" + "e" * 32 + ".arrays", "modes/notes.txt"]
    assert outside.read_text() == "not batcert's"


def test_cache_clear_refuses_a_folder_that_is_not_batcerts(batcert_cli, tmp_path, monkeypatch):
    project = tmp_path / "project"
    (project / "modes").mkdir(parents=True)
    entry = project / "modes" / ("a" * 32 + ".arrays")  # a batcert name, but not its folder
    entry.write_text("mine")
    monkeypatch.setenv("BATCERT_CACHE_DIR", str(project))
    result = batcert_cli("cache", "clear")
    assert result.exit_code == 3 and "not batcert's cache" in result.stderr
    assert entry.read_text() == "mine"
