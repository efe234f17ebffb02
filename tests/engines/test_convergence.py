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


@pytest.mark.slow
@pytest.mark.parametrize("bat", BATS)
def test_defaults_are_within_two_hundredths_of_a_percent_of_converged(bat):
    # Converged: 48 modes (3x), 2.5 us (1/8 of the solid step, 1/5 of the hollow one), shell
    # modes to 16 kHz; refined further (64 modes, 1.25 us, 20 kHz) the results move by under
    # 5e-6 (measured). Every condition's exit speed at the located point and the aggregated
    # metric. Measured with the defaults: solid 4.7e-5, hollow 2.4e-5 at most.
    built = load_bat_any(bat).built
    for name in PROTOCOLS:
        p = load_protocol_any(name)
        default = run_protocol(built, p.protocol, p.ball, FlexibleEngine())
        converged = run_protocol(built, p.protocol, p.ball, FlexibleEngine(**CONVERGED))
        pairs = [(a.exit_speed, b.exit_speed) for a, b in
                 zip(default.conditions, converged.conditions, strict=True)]
        pairs.append((default.value, converged.value))
        for value, limit in pairs:
            assert value == pytest.approx(limit, rel=2e-4), (name, value, limit)
