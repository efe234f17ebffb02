"""The rigid engine never builds a hollow bat's barrel shell (issue 29: a cold rigid run of a
hollow bat used to compute a shell, about 0.3 s, that the engine does not use)."""

import pytest

import batcert
from batcert import workspace
from batcert.physics import barrel
from batcert.physics.barrel import lab, wall


@pytest.fixture
def shells(monkeypatch):
    """Every barrel shell built, by the bat it was built for."""
    built = []
    original = wall.barrel_shell

    def spy(bat):
        built.append(bat)
        return original(bat)

    for module in (wall, lab, barrel):
        monkeypatch.setattr(module, "barrel_shell", spy)
    return built


def test_a_rigid_run_of_a_hollow_bat_builds_no_shell(shells):
    with workspace.active(workspace.Workspace()):  # nothing kept from other tests
        result = batcert.run("aluminium-34", "proposed", engine="rigid")
    assert shells == []
    assert "barrel" not in result.extras and result.barrel is None


def test_a_flexible_run_builds_the_shell_and_records_it(shells):
    # the spy sees what the check above would have seen, had the rigid run built one
    with workspace.active(workspace.Workspace()):
        result = batcert.run("aluminium-34", "proposed")
    assert shells and "barrel" in result.extras
