"""docs/api.md is a doctest: every example on the page runs and prints what it shows, so the
page states what this version computes (the ash bat's BBCOR and its centre of percussion by
Eq. 4 among them); and examples/api_tour.py runs through the API alone."""

from __future__ import annotations

import doctest
import runpy
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]


def test_the_api_page_runs_as_written():
    failed, tried = doctest.testfile(str(REPO / "docs" / "api.md"), module_relative=False,
                                     optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    assert tried >= 15  # the page's examples were found
    assert failed == 0


def test_the_api_tour_runs(capsys):
    runpy.run_path(str(REPO / "examples" / "api_tour.py"), run_name="__main__")
    out = capsys.readouterr().out
    assert "BBCOR" in out and "sweep" in out and "comparison" in out


def test_the_top_level_names_are_the_apis():
    import batcert
    from batcert import api
    assert set(api.__all__) < set(dir(batcert))
    assert batcert.run is api.run


def test_a_result_prints_in_one_short_line():
    # the dataclass's own repr printed every condition's sweep samples: thousands of lines for
    # one run at the interpreter prompt
    import batcert
    result = batcert.run("ash-34", "ncaa-bbcor", engine="rigid")
    text = repr(result)
    assert "\n" not in text and len(text) < 200
    assert text.startswith("RunResult(bat='Ash 34 in") and "protocol='ncaa-bbcor'" in text
    assert f"value={result.value:.6g}" in text and "engine='rigid'" in text
    league = repr(batcert.league("ncaa", ["ash-34", "aluminium-34"], engine="rigid"))
    assert league.startswith("LeagueResult(league='ncaa', bats=[2]")
