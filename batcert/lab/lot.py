"""A session's ball lot calibrated on a reference bat measured with the same balls, as labs
check their lots (docs/lab-reduction.md, "The ball lot").

A session may name a reference bat's session (``reference_session``): the same day's hits on a
reference bat (a wood bat whose level is known) with the same ball file. Its hits are reduced
and certified under the same protocol (:func:`batcert.lab.certify.certify`), and that measured
value, with its combined standard uncertainty, calibrates the ball lot
(:func:`batcert.runner.lot.calibrated_lot`) in place of the ball file's own ``reference_bat``.
The session's model prediction, its barrel calibration and its BPF's ball COR then use that
lot. The measured values of the session itself (BBCOR, BESR, e_A) do not depend on the ball
law: they are reduced from the speeds, the impact location, the MOI and the ball's mass.

The calibration is an INPUT: the reference bat's model value equals its measurement by
construction, so it is no longer a validation of the model.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from pathlib import Path

from batcert.lab.certify import certify
from batcert.lab.session import LabSession, load_lab_session
from batcert.runner.lot import calibrated_lot
from batcert.specs.ball import ReferenceBat, load_ball
from batcert.specs.protocol import ProtocolSpec
from batcert.specs.resolve import display_path
from batcert.specs.session import is_hits_csv
from batcert.units import INCH

FIELD = "reference_session"


@dataclass(frozen=True)
class ReferenceSession:
    """The reference bat's session and what its hits certified."""

    session: LabSession
    value: float  # the certified value under the protocol [metric]
    uncertainty: float  # its combined standard uncertainty [metric]
    hits_used: int
    location_from_tip: float  # [m]


def with_session_lot(session: LabSession,
                     protocol: ProtocolSpec) -> tuple[LabSession, ReferenceSession | None]:
    """``session`` with its ball lot calibrated on its reference session's certified value
    (module notes), and that reference; ``session`` itself and None when it names none. An
    input error at the session's ``reference_session`` line when the reference cannot serve:
    no such file, a hits CSV, the session itself, another ball file, a chain of references,
    a ball law not fitted to ball tests, hits taken about another pivot than the protocol's,
    hits that certify no value, or a value no lot within the bounds reaches."""
    spec = session.spec
    if spec.reference_session is None:
        return session, None
    here = Path(spec.path)
    path = here.parent / spec.reference_session
    _check_path(session, path)
    ref = load_lab_session(path)
    _check_reference(session, ref)
    _check_pivot(session, ref, protocol)
    _, c = certify(ref, protocol)
    if c.value is None or c.location is None:
        raise spec.source.problem(FIELD, f"the reference bat's hits ({display_path(path)}) "
                                  f"certify no {protocol.metric.upper()} under {protocol.id}: "
                                  f"{'; '.join(c.warnings)}")
    measured = ReferenceSession(ref, c.value, c.u_c, len(c.used), c.scan[c.location].from_tip)
    reference = ReferenceBat(
        bat=ref.built.spec.path, protocol=str(protocol.path), value=c.value,
        uncertainty=c.u_c, source=_source(measured, path), line=spec.source.line(FIELD),
        path=spec.path, field=FIELD)
    ball = calibrated_lot(load_ball(session.ball.path), reference)
    return replace(session, ball=ball), measured


def _source(ref: ReferenceSession, path: Path) -> str:
    return (f"measured: session {ref.session.spec.name!r} ({display_path(path)}), the mean of "
            f"{ref.hits_used} hits {ref.location_from_tip / INCH:.2f} in from the tip")


def _check_path(session: LabSession, path: Path) -> None:
    spec = session.spec
    if not path.is_file():
        raise spec.source.problem(FIELD, f"{spec.reference_session}: no such file (relative "
                                  f"to {display_path(Path(spec.path).parent)})")
    if is_hits_csv(path):
        raise spec.source.problem(FIELD, "the reference must be a session file (YAML), which "
                                  "names its bat, ball and pivot, not a bare hits CSV")
    if path.resolve() == Path(spec.path).resolve():
        raise spec.source.problem(FIELD, "a session cannot be its own reference: name the "
                                  "reference bat's session")


def _check_reference(session: LabSession, ref: LabSession) -> None:
    spec = session.spec
    if ref.spec.reference_session is not None:
        raise spec.source.problem(FIELD, f"the reference session {ref.spec.name!r} names a "
                                  "reference session of its own: a lot is calibrated on one "
                                  "reference bat's measured hits, not on another calibration")
    if ref.ball.sha256 != session.ball.sha256:
        raise spec.source.problem(FIELD, f"the reference session's ball file "
                                  f"({display_path(ref.ball.path)}) is not this session's "
                                  f"({display_path(session.ball.path)}): a lot is calibrated "
                                  "on hits with its own balls")
    if session.ball.fit is None:
        raise spec.source.problem(FIELD, f"ball {session.ball.name!r} has no law fitted to "
                                  "ball tests: a reference bat calibrates a lot along its fit "
                                  "(a viscoelastic law with its tests)")


PIVOT_TOLERANCE = 1e-3  # [m] a reference's pivot may differ from the protocol's by this


def _check_pivot(session: LabSession, ref: LabSession, protocol: ProtocolSpec) -> None:
    """The reference's hits were taken at the protocol's pivot: the lot is calibrated on the
    model of the protocol's test (its pivot), which a measurement about another pivot is not."""
    if abs(ref.spec.pivot - protocol.pivot) > PIVOT_TOLERANCE:
        raise session.spec.source.problem(
            FIELD, f"the reference bat's hits were taken pivoted {ref.spec.pivot / INCH:.2f} "
            f"in from the knob, and protocol {protocol.id!r} pivots at "
            f"{protocol.pivot / INCH:.2f} in: the lot is calibrated on the protocol's test, "
            "so the reference must be measured at its pivot")
