"""Fixtures of the physics tests: the barrel cache emptied for a test module and put back."""

from __future__ import annotations

from collections import OrderedDict

import pytest

from batcert.physics import barrel


@pytest.fixture(scope="module")
def own_barrel_cache():
    """The module's walls in a cache of their own, the process's put back afterwards."""
    saved = OrderedDict(barrel._CACHE)
    barrel.clear_barrel_cache()
    yield
    barrel._CACHE.clear()
    barrel._CACHE.update(saved)


@pytest.fixture
def empty_barrel_cache(own_barrel_cache):
    barrel.clear_barrel_cache()
