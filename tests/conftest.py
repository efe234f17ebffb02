"""Shared test fixtures: repository paths and a CLI runner. Kept small on purpose; helpers that
only one test directory needs live in that directory."""

from __future__ import annotations

from pathlib import Path

import pytest
from click.testing import CliRunner, Result

from batcert.cli import main

REPO = Path(__file__).resolve().parents[1]
FIXTURES = REPO / "tests" / "fixtures"


@pytest.fixture(autouse=True, scope="session")
def _cache_dir(tmp_path_factory):
    """The cache directory of the tests' runs (batcert.cache: compiled report templates,
    barrel shells) is a temporary directory, not the user's ~/.cache."""
    import os
    os.environ["BATCERT_CACHE_DIR"] = str(tmp_path_factory.mktemp("batcert-cache"))


@pytest.fixture
def repo_root() -> Path:
    """The checkout's top directory (holds bats/ and protocols/)."""
    return REPO


@pytest.fixture
def fixtures_dir() -> Path:
    """tests/fixtures: good/ and bad/ spec files."""
    return FIXTURES


@pytest.fixture
def batcert_cli():
    """Invoke ``batcert ARGS...`` in-process; returns click's Result (stdout and stderr apart)."""
    runner = CliRunner()

    def invoke(*args: str | Path) -> Result:
        return runner.invoke(main, [str(a) for a in args], catch_exceptions=False)

    return invoke
