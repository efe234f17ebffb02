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
