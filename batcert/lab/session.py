"""A lab session loaded and its hits reduced: the bat (for its MOI about the test pivot), the
ball lot (mass, rigid-wall COR), the hits, and per hit every reduced quantity."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from batcert.methods.reduction import HitReduction, reduce_hits
from batcert.model.build import BuiltBat, build_bat
from batcert.model.mass import mass_properties
from batcert.runner.lot import calibrated_lot
from batcert.specs.ball import BallSpec, load_ball
from batcert.specs.bat import load_bat
from batcert.specs.hits import Hits, load_hits
from batcert.specs.resolve import NotFound, resolve
from batcert.specs.session import SessionSpec, load_session


@dataclass(frozen=True)
class LabSession:
    spec: SessionSpec
    built: BuiltBat
    ball: BallSpec
    hits: Hits
    moi_pivot: float  # the bat's MOI about the test pivot [kg m^2]
    moi_source: str  # "measured" (moved to the pivot by parallel axes) or "model"
    impact_location: np.ndarray  # [m from the pivot]


def load_lab_session(path: str | Path, spec: SessionSpec | None = None) -> LabSession:
    """The session file (or a ``spec`` made for a bare hits CSV), its bat and ball (shipped
    names or paths relative to it) and hits."""
    spec = load_session(path) if spec is None else spec
    where = Path(spec.path)
    try:
        bat_path = resolve("bat", spec.bat, relative_to=where)
        ball_path = resolve("ball", spec.ball, relative_to=where)
    except NotFound as exc:
        field_ = "bat" if "bat" in str(exc) else "ball"
        raise spec.source.problem(field_, str(exc)) from None
    built = build_bat(load_bat(bat_path))
    ball = calibrated_lot(load_ball(ball_path))
    hits = load_hits(where.parent / spec.hits, spec.location_from, spec.gate_spacing)
    mp = mass_properties(built, spec.pivot)
    moi, source = (mp.measured_moi_pivot, "measured") if mp.measured_moi_pivot is not None \
        else (mp.moi_pivot, "model")
    length = built.model.length
    r = {"tip": length - spec.pivot - hits.impact_location,
         "knob": hits.impact_location - spec.pivot,
         "pivot": hits.impact_location}[spec.location_from]
    _check_on_bat(hits, r, length - spec.pivot, spec.location_from)
    return LabSession(spec, built, ball, hits, float(moi), source, r)


def _check_on_bat(hits: Hits, r: np.ndarray, tip: float, origin: str) -> None:
    """Every impact lies between the pivot (with the runner's clearance) and the tip."""
    from batcert.errors import Collector
    from batcert.model.mass import CLEARANCE
    errors = Collector(hits.path)
    for i in np.flatnonzero(~((r >= CLEARANCE) & (r <= tip))):
        errors.add(hits.line[i], "impact_location", f"hit {hits.hit[i]:g} lies "
                   f"{hits.impact_location[i] * 100:.1f} cm from the {origin}: not between the "
                   f"pivot and the tip of this bat ({tip * 100:.1f} cm from the pivot)")
    errors.raise_if_any()


def reduce_session(session: LabSession) -> HitReduction:
    """Every hit of the session reduced (docs/lab-reduction.md); a hit whose reduced values
    are not all finite is an input problem at its line (the CSV's ranges keep them finite; a
    ball whose COR law fails at a hit's speed would not)."""
    h = session.hits
    red = reduce_hits(h.inbound_speed, h.rebound_speed, session.impact_location,
                      session.moi_pivot, session.ball.model.mass, session.ball.model.cor,
                      h.bat_angular_speed_after)
    _check_finite(red, h)
    return red


def _check_finite(red: HitReduction, hits: Hits) -> None:
    from dataclasses import fields

    from batcert.errors import Collector
    errors = Collector(hits.path)
    measured = np.isfinite(hits.bat_angular_speed_after)  # NaN by design where not measured
    for i in range(len(hits.line)):
        bad = [f.name for f in fields(red) if not np.isfinite(getattr(red, f.name)[i])
               and (measured[i] or not f.name.startswith("measured_"))]
        if bad:
            errors.add(hits.line[i], "", f"hit {hits.hit[i]:g} reduces to a non-finite "
                       f"{', '.join(bad)} (inbound speed {hits.inbound_speed[i]:.4g} m/s, the "
                       f"ball's COR there {red.ball_cor[i]:.4g})")
    errors.raise_if_any()
