"""Warnings go to stderr in every mode (issue 24): the terminal view put them on stdout, and
with --json they were only inside the JSON; stdout now holds the results alone."""

from __future__ import annotations

import json

import pytest
from terminal_lines import items

# the rigid engine's BESR maximum lies on the search window's edge: one warning
RUN = ("run", "ash-34", "-p", "ncaa-besr", "--engine", "rigid", "--no-reports")


@pytest.mark.parametrize("as_json", [False, True])
def test_a_warning_goes_to_stderr(batcert_cli, as_json):
    res = batcert_cli(*RUN, *(["--json"] if as_json else []))
    assert "warning: pitched-and-swung: the located impact point lies on the search window" \
        in " ".join(res.stderr.split())
    assert "warning:" not in res.stdout
    if as_json:
        data = json.loads(res.stdout)  # stdout is the JSON alone
        assert any("search window" in w for w in data["results"][0]["warnings"])


def test_quiet_keeps_the_warning_in_the_json_only(batcert_cli):
    res = batcert_cli("-q", *RUN, "--json")
    assert "warning:" not in res.stderr and "warning:" not in res.stdout
    assert json.loads(res.stdout)["results"][0]["warnings"]


@pytest.mark.parametrize("command", [
    ("run", "ash-34", "-p", "proposed", "--engine", "rigid"),
    ("compare", "ash-34", "aluminium-34", "-p", "proposed", "--engine", "rigid"),
    ("league", "ncaa", "ash-34", "--engine", "rigid"),
])
def test_an_out_that_is_a_file_exits_4(batcert_cli, tmp_path, command):
    # documented: 4, the reports cannot be written (checked before any work); it was a usage
    # error (2) from the option's type
    blocker = tmp_path / "reports.txt"
    blocker.write_text("a file, not a folder")
    res = batcert_cli(*command, "--out", blocker)
    assert res.exit_code == 4, res.stderr
    assert "is not a directory" in res.stderr and blocker.read_text() == "a file, not a folder"


@pytest.mark.parametrize("flags", [("-q",), ("--quiet",), ("-v",), ("-vv",), ("--verbose",)])
def test_global_flags_work_after_the_subcommand(batcert_cli, flags):
    before = batcert_cli(*flags, *RUN)
    after = batcert_cli(*RUN, *flags)
    assert after.exit_code == before.exit_code == 0, after.stderr
    assert after.stdout == before.stdout
    if flags[0] in ("-q", "--quiet"):
        # the verdict, the value and the model's known offset for BESR (issue 40, item 11)
        assert "warning:" not in after.stderr and len(items(after.stdout)) == 3
        assert items(after.stdout)[2].lstrip().startswith("known offset of the model")
    else:
        assert "batcert: bat" in after.stderr  # the -v log


def test_a_flag_after_double_dash_is_left_alone(batcert_cli):
    # after "--" every word is an argument: "-q" names a bat here, which does not exist
    res = batcert_cli("run", "-p", "proposed", "--", "-q")
    assert res.exit_code == 2 and "-q" in res.stderr
