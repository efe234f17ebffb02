"""A bat made for one game run under a protocol of the other (issue 40, item 14c): one warning
line naming the bat, the protocol and the mismatch; none when the games agree or the bat file
does not say its game."""

from __future__ import annotations

import pytest
from edits import edited
from jsonout import result as result_of
from terminal_lines import items

from batcert.specs.resolve import resolve

SLOWPITCH = "Slow-pitch composite double-wall 34 in (typical, assumed)"


def _warnings(batcert_cli, bat, protocol):
    res = batcert_cli("run", bat, "-p", protocol, "--engine", "rigid", "--json", "--no-reports")
    assert res.exit_code in (0, 1), res.stderr
    return result_of(res.stdout, "run")["warnings"], res.stderr


def test_a_softball_bat_under_a_baseball_protocol_warns_once(batcert_cli):
    warnings, stderr = _warnings(batcert_cli, "slowpitch-composite-34", "ncaa-bbcor")
    expected = (f"bat {SLOWPITCH!r} is a softball bat, but protocol 'ncaa-bbcor' tests with a "
                "baseball (Collegiate baseball): a bat is certified with its own game's ball")
    assert [w for w in warnings if "softball bat" in w] == [expected]
    # one warning on the terminal (wrapped at its width: issue 40, item 13)
    assert [w for w in items(stderr) if "softball bat" in w] == [f"  warning: {expected}"]


@pytest.mark.parametrize("bat, protocol", [
    ("slowpitch-composite-34", "softball-bpf"),
    ("ash-34", "ncaa-bbcor"),
])
def test_a_bat_under_its_own_games_protocol_does_not(batcert_cli, bat, protocol):
    warnings, _ = _warnings(batcert_cli, bat, protocol)
    assert not [w for w in warnings if " bat, but protocol " in w]


def test_a_baseball_bat_under_a_softball_protocol_warns(batcert_cli):
    warnings, _ = _warnings(batcert_cli, "ash-34", "softball-bpf")
    assert [w for w in warnings if "is a baseball bat, but protocol 'softball-bpf' tests with a "
            "softball" in w]


def test_a_bat_file_that_does_not_say_its_game_does_not(batcert_cli, tmp_path):
    bat = edited(tmp_path, resolve("bat", "slowpitch-composite-34"), ("body: softball\n", ""))
    warnings, _ = _warnings(batcert_cli, bat, "ncaa-bbcor")
    assert not [w for w in warnings if " bat, but protocol " in w]
