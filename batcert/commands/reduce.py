"""``batcert reduce``: a lab session's measured hits reduced to a certified value with its
measurement uncertainty and a verdict under a declared decision rule (docs/lab-reduction.md)."""

from __future__ import annotations

import math

import numpy as np

from batcert.commands.inputs import ProtocolInputs, load_protocol_any
from batcert.lab.certify import DECISION_RULES, MC_DRAWS, Certified, certify, guard_band
from batcert.lab.lot import ReferenceSession, with_session_lot
from batcert.lab.session import LabSession, load_lab_session
from batcert.model.break_in import breaks_in
from batcert.results.lab import (
    CERTIFICATE_FIELDS,
    LabHit,
    LabLocation,
    LabResult,
    certificate_values,
    missing_certificate_fields,
)
from batcert.results.run import BreakInResult
from batcert.results.serialise import utc_now
from batcert.runner.barrel_tests import measured_history
from batcert.runner.runner import decide, identification
from batcert.specs.protocol import ProtocolSpec
from batcert.specs.resolve import display_path
from batcert.version import __version__


def _none(x: float) -> float | None:
    return None if not np.isfinite(x) else float(x)


def _model(session, protocol, ball, engine: str, location_from_tip: float | None,
           value: float | None) -> dict:
    """The model's prediction of the same test on the same bat and ball: the protocol metric
    against the distance from the tip (the first condition's location sweep), its value at the
    certified location and the measured value's difference from it."""
    from batcert.engines import get_engine
    from batcert.runner.runner import run_protocol
    run = run_protocol(session.built, protocol, ball, get_engine(engine))
    c = run.conditions[0]
    tip = session.built.model.length - protocol.pivot
    x = [tip - r for r in c.sweep.impact_location]
    order = np.argsort(x)
    xs, ys = np.asarray(x)[order], np.asarray(c.sweep.metric)[order]
    at = None if location_from_tip is None else float(np.interp(location_from_tip, xs, ys))
    return {"engine": engine, "from_tip": xs.tolist(), "metric": ys.tolist(),
            "value": run.value, "location_from_tip": tip - c.impact_location,
            "at_certified_location": at,
            "difference": None if at is None or value is None else value - at,
            "barrel_calibrated": bool(run.barrel.calibrated) if run.barrel else None}


def _barrel_fits(session, protocol, ball, engine: str, c) -> tuple[list[dict[str, float]],
                                                                  list[str]]:
    """The barrel calibrated from the hits (hollow bats, flexible engine, a certified value),
    and a warning when no stiffness in the bounds meets the measurement."""
    from dataclasses import asdict

    from batcert.engines import get_engine
    from batcert.lab.calibrate import calibrate_barrel
    from batcert.model.calibrate import BARREL_STIFFNESS_BOUNDS
    if c.value is None or engine != "flexible" or c.location is None:
        return [], []
    cal = calibrate_barrel(session, protocol, ball, get_engine(engine),
                           c.scan[c.location].position, c.value, c.u_c)
    warnings = []
    if not cal.fits and cal.span is not None:
        lo, hi = BARREL_STIFFNESS_BOUNDS
        warnings.append(
            f"the barrel cannot be calibrated from the hits: at the certified location the "
            f"model's {protocol.metric.upper()} spans {cal.span[0]:.4f} to {cal.span[1]:.4f} for "
            f"barrel stiffnesses x{lo:g} to x{hi:g}, and the measured value is "
            f"{c.value:.4f}; the model's hollow bats are livelier than measured ones "
            "(docs/validation.md, sections 2 and 3), so the difference is the model's, not a "
            "stiffness")
    return [asdict(f) for f in cal.fits], warnings


def _break_in(session: LabSession, p: ProtocolSpec) -> BreakInResult | None:
    """The session's measured break-in, judged by the protocol's rules (the shipped defaults
    where the protocol has none), or None."""
    readings = session.spec.break_in
    if readings is None:
        return None
    if p.break_in is None:
        from batcert.errors import UsageProblem
        raise UsageProblem(f"the session gives break-in readings, but protocol {p.id!r} has "
                           "no break_in to judge them by")
    out = measured_history(list(readings["compression"]), readings["new_compression"],
                           p.break_in)
    out.source = readings["source"] or ""
    return out


def run_reduce(session_path: str, protocol: str, decision_rule: str = "simple",
               engine: str = "flexible", bat: str | None = None) -> LabResult:
    """Load, reduce, certify and decide; and the model's prediction of the same test.
    ``session_path`` is a session YAML, or a bare hits CSV with ``bat`` (then the protocol
    gives the ball and the pivot)."""
    pin = load_protocol_any(protocol)
    p = pin.protocol
    session, reference = with_session_lot(_session(session_path, pin, bat), p)
    limit = p.limit.max + p.limit.tolerance if p.limit else None
    red, c = certify(session, p, limit)
    barrel_fits, barrel_warnings = _barrel_fits(session, p, session.ball, engine, c)
    margin, verdict = decide(c.value, p.limit, guard_band(decision_rule, c.expanded))
    break_in = _break_in(session, p)
    if break_in is not None and not break_in.complete:
        barrel_warnings.append(f"accelerated break-in: {break_in.outcome}; the hits do not "
                               "follow a completed break-in")
    if break_in is None and p.break_in is not None and p.barrel_compression is not None \
            and breaks_in(session.built.model, session.built.model.length
                          - p.barrel_compression.position):
        barrel_warnings.append("the bat's barrel breaks in (composite plies) and the protocol "
                               "tests it after an accelerated break-in, but the session gives "
                               "no break-in readings (`break_in.compression`)")
    h = session.hits
    spec, bat_spec = session.spec, session.built.spec
    location_from_tip = c.scan[c.location].from_tip if c.location is not None else None
    return LabResult(
        bat_identification=identification(bat_spec),
        session=spec.name, session_path=display_path(spec.path), bat=bat_spec.name,
        protocol=p.id, protocol_title=p.title, metric=p.metric, statement="measured",
        limit=p.limit.max if p.limit else None, tolerance=p.limit.tolerance if p.limit else 0.0,
        decision_rule=decision_rule, decision_rule_text=DECISION_RULES[decision_rule],
        value=c.value, location_from_tip=location_from_tip,
        hits_used=[float(h.hit[i]) for i in c.used], u_a=c.u_a, u_b=c.u_b, u_c=c.u_c,
        dof=c.dof if math.isfinite(c.dof) else None, coverage_factor=c.coverage_factor,
        expanded=c.expanded, mc_std=c.mc_std,
        mc_interval=list(c.mc_interval) if c.mc_interval else None, mc_draws=MC_DRAWS,
        conformance_probability=c.conformance, margin=margin, verdict=verdict,
        moi_pivot=session.moi_pivot, moi_source=session.moi_source,
        ball_mass=session.ball.model.mass, pivot=spec.pivot, scan=_scan(session, c),
        hits=_hits(session, red, c),
        warnings=c.warnings + barrel_warnings + _record_warnings(session, bat_spec, p),
        inputs=_inputs(session, p, reference), batcert_version=__version__, created=utc_now(),
        lab=_lab(spec), protocol_reference=p.reference, protocol_version=p.version,
        speed_unit=h.speed_unit,
        barrel_fits=barrel_fits,
        model=_model(session, p, session.ball, engine, location_from_tip, c.value),
        break_in=break_in, lot_calibration=_lot_calibration(session.ball, reference))


def _lab(spec) -> dict:
    """The session's ``lab:`` block with every certificate field present (None: not given)."""
    given = {k: v for k, v in (spec.lab or {}).items() if v is not None}
    return {**{f.key: None for f in CERTIFICATE_FIELDS}, **given}


def _record_warnings(session: LabSession, bat_spec, p: ProtocolSpec) -> list[str]:
    """What the certificate's record lacks or contradicts: the ISO/IEC 17025 fields the session
    does not give, an MOI that is the model's, a serial the bat file disagrees with."""
    out = []
    missing = missing_certificate_fields(certificate_values(_lab(session.spec), p.reference,
                                                            p.version))
    if missing:
        out.append(f"the session's `lab:` block lacks {len(missing)} of the certificate's "
                   f"ISO/IEC 17025 7.8 fields ({', '.join(missing)}): shown as MISSING")
    if session.moi_source == "model":
        out.append("the bat's MOI about the pivot is the model's: the bat file gives no "
                   "measured MOI (`measured.moi`), which a certified value rests on")
    serial = (session.spec.lab or {}).get("bat_serial")
    filed = (bat_spec.identification or {}).get("serial")
    if serial and filed and str(serial).strip() != str(filed).strip():
        out.append(f"the session's bat serial {serial!r} is not the bat file's "
                   f"({filed!r}): the certificate names the session's")
    return out


def _session(session_path: str, pin: ProtocolInputs, bat: str | None) -> LabSession:
    """The lab session of a session YAML, or of a bare hits CSV with ``bat`` (the protocol's
    ball and pivot)."""
    from batcert.errors import UsageProblem
    from batcert.specs.session import is_hits_csv, session_for_hits
    if is_hits_csv(session_path):
        if bat is None:
            raise UsageProblem("a bare hits CSV needs --bat (or give a session YAML that names "
                               "the bat, the ball lot and the pivot)")
        from batcert.commands.inputs import load_bat_any
        bat_path = str(load_bat_any(bat).path)  # a clear error for an unknown bat, now
        spec = session_for_hits(session_path, bat_path, str(pin.ball.path), pin.protocol.pivot)
        return load_lab_session(session_path, spec)
    if bat is not None:
        raise UsageProblem("--bat is for a bare hits CSV; a session YAML names its bat")
    return load_lab_session(session_path)


def _hits(session: LabSession, red, c: Certified) -> list[LabHit]:
    """Every hit with its reduced values (``red``, :func:`certify`'s reduction), its validity
    and use in the certified value (``c``)."""
    h = session.hits
    tip = session.built.model.length - session.spec.pivot
    used = set(c.used)
    return [LabHit(float(h.hit[i]), h.ball[i], h.line[i], float(h.inbound_speed[i]),
                   float(h.rebound_speed[i]), float(session.impact_location[i]),
                   float(tip - session.impact_location[i]),
                   float(red.collision_efficiency[i]), float(red.recoil_factor[i]),
                   float(red.bbcor[i]), float(red.besr[i]), float(red.bpf[i]),
                   float(red.bat_angular_speed_after[i]), _none(red.measured_cor[i]),
                   not c.reasons[i], list(c.reasons[i]), i in used)
            for i in range(len(h.line))]


def _scan(session: LabSession, c: Certified) -> list[LabLocation]:
    """The locations of the scan with their hits (as numbered in the CSV)."""
    h = session.hits
    return [LabLocation(loc.from_tip, loc.position, [float(h.hit[i]) for i in loc.hits],
                        loc.n_valid, loc.mean, loc.std) for loc in c.scan]


def _inputs(session: LabSession, p: ProtocolSpec,
            reference: ReferenceSession | None) -> list[dict[str, str]]:
    """The files the certificate rests on: session, hits, bat, ball and protocol, hashed; and
    the reference bat's session, hits and bat when it calibrates the lot."""
    spec, h, bat = session.spec, session.hits, session.built.spec
    out = [{"role": "session", "name": spec.name, "path": display_path(spec.path),
            "sha256": spec.source.sha256},
           {"role": "hits", "name": spec.hits, "path": display_path(h.path), "sha256": h.sha256},
           {"role": "bat", "name": bat.name, "path": display_path(bat.path), "sha256": bat.sha256},
           {"role": "ball", "name": session.ball.name, "path": display_path(session.ball.path),
            "sha256": session.ball.sha256},
           {"role": "protocol", "name": p.id, "path": display_path(p.path), "sha256": p.sha256}]
    if reference is not None:
        r = reference.session
        out += [{"role": "reference session", "name": r.spec.name,
                 "path": display_path(r.spec.path), "sha256": r.spec.source.sha256},
                {"role": "reference hits", "name": r.spec.hits, "path": display_path(r.hits.path),
                 "sha256": r.hits.sha256},
                {"role": "reference bat", "name": r.built.spec.name,
                 "path": display_path(r.built.spec.path), "sha256": r.built.spec.sha256}]
    return out


def _lot_calibration(ball, reference: ReferenceSession | None) -> dict:
    """The ball lot the model, the barrel calibration and the BPF use, and what calibrated it
    (:attr:`~batcert.results.lab.LabResult.lot_calibration`)."""
    ref, lot = ball.reference, ball.lot
    if ref is None or lot is None:
        return {"ball": ball.name, "calibrated": False}
    from pathlib import Path
    return {"ball": ball.name, "calibrated": True,
            "calibrated_on": "session" if reference is not None else "ball file",
            "reference_bat": Path(ref.bat).stem, "protocol": Path(ref.protocol).stem,
            "value": ref.value, "uncertainty": ref.uncertainty, "source": ref.source,
            "shift": lot.shift, "u_shift": lot.u_shift,
            "reference_session": None if reference is None
            else display_path(reference.session.spec.path)}


def calibrated_bat_text(result: LabResult, session_path: str) -> str:
    """The session's bat file with ``measured.hoop_frequency`` from the first barrel fit;
    ``ValueError`` when there is none or the bat file has no measured block."""
    from pathlib import Path

    from batcert.lab.calibrate import with_hoop_frequency
    from batcert.specs.bat import load_bat
    if not result.barrel_fits:
        raise ValueError("no barrel calibration: the bat is solid, the engine is not flexible, "
                         "nothing was certified, or no barrel stiffness in x0.25-x4 meets the "
                         "measurement")
    from batcert.specs.resolve import resolve
    from batcert.specs.session import load_session
    spec = load_session(session_path)
    path = resolve("bat", spec.bat, relative_to=Path(spec.path))
    fit = result.barrel_fits[0]
    text = with_hoop_frequency(Path(path).read_text(encoding="utf-8"), fit["hoop_frequency"],
                               f"fitted by batcert reduce from {result.session} "
                               f"({result.created}): barrel stiffness x{fit['scale']:.3f} "
                               f"+- {fit['u_scale']:.3f}")
    import tempfile
    with tempfile.TemporaryDirectory() as tmp:  # the result must be a valid bat file
        probe = Path(tmp) / "bat.yaml"
        probe.write_text(text, encoding="utf-8")
        load_bat(probe)
    return text
