"""benchmarks/compare_figures.py: two benchmark runs' figures side by side."""

from __future__ import annotations

from repo_script import load

compare_figures = load("benchmarks/compare_figures.py")


def test_nested_numbers_get_paths_and_text_is_left_out():
    data = {"batcert": "/usr/bin/batcert", "repeat": 9,
            "figures": {"run": {"median": 0.21, "min": 0.2}, "flag": True, "list": [1.5]}}
    assert compare_figures.numbers(data) == {"repeat": 9.0, "figures/run/median": 0.21,
                                             "figures/run/min": 0.2, "figures/list/0": 1.5}


def test_shared_figures_get_a_ratio_and_the_rest_are_listed_apart():
    lines = compare_figures.compare({"a": 2.0, "b": 1.0, "zero": 0.0},
                                    {"a": 3.0, "c": 4.0, "zero": 1.0})
    body = {line.split()[0]: line.split()[1:] for line in lines[1:]}
    assert body["a"] == ["2", "3", "1.500"]
    assert body["zero"] == ["0", "1", "-"]
    assert body["b"] == ["only", "before:", "1"] and body["c"] == ["only", "after:", "4"]
