"""The metric registry (batcert.methods.metrics.METRICS) holds everything about a metric: every
entry's field is kept where the registry says (the impact record, a run's condition result, a
lab's reduction for the lab metrics), and the views list the registry's metrics."""

from __future__ import annotations

import dataclasses

from batcert.lab.certify import LAB_METRICS
from batcert.methods.metrics import METRICS, ImpactMetrics
from batcert.methods.reduction import HitReduction
from batcert.reports import format as fmt
from batcert.results.run import ConditionResult


def _fields(cls) -> set[str]:
    return {f.name for f in dataclasses.fields(cls)}


def test_every_metric_is_kept_where_the_registry_says():
    for m in METRICS.values():
        assert m.field in _fields(ImpactMetrics), m.name
        assert m.field in _fields(ConditionResult), m.name
        if m.lab:
            assert m.field in _fields(HitReduction), m.name


def test_the_lab_metrics_are_the_registry_s():
    assert LAB_METRICS == {m.name: m.field for m in METRICS.values() if m.lab}
    assert set(LAB_METRICS) == {"bpf", "besr", "bbcor", "collision-efficiency"}


def test_the_condition_tables_show_every_dimensionless_metric():
    shown = [name for name, _, _ in fmt.condition_metrics()]
    assert shown == [m.name for m in METRICS.values() if not m.unit]
    assert "exit-speed" not in shown  # shown as a speed of its own
