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
