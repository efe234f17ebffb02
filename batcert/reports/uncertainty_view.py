"""The certificate's section on a predicted result's uncertainty (``run --uncertainty N``):
the distribution, the probability of passing, what each input contributed and how far to
trust the numbers."""

from __future__ import annotations

import math
from typing import Any

from batcert.reports import format as fmt
from batcert.reports import svg
from batcert.reports.figure import LineFigure
from batcert.reports.table import Table
from batcert.results.run import InputUncertainty, PredictedUncertainty, RunResult
from batcert.units import Display, show


def bins(samples: int) -> int:
    """Histogram bins of the draws: about sqrt(N) / 2, from 8 to 30 (15 for N = 1000)."""
    return min(30, max(8, round(math.sqrt(samples) / 2)))


def _amount(value: float, u: float, dimension: str | None, us: bool = True) -> Display:
    if dimension is None:
        return Display(f"{value:.{fmt.two_significant(u, 3)}f}", None)
    shown = show(value, dimension, fmt.two_significant(u, 3))
    return shown if us else Display(shown.si, None)


def input_value(i: InputUncertainty) -> tuple[Display, Display]:
    """The input's nominal value (a list of stations or points: its range) and its stated
    +/- (the largest, when stations state several), the +/- in SI only."""
    k = max(range(len(i.u)), key=lambda j: i.u[j])
    stated = i.u[k] * (math.sqrt(3.0) if i.distribution == "uniform" else 1.0)
    spread = _amount(stated, i.u[k], i.dimension, us=False)
    if len(i.nominal) == 1:
        return _amount(i.nominal[0], i.u[k], i.dimension), spread
    lo, hi = (_amount(v, i.u[k], i.dimension, us=False).si for v in (min(i.nominal),
                                                                       max(i.nominal)))
    what = "stations" if i.field == "wall" else "points"
    return Display(f"{lo} to {hi} ({len(i.nominal)} {what})", None), spread


def inputs_table(result: RunResult) -> Table:
    u = result.uncertainty
    assert u is not None
    rows = []
    for i in u.inputs:
        value, spread = input_value(i)
        where = f"{i.path}:{i.line}" if i.line else i.path
        rows.append([f"{i.file} {i.field}", where, value, spread,
                     i.distribution,
                     fmt.metric_spread(i.sensitivity, result.metric, signed_=True),
                     f"{100 * i.variance_share:.1f} %"])
    return Table(["Input", "File:line", "Value", "±", "Distribution",
                  f"{fmt.metric_word(result.metric)} per u", "Share of variance"], rows,
                 numeric=[False, False, True, True, False, True, True])


def summary_sentence(result: RunResult) -> str:
    u = result.uncertainty
    assert u is not None
    m = result.metric
    spread = fmt.metric_spread(u.standard_deviation, m).si
    digits = fmt.two_significant(u.standard_deviation)  # the values to the spread's decimals
    v = lambda x: f"{x:.{digits}f}" + (" m/s" if m == "exit-speed" else "")  # noqa: E731
    text = (f"Over {u.samples} Monte Carlo draws of the stated input uncertainties (seed "
            f"{u.seed}), {fmt.metric_word(m)} = {v(u.mean)} with standard deviation "
            f"{spread}; 95 % of the draws lie between {v(u.interval_low)} and "
            f"{v(u.interval_high)}.")
    if u.pass_probability is not None:
        text += (f" Probability of passing: {u.pass_probability:.3f} (Monte Carlo standard "
                 f"error {u.pass_probability_standard_error:.3f}).")
    return text + propagation_sentence(result)


def _difference(value: float | None, metric: str) -> str:
    return "none" if value is None else fmt.metric_spread(value, metric).si


def propagation_sentence(result: RunResult) -> str:
    """How the draws' results were found: the response surface and its check against the
    engine, or every draw by the engine (and why, when the surface was asked for)."""
    u = result.uncertainty
    assert u is not None
    p = u.propagation
    if p is None:
        return ""
    m = result.metric
    bound = fmt.metric_spread(p.bound, m).si
    if p.method == "surrogate":
        return (f" The draws' results come from a response surface fitted on "
                f"{p.design_points} engine runs; the engine's own results for "
                f"{p.checked_draws} of the draws differ from it by at most "
                f"{_difference(p.largest_difference, m)} (bound {bound}); {p.engine_draws} "
                "engine runs in all.")
    if p.requested == "full":
        return f" Every draw solved by the engine ({p.engine_draws} engine runs)."
    return (f" Every draw solved by the engine ({p.engine_draws} engine runs), not by the "
            f"response surface: {p.reason}.")


def checks_table(result: RunResult) -> Table:
    u = result.uncertainty
    assert u is not None
    m = result.metric
    return Table(["Check", "Value", "Meaning"], [
        ["Standard error of the mean", fmt.metric_spread(u.mean_standard_error, m),
         "standard deviation / sqrt(draws)"],
        ["Full-run check", fmt.metric_spread(u.full_run_difference, m),
         f"largest difference, over {u.checked_draws} draws, between the Monte Carlo's result "
         "and a full run of the drawn bat (new modes, the whole search)"],
        *_surface_rows(u, m),
        ["Largest move of an impact point", fmt.quantity(u.largest_location_shift, "length", 4),
         "how far an engine-solved draw's located impact point moved from the nominal one"],
        ["Linear R²", f"{u.linear_r2:.3f}",
         "share of the variance a straight line in the inputs explains"],
    ], numeric=[False, True, False])


def _surface_rows(u: PredictedUncertainty, m: str) -> list[list[Any]]:
    """The checks' rows on how the draws' results were found (none for an older result)."""
    p = u.propagation
    if p is None:
        return []
    method = {"surrogate": "response surface", "full": "every draw by the engine"}[p.method]
    rows: list[list[Any]] = [["Propagation", method, p.reason or (
        f"{p.engine_draws} draws solved by the engine in all"
        + (f" ({p.design_points} design points, {p.checked_draws} checked draws)"
           if p.method == "surrogate" else ""))]]
    if p.largest_difference is not None:
        rows.append(["Surrogate check", fmt.metric_spread(p.largest_difference, m),
                     f"largest difference, over {p.checked_draws} draws (the extremes and some "
                     f"at random), between the response surface and the engine; bound "
                     f"{fmt.metric_spread(p.bound, m).si}"])
    return rows


def uncertainty_view(result: RunResult) -> dict[str, Any] | None:
    """The section's content, None without ``--uncertainty``."""
    u = result.uncertainty
    if u is None:
        return None
    return {"sentence": summary_sentence(result), "inputs": inputs_table(result),
            "legend": "± is the standard uncertainty of a normal distribution and the "
                      "half-width of a uniform one (whose standard uncertainty is ±/√3); the "
                      "effect per u is the least-squares slope of the result on the input's "
                      "draws, in standard uncertainties.",
            "checks": checks_table(result), "method": u.method, "note": u.note}


def histogram(u: PredictedUncertainty) -> tuple[list[float], list[float]]:
    """Bin centres and the share of draws per bin [-] (:func:`bins` bins over the draws)."""
    lo, hi = u.minimum, u.maximum
    if hi <= lo:
        return [lo], [1.0]
    n = bins(len(u.values))
    width = (hi - lo) / n
    counts = [0] * n
    for x in u.values:
        counts[min(int((x - lo) / width), n - 1)] += 1
    return ([lo + (k + 0.5) * width for k in range(n)], [c / len(u.values) for c in counts])


def uncertainty_figure(result: RunResult) -> LineFigure | None:
    """The draws' distribution with the limit, the nominal value and the 95 % interval."""
    u = result.uncertainty
    if u is None:
        return None
    name = fmt.metric_name(result.metric)
    x, y = histogram(u)
    lines = [svg.VLine(u.nominal_value, "nominal"), svg.VLine(u.interval_low, "2.5 %"),
             svg.VLine(u.interval_high, "97.5 %")]
    if result.limit is not None:
        lines.append(svg.VLine(result.limit + result.tolerance, "limit", svg.PALETTE[1]))
    return LineFigure("uncertainty", f"{name} over {u.samples} draws of the input "
                      "uncertainties", f"{name} [-]", "Share of draws per bin [-]",
                      [svg.Series("draws", x, y)], vlines=lines, hlines=[(0.0, "")],
                      caption="Frequency polygon of the Monte Carlo draws.")
