"""write_reports / atomic_write_text: render everything first, then replace each file atomically."""

from __future__ import annotations

import os
import stat
from pathlib import Path

import pytest
from sample import sample_result, set_leftovers

from batcert.reports import html, markdown, write
from batcert.reports.linkset import SETS
from batcert.reports.write import SUFFIXES as FORMATS
from batcert.reports.write import atomic_write_text, render, write_reports
from batcert.reports.write import run_stem as default_stem
from batcert.results.run import RunResult

STEM = "ash-34-in-smith-2001--proposed"


@pytest.fixture
def result():
    return sample_result()


def names(directory: Path) -> set[str]:
    """The names a reader sees (dangling links of a set never switched in are not there);
    the folder of linked sets is batcert's own (batcert.reports.linkset)."""
    return {p.name for p in directory.iterdir() if p.name != SETS and (p.exists() or
                                                                        not p.is_symlink())}


def temp_files(directory: Path) -> list[str]:
    return set_leftovers(directory)


def break_renderer(monkeypatch: pytest.MonkeyPatch, fmt: str) -> None:
    def boom(result):
        raise RuntimeError(f"{fmt} renderer failed")

    if fmt == "json":
        monkeypatch.setattr(RunResult, "to_json", boom)
    else:
        module, name = {"md": (markdown, "run_markdown"), "html": (html, "run_html")}[fmt]
        monkeypatch.setattr(module, name, boom)


def test_default_stem_and_paths(result, tmp_path):
    assert default_stem(result) == STEM
    paths = write_reports(result, tmp_path, ("md", "html", "json", "md"))
    assert [p.name for p in paths] == [f"{STEM}.md", f"{STEM}.html", f"{STEM}.json"]
    assert names(tmp_path) == {p.name for p in paths}
    for p, fmt in zip(paths, ("md", "html", "json"), strict=True):
        assert p.read_text(encoding="utf-8") == render(result, fmt)


@pytest.mark.parametrize("broken", ["md", "html", "json"])
def test_renderer_error_writes_nothing(result, tmp_path, monkeypatch, broken):
    existing = {fmt: (tmp_path / f"{STEM}{FORMATS[fmt]}") for fmt in FORMATS}
    old = {fmt: f"old {fmt} report \u2713\n".encode() + bytes(range(256)) for fmt in FORMATS}
    for fmt, path in existing.items():
        path.write_bytes(old[fmt])
    before = {fmt: path.stat() for fmt, path in existing.items()}
    break_renderer(monkeypatch, broken)

    with pytest.raises(RuntimeError, match=f"{broken} renderer failed"):
        write_reports(result, tmp_path, ("md", "html", "json"))

    assert names(tmp_path) == {p.name for p in existing.values()}  # nothing new, no temp files
    for fmt, path in existing.items():
        assert path.read_bytes() == old[fmt]
        assert path.stat().st_mtime_ns == before[fmt].st_mtime_ns
        assert path.stat().st_ino == before[fmt].st_ino


def test_renderer_error_creates_no_directory(result, tmp_path, monkeypatch):
    break_renderer(monkeypatch, "json")
    out = tmp_path / "reports" / "nested"
    with pytest.raises(RuntimeError):
        write_reports(result, out)
    assert not (tmp_path / "reports").exists()


def test_no_temp_files_after_success(result, tmp_path):
    write_reports(result, tmp_path)
    write_reports(result, tmp_path)  # second time over existing files
    assert temp_files(tmp_path) == []
    assert len(names(tmp_path)) == 3


def test_replace_failure_cleans_up_and_keeps_old(result, tmp_path, monkeypatch):
    html = tmp_path / f"{STEM}.html"
    html.write_text("old html", encoding="utf-8")

    def failing_replace(src, dst):
        raise OSError("disk on fire")

    monkeypatch.setattr(write.os, "replace", failing_replace)
    with pytest.raises(OSError, match="disk on fire"):
        write_reports(result, tmp_path, ("html", "md"))
    assert temp_files(tmp_path) == []
    assert names(tmp_path) == {html.name}
    assert html.read_text(encoding="utf-8") == "old html"


def test_staging_failure_cleans_up_earlier_stages(result, tmp_path, monkeypatch):
    """The second file fails while being written: the first file's staged copy is removed too."""
    real_fdopen, calls = os.fdopen, []

    def fdopen(fd, *args, **kwargs):
        calls.append(fd)
        if len(calls) == 2:
            os.close(fd)
            raise OSError("no space left on device")
        return real_fdopen(fd, *args, **kwargs)

    monkeypatch.setattr(write.os, "fdopen", fdopen)
    with pytest.raises(OSError, match="no space"):
        write_reports(result, tmp_path, ("md", "html", "json"))
    assert names(tmp_path) == set()


def test_existing_report_is_replaced_whole(result, tmp_path):
    path = tmp_path / f"{STEM}.md"
    path.write_text("x" * 500_000, encoding="utf-8")  # longer than the new report
    os.chmod(path, 0o640)
    reader = path.open("rb")  # a reader that opened the old report keeps seeing all of it
    try:
        write_reports(result, tmp_path, ("md",))
        assert reader.read() == b"x" * 500_000
    finally:
        reader.close()
    new = path.read_text(encoding="utf-8")
    assert new == render(result, "md")
    assert "x" * 100 not in new
    assert stat.S_IMODE(path.stat().st_mode) == 0o640  # permissions of the old report kept


def test_new_report_gets_umask_permissions(result, tmp_path):
    umask = os.umask(0o022)
    try:
        [path] = write_reports(result, tmp_path, ("json",))
    finally:
        os.umask(umask)
    assert stat.S_IMODE(path.stat().st_mode) == 0o644


def test_out_dir_is_created(result, tmp_path):
    out = tmp_path / "a" / "b" / "reports"
    paths = write_reports(result, out)
    assert out.is_dir()
    assert sorted(p.name for p in paths) == sorted(names(out))
    assert all(p.parent == out for p in paths)


def test_out_dir_as_str(result, tmp_path):
    [path] = write_reports(result, str(tmp_path / "s"), ["md"])
    assert path.is_file()


@pytest.mark.parametrize("stem", ["", ".", "..", "a/b", "a\\b", "a\0b"])
def test_bad_stem_refused(result, tmp_path, stem):
    with pytest.raises(ValueError, match="plain file name"):
        write_reports(result, tmp_path / "out", ("md",), stem=stem)
    assert not (tmp_path / "out").exists()


def test_unknown_format_refused_before_rendering(result, tmp_path):
    with pytest.raises(ValueError, match="'pdf'"):
        write_reports(result, tmp_path / "out", ("md", "pdf"))
    assert not (tmp_path / "out").exists()
    with pytest.raises(ValueError, match="unknown report format"):
        render(result, "pdf")


def test_custom_stem(result, tmp_path):
    [path] = write_reports(result, tmp_path, ("html",), stem="certificate")
    assert path == tmp_path / "certificate.html"


# ---- atomic_write_text ----


def test_atomic_write_text_creates_and_replaces(tmp_path):
    path = tmp_path / "note.txt"
    assert atomic_write_text(path, "first \u2014 one\n") == path
    assert path.read_text(encoding="utf-8") == "first \u2014 one\n"
    atomic_write_text(str(path), "2")
    assert path.read_text(encoding="utf-8") == "2"
    assert names(tmp_path) == {"note.txt"}


def test_atomic_write_text_encoding(tmp_path):
    path = atomic_write_text(tmp_path / "l1.txt", "caf\u00e9", encoding="latin-1")
    assert path.read_bytes() == b"caf\xe9"


def test_atomic_write_text_keeps_old_file_when_replace_fails(tmp_path, monkeypatch):
    path = tmp_path / "report.html"
    path.write_bytes(b"old contents\n")

    def failing_replace(src, dst):
        raise PermissionError("replace refused")

    monkeypatch.setattr(write.os, "replace", failing_replace)
    with pytest.raises(PermissionError):
        atomic_write_text(path, "new contents")
    assert path.read_bytes() == b"old contents\n"
    assert names(tmp_path) == {"report.html"}


def test_atomic_write_text_keeps_old_file_when_write_fails_midway(tmp_path, monkeypatch):
    """The temporary file receives part of the data, then the write fails."""
    path = tmp_path / "report.md"
    path.write_bytes(b"old contents\n")
    real_fdopen = os.fdopen

    class HalfWriter:
        def __init__(self, fh):
            self.fh = fh

        def __enter__(self):
            return self

        def __exit__(self, *exc):
            self.fh.close()
            return False

        def write(self, data):
            self.fh.write(data[: len(data) // 2])
            self.fh.flush()
            raise OSError("device full")

        def __getattr__(self, name):
            return getattr(self.fh, name)

    def fdopen(fd, *args, **kwargs):
        return HalfWriter(real_fdopen(fd, *args, **kwargs))

    monkeypatch.setattr(write.os, "fdopen", fdopen)
    with pytest.raises(OSError, match="device full"):
        atomic_write_text(path, "new " * 10_000)
    assert path.read_bytes() == b"old contents\n"
    assert names(tmp_path) == {"report.md"}


def test_atomic_write_text_keeps_old_file_when_fsync_fails(tmp_path, monkeypatch):
    path = tmp_path / "report.json"
    path.write_bytes(b"{}\n")

    def failing_fsync(fd):
        raise OSError("I/O error")

    monkeypatch.setattr(write.os, "fsync", failing_fsync)
    with pytest.raises(OSError, match="I/O error"):
        atomic_write_text(path, '{"new": true}\n')
    assert path.read_bytes() == b"{}\n"
    assert names(tmp_path) == {"report.json"}


def test_atomic_write_text_interrupted(tmp_path, monkeypatch):
    """Even a KeyboardInterrupt between staging and replacing leaves no temporary file."""
    path = tmp_path / "report.md"
    path.write_bytes(b"old")

    def interrupted(src, dst):
        raise KeyboardInterrupt

    monkeypatch.setattr(write.os, "replace", interrupted)
    with pytest.raises(KeyboardInterrupt):
        atomic_write_text(path, "new")
    assert path.read_bytes() == b"old"
    assert names(tmp_path) == {"report.md"}


@pytest.mark.parametrize("fail_at", [1, 2, 3, 4])
def test_a_set_is_replaced_whole_or_not_at_all(result, tmp_path, monkeypatch, fail_at):
    # The set's journal is renamed into place (the commit point), then three staged reports
    # onto the old ones: four renames. Whichever fails, the old set is back whole and no
    # staged file, backup or journal is left.
    old = {fmt: f"old {fmt}" for fmt in FORMATS}
    for fmt, text in old.items():
        (tmp_path / f"{STEM}{FORMATS[fmt]}").write_text(text, encoding="utf-8")
    real_replace, calls = os.replace, []

    def replace(src, dst):
        calls.append((src, dst))
        if len(calls) == fail_at:
            raise OSError(28, "No space left on device")
        return real_replace(src, dst)

    monkeypatch.setattr(write.os, "replace", replace)
    with pytest.raises(write.OutputError, match="No space left on device"):
        write_reports(result, tmp_path, ("md", "html", "json"))
    monkeypatch.setattr(write.os, "replace", real_replace)
    assert temp_files(tmp_path) == []
    for fmt, text in old.items():
        assert (tmp_path / f"{STEM}{FORMATS[fmt]}").read_text(encoding="utf-8") == text


def test_a_directory_in_the_way_leaves_the_set_as_it_was(result, tmp_path):
    (tmp_path / f"{STEM}.md").write_text("old md", encoding="utf-8")
    (tmp_path / f"{STEM}.html").mkdir()
    with pytest.raises(write.OutputError, match="a directory is in the way"):
        write_reports(result, tmp_path)
    assert (tmp_path / f"{STEM}.md").read_text(encoding="utf-8") == "old md"
    assert not (tmp_path / f"{STEM}.json").exists() and temp_files(tmp_path) == []


@pytest.mark.parametrize("where", ["file", "under-file", "long-name", "proc"])
def test_check_output_dir_refuses_without_writing(tmp_path, where):
    regular = tmp_path / "a-file"
    regular.write_text("x")
    target = {"file": regular, "under-file": regular / "reports",
              "long-name": tmp_path / ("x" * 300), "proc": Path("/proc/batcert-reports")}[where]
    with pytest.raises(write.OutputError):
        write.check_output_dir(target)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a-file"]


def test_check_output_dir_creates_nothing(tmp_path):
    write.check_output_dir(tmp_path / "new" / "reports")
    assert list(tmp_path.iterdir()) == []
