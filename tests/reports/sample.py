"""A realistic RunResult built by hand, for report tests (no engine involved).

Ash 34 in bat of Smith (2001): 906 g, CG 0.429 m and MOI 0.209 kg m^2 about a pivot 0.150 m from
the knob, run under the "proposed" matched-relative-speed protocol (60 m/s, three set-ups, BPF at
the sweet spot). The sweeps come from the rigid closed form with a COR that falls off away from
a node near 0.56 m, which is enough to give curves of the right shape and size; the numbers are
illustrative, not validated.
"""

from __future__ import annotations

import hashlib
import math

from batcert.results.run import ConditionResult, InputFile, MassProperties, RunResult, Sweep

BALL_MASS = 0.145  # [kg]
BALL_COR = 0.50  # rigid-wall COR at 60 m/s [-]
MOI = 0.209  # [kg m^2] about the pivot
MASS, CG = 0.906, 0.429  # [kg], [m from pivot]
LENGTH, PIVOT = 0.860, 0.150  # [m], [m from knob]
NODE = 0.56  # [m from pivot] where the illustrative COR peaks


def _cor(r: float, shift: float = 0.0) -> float:
    """Illustrative COR: peaks near the node, moved by ``shift`` [m] for faster swings."""
    return 0.52 * (1.0 - 15.0 * (r - NODE - shift) ** 2) - 3.0 * max(0.0, r - 0.64) ** 2


def _exit_speed(r: float, pitch_speed: float, w1: float) -> float:
    e, m, i = _cor(r, _shift(w1)), BALL_MASS, MOI
    return ((1 + e) * i * w1 * r + pitch_speed * (m * r * r - e * i)) / (i + m * r * r)


def _shift(w1: float) -> float:
    return 0.0002 * w1


def _condition(name: str, setup: str, pitch_speed: float, w1: float,
               metric: str = "bpf") -> ConditionResult:
    locations = [0.40 + 0.005 * k for k in range(71)]  # 0.40 .. 0.75 m from the pivot
    exit_speeds = [_exit_speed(r, pitch_speed, w1) for r in locations]
    by_exit_speed = metric == "exit-speed"
    bpf = [_cor(r, _shift(w1)) / BALL_COR for r in locations]
    values = exit_speeds if by_exit_speed else bpf
    best = max(range(len(locations)), key=exit_speeds.__getitem__)
    r, v_b, e = locations[best], exit_speeds[best], _cor(locations[best], _shift(w1))
    k = BALL_MASS * r * r / MOI
    e_a = (e - k) / (1 + k)
    ratio = pitch_speed / w1 if w1 else 0.0
    rigid = None if w1 == 0 else ratio + math.sqrt(MOI / BALL_MASS + ratio**2)  # Eq. 7
    return ConditionResult(
        name=name, setup=setup, pitch_speed=pitch_speed, bat_angular_speed=w1,
        relative_speed=w1 * r - pitch_speed, impact_location=r, exit_speed=v_b,
        bat_angular_speed_after=w1 + BALL_MASS * (pitch_speed - v_b) * r / MOI,
        cor=e, ball_cor=BALL_COR, bpf=e / BALL_COR,
        besr=(v_b - (w1 * r + pitch_speed) / 2) / (w1 * r - pitch_speed),
        bbcor=e_a * (1 + k) + k, collision_efficiency=e_a,
        metric_value=v_b if by_exit_speed else e / BALL_COR,
        cop=MOI / (MASS * CG), sweet_spot=r, rigid_sweet_spot=rigid,
        at_window_edge=best in (0, len(locations) - 1),
        sweep=Sweep(impact_location=locations, exit_speed=exit_speeds, metric=values),
    )


def _sha(text: str) -> str:
    return hashlib.sha256(text.encode()).hexdigest()


def sample_result(*, limit: float | None = 1.05, warnings: list[str] | None = None,
                  metric: str = "bpf", extras: dict | None = None) -> RunResult:
    """The ash bat under the proposed protocol; ``limit=None`` gives a result without verdict.

    ``metric="exit-speed"`` makes the sweeps' metric the exit speed [m/s] (pass a limit in m/s);
    ``extras`` replaces the default engine diagnostics.
    """
    conditions = [
        _condition("stationary bat", "stationary-bat", -60.0, 0.0, metric),
        _condition("stationary ball", "stationary-ball", 0.0, 60.0 / NODE, metric),
        _condition("pitched and swung", "pitched-and-swung", -30.0, 30.0 / NODE, metric),
    ]
    value = sum(c.metric_value for c in conditions) / len(conditions)
    tolerance = 0.005 if limit is not None else 0.0
    margin = None if limit is None else limit + tolerance - value
    verdict = None if margin is None else ("pass" if margin >= 0 else "fail")
    return RunResult(
        protocol="proposed",
        protocol_title="Matched relative speed at the sweet spot",
        protocol_version="1.0",
        protocol_reference="L. V. Smith, Evaluating baseball bat performance, "
                           "Sports Engineering 4 (2001) 205-214",
        protocol_notes="All three set-ups are raised to the same relative speed, 60 m/s, at the "
                       "impact point.\n\nThe impact point is the experimentally located sweet "
                       "spot; BPF uses the bat's recoil from the momentum balance (Eq. 1).",
        bat="Ash 34 in (Smith 2001)",
        ball="collegiate baseball",
        metric=metric, aggregate="mean", value=value, limit=limit, tolerance=tolerance,
        margin=margin, verdict=verdict, impact_rule="sweet-spot", engine="flexible",
        engine_settings={"modes": 18, "time_step": 5e-6, "slices": 86},
        support="pinned",
        mass_properties=MassProperties(
            length=LENGTH, pivot=PIVOT, mass=MASS, cg=CG, moi_pivot=MOI, cop=MOI / (MASS * CG),
            geometry_mass=0.871, geometry_cg=0.421, geometry_moi_pivot=0.198,
            measured_mass=MASS, measured_cg=CG, measured_moi_pivot=MOI,
            reconciliation="density scaled by 1.032, 11 g at the knob and 6 g at the cap",
            corrections={"density_scale": 1.032, "knob_mass": 0.011, "cap_mass": 0.006},
        ),
        conditions=conditions,
        inputs=[
            InputFile("bat", "ash-34", "bats/ash-34.yaml", _sha("bat")),
            InputFile("protocol", "proposed", "protocols/proposed.yaml", _sha("protocol")),
            InputFile("ball", "collegiate", "protocols/balls/collegiate.yaml", _sha("ball")),
        ],
        batcert_version="0.1.0",
        created="2025-03-14T09:26:53Z",
        warnings=list(warnings or []),
        extras=dict(extras) if extras is not None else {
            "modes_hz": [172.4, 571.9, 1180.6, 1851.2], "contact_time_ms": 0.71,
            "barrel": {"model": "solid", "hoop_frequency_hz": None}},
    )


def set_leftovers(directory):
    """What a report write left in ``directory`` besides its reports: hidden or temporary
    names, and in the folder of linked sets (batcert.reports.linkset) anything but the stems'
    current links and the set folders they show."""
    import os

    from batcert.reports.linkset import SETS
    out = [p.name for p in directory.iterdir()
           if p.name != SETS and (p.name.startswith(".") or p.name.endswith(".tmp"))]
    sets = directory / SETS
    if sets.is_dir():
        current = {c.name for c in sets.iterdir() if c.name.endswith(".current")}
        shown = {os.readlink(sets / c) for c in current}
        out += [f"{SETS}/{p.name}" for p in sets.iterdir()
                if p.name not in current and p.name not in shown]
    return sorted(out)
