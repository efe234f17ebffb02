"""Read a command's ``--json`` output: the one envelope of every command (docs/results-json.md),
checked, then its results."""

from __future__ import annotations

import json
from typing import Any


def results(stdout: str, command: str) -> list[Any]:
    """The ``results`` of ``batcert COMMAND --json``'s output, after checking the envelope."""
    data = json.loads(stdout)
    assert list(data)[:4] == ["schema", "command", "batcert_version", "results"], list(data)
    assert data["schema"] == "batcert/1" and data["command"] == command
    return data["results"]


def result(stdout: str, command: str) -> Any:
    """The one result of a command that gives one (compare, league, sweep, reduce, inspect)."""
    (only,) = results(stdout, command)
    return only
