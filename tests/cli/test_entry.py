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


def _launch(tmp_path, argv: list[str], before: str) -> subprocess.CompletedProcess:
    """``batcert ARGV`` through the installed command's first lines (:func:`batcert.launch.entry`)
    in a fresh process, after the Python lines ``before``."""
    script = tmp_path / "launch.py"
    script.write_text(textwrap.dedent(before) + "\nimport sys\nimport batcert.launch as launch\n"
                      "launch._load_cli = globals().get('load_cli', launch._load_cli)\n"
                      f"sys.argv = ['batcert', *{argv!r}]\nlaunch.entry()\n")
    return subprocess.run([sys.executable, str(script)], capture_output=True, text=True,
                          timeout=300, cwd=tmp_path)


def test_ctrl_c_while_the_command_line_loads_is_one_line_and_130(tmp_path):
    # a Ctrl-C in the first tenth of a second, while click, rich and the commands are imported:
    # it was a Python traceback (KeyboardInterrupt in an import)
    proc = _launch(tmp_path, ["--version"], before="""
        import os, signal, time
        def load_cli():
            os.kill(os.getpid(), signal.SIGINT)
            time.sleep(5)
            raise AssertionError("the interrupt did not end the process")
        """)
    assert proc.returncode == 130
    assert proc.stderr == "error: interrupted\n" and proc.stdout == ""


def test_ctrl_c_while_arguments_are_parsed_is_130_not_aborted(tmp_path):
    # an interrupt outside a command's guard (here while click parses the arguments): click
    # printed "Aborted!" and exited 1, the code for "a verdict fails"
    proc = _launch(tmp_path, ["protocols"], before="""
        import click
        def interrupted(self, ctx, args):
            raise KeyboardInterrupt
        click.Group.parse_args = interrupted
        """)
    assert proc.returncode == 130, proc.stderr
    assert "Aborted" not in proc.stderr and "Traceback" not in proc.stderr
    assert [line for line in proc.stderr.splitlines() if line.strip()] == ["error: interrupted"]


def test_the_installed_command_starts_with_the_interrupt_guard():
    # pyproject's script is batcert.launch:entry, so the guard is in place before anything loads
    import tomllib
    from pathlib import Path
    project = tomllib.loads((Path(__file__).parents[2] / "pyproject.toml").read_text())
    assert project["project"]["scripts"]["batcert"] == "batcert.launch:entry"


@pytest.mark.parametrize("given, expected", [(None, "1"), ("2", "2")])
def test_the_command_runs_blas_on_one_thread_unless_told(tmp_path, given, expected):
    # the engine's small matrix products with the multithreaded BLAS's default threads took
    # 3.5-4.3x as long on a busy 2-core machine (docs/performance.md); a user's own setting wins
    script = tmp_path / "threads.py"
    script.write_text("import os, sys\nfrom batcert import launch\n"
                      "launch._load_cli = lambda: lambda: print(os.environ['OPENBLAS_NUM_THREADS'],"
                      " os.environ['OMP_NUM_THREADS'], os.environ['MKL_NUM_THREADS'], "
                      "'numpy' in sys.modules)\nlaunch.entry()\n")
    env = {k: v for k, v in os.environ.items() if not k.endswith("_NUM_THREADS")}
    if given is not None:
        env.update(OPENBLAS_NUM_THREADS=given, OMP_NUM_THREADS=given, MKL_NUM_THREADS=given)
    proc = subprocess.run([sys.executable, str(script)], capture_output=True, text=True,
                          timeout=60, cwd=tmp_path, env=env)
    # numpy not loaded before the entry sets them: BLAS reads them when numpy loads
    assert proc.stdout.split() == [expected] * 3 + ["False"], proc.stderr
