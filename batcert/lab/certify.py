"""From reduced hits to a certified value: validity checks, the location scan, the protocol's
location rule, the mean of the required consecutive valid hits, its measurement uncertainty
(GUM, JCGM 100; checked by Monte Carlo, JCGM 101) and the decision (docs/lab-reduction.md).

Validity (a hit failing any is kept, shown with its reasons, and not used):
- the operator's flag;
- the inbound speed within ``speed_tolerance`` of the protocol's speed;
- the ball's hit count within ``hits_per_ball``;
- at the certified location, a robust outlier test: more than 3.5 scaled median absolute
  deviations from the median (Iglewicz & Hoaglin 1993), flagged, never silently dropped.

The location scan groups hits to the session's ``location_step``; the protocol's rule picks the
location: ``max-metric`` the largest mean metric, ``sweet-spot`` the largest mean rebound speed,
``cop`` the location nearest the centre of percussion, ``fixed-from-tip`` the nearest to it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from batcert.lab.session import LabSession, reduce_session
from batcert.methods.metrics import METRICS
from batcert.methods.reduction import HitReduction
from batcert.numerics import student_t_quantile
from batcert.specs.protocol import ProtocolSpec
from batcert.units import FAST_UNITS

OUTLIER_Z = 3.5  # robust z above which a hit is flagged (Iglewicz & Hoaglin 1993)
COVERAGE = 0.95  # coverage probability of the expanded uncertainty
MC_DRAWS = 200_000  # Monte Carlo draws (JCGM 101)
MC_CHUNK = 20_000  # draws reduced at a time (memory only: the draws are made first, in order)
# the metrics a stationary-bat lab test measures (the metric registry's lab entries), by name
LAB_METRICS = {m.name: m.field for m in METRICS.values() if m.lab}


@dataclass(frozen=True)
class Location:
    position: float  # [m from the pivot], the mean of its hits
    from_tip: float  # [m]
    hits: list[int]  # indices of its hits
    n_valid: int
    mean: float | None  # mean metric of its valid hits
    std: float | None


@dataclass(frozen=True)
class Certified:
    value: float | None
    used: list[int]  # indices of the hits averaged
    location: int | None  # index into the scan
    reasons: list[list[str]]  # per hit, why it is not valid (empty when valid)
    scan: list[Location]
    u_a: float  # type A standard uncertainty (scatter of the used hits) [metric]
    u_b: dict[str, float]  # type B contributions (sensitivity x input uncertainty)
    u_c: float  # combined standard uncertainty
    dof: float  # effective degrees of freedom (Welch-Satterthwaite, GUM G.4.1; inf: type B only)
    coverage_factor: float  # k = t_95(dof) (GUM G.6.4)
    expanded: float  # U = k u_c
    mc_std: float | None  # Monte Carlo standard uncertainty
    mc_interval: tuple[float, float] | None  # 95 % probabilistically symmetric interval
    conformance: float | None  # probability that the true value is within the limit
    warnings: list[str]


def nominal_speed(protocol: ProtocolSpec) -> float:
    """The ball speed of the protocol's stationary-bat condition (the ball-cannon test a lab
    runs); a protocol without one cannot be measured this way."""
    for c in protocol.conditions:
        if c.relative_speed is not None and c.stationary == "bat":
            return c.relative_speed
        if c.relative_speed is None and c.pitch_speed and not c.bat_angular_speed \
                and not c.bat_speed:
            return c.pitch_speed
    from batcert.errors import UsageProblem
    raise UsageProblem(f"protocol {protocol.id!r} has no stationary-bat condition: a "
                       "ball-cannon lab test does not measure it")


def _validity(session: LabSession, protocol: ProtocolSpec) -> list[list[str]]:
    h, s = session.hits, session.spec
    reasons: list[list[str]] = [[] for _ in h.line]
    speed = nominal_speed(protocol)
    count: dict[str, int] = {}
    for i in range(len(h.line)):
        if not h.valid[i]:
            reasons[i].append("marked invalid" + (f" ({h.note[i]})" if h.note[i] else ""))
        if abs(h.inbound_speed[i] - speed) > s.speed_tolerance:
            u, f = h.speed_unit, FAST_UNITS["speed"][h.speed_unit]  # the lab's own unit
            reasons[i].append(f"inbound speed {h.inbound_speed[i] / f:.2f} {u} is more than "
                              f"{s.speed_tolerance / f:.2f} {u} from {speed / f:.2f} {u}")
        count[h.ball[i]] = count.get(h.ball[i], 0) + 1
        if s.hits_per_ball is not None and count[h.ball[i]] > s.hits_per_ball:
            reasons[i].append(f"ball {h.ball[i]}'s hit {count[h.ball[i]]} (at most "
                              f"{s.hits_per_ball})")
    return reasons


def _scan(session: LabSession, values: np.ndarray, ok: np.ndarray) -> list[Location]:
    r, step = session.impact_location, session.spec.location_step
    tip = session.built.model.length - session.spec.pivot
    keys = np.round((tip - r) / step).astype(int)  # the lab's grid: steps from the tip
    out = []
    for key in sorted(set(keys.tolist()), reverse=True):  # from the handle side to the tip
        idx = [int(i) for i in np.flatnonzero(keys == key)]
        good = [i for i in idx if ok[i]]
        v = values[good]
        pos = float(np.mean(r[idx]))
        out.append(Location(pos, tip - pos, idx, len(good),
                            float(np.mean(v)) if len(v) else None,
                            float(np.std(v, ddof=1)) if len(v) > 1 else None))
    return out


def _choose(session: LabSession, protocol: ProtocolSpec, scan: list[Location],
            red: HitReduction) -> int | None:
    rule = protocol.impact_location.rule
    candidates = [j for j, loc in enumerate(scan) if loc.n_valid > 0]
    if not candidates:
        return None
    if rule == "max-metric":
        return max(candidates, key=lambda j: scan[j].mean or -math.inf)
    if rule == "sweet-spot":
        rebound = session.hits.rebound_speed
        return max(candidates, key=lambda j: float(np.mean(rebound[scan[j].hits])))
    if rule == "cop":
        from batcert.model.mass import mass_properties
        cop = mass_properties(session.built, session.spec.pivot).cop
        return min(candidates, key=lambda j: abs(scan[j].position - cop))
    target = protocol.impact_location.from_tip or 0.0
    return min(candidates, key=lambda j: abs(scan[j].from_tip - target))


def _consecutive(idx: list[int], ok: np.ndarray, n: int) -> list[int] | None:
    """The first run of ``n`` consecutive valid hits among ``idx`` (in hit order)."""
    run: list[int] = []
    for i in idx:
        run = run + [i] if ok[i] else []
        if len(run) == n:
            return run
    return None


def _outliers(values: np.ndarray, idx: list[int]) -> list[int]:
    v = values[idx]
    med = np.median(v)
    mad = 1.4826 * np.median(np.abs(v - med))
    if mad == 0:
        return []
    return [i for i, x in zip(idx, v, strict=True) if abs(x - med) / mad > OUTLIER_Z]


def _sensitivities(session: LabSession, used: list[int], metric: str) -> dict[str, float]:
    """Type B contributions c_i u_i of the common-mode inputs (speed calibration, location,
    MOI, ball mass) to the mean, from the derivatives of (R3)-(R7) at the used hits' means."""
    u = session.spec.uncertainty or {}
    h = session.hits
    v_i = float(np.mean(h.inbound_speed[used]))
    v_r = float(np.mean(h.rebound_speed[used]))
    r = float(np.mean(session.impact_location[used]))
    m, inertia = session.ball.model.mass, session.moi_pivot
    k = m * r * r / inertia
    e_a = v_r / v_i
    if metric == "bbcor":
        d_vr, d_vi, d_k = (1 + k) / v_i, -(1 + k) * v_r / v_i**2, 1 + e_a
    elif metric == "collision_efficiency":
        d_vr, d_vi, d_k = 1 / v_i, -v_r / v_i**2, 0.0
    elif metric == "besr":
        d_vr, d_vi, d_k = 1 / v_i, -v_r / v_i**2, 0.0
    else:  # bpf = bbcor / e_b(v_i); e_b's own slope is the ball lot's, not a measurement
        e_b = float(session.ball.model.cor(v_i))
        d_vr, d_vi, d_k = (1 + k) / v_i / e_b, -(1 + k) * v_r / v_i**2 / e_b, (1 + e_a) / e_b
    return {
        "speed (inbound)": abs(d_vi) * u.get("speed", 0.0),
        "speed (rebound)": abs(d_vr) * u.get("speed", 0.0),
        "impact_location": abs(d_k * 2 * m * r / inertia) * u.get("impact_location", 0.0),
        "moi": abs(d_k * k / inertia) * u.get("moi", 0.0),
        "ball_mass": abs(d_k * k / m) * u.get("ball_mass", 0.0),
    }


def _monte_carlo(session: LabSession, used: list[int], metric: str, values: np.ndarray,
                 limit: float | None, seed: int = 2026
                 ) -> tuple[float | None, tuple[float, float] | None, float | None, int]:
    """JCGM 101: the certified mean with its inputs drawn from their distributions (common
    speed, location, MOI and mass offsets, normal; the hits' scatter as a scaled and shifted
    t with n - 1 degrees of freedom); the standard deviation, the 95 % interval, the
    fraction within the limit and the number of draws left out because they reduce to no
    finite value (an input drawn to zero, e.g. an inbound speed when the speed's uncertainty
    is comparable to the speed itself)."""
    from batcert.methods.reduction import BALL_COR_FIELDS, reduce_hits
    u = session.spec.uncertainty or {}
    rng = np.random.default_rng(seed)
    n = len(used)
    h = session.hits
    draws = MC_DRAWS
    dv = rng.normal(0, u.get("speed", 0.0), (draws, 1))
    dv2 = rng.normal(0, u.get("speed", 0.0), (draws, 1))
    dr = rng.normal(0, u.get("impact_location", 0.0), (draws, 1))
    inertia = session.moi_pivot + rng.normal(0, u.get("moi", 0.0), (draws, 1))
    mass = session.ball.model.mass + rng.normal(0, u.get("ball_mass", 0.0), (draws, 1))
    cor = session.ball.model.cor if metric in BALL_COR_FIELDS else None
    inbound, rebound = h.inbound_speed[used][None, :], h.rebound_speed[used][None, :]
    location = session.impact_location[used][None, :]
    mean = np.empty(draws)
    for a in range(0, draws, MC_CHUNK):  # in chunks: a few MB at a time, not 200k x hits
        b = a + MC_CHUNK
        red = reduce_hits(inbound + dv[a:b], rebound + dv2[a:b], location + dr[a:b],
                          inertia[a:b], mass[a:b], cor)
        mean[a:b] = getattr(red, metric).mean(axis=1)
    if n > 1:  # the scatter of the hits about their mean: Student's t, n - 1 dof (JCGM 101 6.4.9)
        s = float(np.std(values[used], ddof=1))
        mean = mean + s / math.sqrt(n) * rng.standard_t(n - 1, draws)
    finite = np.isfinite(mean)
    mean = mean[finite]
    dropped = int(draws - finite.sum())
    std = float(np.std(mean)) if mean.size else math.inf  # overflows for draws near 1e154
    if not math.isfinite(std):
        return None, None, None, dropped
    lo, hi = np.quantile(mean, [0.025, 0.975])
    within = float(np.mean(mean <= limit)) if limit is not None else None
    return std, (float(lo), float(hi)), within, dropped


def certify(session: LabSession, protocol: ProtocolSpec,
            limit: float | None = None) -> tuple[HitReduction, Certified]:
    """Reduce, check, scan, choose, average, state the uncertainty and the conformance."""
    metric = LAB_METRICS.get(protocol.metric)
    if metric is None:
        from batcert.errors import UsageProblem
        raise UsageProblem(f"protocol {protocol.id!r} certifies {protocol.metric}, which a "
                           f"stationary-bat lab test does not measure (lab metrics: "
                           f"{', '.join(LAB_METRICS)})")
    nominal_speed(protocol)  # a protocol a lab cannot run is refused before anything else
    red = reduce_session(session)
    values = np.asarray(getattr(red, metric), float)
    reasons = _validity(session, protocol)
    ok = np.array([not r for r in reasons])
    scan = _scan(session, values, ok)
    warnings: list[str] = []
    chosen = _choose(session, protocol, scan, red)
    if chosen is None:
        warnings.append("no value can be certified: no hit passes the validity checks (see "
                        "each hit's reasons)")
    used: list[int] = []
    if chosen is not None:
        idx = scan[chosen].hits
        for i in _outliers(values, [i for i in idx if ok[i]]):
            reasons[i].append(f"outlier: more than {OUTLIER_Z} robust standard deviations "
                              "from the location's median")
            ok[i] = False
        scan = _scan(session, values, ok)
        need = session.spec.hits_required
        run = _consecutive(scan[chosen].hits, ok, need)
        if run is None:
            warnings.append(f"no value can be certified: fewer than {need} consecutive valid "
                            "hits at the certified location")
        else:
            used = run
    value = float(np.mean(values[used])) if used else None
    n = len(used)
    u_a = float(np.std(values[used], ddof=1) / math.sqrt(n)) if n > 1 else 0.0
    u_b = _sensitivities(session, used, metric) if used else {}
    u_c = math.sqrt(u_a**2 + sum(x**2 for x in u_b.values()))
    # the type B inputs are taken as known exactly enough (infinite degrees of freedom)
    dof = u_c**4 / (u_a**4 / (n - 1)) if n > 1 and u_a > 0 else math.inf
    k_cov = student_t_quantile(0.5 + COVERAGE / 2, dof)  # dof inf: the normal's
    mc_std = mc_interval = conformance = None
    if used:
        mc_std, mc_interval, conformance, dropped = _monte_carlo(session, used, metric, values,
                                                                 limit)
        if dropped:
            warnings.append(f"{dropped:,} of {MC_DRAWS:,} Monte Carlo draws reduce to no finite "
                            "value and are left out: an input's uncertainty is comparable to "
                            "the input itself")
        if mc_std is None:
            warnings.append("the Monte Carlo check gives no finite spread (an input's "
                            "uncertainty is comparable to the input itself); only the GUM "
                            "uncertainty is stated")
    return red, Certified(value, used, chosen, reasons, scan, u_a, u_b, u_c, dof, k_cov,
                          k_cov * u_c, mc_std, mc_interval, conformance, warnings)


DECISION_RULES = {
    "simple": "simple acceptance (ILAC-G8 / JCGM 106 8.2): pass when the measured value is within "
              "the limit as written; the measurement uncertainty is stated, not applied",
    "guarded": "guarded acceptance (JCGM 106 8.3.2): pass when the measured value plus its "
               "expanded uncertainty U (95 % coverage) is within the limit",
}


def guard_band(rule: str, expanded: float) -> float:
    """The guard band a decision rule takes off the limit: none for simple acceptance, the
    expanded uncertainty for guarded acceptance (the verdict itself:
    :func:`batcert.runner.runner.decide`)."""
    return expanded if rule == "guarded" else 0.0
