"""The JSON report: a lossless RunResult that follows the documented contract."""

from __future__ import annotations

import json
import math

import pytest
from sample import sample_result

from batcert.reports.write import render
from batcert.results.run import ConditionResult, RunResult, Sweep

TOP_KEYS = {"protocol", "metric", "value", "limit", "verdict", "conditions"}
CONDITION_KEYS = {"name", "pitch_speed", "bat_angular_speed", "impact_location", "exit_speed",
                  "bat_angular_speed_after", "cor", "bpf", "besr", "bbcor",
                  "collision_efficiency", "sweep"}


@pytest.mark.parametrize("kwargs", [
    {}, {"limit": 0.95}, {"limit": None}, {"metric": "exit-speed", "limit": 50.0},
    {"warnings": ["edge \u26a0", "<b> & \"quotes\""]}, {"extras": {}},
])
def test_round_trip(kwargs):
    result = sample_result(**kwargs)
    text = render(result, "json")
    assert text.endswith("}\n")
    back = RunResult.from_dict(json.loads(text))
    assert back == result
    assert render(back, "json") == text  # stable when re-rendered from a saved results JSON
    assert isinstance(back.conditions[0], ConditionResult)
    assert isinstance(back.conditions[0].sweep, Sweep)


def test_contract_keys():
    data = json.loads(render(sample_result(), "json"))
    assert TOP_KEYS <= set(data)
    assert data["protocol"] == "proposed" and data["metric"] == "bpf"
    assert data["verdict"] == "pass" and data["limit"] == 1.05
    assert isinstance(data["value"], float)
    assert len(data["conditions"]) == 3
    for cond in data["conditions"]:
        assert CONDITION_KEYS <= set(cond)
        for key in CONDITION_KEYS - {"name", "sweep"}:
            assert isinstance(cond[key], float) and math.isfinite(cond[key]), key
        sweep = cond["sweep"]
        assert {"impact_location", "exit_speed"} <= set(sweep)
        assert len(sweep["impact_location"]) == len(sweep["exit_speed"]) > 1
        assert len(sweep["metric"]) == len(sweep["impact_location"])
        assert sweep["impact_location"] == sorted(sweep["impact_location"])
    assert [i["role"] for i in data["inputs"]] == ["bat", "protocol", "ball"]
    assert all(len(i["sha256"]) == 64 for i in data["inputs"])


def test_no_limit_is_null():
    data = json.loads(render(sample_result(limit=None), "json"))
    assert data["limit"] is None and data["verdict"] is None and data["margin"] is None
    assert TOP_KEYS <= set(data)


def test_strict_json():
    """No NaN or Infinity tokens: the output is standard JSON any parser accepts."""
    text = render(sample_result(), "json")

    def refuse(token):
        raise AssertionError(f"non-standard JSON constant {token}")

    json.loads(text, parse_constant=refuse)
    result = sample_result()
    result.conditions[0].sweep.exit_speed[3] = math.nan
    with pytest.raises(ValueError):
        render(result, "json")


def test_from_dict_ignores_unknown_keys():
    data = json.loads(render(sample_result(), "json"))
    data["added_in_a_later_version"] = 1
    assert RunResult.from_dict(data) == sample_result()


@pytest.mark.parametrize("fmt", ["md", "html"])
def test_reports_regenerate_from_saved_json(fmt):
    """Reports only read the result: one rebuilt from its JSON renders byte for byte the same."""
    result = sample_result(warnings=["edge"])
    back = RunResult.from_dict(json.loads(render(result, "json")))
    assert render(back, fmt) == render(result, fmt)
