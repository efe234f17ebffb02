"""The installed command's exit (batcert.cli.entry): the interpreter's teardown is skipped, and
everything an exit must do still happens: exit codes, flushed output, atexit handlers, other
threads finished."""

from __future__ import annotations

import os
import subprocess
import sys
import textwrap

import pytest

import batcert.cli as cli


def _entry(tmp_path, argv: list[str], before: str = "") -> subprocess.CompletedProcess:
    """``batcert ARGV`` through :func:`batcert.cli.entry` in a fresh process, after the Python
    lines ``before``."""
    script = tmp_path / "entry.py"
    script.write_text(textwrap.dedent(before) + "\nimport sys\nfrom batcert.cli import entry\n"
                      f"sys.argv = ['batcert', *{argv!r}]\nentry()\n")
    env = {k: v for k, v in os.environ.items() if k != "PYTHONUNBUFFERED"}  # buffered, as usual
    return subprocess.run([sys.executable, str(script)], capture_output=True, text=True,
                          timeout=300, cwd=tmp_path, env=env)


def test_exit_code_and_piped_output_survive(tmp_path):
    # the verdict's exit code (1: aluminium-34's predicted BBCOR about 0.56 fails 0.500) and
    # every byte of a piped stdout, which is block-buffered and lost if the exit skipped the flush
    proc = _entry(tmp_path, ["run", "aluminium-34", "-p", "ncaa-bbcor", "--json"])
    assert proc.returncode == 1, proc.stderr
    assert proc.stdout.rstrip().endswith("}") and '"verdict": "fail"' in proc.stdout


def test_buffered_output_is_flushed(tmp_path):
    # text left in stdout's pipe buffer (batcert's console and click flush their own; an
    # exit handler's output, written after them, is flushed only by the exit)
    proc = _entry(tmp_path, ["--version"], before="""
        import atexit, sys
        atexit.register(sys.stdout.write, "written at exit")
        """)
    assert proc.returncode == 0
    assert proc.stdout.startswith("batcert") and proc.stdout.endswith("written at exit")


def test_usage_error_keeps_exit_code_2(tmp_path):
    proc = _entry(tmp_path, ["run", "ash-34", "-p", "no-such-protocol"])
    assert proc.returncode == 2 and "no-such-protocol" in proc.stderr


def test_atexit_handlers_still_run(tmp_path):
    proc = _entry(tmp_path, ["--version"], before="""
        import atexit, pathlib
        atexit.register(pathlib.Path("atexit-ran").write_text, "yes")
        """)
    assert proc.returncode == 0 and "batcert" in proc.stdout
    assert (tmp_path / "atexit-ran").read_text() == "yes"


def test_a_live_thread_is_waited_for(tmp_path):
    # a non-daemon thread still working at the end gets the interpreter's normal exit
    proc = _entry(tmp_path, ["--version"], before="""
        import pathlib, threading, time
        def late():
            time.sleep(0.5)
            pathlib.Path("thread-finished").write_text("yes")
        threading.Thread(target=late).start()
        """)
    assert proc.returncode == 0
    assert (tmp_path / "thread-finished").read_text() == "yes"


@pytest.mark.parametrize(("code", "status", "stderr"),
                         [(None, 0, ""), (0, 0, ""), (3, 3, ""), (130, 130, ""),
                          ("bad things", 1, "bad things\n")])
def test_status_as_the_interpreter_gives_it(monkeypatch, capsys, code, status, stderr):
    # sys.exit's argument becomes the process status exactly as the interpreter maps it
    class Exited(Exception):
        pass

    def fake_exit(value):
        raise Exited(value)

    monkeypatch.setattr("os._exit", fake_exit)
    monkeypatch.setattr("threading.active_count", lambda: 1)
    monkeypatch.setattr("atexit._run_exitfuncs", lambda: None)  # not pytest's own handlers
    with pytest.raises(Exited) as exited:
        cli._exit_now(code)
    assert exited.value.args == (status,)
    assert capsys.readouterr().err == stderr
