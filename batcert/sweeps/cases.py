"""What a sweep varies and what one variant is made of: the :class:`Parameter` entry of the
registry (:data:`batcert.sweeps.variants.PARAMETERS`), the :class:`Case` a variant is made
from, and the error of a parameter that cannot be used."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, replace

from batcert.errors import UsageProblem
from batcert.model.build import BuiltBat
from batcert.specs.bat import BatSpec
from batcert.specs.protocol import ProtocolSpec


@dataclass(frozen=True)
class Case:
    """What one variant is made from: a bat spec and a protocol (picklable, for workers)."""

    bat: BatSpec
    protocol: ProtocolSpec


@dataclass(frozen=True)
class Parameter:
    """One parameter a sweep can vary."""

    name: str
    label: str  # the name in words, for reports' axes and legends ("bat angular speed")
    dimension: str | None  # a batcert.units dimension, None for a plain number
    changes: str  # geometry | measured | protocol
    doc: str
    nominal: Callable[[Case, BuiltBat], float | None]  # the nominal value [SI], if any
    apply: Callable[[Case, BuiltBat, float], Case]  # the case with the value [SI]
    bounds: tuple[float, float]  # accepted values [SI] (the bat file's field ranges)
    tolerance: float  # default tolerance of `batcert design` [SI]
    unit: str = ""  # the unit of a plain number (``dimension`` None) as shown, e.g. "deg"

    @property
    def construction(self) -> bool:
        """Whether the parameter changes the bat's construction or material (its shape, wall,
        material or layup, or the measured hoop frequency its barrel is calibrated to): what
        an engine without the bat's flexibility (the rigid one) sees only through the mass
        properties, if at all."""
        return self.changes == "geometry" or self.name == "hoop_frequency"


class ParameterError(UsageProblem):
    """A parameter or value a sweep cannot use (exit 2, before any work)."""


def geometry_only(spec: BatSpec) -> BatSpec:
    """The bat as its geometry gives it: no measured block (hence no reconciliation and no
    frequency or barrel calibration)."""
    return replace(spec, measured=None)


def hollow(case: Case, what: str) -> None:
    """A hollow bat, or a :class:`ParameterError` naming ``what`` needs one."""
    if case.bat.construction != "hollow":
        raise ParameterError(f"{what} needs a hollow bat; {case.bat.name!r} is solid")
