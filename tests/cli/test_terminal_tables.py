"""A number is never cut in any layout (issue 24): at 80 columns a run's table used to show BPF
as "0.97..." and the exit speed as "(172..."; a table wider than the terminal now shows each
row's cells one per line, in full."""

from __future__ import annotations

import io

import pytest
from rich.console import Console

from batcert import console
from batcert.reports.table import Table


def _wide_table() -> Table:
    heads = ["condition", "pitch\n[m/s]", "exit speed\n[m/s (mph)]", "COR", "BPF", "BESR",
             "BBCOR", "e_A", "sweet spot\n[m from pivot]", "COP\n[m from pivot]"]
    row = ["pitched-and-swung", "31.0", "76.97 m/s (172.2 mph)", "0.5261", "0.9765",
           "0.7828", "0.5261", "0.2828", "0.522", "0.538"]
    return Table(heads, [row, ["stationary-bat", *row[1:]]], numeric=[False] + [True] * 9)


@pytest.mark.parametrize("width", [60, 80, 200])
@pytest.mark.parametrize("on_terminal", [True, False])
def test_no_cell_is_ever_cut(monkeypatch, capsys, width, on_terminal):
    screen = io.StringIO()
    monkeypatch.setattr(console, "_terminal", lambda stream: on_terminal)
    monkeypatch.setattr(console, "_console", lambda stderr: Console(
        file=screen, width=width, highlight=False, emoji=False, markup=False))
    monkeypatch.setenv("COLUMNS", str(width))
    table = _wide_table()
    console.table(table, "conditions")
    shown = screen.getvalue() + capsys.readouterr().out
    assert "\u2026" not in shown and "..." not in shown
    for row in table.rows:
        for cell in row:
            assert cell in shown, (width, on_terminal, cell)
    assert max(len(line) for line in shown.splitlines()) <= width
