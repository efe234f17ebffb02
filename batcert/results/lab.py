"""Results of a lab reduction (``batcert reduce``): measured hits, the location scan, the
certified value with its measurement uncertainty and the decision. SI units, metric values
dimensionless."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from batcert.results.run import BreakInResult
from batcert.results.serialise import Serialisable


@dataclass(frozen=True)
class CertificateField:
    """One thing a certificate must show (ISO/IEC 17025:2017, 7.8), from the session's ``lab:``
    block: its key there, the certificate's word for it, the clause that asks for it and, for a
    block of several values, each part's key and word."""

    key: str
    word: str
    clause: str
    parts: tuple[tuple[str, str], ...] = ()


# What a certificate shows of the session's ``lab:`` block, in the certificate's order. A field
# the session does not give is shown as MISSING, never left out, and named in a warning.
CERTIFICATE_FIELDS = (
    CertificateField("certificate_number", "Certificate number", "7.8.2.1 d"),
    CertificateField("laboratory", "Laboratory", "7.8.2.1 b"),
    CertificateField("location", "Where tested", "7.8.2.1 c"),
    CertificateField("accreditation", "Accreditation", "7.8.1.1"),
    CertificateField("customer", "Customer", "7.8.2.1 e"),
    CertificateField("standard", "Method (standard, version)", "7.8.2.1 f"),
    CertificateField("deviations", "Deviations from the method", "7.8.2.1 n"),
    CertificateField("bat_serial", "Bat serial number", "7.8.2.1 g"),
    CertificateField("item_condition", "Bat condition on receipt", "7.8.2.1 g"),
    CertificateField("receipt_date", "Date received", "7.8.2.1 h"),
    CertificateField("test_date", "Date tested", "7.8.2.1 i"),
    CertificateField("issue_date", "Date issued", "7.8.2.1 j"),
    CertificateField("operator", "Operator", "7.8.1.2"),
    CertificateField("environment", "Environment during the test", "7.8.3.1 a",
                     (("temperature", "temperature"), ("humidity", "humidity"))),
    CertificateField("ball_lot", "Ball lot and conditioning", "7.8.3.1 a",
                     (("lot", "lot"), ("temperature", "temperature"), ("humidity", "humidity"),
                      ("conditioning", "conditioned for"), ("age", "age"))),
    CertificateField("equipment", "Equipment and calibration", "7.8.3.1 e",
                     (("identifier", "identifier"), ("calibrated", "calibrated"),
                      ("calibration_due", "due"))),
    CertificateField("signatures", "Approved by", "7.8.2.1 o"),
)


def certificate_values(lab: dict[str, Any], protocol_reference: str | None = None,
                       protocol_version: str | None = None) -> dict[str, Any]:
    """Each certificate field's value from a session's ``lab:`` block (None: not given), with
    the two that have a stated fallback: the method is the protocol file's reference and
    version, the place the laboratory's address."""
    values = {f.key: lab.get(f.key) for f in CERTIFICATE_FIELDS}
    if not values["standard"] and protocol_reference:
        values["standard"] = (f"{protocol_reference}, protocol version "
                              f"{protocol_version or 'not given'} (the protocol file's)")
    if not values["location"] and values["laboratory"]:
        values["location"] = "at the laboratory's address"
    return values


def missing_certificate_fields(values: dict[str, Any]) -> list[str]:
    """The certificate fields (and parts, ``ball_lot.age``) without a value
    (:func:`certificate_values`)."""
    out = []
    for f in CERTIFICATE_FIELDS:
        value = values.get(f.key)
        if value in (None, "", []):
            out.append(f.key)
        elif f.parts:
            items = value if isinstance(value, list) else [value]
            out += list(dict.fromkeys(f"{f.key}.{k}" for item in items for k, _ in f.parts
                                      if item.get(k) in (None, "")))
    return out


@dataclass
class LabHit:
    hit: float  # the hit's number as written
    ball: str
    line: int  # its line in the hits CSV
    inbound_speed: float  # [m/s]
    rebound_speed: float  # [m/s]
    impact_location: float  # [m from pivot]
    from_tip: float  # [m]
    collision_efficiency: float  # e_A [-]
    recoil_factor: float  # k [-]
    bbcor: float  # [-]
    besr: float  # [-]
    bpf: float  # [-]
    bat_angular_speed_after: float  # from momentum [rad/s]
    measured_cor: float | None  # from a measured bat speed (BPF method) [-]
    valid: bool  # passes every validity check
    reasons: list[str]  # why not, when not
    used: bool  # one of the hits averaged into the certified value


@dataclass
class LabLocation:
    from_tip: float  # [m], the mean of its hits
    impact_location: float  # [m from pivot]
    hits: list[float]  # hit numbers
    valid_hits: int
    mean: float | None  # mean metric of the valid hits
    std: float | None  # sample standard deviation


@dataclass(repr=False)
class LabResult(Serialisable):
    KIND = "lab"
    SUMMARY = ("bat", "protocol", "metric", "value", "expanded", "verdict")

    session: str
    session_path: str
    bat: str
    protocol: str
    protocol_title: str
    metric: str
    statement: str  # "measured": the values come from measured hits, not from the model
    limit: float | None
    tolerance: float
    decision_rule: str  # simple | guarded
    decision_rule_text: str
    value: float | None  # the certified value (mean of the hits used)
    location_from_tip: float | None  # the certified location [m]
    hits_used: list[float]
    u_a: float  # type A standard uncertainty [metric]
    u_b: dict[str, float]  # type B contributions [metric]
    u_c: float  # combined standard uncertainty
    dof: float | None  # effective degrees of freedom (None: infinite)
    coverage_factor: float
    expanded: float  # U at 95 % coverage
    mc_std: float | None  # Monte Carlo (JCGM 101) standard uncertainty
    mc_interval: list[float] | None  # 95 % probabilistically symmetric coverage interval
    mc_draws: int
    conformance_probability: float | None  # P(true value <= limit + tolerance), JCGM 106
    margin: float | None  # under the decision rule
    verdict: str | None  # pass | fail | None (no value or no limit)
    moi_pivot: float  # the bat's MOI about the pivot used [kg m^2]
    moi_source: str  # measured | model
    ball_mass: float  # [kg]
    pivot: float  # [m from knob]
    scan: list[LabLocation]
    hits: list[LabHit]
    warnings: list[str]
    inputs: list[dict[str, str]]
    batcert_version: str
    created: str
    # the session's lab: block, every certificate field present (None: not given)
    lab: dict[str, Any] = field(default_factory=dict)
    protocol_reference: str | None = None  # the protocol file's reference and version
    protocol_version: str | None = None
    speed_unit: str = "m/s"  # the unit the lab's hits CSV gives speeds in: shown in it
    # hollow bats: every barrel stiffness scale at which the model meets the measurement at the
    # certified location (scale, u_scale, hoop_frequency [Hz], u_hoop_frequency [Hz], slope)
    barrel_fits: list[dict[str, float]] = field(default_factory=list)
    # the model's prediction of the same test (engine, from_tip [m], metric, value,
    # location_from_tip [m], at_certified_location, difference = measured - model)
    model: dict[str, Any] = field(default_factory=dict)
    bat_identification: dict[str, str] = field(default_factory=dict)  # maker, model, serial, lot
    break_in: BreakInResult | None = None  # the measured accelerated break-in before the hits
    # the ball lot the model, the barrel calibration and the BPF use: its name and, when
    # calibrated on a reference bat (an input), the bat, the value, its uncertainty, the
    # source, the lot's shift [standard uncertainties of the COR tests] and its own, and
    # calibrated_on: 'session' (the session's reference_session) or 'ball file'
    lot_calibration: dict[str, Any] = field(default_factory=dict)

    def return_code(self) -> int:
        """0 when the measured value passes (or the protocol sets no limit), 1 when it fails or
        nothing could be certified."""
        return 0 if self.verdict in ("pass", None) and self.value is not None else 1
