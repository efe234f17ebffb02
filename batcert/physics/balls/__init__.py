"""Ball contact laws: a registry, one entry per law, each with everything about it.

A law is a frozen dataclass of its parameters with the same methods (the interface the engines,
the fit and ``inspect`` use):

* ``wall_cor(mass, speed)``: the COR of the ball fired at a rigid flat wall [-];
* ``body_cor(mass, speed, recoil, rule)``: against a rigid body of effective-mass ratio
  ``recoil`` (the rigid engine);
* ``march_rows(...)``: its state in a batched time integration (the flexible engine,
  :func:`batcert.physics.balls.impact1d.body_impact`): the forces at a step's stages, the
  contact measure whose sign change is separation;
* ``describe()``: its parameters for reports.

Laws (:data:`LAWS`): ``power-law-hysteresis`` (Nathan 2000: a rate-independent hysteresis loop;
the law of the published validations), ``viscoelastic`` (a nonlinear standard linear solid:
the loss follows the rate of the squeeze, as in the finite-element ball of the 2001 study; its
parameters are fitted to ball tests, :mod:`batcert.physics.balls.fit`) and ``viscoelastic-2``
(the same with two relaxation times, whose COR can keep falling with speed).
"""

from __future__ import annotations

from dataclasses import dataclass

from batcert.physics.balls.hysteresis import PowerLawHysteresis
from batcert.physics.balls.law import ContactLaw
from batcert.physics.balls.viscoelastic import TwoTimeViscoelastic, Viscoelastic

__all__ = ["LAWS", "ContactLaw", "LawEntry", "PowerLawHysteresis", "TwoTimeViscoelastic",
           "Viscoelastic"]


@dataclass(frozen=True)
class LawEntry:
    """One contact law: its name (the ball file's ``contact.model``), its parameter class
    (a :class:`~batcert.physics.balls.law.ContactLaw`), a display word, a line of documentation,
    and what the engines, the runner and the uncertainty need to know of it."""

    name: str
    law: type
    title: str
    doc: str
    # its COR against a rigid body comes in closed form (no integration: the rigid engine and
    # the runner read it per impact)
    closed_form_cor: bool = False
    # the ball file's COR points are its parameters (a stated uncertainty on them moves it)
    cor_parameters: bool = False


LAWS: dict[str, LawEntry] = {
    PowerLawHysteresis.name: LawEntry(
        PowerLawHysteresis.name, PowerLawHysteresis, "power-law hysteresis (Nathan 2000)",
        "F = k1 u^alpha on compression, k2 u^beta on restitution, beta = (1 + alpha)/e0^2 - 1; "
        "e0 from the ball's COR points: a loss that does not depend on the rate",
        closed_form_cor=True, cor_parameters=True),
    Viscoelastic.name: LawEntry(
        Viscoelastic.name, Viscoelastic, "viscoelastic (standard linear solid)",
        "F = k0 u^a - k1 s, ds/dt = (u^a - s)/tau, F >= 0: the loss follows the rate of the "
        "squeeze; parameters fitted to the ball's tests (COR at several speeds, contact "
        "times, compression)"),
    TwoTimeViscoelastic.name: LawEntry(
        TwoTimeViscoelastic.name, TwoTimeViscoelastic,
        "viscoelastic, two relaxation times (generalised Maxwell)",
        "F = k0 u^a - k_s s_s - k_f s_f, ds_j/dt = (u^a - s_j)/tau_j, F >= 0: a slow branch "
        "holds the loss of slow impacts, a fast one a loss that grows as the contact shortens, "
        "so the COR can fall with speed over the whole range; fitted to the ball's tests"),
}
