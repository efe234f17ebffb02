"""``batcert field``: what bats do in play for batter profiles, against a reference bat. Every
input is loaded before anything runs."""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, replace
from pathlib import Path

from batcert.commands.inputs import BatterInputs, load_bats, load_batter_any, same_file
from batcert.engines import get_engine
from batcert.errors import UsageProblem
from batcert.inplay.barrel import WINDOW_FROM_TIP
from batcert.inplay.evaluate import MODEL_OFFSET, Launch, evaluate_batter
from batcert.physics.trajectory import RPM, air_density, default_spin
from batcert.results.field import FieldResult
from batcert.results.serialise import utc_now
from batcert.specs.resolve import display_path, resolve, shipped_names
from batcert.version import __version__

DEFAULT_REFERENCE = "ash-34"
DEFAULT_BATTER = "college"
SPIN_SOURCE = ("Nathan's trajectory calculator's default spin, the Statcast regression "
               "backspin = -763 + 120 LA [rpm], sidespin = -849 rpm (a right-handed batter's "
               "ball to centre field)")


@dataclass(frozen=True)
class FieldSettings:
    """How the batted ball is launched and the air it flies through (SI)."""

    launch_angle: float = math.radians(28.0)  # [rad]
    backspin: float | None = None  # [rad/s]; None: the calculator's default for the angle
    sidespin: float | None = None  # [rad/s]
    temperature: float = 294.261  # [K] (70 F)
    elevation: float = 0.0  # [m]
    relative_humidity: float = 0.5  # [-]
    pitch_speed: float | None = None  # [m/s]; None: each batter profile's own


def batter_names(values: Sequence[str]) -> list[str]:
    """The batter profiles asked for; ``all`` is every shipped one."""
    out: list[str] = []
    for v in values or [DEFAULT_BATTER]:
        for name in (list(shipped_names("batter")) if v == "all" else [v]):
            if name not in out:
                out.append(name)
    return out


def _check_finite(settings: FieldSettings) -> None:
    """UsageProblem at a launch, spin or air setting that is not a finite number (a NaN angle
    flew until the trajectory's time limit and ended in a traceback)."""
    for name, value in vars(settings).items():
        if value is not None and not math.isfinite(value):
            raise UsageProblem(f"{name} must be a finite number, got {value!r}")


def _launch(settings: FieldSettings) -> tuple[Launch, str]:
    back, side = (float(x) for x in default_spin(settings.launch_angle))
    given = settings.backspin is not None or settings.sidespin is not None
    source = "as given" if given else SPIN_SOURCE
    rho = float(air_density(settings.temperature, elevation=settings.elevation,
                            relative_humidity=settings.relative_humidity))
    return Launch(settings.launch_angle,
                  back if settings.backspin is None else settings.backspin,
                  side if settings.sidespin is None else settings.sidespin, rho), source


def _warnings(batters: list[BatterInputs], launch: Launch) -> list[str]:
    out = []
    if any(b.batter.body == "softball" for b in batters):
        out.append("softballs fly with the baseball's drag and lift coefficients of Nathan's "
                   "calculator: no measured softball coefficients were found (their distances "
                   "are an estimate)")
    if launch.backspin < 0:
        out.append(f"the backspin is negative ({launch.backspin / RPM:.0f} rpm): topspin at "
                   "this launch angle")
    return out


def run_field(bats: Sequence[str], batters: Sequence[str] = (), reference: str | None = None,
              engine: str = "flexible", settings: FieldSettings = FieldSettings()
              ) -> FieldResult:
    """Every bat (and the reference bat) swung by every batter profile: swing speed from the
    bat's MOI, batted-ball speed along the barrel, sweet zone, e_A and carry, with gains over the
    reference."""
    if not bats:
        raise UsageProblem("give at least one bat (a shipped name such as aluminium-34, or a "
                           "bat YAML path)")
    _check_finite(settings)
    paths: list[Path] = []
    for value in bats:  # a bat given twice, or also as the reference, is built and swung once
        path = resolve("bat", value)
        if not any(same_file(path, kept) for kept in paths):
            paths.append(path)
    ref_path = resolve("bat", reference or DEFAULT_REFERENCE)
    at = next((i for i, path in enumerate(paths) if same_file(path, ref_path)), None)
    if at is None:  # the reference is swung too, last
        paths.append(ref_path)
        at = len(paths) - 1
    loaded = load_bats([str(path) for path in paths])
    profiles: list[BatterInputs] = []
    for name in batter_names(batters):  # a profile named twice (or by its path) runs once
        p = load_batter_any(name)
        if not any(same_file(Path(p.batter.path), Path(q.batter.path)) for q in profiles):
            profiles.append(p)
    if settings.pitch_speed is not None:
        profiles = [replace(p, batter=replace(p.batter, pitch_speed=settings.pitch_speed))
                    for p in profiles]
    eng = get_engine(engine)
    launch, spin_source = _launch(settings)
    named = [(b.built.spec.name, display_path(b.path), b.built) for b in loaded]
    results = [evaluate_batter(p.batter, p.ball, named, at, eng, launch) for p in profiles]
    for r in results:
        r.path = display_path(r.path)
    return FieldResult(
        loaded[at].built.spec.name, eng.name, launch.launch_angle, launch.backspin,
        launch.sidespin, spin_source, launch.air_density, settings.temperature,
        settings.elevation, settings.relative_humidity, list(WINDOW_FROM_TIP), results,
        __version__, utc_now(), _warnings(profiles, launch), MODEL_OFFSET)
