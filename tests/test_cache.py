"""The cache directory's array store (batcert.cache): entries survive a round trip exactly,
follow the code that made them, and every failure is only a miss."""

from __future__ import annotations

import os

import numpy as np
import pytest

from batcert.cache import ArrayStore, cache_dir, code_fingerprint

ARRAYS = {"a": np.linspace(0.0, 1.0, 7), "b": np.arange(6.0).reshape(2, 3),
          "s": np.array(("closed", "open")), "x": np.array(2.5), "n": np.arange(3, dtype=np.int64),
          "c": np.array([1 + 2j, 3 - 4j]), "t": np.arange(12.0).reshape(3, 4).T,
          "e": np.zeros((0, 3)), "f": np.array([True, False])}


@pytest.fixture
def where(tmp_path, monkeypatch):
    monkeypatch.setenv("BATCERT_CACHE_DIR", str(tmp_path / "cache"))
    return tmp_path / "cache" / "things"


def same(a, b):
    return a.keys() == b.keys() and all(np.array_equal(a[k], b[k]) for k in a)


def test_an_entry_round_trips_exactly(where):
    store = ArrayStore("things", code=("batcert.cache",))
    assert store.load("k") is None
    store.save("k", ARRAYS)
    assert same(store.load("k"), ARRAYS)
    assert [p.suffix for p in where.iterdir()] == [".arrays"]  # no temporary file left


def test_entries_follow_the_code_that_made_them(where):
    ArrayStore("things", code=("batcert.cache",)).save("k", ARRAYS)
    assert ArrayStore("things", code=("batcert.units",)).load("k") is None
    assert code_fingerprint(("batcert.cache",)) != code_fingerprint(("batcert.units",))
    # a library is fingerprinted by its release file, a module by its source
    assert code_fingerprint(("numpy", "batcert.cache")) is not None


def test_no_code_no_store(where):
    store = ArrayStore("things", code=("batcert.no_such_module",))
    store.save("k", ARRAYS)
    assert store.load("k") is None
    assert not where.exists() or not any(where.iterdir())


@pytest.mark.parametrize("damage", ["foreign", "truncated", "header", "shape"])
def test_a_damaged_entry_is_a_miss_and_is_replaced(where, damage):
    store = ArrayStore("things", code=("batcert.cache",))
    store.save("k", ARRAYS)
    (path,) = where.glob("*.arrays")
    data = path.read_bytes()
    path.write_bytes({"foreign": b"PK\x03\x04 not ours",
                      "truncated": data[:len(data) // 2],
                      "header": data.replace(b'"shape"', b'"shope"', 1),
                      "shape": data.replace(b"[2, 3]", b"[9, 9]", 1)}[damage])
    assert store.load("k") is None
    store.save("k", ARRAYS)
    assert same(store.load("k"), ARRAYS)


def test_loaded_arrays_are_writable_and_arrays_of_objects_are_not_kept(where):
    store = ArrayStore("things", code=("batcert.cache",))
    store.save("k", ARRAYS)
    loaded = store.load("k")
    loaded["a"][0] = 5.0  # a private copy of the file's bytes
    assert same(store.load("k"), ARRAYS)
    store.save("objects", {"o": np.array([{}, None], dtype=object)})
    assert store.load("objects") is None


def test_an_unwritable_cache_is_passed_over(tmp_path, monkeypatch):
    (tmp_path / "file").write_text("not a directory")
    monkeypatch.setenv("BATCERT_CACHE_DIR", str(tmp_path / "file"))
    assert cache_dir("things") is None
    store = ArrayStore("things", code=("batcert.cache",))
    store.save("k", ARRAYS)  # no error
    assert store.load("k") is None


def test_the_least_recently_used_entries_go_first(where):
    size = ArrayStore("things", code=("batcert.cache",))
    size.save("probe", ARRAYS)
    (probe,) = where.glob("*.arrays")
    one = probe.stat().st_size
    probe.unlink()
    store = ArrayStore("things", code=("batcert.cache",), limit=int(2.5 * one))
    store.save("first", ARRAYS)
    store.save("second", ARRAYS)
    old = [(p, p.stat().st_mtime) for p in where.glob("*.arrays")]
    for p, _ in old:  # make "first" the older and then read it: it becomes the recent one
        os.utime(p, (1, 1))
    assert store.load("first") is not None
    store.save("third", ARRAYS)
    assert store.load("first") is not None and store.load("third") is not None
    assert store.load("second") is None
    assert len(list(where.glob("*.arrays"))) == 2
