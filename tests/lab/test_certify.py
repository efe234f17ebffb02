"""batcert.lab.certify and `batcert reduce` on the shipped example sessions and on hand-made
cases: the location rule, consecutive valid hits, validity checks, the uncertainty budget
against its own formulas and against Monte Carlo, and the decision rules."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

from batcert.commands.inputs import load_protocol_any
from batcert.commands.reduce import run_reduce
from batcert.lab.certify import certify, guard_band
from batcert.lab.session import load_lab_session
from batcert.runner.runner import decide
from batcert.specs.protocol import LimitSpec

LAB = Path(__file__).resolve().parents[2] / "examples" / "lab"
INCH = 0.0254


@pytest.fixture(scope="module")
def bbcor():
    return load_protocol_any("ncaa-bbcor").protocol


def test_exact_session_certifies_its_true_maximum(bbcor):
    """The generator's truth peaks at 6 in from the tip at 0.495 (scripts/make_synthetic_hits.py);
    the six exact hits there give it back within the speeds' rounding (1.3e-5), with no
    scatter, so u_A = 0 and, with no instrument uncertainty stated, U = 0."""
    s = load_lab_session(LAB / "synthetic-exact.yaml")
    _, c = certify(s, bbcor, 0.5)
    assert c.scan[c.location].from_tip == pytest.approx(6 * INCH, abs=1e-12)
    assert c.value == pytest.approx(0.495, abs=1.3e-5)
    assert c.used == list(range(18, 24)) and c.u_c == 0.0 and c.conformance == 1.0


def test_scatter_session_skips_the_invalid_hit_and_states_its_uncertainty(bbcor):
    s = load_lab_session(LAB / "synthetic-scatter.yaml")
    red, c = certify(s, bbcor, 0.5)
    hits = [int(s.hits.hit[i]) for i in c.used]
    assert hits == [20, 21, 22, 23, 24, 25]  # after the seam strike (hit 19) at 6 in
    assert c.reasons[18] == ["marked invalid (seam strike (operator))"]
    used = red.bbcor[c.used]
    assert c.value == pytest.approx(float(np.mean(used)), abs=1e-15)
    assert c.u_a == pytest.approx(float(np.std(used, ddof=1)) / math.sqrt(6), rel=1e-12)
    # the budget's own arithmetic: u_c^2 = u_A^2 + sum of the type B contributions^2
    assert c.u_c**2 == pytest.approx(c.u_a**2 + sum(x**2 for x in c.u_b.values()), rel=1e-12)
    # Welch-Satterthwaite with type B of infinite degrees of freedom: nu = u_c^4 / (u_A^4 / 5)
    assert c.dof == pytest.approx(c.u_c**4 / (c.u_a**4 / 5), rel=1e-12)
    # Monte Carlo (JCGM 101) against the GUM: the t-distributed type A (5 dof, standard
    # deviation sqrt(5/3) u_A) makes the MC spread larger than u_c; the GUM with the effective
    # degrees of freedom predicts it: sqrt(u_B^2 + 5/3 u_A^2), to the MC's sampling (1 %)
    u_b2 = sum(x**2 for x in c.u_b.values())
    assert c.mc_std == pytest.approx(math.sqrt(u_b2 + 5 / 3 * c.u_a**2), rel=0.01)
    lo, hi = c.mc_interval
    assert (hi - lo) / 2 == pytest.approx(c.expanded, rel=0.12)  # t vs normal tails
    assert 0.98 < c.conformance < 1.0  # 0.4933 with U 0.0049 against 0.500


def test_type_b_sensitivities_by_finite_differences(bbcor):
    """Each type B contribution is |d value / d input| x u(input): check the derivative by
    shifting the input in the reduction itself."""
    from batcert.methods.reduction import reduce_hits
    s = load_lab_session(LAB / "synthetic-scatter.yaml")
    _, c = certify(s, bbcor, 0.5)
    h, u = s.hits, s.spec.uncertainty
    args = dict(inbound_speed=h.inbound_speed[c.used], rebound_speed=h.rebound_speed[c.used],
                impact_location=s.impact_location[c.used], moi_pivot=s.moi_pivot,
                ball_mass=s.ball.model.mass, ball_cor_at=s.ball.model.cor)

    def mean(**change):
        return float(np.mean(reduce_hits(**{**args, **change}).bbcor))

    base = mean()
    d = 1e-6
    checks = {"speed (rebound)": ("rebound_speed", u["speed"]),
              "speed (inbound)": ("inbound_speed", u["speed"]),
              "impact_location": ("impact_location", u["impact_location"]),
              "moi": ("moi_pivot", u["moi"]), "ball_mass": ("ball_mass", u["ball_mass"])}
    for name, (arg, ui) in checks.items():
        slope = (mean(**{arg: args[arg] + d}) - base) / d
        # the budget takes the derivative at the used hits' mean speeds and location: equal to
        # the mean of the per-hit derivatives to second order in their spread (1e-3 relative)
        assert c.u_b[name] == pytest.approx(abs(slope) * ui, rel=2e-3), name


def test_decision_rules():
    limit = LimitSpec(0.5, 0.0, None)
    assert decide(0.497, limit, guard_band("simple", 0.004)) == (pytest.approx(0.003), "pass")
    assert decide(0.497, limit, guard_band("guarded", 0.004)) == (pytest.approx(-0.001), "fail")
    assert decide(None, limit) == (None, None)
    assert decide(0.6, None) == (None, None)


def test_too_few_consecutive_valid_hits(bbcor, tmp_path):
    """Mark a second hit at the best location invalid: only four consecutive valid hits
    remain there; nothing is certified and the warning says why."""
    text = (LAB / "synthetic-scatter.csv").read_text(encoding="utf-8")
    text = text.replace("\n22,B04,", "\n22,B04,", 1)
    lines = text.splitlines()
    k = next(i for i, ln in enumerate(lines) if ln.startswith("22,"))
    lines[k] = lines[k].replace(",yes,", ",no,")
    (tmp_path / "hits.csv").write_text("\n".join(lines) + "\n", encoding="utf-8")
    session = (LAB / "synthetic-scatter.yaml").read_text(encoding="utf-8")
    session = session.replace("bat: aluminium-34", "bat: aluminium-34").replace(
        "hits: synthetic-scatter.csv", "hits: hits.csv")
    (tmp_path / "s.yaml").write_text(session, encoding="utf-8")
    _, c = certify(load_lab_session(tmp_path / "s.yaml"), bbcor, 0.5)
    assert c.value is None and c.used == []
    assert "fewer than 6 consecutive valid hits" in c.warnings[0]
    assert c.warnings[0].startswith("no value can be certified")


def test_a_hit_far_from_the_protocols_speed_is_invalid(bbcor, tmp_path):
    lines = (LAB / "synthetic-exact.csv").read_text(encoding="utf-8").splitlines()
    k = next(i for i, ln in enumerate(lines) if ln.startswith("20,"))
    lines[k] = lines[k].replace("60.797,", "58.000,", 1)
    (tmp_path / "hits.csv").write_text("\n".join(lines) + "\n", encoding="utf-8")
    session = (LAB / "synthetic-exact.yaml").read_text(encoding="utf-8").replace(
        "hits: synthetic-exact.csv", "hits: hits.csv")
    (tmp_path / "s.yaml").write_text(session, encoding="utf-8")
    _, c = certify(load_lab_session(tmp_path / "s.yaml"), bbcor, 0.5)
    assert "inbound speed 58.00 m/s is more than 0.45 m/s from 60.80 m/s" in c.reasons[19][0]
    assert c.value is None  # hits 19 and 21-24 are not six consecutive


def test_reduce_json_and_model_overlay():
    r = run_reduce(str(LAB / "synthetic-scatter.yaml"), "ncaa-bbcor", "guarded", "rigid")
    d = json.loads(r.to_json())
    assert d["statement"] == "measured" and d["decision_rule"] == "guarded"
    assert d["verdict"] == "pass" and d["margin"] == pytest.approx(0.5 - d["expanded"]
                                                                   - d["value"])
    assert len(d["hits"]) == 43 and [h["hit"] for h in d["hits"] if h["used"]] == \
        [20, 21, 22, 23, 24, 25]
    m = d["model"]
    assert m["engine"] == "rigid" and len(m["from_tip"]) == len(m["metric"]) > 10
    assert m["difference"] == pytest.approx(d["value"] - m["at_certified_location"])


def test_reduce_cli(tmp_path):
    from click.testing import CliRunner

    from batcert.cli import main
    out = tmp_path / "r"
    res = CliRunner().invoke(main, ["reduce", str(LAB / "synthetic-scatter.yaml"), "-p",
                                    "ncaa-bbcor", "--engine", "rigid", "--out", str(out)])
    assert res.exit_code == 0, res.output
    assert sorted(p.suffix for p in out.glob("[!.]*")) == [".html", ".json", ".md"]
    md = next(out.glob("*.md")).read_text(encoding="utf-8")
    assert "Measured BBCOR 0.4933" in md and "simple acceptance" in md
    assert "| Bat serial number | AL34-0001 |" in md  # the session's lab: block
    html = next(out.glob("*.html")).read_text(encoding="utf-8")
    assert 'counter(page) " of " counter(pages)' in html and "EX\\2d 2026\\2d 001" in html
    res = CliRunner().invoke(main, ["reduce", str(LAB / "synthetic-scatter.yaml"), "-p",
                                    "stationary-ball", "--no-reports"])
    assert res.exit_code == 2 and "has no stationary-bat condition" in res.output
    # proposed has one (60 m/s): these 136 mph hits are all out of its speed tolerance
    res = CliRunner().invoke(main, ["reduce", str(LAB / "synthetic-scatter.yaml"), "-p",
                                    "proposed", "--engine", "rigid", "--no-reports"])
    assert res.exit_code == 1 and "no value can be certified" in res.output


def test_a_bare_hits_csv_with_bat():
    """`reduce HITS.csv --bat BAT`: the protocol gives the ball and the pivot (ncaa-bbcor: the
    collegiate baseball, 6 in, as the exact session's), so the certified value is the same."""
    from batcert.errors import UsageProblem
    bare = run_reduce(str(LAB / "synthetic-exact.csv"), "ncaa-bbcor", engine="rigid",
                      bat="aluminium-34")
    full = run_reduce(str(LAB / "synthetic-exact.yaml"), "ncaa-bbcor", engine="rigid")
    assert bare.value == full.value and bare.hits_used == full.hits_used
    with pytest.raises(UsageProblem, match="needs --bat"):
        run_reduce(str(LAB / "synthetic-exact.csv"), "ncaa-bbcor", engine="rigid")
    with pytest.raises(UsageProblem, match="a session YAML names its bat"):
        run_reduce(str(LAB / "synthetic-exact.yaml"), "ncaa-bbcor", engine="rigid",
                   bat="ash-34")


def test_tiny_gate_times_exit_3_with_nothing_written(tmp_path, batcert_cli):
    """A gate time of 1e-300 s made an inbound speed of 5e299 m/s, a NaN BPF and a traceback
    from the JSON writer; it is refused at its cell and nothing is written."""
    rows = "".join(f"{n},B1,1e-300,0.04,6\n" for n in range(1, 7))
    (tmp_path / "hits.csv").write_text("hit,ball,inbound_gate_time [s],rebound_gate_time [s],"
                                       f"impact_location [in from tip]\n{rows}", encoding="utf-8")
    session = (LAB / "synthetic-exact.yaml").read_text(encoding="utf-8").replace(
        "hits: synthetic-exact.csv", "hits: hits.csv") + "gate_spacing: 0.5 m\n"
    (tmp_path / "session.yaml").write_text(session, encoding="utf-8")
    out = tmp_path / "reports"
    res = batcert_cli("reduce", tmp_path / "session.yaml", "-p", "ncaa-bbcor", "--engine",
                      "rigid", "--out", out)
    assert res.exit_code == 3
    lines = res.stderr.splitlines()
    assert lines[0] == "invalid input"
    assert lines[1].startswith(f"{tmp_path / 'hits.csv'}:2: inbound_gate_time: gives inbound "
                               "speed 5e+299 m/s")
    assert not out.exists() or not any(out.iterdir())


def test_a_hit_that_reduces_to_a_non_finite_value_is_a_problem_at_its_line(monkeypatch):
    """The CSV's ranges keep every reduced value finite; should a ball's COR law still fail at
    a hit's speed, the hit is an input problem at its line, not a NaN in a report."""
    from dataclasses import replace

    from batcert.errors import InputError
    from batcert.lab import session as lab_session
    real = lab_session.reduce_hits

    def failing(*args):
        red = real(*args)
        cor = red.ball_cor.copy()
        cor[2] = np.nan
        return replace(red, ball_cor=cor, bpf=red.bbcor / cor)
    monkeypatch.setattr(lab_session, "reduce_hits", failing)
    s = load_lab_session(LAB / "synthetic-exact.yaml")
    with pytest.raises(InputError) as exc:
        lab_session.reduce_session(s)
    (problem,) = exc.value.problems
    assert problem.file == s.hits.path and problem.line == s.hits.line[2]
    assert "reduces to a non-finite ball_cor, bpf (inbound speed" in problem.message


def test_monte_carlo_draws_without_a_finite_value_are_left_out_and_said(bbcor, monkeypatch):
    from dataclasses import replace

    from batcert.lab.certify import MC_DRAWS
    from batcert.methods import reduction
    real = reduction.reduce_hits

    chunks = []

    def some_infinite(*args, **kwargs):
        red = real(*args, **kwargs)
        if red.bbcor.ndim == 2:  # the Monte Carlo's draws (in chunks), not the hits
            chunks.append(red.bbcor.shape[0])
            if len(chunks) == 1:  # ten draws of the first chunk
                bbcor = red.bbcor.copy()
                bbcor[:10, 0] = np.inf
                return replace(red, bbcor=bbcor)
        return red
    monkeypatch.setattr(reduction, "reduce_hits", some_infinite)
    _, c = certify(load_lab_session(LAB / "synthetic-scatter.yaml"), bbcor, 0.5)
    assert c.mc_std is not None and math.isfinite(c.mc_std)
    assert f"10 of {MC_DRAWS:,} Monte Carlo draws reduce to no finite value" in " ".join(c.warnings)
    assert sum(chunks) == MC_DRAWS
