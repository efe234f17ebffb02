"""A hollow bat's wall kept between processes (batcert.workspace, batcert.cache): a
stored wall is the computed one exactly, a stored entry that does not fit is recomputed, and
the command line's second run reads the wall instead of computing it. Also the pure-numpy
Bessel function the barrel's response uses instead of scipy's."""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest

from batcert import workspace
from batcert.physics import barrel
from batcert.physics.barrel import wall

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "engines"))
from dict_store import installed  # noqa: E402
from test_flexible import hollow_bat  # noqa: E402


@pytest.fixture
def store():
    with installed("barrel") as s:
        yield s


def equal(a: barrel.BarrelModes, b: barrel.BarrelModes) -> bool:
    return (a.orders == b.orders and a.max_frequency == b.max_frequency
            and all(np.array_equal(getattr(a, f), getattr(b, f))
                    for f in ("green", "omega", "mode_orders", "shapes"))
            and all(np.array_equal(getattr(a.shell, f), getattr(b.shell, f))
                    for f in ("z", "r", "thickness", "density", "youngs_modulus"))
            and a.shell.ends == b.shell.ends and a.green_scale == b.green_scale)


def test_a_stored_wall_is_the_computed_one(store, monkeypatch):
    bat = hollow_bat(2.5e-3)
    computed = barrel.cached_barrel_modes(bat)
    assert (store.saves, len(store.entries)) == (1, 1)
    workspace.current().clear()

    def refuse(*args, **kwargs):
        raise AssertionError("the wall was computed again")

    monkeypatch.setattr(wall, "shell_modes", refuse)
    assert equal(barrel.cached_barrel_modes(bat), computed)
    assert store.saves == 1


def test_a_stored_entry_that_does_not_fit_is_recomputed(store):
    bat = hollow_bat(2.5e-3)
    computed = barrel.cached_barrel_modes(bat)
    (key,) = store.entries
    for damage in ({"green": np.zeros((2, 3, 4))}, {"max_frequency": np.array(1.0)},
                   {"omega": None}):
        entry = dict(store.entries[key])
        for name, value in damage.items():
            if value is None:
                del entry[name]
            else:
                entry[name] = value
        store.entries[key] = entry
        workspace.current().clear()
        assert equal(barrel.cached_barrel_modes(bat), computed)
        # and the entry is written again, whole
        assert wall._from_arrays(store.entries[key], barrel.NOMINAL_CUT) is not None


def test_the_second_run_reads_the_wall(batcert_cli, tmp_path, monkeypatch):
    monkeypatch.setenv("BATCERT_CACHE_DIR", str(tmp_path / "cache"))
    workspace.current().clear()
    first = batcert_cli("run", "aluminium-34", "-p", "ncaa-bbcor", "--json")
    stored = list((tmp_path / "cache" / "barrels").glob("*.arrays"))
    assert len(stored) == 1
    workspace.current().clear()
    monkeypatch.setattr(wall, "shell_modes",
                        lambda *a, **k: pytest.fail("the wall was computed again"))
    second = batcert_cli("run", "aluminium-34", "-p", "ncaa-bbcor", "--json")
    assert first.exit_code == second.exit_code
    strip = [line for line in first.stdout.splitlines() if '"created"' not in line]
    assert strip == [line for line in second.stdout.splitlines() if '"created"' not in line]
    workspace.current().clear()
