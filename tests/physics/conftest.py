"""Fixtures of the physics tests: the barrel cache emptied for a test module and put back."""

from __future__ import annotations

import pytest

from batcert import workspace


@pytest.fixture(scope="module")
def own_barrel_cache():
    """The module's walls in a workspace of their own, the process's untouched."""
    with workspace.active(workspace.Workspace()) as ws:
        yield ws


@pytest.fixture
def empty_barrel_cache(own_barrel_cache):
    own_barrel_cache.clear()
    return own_barrel_cache
