"""The workspace (batcert.workspace): content keys, least recently used out, batches too
large to keep, an attached disk store, one workspace per block."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from batcert import workspace
from batcert.physics.batmodel import Material

CALLS: list[tuple] = []


def square(x):
    CALLS.append((x,))
    return np.asarray(x) ** 2


def halve(x):
    return np.asarray(x) / 2


@pytest.fixture
def ws():
    CALLS.clear()
    with workspace.active(workspace.Workspace()) as w:
        yield w


def test_equal_content_shares_an_entry_and_any_difference_does_not(ws):
    a = np.arange(5.0)
    first = ws.call("footprint", square, a)
    assert ws.call("footprint", square, a.copy()) is first  # another array, same content
    assert ws.call("footprint", square, a.astype(np.float32)) is not first  # another dtype
    assert ws.call("footprint", square, a.reshape(5, 1)) is not first  # another shape
    assert ws.call("footprint", halve, a) is not first  # another function
    b = a.copy()
    b[4] = np.nextafter(4.0, 5.0)  # one ulp
    assert ws.call("footprint", square, b) is not first
    assert len(CALLS) == 4


def test_dataclasses_are_keyed_by_every_field():
    m = Material("ash", 650.0, 12e9, 0.8e9, 0.3, 0.01)
    key = workspace.content_key(m)
    assert workspace.content_key(dataclasses.replace(m)) == key
    for f in dataclasses.fields(m):
        value = getattr(m, f.name)
        other = value + "x" if isinstance(value, str) else value * 1.5
        assert workspace.content_key(dataclasses.replace(m, **{f.name: other})) != key, f.name


def test_what_has_no_content_cannot_be_a_key():
    with pytest.raises(TypeError):
        workspace.content_key(object())
    with pytest.raises(TypeError):
        workspace.content_key(lambda x: x)  # a lambda's name says nothing of what it computes
    assert workspace.content_key(1) != workspace.content_key(1.0) != workspace.content_key("1")
    assert workspace.content_key((1, 2)) != workspace.content_key([1, 2])


def test_a_read_only_array_changed_through_its_base_is_hashed_anew():
    # the digest of a large read-only array is remembered while the array lives; a writeable
    # array is hashed every time
    a = np.zeros(10000)
    before = workspace.content_key(a)
    a[0] = 1.0
    assert workspace.content_key(a) != before
    a.setflags(write=False)
    ro = workspace.content_key(a)
    assert workspace.content_key(a) == ro == workspace.content_key(a.copy())


def test_least_recently_used_out(ws, monkeypatch):
    monkeypatch.setitem(workspace.KINDS, "footprint", workspace.Kind(2, None, "test"))
    for x in (1.0, 2.0, 1.0, 3.0):  # 1 is used again before 3 arrives: 2 goes
        ws.call("footprint", square, x)
    assert ws.count("footprint") == 2
    ws.call("footprint", square, 1.0)
    assert len(CALLS) == 3
    ws.call("footprint", square, 2.0)
    assert len(CALLS) == 4


def test_a_large_batch_is_computed_and_not_kept(ws):
    rows = workspace.BATCH_ROWS + 1
    ws.call("patch-factors", square, np.zeros(rows), rows=rows)
    assert ws.count("patch-factors") == 0
    ws.call("patch-factors", square, np.zeros(3), rows=3)
    assert ws.count("patch-factors") == 1


def test_a_disk_store_serves_another_workspace(ws):
    from dict_store import DictStore

    disk = DictStore()
    ws.attach(lambda folder: disk)
    save = lambda v: {"v": v}  # noqa: E731
    load = lambda a: None if a is None else np.array(a["v"])  # noqa: E731
    first = ws.call("ball-wall", square, np.arange(3.0), save=save, load=load)
    assert disk.saves == 1 and len(CALLS) == 1
    other = workspace.Workspace()
    other.attach(lambda folder: disk)
    again = other.call("ball-wall", square, np.arange(3.0), save=save, load=load)
    np.testing.assert_array_equal(again, first)
    assert len(CALLS) == 1  # read, not computed
    # a kind kept in the process only never reaches the disk
    ws.call("footprint", square, 2.0, save=save, load=load)
    assert disk.saves == 1


def test_active_sets_the_workspace_for_the_block_only():
    outer = workspace.current()
    inner = workspace.Workspace()
    with workspace.active(inner):
        assert workspace.current() is inner
    assert workspace.current() is outer


def test_every_kind_is_documented_and_disk_kinds_have_folders():
    folders = [k.folder for k in workspace.KINDS.values() if k.folder is not None]
    assert len(folders) == len(set(folders))
    assert all(k.size > 0 and k.what for k in workspace.KINDS.values())

