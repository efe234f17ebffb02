"""Impact engines: the registry of tiers behind one interface (:mod:`batcert.engines.base`).

Each entry names the module and class that implement the tier; the module is imported only when
the engine is asked for, so a run with the rigid engine does not load the flexible one.
"""

from __future__ import annotations

import importlib
from dataclasses import dataclass

from batcert.engines.base import Engine, ImpactBatch, ImpactOutcome, Job
from batcert.errors import UsageProblem

__all__ = ["ENGINES", "Engine", "EngineEntry", "EngineUnavailable", "ImpactBatch",
           "ImpactOutcome", "Job", "available_engines", "construction_warning", "get_engine"]


@dataclass(frozen=True)
class EngineEntry:
    """One engine tier: its name, where it lives and what it does."""

    name: str
    module: str
    cls: str
    doc: str


ENGINES: dict[str, EngineEntry] = {
    "rigid": EngineEntry("rigid", "batcert.engines.rigid", "RigidEngine",
                         "closed-form rigid bat (Smith 2001 Eqs. 1-7): exact and instant"),
    "flexible": EngineEntry("flexible", "batcert.engines.flexible", "FlexibleEngine",
                            "vibrating Timoshenko beam and hollow barrel against the ball's "
                            "contact law (viscoelastic, or Nathan's 2000 hysteresis), batched"),
}


class EngineUnavailable(UsageProblem, LookupError):
    """The requested engine tier does not exist in this installation."""


def available_engines() -> list[str]:
    return sorted(ENGINES)


def get_engine(name: str, **options) -> Engine:
    """A new engine of tier ``name`` with ``options``; :class:`EngineUnavailable` if unknown."""
    entry = ENGINES.get(name)
    if entry is None:
        raise EngineUnavailable(f"the {name!r} engine is not available in this installation "
                                f"(available: {', '.join(available_engines())}); choose one "
                                "with --engine")
    engine: Engine = getattr(importlib.import_module(entry.module), entry.cls)(**options)
    return engine


def construction_warning(name: str) -> str | None:
    """What a result of engine ``name`` does not show of a bat's construction and material
    (:attr:`Engine.construction_warning`), without making the engine; None for an unknown one."""
    entry = ENGINES.get(name)
    if entry is None:
        return None
    cls = getattr(importlib.import_module(entry.module), entry.cls)
    return cls.construction_warning
