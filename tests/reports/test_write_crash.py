"""A report set survives kill -9 at every step of its writing: a reader finds the whole old set
or the whole new set at once, before anyone mends anything (the set is switched in one step,
batcert.reports.linkset; issue 40, item 7: a reader saw old and new files side by side until
the next run), and the next writer removes what the crash left.

Each case runs a writer in a child process whose file-system calls are counted; at the chosen
call the child kills itself with SIGKILL (no handler, no cleanup runs). The cases cover every
call a write makes, from the first staged file to the journal's removal.
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest
from sample import set_leftovers

from batcert.reports import fileset
from batcert.reports.write import atomic_write_text

pytestmark = pytest.mark.skipif(sys.platform == "win32", reason="POSIX signals")

NAMES = ("r.md", "r.html", "r.json")
OLD = {n: f"old {n}\n" for n in NAMES}
NEW = {n: f"new {n}\n" * 50 for n in NAMES}

CHILD = textwrap.dedent("""
    import os, signal, sys
    from pathlib import Path
    from batcert.reports import fileset
    kill_at, directory, new = int(sys.argv[1]), Path(sys.argv[2]), sys.argv[3:]
    calls = 0
    def counted(real):
        def call(*args, **kwargs):
            global calls
            calls += 1
            if calls == kill_at:
                os.kill(os.getpid(), signal.SIGKILL)
            return real(*args, **kwargs)
        return call
    for name in ("replace", "unlink", "link", "fsync", "chmod", "open"):
        setattr(os, name, counted(getattr(os, name)))
    files = {n: t.encode() for n, t in zip(new[0::2], new[1::2])}
    fileset.write_set(directory, files, {n: 0o644 for n in files})
    print(calls)
""")


def write_in_child(directory: Path, kill_at: int, texts: dict[str, str]) -> subprocess.CompletedProcess:
    args = [a for name, text in texts.items() for a in (name, text)]
    return subprocess.run([sys.executable, "-c", CHILD, str(kill_at), str(directory), *args],
                          capture_output=True, text=True, timeout=60)


def visible(directory: Path) -> dict[str, str]:
    """What a reader finds: the files it can open (a link whose set was never switched in
    cannot be opened, as a file not yet written)."""
    return {p.name: p.read_text() for p in directory.iterdir()
            if not p.name.startswith(".") and p.exists()}


def hidden(directory: Path) -> list[str]:
    return set_leftovers(directory)


def calls_of_a_whole_write(tmp_path: Path, old: bool) -> int:
    d = tmp_path / "count"
    d.mkdir()
    if old:
        for n, t in OLD.items():
            (d / n).write_text(t)
    done = write_in_child(d, 0, NEW)
    assert done.returncode == 0, done.stderr
    assert visible(d) == NEW and hidden(d) == []
    return int(done.stdout)


@pytest.mark.parametrize("old", [True, False], ids=["over-an-old-set", "new-set"])
def test_kill_9_at_every_step_leaves_a_whole_set_after_recovery(tmp_path, old):
    steps = calls_of_a_whole_write(tmp_path, old)
    assert steps > 20  # staging, links, journal, renames, removals, fsyncs
    before = OLD if old else {}
    outcomes = set()
    for kill_at in range(1, steps + 1):
        d = tmp_path / f"k{kill_at}"
        d.mkdir()
        for n, t in before.items():
            (d / n).write_text(t)
        child = write_in_child(d, kill_at, NEW)
        assert child.returncode == -signal.SIGKILL, (kill_at, child.stderr)
        assert visible(d) in (before, NEW), f"killed at call {kill_at}: a reader sees a mix"
        fileset.recover(d)
        after = visible(d)
        assert after in (before, NEW), f"killed at call {kill_at} of {steps}: a mixed set"
        assert hidden(d) == [], f"killed at call {kill_at}: leftovers {hidden(d)}"
        outcomes.add("new" if after == NEW else "old")
    assert outcomes == {"old", "new"}  # the commit point is inside the range


def test_the_next_report_write_mends_a_crashed_set(tmp_path):
    """Not an explicit recovery: writing any other report into the directory finishes it."""
    steps = calls_of_a_whole_write(tmp_path, True)
    for kill_at in range(1, steps + 1):
        d = tmp_path / f"k{kill_at}"
        d.mkdir()
        for n, t in OLD.items():
            (d / n).write_text(t)
        write_in_child(d, kill_at, NEW)
        atomic_write_text(d / "other.md", "another report\n")
        after = visible(d)
        assert after.pop("other.md") == "another report\n"
        assert after in (OLD, NEW) and hidden(d) == [], kill_at


def test_leftovers_of_the_old_writer_are_removed_and_nothing_else(tmp_path):
    # batcert 0.2 staged ".<report>.<8 chars>.tmp" and set aside ".<report>.<8 chars>.bak"
    stale = [".ash--proposed.html.k2j_9x0a.tmp", ".ash--proposed.md.0abcdefg.bak",
             ".r.md.batcert-0123abcd.tmp", ".batcert-probe.abcd_123.tmp",
             ".batcert-set.0123abcd.journal", ".batcert-set.0123abcd.journal.tmp"]
    kept = [".gitignore", ".notes.txt.abcdefgh.tmp", "data.csv.abcdefgh.tmp", ".hidden",
            "report.md"]
    for name in stale + kept:
        (tmp_path / name).write_text("x")
    fileset.recover(tmp_path)
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted(kept)


def test_a_journal_not_ours_or_damaged_is_not_acted_on(tmp_path):
    (tmp_path / "r.md").write_text("old")
    (tmp_path / ".r.md.batcert-0123abcd.tmp").write_text("staged")
    (tmp_path / ".batcert-set.0123abcd.journal").write_text(json.dumps(
        {"format": "batcert-fileset/1", "state": "commit",
         "entries": [{"target": "../escape", "staged": ".r.md.batcert-0123abcd.tmp",
                      "backup": None}]}))
    fileset.recover(tmp_path)
    assert (tmp_path / "r.md").read_text() == "old"
    assert not (tmp_path.parent / "escape").exists()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["r.md"]


def test_concurrent_writers_take_turns(tmp_path):
    """Two processes write their own full sets into one directory twenty times each: the
    directory always ends holding one writer's whole set and no leftovers."""
    script = textwrap.dedent("""
        import sys
        from pathlib import Path
        from batcert.reports import fileset
        who, d = sys.argv[1], Path(sys.argv[2])
        for i in range(20):
            files = {n: f"{who} {i} {n}".encode() * 200 for n in ("a.md", "a.html", "a.json")}
            fileset.write_set(d, files, {n: 0o644 for n in files})
    """)
    procs = [subprocess.Popen([sys.executable, "-c", script, who, str(tmp_path)])
             for who in ("one", "two")]
    assert [p.wait(timeout=120) for p in procs] == [0, 0]
    texts = {p.name: p.read_bytes() for p in tmp_path.iterdir() if p.is_file()}
    assert sorted(texts) == ["a.html", "a.json", "a.md"]
    heads = {t.split(b" ")[0] + t.split(b" ")[1] for t in texts.values()}
    assert len(heads) == 1  # every file from the same writer's same round


def test_a_rename_refused_after_the_commit_point_rolls_back(tmp_path, monkeypatch):
    for n, t in OLD.items():
        (tmp_path / n).write_text(t)
    real, calls = os.replace, []

    def replace(src, dst):
        calls.append(dst)
        if len(calls) == 3:  # the journal, one report, then this one
            raise PermissionError(13, "Permission denied")
        return real(src, dst)

    monkeypatch.setattr(os, "replace", replace)
    with pytest.raises(PermissionError):
        fileset.write_set(tmp_path, {n: t.encode() for n, t in NEW.items()},
                          {n: 0o644 for n in NEW})
    assert visible(tmp_path) == OLD and hidden(tmp_path) == []


def test_a_sets_folder_that_is_a_link_is_not_followed(tmp_path):
    # a `.batcert-sets` planted as a link to another folder: the set is written by the journal
    # instead, and nothing is written where the link points
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    d = tmp_path / "d"
    d.mkdir()
    (d / ".batcert-sets").symlink_to(elsewhere)
    fileset.write_set(d, {n: t.encode() for n, t in NEW.items()}, {n: 0o644 for n in NEW})
    assert visible(d) == NEW and list(elsewhere.iterdir()) == []
    assert all(not (d / n).is_symlink() for n in NEW)


def test_rewriting_one_format_keeps_the_others_of_the_set(tmp_path):
    fileset.write_set(tmp_path, {n: t.encode() for n, t in OLD.items()}, {n: 0o644 for n in OLD})
    assert all((tmp_path / n).is_symlink() for n in OLD)  # linked through the set's one link
    two = {"r.md": b"md 2\n", "r.json": b"json 2\n"}
    fileset.write_set(tmp_path, two, {n: 0o644 for n in two})
    assert visible(tmp_path) == {"r.md": "md 2\n", "r.json": "json 2\n", "r.html": OLD["r.html"]}
    assert hidden(tmp_path) == []
