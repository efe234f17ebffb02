"""The examples in the physics docstrings run and reproduce their published numbers (Smith 2001
Eqs. 2, 4 and 7; Nathan 2000's ball), on the installed package."""

from __future__ import annotations

import doctest

import pytest

from batcert.physics import rigid
from batcert.physics.balls import power_law


@pytest.mark.parametrize("module", [rigid, power_law], ids=lambda m: m.__name__)
def test_docstring_examples(module):
    result = doctest.testmod(module, optionflags=doctest.NORMALIZE_WHITESPACE)
    assert result.attempted > 0 and result.failed == 0
