"""The physics' in-process memo (batcert.physics.stores.Memo): least recently used out."""

from __future__ import annotations

from batcert.physics.stores import Memo


def test_keeps_the_most_recently_used():
    memo: Memo[str, int] = Memo(2)
    assert memo.keep("a", 1) == 1
    memo.keep("b", 2)
    assert memo.look("a") == 1  # "a" is now the most recently used
    memo.keep("c", 3)  # so "b" goes
    assert list(memo) == ["a", "c"] and memo.look("b") is None


def test_keeping_again_refreshes_an_entry():
    memo: Memo[str, int] = Memo(2)
    memo.keep("a", 1)
    memo.keep("b", 2)
    memo.keep("a", 10)
    memo.keep("c", 3)
    assert dict(memo) == {"a": 10, "c": 3}


def test_a_miss_changes_nothing():
    memo: Memo[str, int] = Memo(3)
    memo.keep("a", 1)
    memo.keep("b", 2)
    assert memo.look("x") is None and list(memo) == ["a", "b"]


def test_a_batch_is_kept_by_its_owner_and_contents(monkeypatch):
    # one computation per owner, key and array contents; a batch above MEMO_ROWS rows is
    # recomputed every time and leaves nothing behind
    import numpy as np

    from batcert.physics import stores

    monkeypatch.setattr(stores, "MEMO_ROWS", 3)
    memo: Memo[tuple, tuple] = Memo(8)
    owner, other = object(), object()
    calls = []

    def solve(tag):
        calls.append(tag)
        return tag

    rows = np.arange(3.0)
    assert memo.batch(owner, ("k",), (rows,), lambda: solve(1)) == 1
    assert memo.batch(owner, ("k",), (rows.copy(),), lambda: solve(2)) == 1  # same contents
    assert memo.batch(owner, ("k",), (rows + 1,), lambda: solve(3)) == 3
    assert memo.batch(other, ("k",), (rows,), lambda: solve(4)) == 4
    assert memo.batch(owner, ("j",), (rows,), lambda: solve(5)) == 5
    kept = len(memo)
    large = np.arange(4.0)
    memo.batch(owner, ("k",), (large,), lambda: solve(6))
    memo.batch(owner, ("k",), (large,), lambda: solve(7))
    assert calls == [1, 3, 4, 5, 6, 7] and len(memo) == kept == 4
