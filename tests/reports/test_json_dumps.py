"""batcert.results.serialise.dumps: the reports' and --json's JSON writer (issue 29: the
standard library's indenting encoder took 0.2 s of an 800-variant sweep's serial part)."""

import json
import math

import pytest
from hypothesis import given
from hypothesis import strategies as st

from batcert.results.serialise import dumps

scalars = st.one_of(st.none(), st.booleans(), st.integers(-10**12, 10**12),
                    st.floats(allow_nan=False, allow_infinity=False), st.text(max_size=8))
documents = st.recursive(scalars, lambda inner: st.one_of(
    st.lists(inner, max_size=5), st.dictionaries(st.text(max_size=6), inner, max_size=5)),
    max_leaves=30)


@given(documents)
def test_dumps_reads_back_as_the_standard_librarys_json(doc):
    assert json.loads(dumps(doc)) == json.loads(json.dumps(doc, indent=2))


def test_lists_of_numbers_on_one_line_objects_indented():
    text = dumps({"values": [1.0, 2.5, None], "rows": [{"a": 1}]})
    assert text.splitlines() == ['{', '  "values": [1.0, 2.5, null],', '  "rows": [',
                                 '    {', '      "a": 1', '    }', '  ]', '}']


@pytest.mark.parametrize("bad", [math.nan, math.inf, -math.inf])
def test_non_finite_numbers_are_refused(bad):
    with pytest.raises(ValueError):
        dumps({"x": [1.0, bad]})
