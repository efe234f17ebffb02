"""Good input: shipped and fixture specs load to the right SI values, defaults and rules."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from batcert.commands.inputs import detect_kind, load_protocol_any
from batcert.errors import InputError
from batcert.model.build import build_bat
from batcert.specs.ball import load_ball
from batcert.specs.bat import load_bat
from batcert.specs.protocol import load_protocol
from batcert.specs.resolve import NotFound, resolve, shipped_names
from batcert.specs.yamlio import load_yaml_text

IN = 0.0254  # [m], REFERENCE-DATA Units
MPH = 0.44704  # [m/s]
OZ = 0.028349523125  # [kg]

SHIPPED_PROTOCOLS = {"astm-bpf", "ncaa-bbcor", "ncaa-besr", "ncaa-softball-bbs", "proposed",
                     "softball-bpf", "stationary-ball", "usa-softball-2004",
                     "usa-softball-2013-slowpitch", "wbsc-bbs"}


def test_shipped_names_resolve():
    assert set(shipped_names("protocol")) == SHIPPED_PROTOCOLS
    assert {"collegiate-baseball", "nathan-2000"} <= set(shipped_names("ball"))
    assert {"ash-34", "aluminium-34", "r161"} <= set(shipped_names("bat"))
    assert resolve("protocol", "proposed").name == "proposed.yaml"


def test_unknown_shipped_name_suggests():
    with pytest.raises(NotFound, match=r"did you mean 'aluminium-34'\?"):
        resolve("bat", "aluminum-34")


def test_every_shipped_file_validates(repo_root, batcert_cli):
    files = [f for d in ("bats", "protocols", "protocols/balls", "protocols/batters")
             for f in sorted((repo_root / d).glob("*.yaml"))]
    result = batcert_cli("validate", *files)
    assert result.exit_code == 0, result.stderr
    assert result.stdout.count("ok  ") == len(files)


def test_ash_spec_in_si(repo_root):
    spec = load_bat(repo_root / "bats" / "ash-34.yaml")
    assert spec.length == pytest.approx(0.860)
    z, d = spec.profile
    assert z[0] == 0.0 and z[-1] == pytest.approx(0.860)
    assert d[0] == pytest.approx(2.40 * IN)
    assert spec.measured.pivot == pytest.approx(0.150)
    assert spec.measured.mass == pytest.approx(0.906)
    assert spec.measured.cg == pytest.approx(0.429)
    assert spec.measured.moi == pytest.approx(0.209)
    assert spec.material.name == "ash-bat"
    # two comment lines and the pivot lie between `measured:` and its mass
    assert spec.source.line("measured", "mass") == spec.source.line("measured") + 4
    # the stated uncertainties: half the last digit, uniform (u = half-width / sqrt 3)
    assert spec.measured.mass.u == pytest.approx(0.0005 / np.sqrt(3))
    assert spec.measured.moi.distribution == "uniform"
    assert len(spec.sha256) == 64


def test_bat_defaults(fixtures_dir):
    v = load_bat(fixtures_dir / "good" / "solid-bat.yaml")
    assert v.knob_mass == 0.0 and v.end_cap_mass == 0.0
    assert v.slice_length == 0.01
    assert v.reconcile == "density-profile"
    assert v.measured is None and v.wall is None


def test_wall_constant_and_per_station(fixtures_dir, repo_root):
    assert load_bat(fixtures_dir / "good" / "hollow-bat.yaml").wall == pytest.approx(0.0025)
    z, t = load_bat(repo_root / "bats" / "aluminium-34.yaml").wall
    assert z[1] == pytest.approx(11 * IN) and t[-1] == pytest.approx(0.0027)


def test_inline_material_and_measured_default_pivot(repo_root):
    v = load_bat(repo_root / "bats" / "r161.yaml")
    m = v.material
    assert (m.density, m.youngs_modulus, m.shear_modulus) == (649.0, 1.814e10, 1.05e9)
    assert m.poisson_ratio == 0.3 and m.loss_factor == 0.0  # schema defaults
    assert v.measured.pivot == pytest.approx(6 * IN)  # default: 6 in from the knob
    assert v.shear_correction == 1.0


def test_protocol_values_and_defaults(repo_root):
    p = load_protocol(repo_root / "protocols" / "ncaa-besr.yaml")
    assert p.pivot == pytest.approx(6 * IN)
    c = p.conditions[0]
    assert c.pitch_speed == pytest.approx(70 * MPH)
    assert c.bat_speed == pytest.approx(66 * MPH)
    assert c.bat_speed_from_tip == pytest.approx(6 * IN)
    loc = p.impact_location
    assert loc.window == pytest.approx((2 * IN, 12 * IN))
    assert (loc.sweep_points, loc.resolution) == (36, 0.001)  # defaults
    assert p.support == "pinned" and p.aggregate == "mean"
    assert (p.limit.max, p.limit.tolerance) == (0.728, 0.0)
    assert p.line("limit", "max") is not None and p.line("limit", "max") > p.line("limit")
    proposed = load_protocol(repo_root / "protocols" / "proposed.yaml")
    assert proposed.impact_location.window == (0.03, 0.30)  # default window from the tip
    assert proposed.limit is None


def test_ball_values(repo_root):
    spec = load_ball(repo_root / "protocols" / "balls" / "collegiate-baseball.yaml")
    ball = spec.model
    assert ball.mass == pytest.approx(5.125 * OZ)
    assert ball.radius == pytest.approx(0.0369)
    assert ball.contact_model == "viscoelastic-2" and spec.fit is not None
    assert spec.fit.held == ("fast_relaxation_time",)
    assert spec.reference is not None and spec.reference.value == pytest.approx(0.490)
    assert Path(spec.reference.bat).name == "ash-34.yaml" and spec.lot is None  # not yet applied
    speeds = [p.condition for key, p in spec.tests if key == "cor"]
    assert speeds == pytest.approx([1.0, 85 * 0.3048, 58.0])
    assert [key for key, _ in spec.tests].count("collision_time") == 4
    nathan = load_ball(repo_root / "tests" / "fixtures" / "good" / "ball-nathan-law.yaml").model
    # YAML 1.1 reads 6.53e7 as text: converted
    assert nathan.law.k1 == 6.53e7 and nathan.law.alpha == 1.84


def test_cor_interpolation_rule(repo_root):
    """Nathan's law: piecewise linear in speed between the points, constant outside them
    (docs/inputs.md)."""
    ball = load_ball(repo_root / "tests" / "fixtures" / "good" / "ball-nathan-law.yaml").model
    v1, v2 = 85 * 0.3048, 71.0
    mid = 0.5 * (v1 + v2)
    assert ball.cor(mid) == pytest.approx(0.5 * (0.546 + 0.50))
    assert ball.cor(0.1) == pytest.approx(0.64)  # below the first point: held
    assert ball.cor(120.0) == pytest.approx(0.50)  # above the last point: held
    assert ball.cor(-mid) == pytest.approx(ball.cor(mid))  # the speed's sign does not matter
    single = load_ball(repo_root / "protocols" / "balls" / "nathan-2000.yaml").model
    assert np.all(single.cor(np.array([1.0, 58.0, 100.0])) == 0.53)


def test_batter_values_and_defaults(fixtures_dir):
    from batcert.commands.inputs import batter_inputs
    loaded = batter_inputs(fixtures_dir / "good" / "batter.yaml")
    b, law = loaded.batter, loaded.batter.swing
    assert b.id == "batter" and b.body == "baseball" and loaded.ball.name == "Collegiate baseball"
    assert b.pitch_speed == pytest.approx(85 * MPH)
    assert float(law.bat_speed) == pytest.approx(65 * MPH)
    assert law.bat_speed_uncertainty == pytest.approx(2 * MPH)
    assert law.reference_moi == pytest.approx(18900 * OZ * IN**2)
    # defaults: measured 6 in from the tip, about the knob, no stated spread of n
    assert (law.speed_from_tip, law.axis_from_knob, law.exponent_uncertainty) == (
        pytest.approx(6 * IN), 0.0, 0.0)
    assert law.station_radius == pytest.approx(28 * IN)  # 34 in - 6 in from the tip


def test_batter_ball_path_relative_to_batter(tmp_path, fixtures_dir):
    from batcert.commands.inputs import load_batter_any
    (tmp_path / "my-ball.yaml").write_text((fixtures_dir / "good" / "ball.yaml").read_text())
    text = (fixtures_dir / "good" / "batter.yaml").read_text()
    (tmp_path / "mine.yaml").write_text(text.replace("ball: collegiate-baseball",
                                                     "ball: my-ball.yaml"))
    assert load_batter_any(str(tmp_path / "mine.yaml")).ball.name == "Test ball"


def test_protocol_ball_path_relative_to_protocol(tmp_path, fixtures_dir):
    (tmp_path / "my-ball.yaml").write_text((fixtures_dir / "good" / "ball.yaml").read_text())
    proto = tmp_path / "mine.yaml"
    proto.write_text("id: mine\ntitle: t\nreference: r\nversion: '1'\nball: my-ball.yaml\n"
                     "conditions:\n  - name: c\n    relative_speed: 60 m/s\n    stationary: ball\n"
                     "impact_location:\n  rule: sweet-spot\nmetric: exit-speed\n")
    inputs = load_protocol_any(str(proto))
    assert inputs.ball.name == "Test ball"
    assert inputs.protocol.conditions[0].stationary == "ball"


@pytest.mark.parametrize("name, kind", [("good/solid-bat.yaml", "bat"), ("good/ball.yaml", "ball"),
                                        ("good/batter.yaml", "batter")])
def test_detect_kind(fixtures_dir, name, kind):
    assert detect_kind(str(fixtures_dir / name)) == kind


def test_yaml_positions():
    data = load_yaml_text("a: 1\nb:\n  c: 2\n  d: [1, 2]\n", "x.yaml")
    assert data.key_pos["b"] == (2, 1)
    assert data["b"].value_pos["c"] == (3, 6)
    assert data["b"]["d"].item_pos == [(4, 7), (4, 10)]


def test_load_errors_are_input_errors(tmp_path):
    with pytest.raises(InputError, match="file not found"):
        load_bat(tmp_path / "missing.yaml")


def test_build_bat_reports_model_errors_at_spec_line(fixtures_dir):
    spec = load_bat(fixtures_dir / "bad" / "bat-wall-too-thick.yaml")  # the schema accepts it
    with pytest.raises(InputError) as exc:
        build_bat(spec)
    (problem,) = exc.value.problems
    assert (problem.line, problem.field) == (10, "wall")


def test_profile_beyond_the_tip_is_refused(tmp_path, fixtures_dir):
    text = (fixtures_dir / "good" / "solid-bat.yaml").read_text().replace("[34 in, 2.5 in]",
                                                                         "[35 in, 2.5 in]")
    path = tmp_path / "long-profile.yaml"
    path.write_text(text)
    with pytest.raises(InputError) as exc:
        load_bat(path)
    (problem,) = exc.value.problems
    assert problem.field == "profile" and "between the knob (0) and the tip (the length, 34.00 in, line 4)" in (
        problem.message)
    assert Path(problem.file) == path and problem.line == 5  # the `profile:` key


def test_a_cor_written_dimensionless_is_a_problem_at_its_line(tmp_path, repo_root):
    """Dimensionless values (COR, limits) are plain numbers; "0.65 dimensionless" is refused
    at its line like any other text (issue 24)."""
    from batcert.specs.ball import load_ball
    text = (repo_root / "protocols" / "balls" / "collegiate-baseball.yaml").read_text(
        encoding="utf-8").replace("- [1 m/s, 0.65 +/- 0.01 (uniform)]", "- [1 m/s, 0.65 dimensionless]")
    path = tmp_path / "ball.yaml"
    path.write_text(text, encoding="utf-8")
    with pytest.raises(InputError) as exc:
        load_ball(path)
    (problem,) = exc.value.problems
    assert problem.field == "cor[0]" and "COR must be a number" in problem.message
    assert text.splitlines()[problem.line - 1].strip() == "- [1 m/s, 0.65 dimensionless]"
