"""batcert.analysis.compare: relative performance (Smith 2001 Eq. 6), spread, reference, claims, studies.

The comparison is pure: these tests build RunResults by hand (no engine), so every expected
number follows from the inputs by arithmetic.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest

from batcert.analysis.claims import CHECKS, evaluate_claim
from batcert.analysis.compare import compare, relative_performance
from batcert.errors import InputError
from batcert.results.compare import ComparisonResult, Spread
from batcert.results.run import ConditionResult, InputFile, MassProperties, RunResult, Sweep
from batcert.specs.common import spec_from
from batcert.specs.kinds import CLAIM_CHECKS
from batcert.specs.study import CLAIM_SCHEMA, ClaimSpec, load_study

REPO = Path(__file__).resolve().parents[2]
STUDY = REPO / "protocols" / "studies" / "smith2001.yaml"


def _condition(name: str, value: float, *, cop: float = 0.54, sweet: float = 0.56,
               edge: bool = False, rigid: float | None = None) -> ConditionResult:
    # a sweep whose maximum lies inside the window unless ``edge`` (then at its last point)
    xs = [0.40, 0.50, sweet, 0.62, 0.68]
    ys = [30.0, 35.0, 40.0, 38.0, 41.0 if edge else 33.0]
    return ConditionResult(
        name=name, setup="stationary-bat", pitch_speed=-31.0, bat_angular_speed=0.0,
        relative_speed=31.0, impact_location=sweet, exit_speed=40.0, bat_angular_speed_after=0.0,
        cor=0.5, ball_cor=0.5, bpf=value, besr=value, bbcor=value, collision_efficiency=0.2,
        metric_value=value, cop=cop, sweet_spot=sweet, rigid_sweet_spot=rigid,
        at_window_edge=edge, sweep=Sweep(xs, ys, ys))


def _run(bat: str, protocol: str, values: list[float], *, aggregate_value: float | None = None,
         moi: float = 0.2, engine: str = "rigid", **cond) -> RunResult:
    names = ["stationary-bat", "stationary-ball", "pitched-and-swung"][: len(values)]
    conds = [_condition(n, v, **cond) for n, v in zip(names, values, strict=True)]
    mp = MassProperties(0.86, 0.15, 0.9, 0.43, moi, moi / (0.9 * 0.43), 0.9, 0.43, moi, None,
                        None, None, "none")
    value = sum(values) / len(values) if aggregate_value is None else aggregate_value
    return RunResult(
        protocol=protocol, protocol_title=protocol, protocol_version="1", protocol_reference="ref",
        protocol_notes="", bat=bat, ball="ball", metric="bpf", aggregate="mean", value=value,
        limit=None, tolerance=0.0, margin=None, verdict=None, impact_rule="sweet-spot",
        engine=engine, engine_settings={}, support="pinned", mass_properties=mp,
        conditions=conds, inputs=[InputFile("bat", bat, f"/bats/{bat}.yaml", "0" * 64)],
        batcert_version="test", created="2024-01-01T00:00:00+00:00")


# ---------------------------------------------------------------- Eq. 6 and the spread


def test_relative_performance_is_smith_eq6():
    # Smith 2001 Eq. 6: P = (P_a - P_w) / P_w; 1.10 against 1.00 is +10 %
    assert relative_performance(1.10, 1.00) == pytest.approx(0.10)
    assert relative_performance(0.90, 1.00) == pytest.approx(-0.10)
    assert relative_performance(0.5, 0.5) == 0.0


@pytest.mark.parametrize("ref", [0.0, math.nan, math.inf])
def test_relative_performance_undefined(ref):
    assert relative_performance(1.0, ref) is None


def test_compare_per_condition_p_mean_and_spread():
    ash = _run("ash", "p1", [1.00, 0.80, 0.50])
    alu = _run("alu", "p1", [1.10, 0.76, 0.55])
    result = compare([[ash], [alu]])
    p = result.protocols[0]
    got = [c.bats["alu"].relative for c in p.conditions]
    assert got == pytest.approx([0.10, -0.05, 0.10])  # Eq. 6 per condition
    assert [c.bats["ash"].relative for c in p.conditions] == [0.0, 0.0, 0.0]
    s = p.relative_spread["alu"]
    mean = (0.10 - 0.05 + 0.10) / 3
    std = math.sqrt(((0.10 - mean) ** 2 * 2 + (-0.05 - mean) ** 2) / 3)  # population std
    assert s.mean == pytest.approx(mean)
    assert s.std == pytest.approx(std)
    assert (s.min, s.max, s.range) == pytest.approx((-0.05, 0.10, 0.15))
    assert p.aggregate_relative["alu"] == pytest.approx((2.41 / 3 - 2.30 / 3) / (2.30 / 3))


def test_spread_of_one_condition_and_undefined():
    assert Spread.of([0.2]) == Spread(0.2, 0.0, 0.2, 0.2, 0.0)
    assert Spread.of([0.1, None]).mean is None


def test_reference_selection():
    ash, alu = _run("ash", "p1", [1.0]), _run("alu", "p1", [1.25])
    default = compare([[ash], [alu]])
    assert default.reference == "ash" and default.compared == ["alu"]
    assert default.protocols[0].conditions[0].bats["alu"].relative == pytest.approx(0.25)
    flipped = compare([[ash], [alu]], reference=1)
    assert flipped.reference == "alu"
    assert flipped.protocols[0].conditions[0].bats["ash"].relative == pytest.approx(-0.2)
    with pytest.raises(ValueError):
        compare([[ash], [alu]], reference=2)


def test_compare_rejects_mismatched_inputs():
    ash = _run("ash", "p1", [1.0])
    with pytest.raises(ValueError, match="two bats"):
        compare([[ash]])
    with pytest.raises(ValueError, match="differs"):
        compare([[ash], [_run("alu", "p2", [1.0])]])
    with pytest.raises(ValueError, match="conditions"):
        compare([[_run("ash", "p1", [1.0, 1.0])], [_run("alu", "p1", [1.0])]])
    with pytest.raises(ValueError, match="engine"):
        compare([[ash], [_run("alu", "p1", [1.0], engine="flexible")]])


def test_duplicate_bat_names_get_unique_labels():
    a, b = _run("same", "p1", [1.0]), _run("same", "p1", [1.1])
    b.inputs = [InputFile("bat", "same", "/other/place.yaml", "1" * 64)]
    result = compare([[a], [b]])
    labels = [x.label for x in result.bats]
    assert len(set(labels)) == 2


def test_cop_and_sweet_spot_per_bat_and_condition():
    ash = _run("ash", "p1", [1.0, 1.0], cop=0.54, sweet=0.58)
    alu = _run("alu", "p1", [1.0, 1.0], cop=0.55, sweet=0.56, edge=True)
    c = compare([[ash], [alu]]).protocols[0].conditions[0]
    assert c.bats["ash"].sweet_spot_minus_cop == pytest.approx(0.04)
    assert not c.bats["ash"].sweet_spot_at_edge
    assert c.bats["alu"].sweet_spot_at_edge  # read from the sweep: maximum on its last point


def test_json_round_trip():
    result = compare([[_run("ash", "p1", [1.0, 0.9])], [_run("alu", "p1", [1.1, 0.8])]])
    text = result.to_json()
    again = ComparisonResult.from_dict(json.loads(text))
    assert again == result
    assert again.to_json() == text


# ---------------------------------------------------------------- findings and claims


def _claim(check: str, protocols: list[str], **kw) -> ClaimSpec:
    defaults = {f.name: f.default for f in CLAIM_SCHEMA.fields}  # the study file's defaults
    return spec_from(ClaimSpec, {**defaults, "id": check, "statement": "s", "check": check,
                                 "protocols": protocols, **kw})


def test_every_claim_check_has_its_test():
    assert list(CHECKS) == list(CLAIM_CHECKS)


def test_every_claim_check_is_documented_in_the_input_docs():
    doc = (REPO / "docs" / "inputs.md").read_text(encoding="utf-8")
    for name, check in CLAIM_CHECKS.items():
        assert f"| `{name}` | {check.doc} |" in doc


def test_sign_disagreement_and_consistency():
    # p1: aluminium ahead in one set-up, behind in another; p2: ahead by about 3 % everywhere
    ash = [_run("ash", "p1", [1.0, 1.0, 1.0]), _run("ash", "p2", [1.0, 1.0, 1.0])]
    alu = [_run("alu", "p1", [1.05, 0.95, 1.0]), _run("alu", "p2", [1.03, 1.03, 1.035])]
    result = compare([ash, alu])
    assert evaluate_claim(result, _claim("sign-disagreement", ["p1"])).status == "supported"
    assert evaluate_claim(result, _claim("sign-disagreement", ["p2"])).status == "not-supported"
    consistent = _claim("consistent-across-conditions", ["p2"], compare_with=["p1"])
    assert evaluate_claim(result, consistent).status == "supported"
    assert evaluate_claim(result, _claim("consistent-across-conditions", ["p1"])
                          ).status == "not-supported"
    assert evaluate_claim(result, _claim("advantage", ["p2"])).status == "supported"
    hidden = _claim("advantage", ["p1"], expected="not-shown")
    assert evaluate_claim(result, hidden).status == "supported"
    low = evaluate_claim(result, _claim("lower-than", ["p1", "p2"]))
    assert low.status == "supported" and "MOI" in low.evidence


def test_no_difference_is_not_consistency():
    # P = 0 everywhere (e.g. BPF with the rigid engine) must not count as a consistent advantage
    result = compare([[_run("ash", "p", [1.0, 1.0])], [_run("alu", "p", [1.0, 1.0])]])
    assert evaluate_claim(result, _claim("consistent-across-conditions", ["p"])
                          ).status == "not-supported"
    assert evaluate_claim(result, _claim("advantage", ["p"])).status == "not-supported"
    assert any("no difference" in f for f in result.findings)


def test_location_claims_skip_sweet_spots_on_the_window_edge():
    ash = _run("ash", "p", [1.0, 1.0], cop=0.54, sweet=0.58)
    alu = _run("alu", "p", [1.0, 1.0], cop=0.55, sweet=0.565)
    result = compare([[ash], [alu]])
    assert evaluate_claim(result, _claim("cop-not-sweet-spot", ["p"], location_tolerance=0.01)
                          ).status == "supported"  # offsets 4.0 and 1.5 cm
    assert evaluate_claim(result, _claim("cop-offset-differs", ["p"], location_tolerance=0.01)
                          ).status == "supported"  # 4.0 against 1.5 cm
    edge = compare([[_run("ash", "p", [1.0], edge=True)], [_run("alu", "p", [1.0], edge=True)]])
    assert evaluate_claim(edge, _claim("cop-not-sweet-spot", ["p"])).status == "not-testable"


def test_sweet_spot_movement_against_eq7():
    def runs(sweets, rigids):
        out = []
        for bat in ("ash", "alu"):
            r = _run(bat, "p", [1.0, 1.0])
            for c, s, rg in zip(r.conditions, sweets, rigids, strict=True):
                c.sweet_spot, c.rigid_sweet_spot = s, rg
                c.sweep = Sweep([0.4, s, 0.7], [1.0, 2.0, 1.0], [1.0, 2.0, 1.0])
            out.append([r])
        return out
    small = compare(runs([0.56, 0.57], [0.60, 0.70]))  # 1 cm against 10 cm
    claim = _claim("sweet-spot-moves-less-than-rigid", ["p"], factor=0.5)
    assert evaluate_claim(small, claim).status == "supported"
    same = compare(runs([0.60, 0.70], [0.60, 0.70]))  # a rigid model moves exactly as Eq. 7
    assert evaluate_claim(same, claim).status == "not-supported"
    none = compare([[_run("ash", "p", [1.0])], [_run("alu", "p", [1.0])]])  # Eq. 7 undefined
    assert evaluate_claim(none, claim).status == "not-testable"


def test_claim_on_unknown_protocol_is_not_testable():
    result = compare([[_run("ash", "p", [1.0])], [_run("alu", "p", [1.0])]])
    assert evaluate_claim(result, _claim("advantage", ["missing"])).status == "not-testable"


# ---------------------------------------------------------------- study files


def test_shipped_study_loads_and_resolves_every_protocol():
    study = load_study(STUDY)
    assert study.id == "smith2001"
    assert [p.id for p in study.protocols] == [
        "smith2001-bpf-cop", "smith2001-besr-sweet-spot", "smith2001-bpf-sweet-spot",
        "proposed", "smith2001-besr-matched"]
    assert [b.name for b in study.bats] == ["ash-34.yaml", "aluminium-34.yaml"]
    ids = {p.id for p in study.protocols}
    for claim in study.claims:
        assert set(claim.protocols) <= ids
    # the study speeds: 31 m/s pitch, 53 rad/s swing, pivot 150 mm
    cop = study.protocols[0]
    assert cop.pivot == pytest.approx(0.150)
    speeds = {(c.pitch_speed, c.bat_angular_speed) for c in cop.conditions}
    assert speeds == {(31.0, 0.0), (0.0, 53.0), (31.0, 53.0)}
    matched = study.protocols[3].conditions
    assert {c.relative_speed for c in matched} == {60.0}


def test_study_resolves_by_name():
    from batcert.commands.inputs import load_study_any
    assert load_study_any("smith2001").id == "smith2001"


def test_inline_protocol_and_bad_claims(tmp_path):
    good = tmp_path / "study.yaml"
    good.write_text(f"""id: s
title: t
reference: r
version: "1"
protocols:
  - {REPO / 'protocols' / 'astm-bpf.yaml'}
  - id: inline
    title: inline protocol
    reference: r
    version: "1"
    ball: collegiate-baseball
    conditions:
      - name: a
        pitch_speed: 31 m/s
        bat_angular_speed: 0 rad/s
    impact_location:
      rule: cop
    metric: bpf
claims:
  - id: c
    statement: s
    check: advantage
    protocols: [inline, astm-bpf]
""")
    study = load_study(good)
    assert [p.id for p in study.protocols] == ["astm-bpf", "inline"]
    bad = tmp_path / "bad.yaml"
    bad.write_text(good.read_text().replace("[inline, astm-bpf]", "[inlin]")
                   .replace("check: advantage", "check: advantag"))
    with pytest.raises(InputError) as info:
        load_study(bad)
    text = info.value.render()
    assert "did you mean 'advantage'" in text and f"{bad}:" in text
    bad.write_text(good.read_text().replace("[inline, astm-bpf]", "[inlin]"))
    with pytest.raises(InputError, match="'inlin' is not a protocol of this study"):
        load_study(bad)
