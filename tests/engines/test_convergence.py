"""The flexible engine's defaults against its converged limit, on every shipped bat under every
shipped protocol: an exit speed needs 0.1 %; the defaults are chosen for 0.01 % and checked
here against the issue's 0.02 % (engines/flexible.py, DEFAULT_MODES and the steps)."""

from __future__ import annotations

import pytest

from batcert.commands.inputs import load_bat_any, load_protocol_any
from batcert.engines.flexible import FlexibleEngine
from batcert.runner.runner import run_protocol

BATS = ["ash-34", "r161", "aluminium-34", "bbcor-alloy-34"]
PROTOCOLS = ["astm-bpf", "ncaa-bbcor", "ncaa-besr", "proposed", "stationary-ball"]
CONVERGED = dict(n_modes=48, time_step=2.5e-6, shell_max_frequency=16_000.0)


def _assert_defaults_converged(built, protocols) -> None:
    """Every condition's exit speed at the located point and the aggregated metric of each
    protocol, with the defaults, within 0.02 % of the converged engine."""
    for p in protocols:
        default = run_protocol(built, p.protocol, p.ball, FlexibleEngine())
        converged = run_protocol(built, p.protocol, p.ball, FlexibleEngine(**CONVERGED))
        pairs = [(a.exit_speed, b.exit_speed) for a, b in
                 zip(default.conditions, converged.conditions, strict=True)]
        pairs.append((default.value, converged.value))
        for value, limit in pairs:
            assert value == pytest.approx(limit, rel=2e-4), (p.protocol.id, value, limit)


@pytest.mark.parametrize("bat", BATS)
def test_defaults_are_within_two_hundredths_of_a_percent_of_converged(bat):
    # Converged: 48 modes (3x), 2.5 us (1/5 of the default step), shell modes to 16 kHz;
    # refined further (64 modes, 1.25 us, 20 kHz) the results move by under 5e-6 (measured).
    # Measured with the defaults and the shipped viscoelastic ball: ash-34 7.7e-5, r161
    # 6.5e-5, aluminium-34 5.8e-5, bbcor-alloy-34 6.5e-5 at most.
    _assert_defaults_converged(load_bat_any(bat).built,
                               [load_protocol_any(name) for name in PROTOCOLS])


@pytest.mark.parametrize("wall", [1.8e-3, 3.2e-3])
def test_defaults_hold_for_thin_and_thick_walls(wall):
    # aluminium-34 with its wall made 1.8 and 3.2 mm (the sweeps' wall parameter). Measured
    # with the defaults and the two-relaxation-time ball: 1.6e-4 on the thin wall's BBCOR exit
    # speed, mostly the 12 kHz shell-mode cut (at 10 kHz it was 5.1e-4).
    from batcert.model.build import build_bat
    from batcert.sweeps.variants import Case, lookup_parameter

    nominal = load_bat_any("aluminium-34").built
    protocols = [load_protocol_any(name) for name in PROTOCOLS]
    case = lookup_parameter("wall").apply(Case(nominal.spec, protocols[0].protocol), nominal,
                                          wall)
    _assert_defaults_converged(build_bat(case.bat), protocols)
