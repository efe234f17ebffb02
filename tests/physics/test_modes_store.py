"""A bat's beam modes kept between processes (batcert.workspace, batcert.cache): stored
modes are the computed ones exactly, an entry that does not fit is recomputed, and the command
line's second run reads the modes instead of computing them."""

from __future__ import annotations

import numpy as np
import pytest
from dict_store import forget, installed
from r161 import r161_bat

from batcert.physics import modes as modes_module

PIVOT = 0.1524  # [m from knob]
FIELDS = ("z", "omega", "shapes", "rotations")


@pytest.fixture
def store():
    with installed("modes") as s:
        yield s


def refuse(*args, **kwargs):
    pytest.fail("the modes were computed again")


@pytest.mark.parametrize("support", ["pinned", "free"])
def test_stored_modes_are_the_computed_ones(store, monkeypatch, support):
    bat = r161_bat()
    computed = modes_module.cached_modes(bat, support, PIVOT, 16)
    assert store.saves == 1
    forget("modes")
    monkeypatch.setattr(modes_module, "compute_modes", refuse)
    read = modes_module.cached_modes(bat, support, PIVOT, 16)
    assert (read.support, read.pivot, read.n_rigid) == (support, PIVOT, computed.n_rigid)
    for f in FIELDS:
        np.testing.assert_array_equal(getattr(read, f), getattr(computed, f))
        assert not getattr(read, f).flags.writeable  # shared, as computed ones are
    # another pivot, number of modes or support is another entry
    monkeypatch.undo()
    modes_module.cached_modes(bat, support, PIVOT + 0.01, 16)
    modes_module.cached_modes(bat, support, PIVOT, 12)
    assert store.saves == len(store.entries) == 3


@pytest.mark.parametrize("damage", [
    lambda a: a.pop("shapes"),
    lambda a: a.update(shapes=a["shapes"][:, :-1]),
    lambda a: a.update(n_rigid=np.array(0)),
    lambda a: a.update(omega=np.array("not numbers")),
])
def test_an_entry_that_does_not_fit_is_recomputed(store, damage):
    bat = r161_bat()
    computed = modes_module.cached_modes(bat, "pinned", PIVOT, 16)
    (entry,) = store.entries.values()
    damage(entry)
    forget("modes")
    again = modes_module.cached_modes(bat, "pinned", PIVOT, 16)
    for f in FIELDS:
        np.testing.assert_array_equal(getattr(again, f), getattr(computed, f))
    assert store.saves == 2  # and written again, whole


def test_the_second_run_reads_the_modes(batcert_cli, tmp_path, monkeypatch):
    # the ball lot's calibration on its reference bat (ash-34 under ncaa-bbcor, two more sets
    # of modes) is made here first, while the default cache is attached: otherwise whether the
    # run below computes it depended on which tests had run before in the same process (4 mode
    # files or 2: it failed in one full run of the suite)
    from batcert.commands.inputs import load_protocol_any
    load_protocol_any("proposed")
    monkeypatch.setenv("BATCERT_CACHE_DIR", str(tmp_path / "cache"))
    forget("modes")
    first = batcert_cli("run", "ash-34", "-p", "proposed", "--json")
    # the engine's pinned modes and the report's free ones
    assert len(list((tmp_path / "cache" / "modes").glob("*.arrays"))) == 2
    forget("modes")
    monkeypatch.setattr(modes_module, "compute_modes", refuse)
    second = batcert_cli("run", "ash-34", "-p", "proposed", "--json")
    assert first.exit_code == second.exit_code == 0
    strip = [line for line in first.stdout.splitlines() if '"created"' not in line]
    assert strip == [line for line in second.stdout.splitlines() if '"created"' not in line]
    forget("modes")
