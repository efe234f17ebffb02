"""The league rule kind ``min-barrel-compression``: the barrel compression of the rule's
protocol run (after its break-in), against a force; evaluated on a hand-made run result so that
every number is known (batcert.analysis.league)."""

from __future__ import annotations

import pytest

from batcert.analysis.league import EVALUATIONS
from batcert.results.run import CompressionResult
from batcert.specs.league import LIMIT_KINDS, runs_protocol


class _Run:  # the two fields the rule reads of a RunResult
    def __init__(self, compression):
        self.compression, self.break_in, self.protocol = compression, None, "p"


class _Rule:
    id, kind, protocol = "compression", "min-barrel-compression", "p"

    def __init__(self, limit):
        self.limit = limit


def _compression(force: float) -> CompressionResult:
    return CompressionResult(0.1524, 0.0254, 0.001016, force, force / 0.001016, None, None,
                             None)


@pytest.mark.parametrize("force, verdict, margin", [(5000.0, "pass", 1000.0),
                                                    (3000.0, "fail", -1000.0),
                                                    (4000.0, "pass", 0.0)])
def test_the_force_is_held_against_the_minimum(force, verdict, margin):
    got = EVALUATIONS["min-barrel-compression"](_Rule(4000.0), None, _Run(_compression(force)))
    assert got.verdict == verdict and got.margin == pytest.approx(margin) and got.unit == "N"


def test_a_run_without_a_compression_test_is_not_modelled():
    got = EVALUATIONS["min-barrel-compression"](_Rule(4000.0), None, _Run(None))
    assert got.verdict == "not-modelled" and "no barrel compression test" in got.note


def test_the_rule_runs_its_protocol_and_reads_a_force():
    assert runs_protocol("min-barrel-compression") and runs_protocol("performance")
    assert not runs_protocol("max-length")
    assert "force" in LIMIT_KINDS
