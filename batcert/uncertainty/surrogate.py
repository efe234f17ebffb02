"""A response surface for the Monte Carlo's draws: the result as a low polynomial in the drawn
inputs.

Each stated input is one independent source, drawn as ``k`` of its standard uncertainties
(:func:`batcert.uncertainty.inputs.draw`). The protocol's result is a smooth function of the
``k``: the metric at the impact point the protocol's rule locates (the vertex of a parabola, the
centre of percussion or a fixed point, :mod:`batcert.runner.sampled`), of a bat and ball whose
properties move smoothly with the inputs. Over the few standard uncertainties the draws span, a
polynomial in the ``k``, cubic in the strong ones, with their interactions (Box and Wilson 1951;
Myers, Montgomery and Anderson-Cook, *Response Surface Methodology*, ch. 7) follows it to far
less than its spread, so a thousand draws need only the few dozen engine runs of the surface's
design, in two stages:

1. :func:`axial`: the centre and each input alone at ``+/- a_j``, where ``a_j`` is its largest
   drawn ``|k|`` (about 3.3 for a normal input in 1000 draws, sqrt 3 for a uniform one): each
   input's slope and curvature, and its effect. An input is strong when its effect is at least
   :data:`STRONG` of the strongest one's.
2. :func:`second_stage`: each strong input alone at ``+/- a_j / 2`` (its cubic term, with a
   point to spare), and for each pair of inputs of which at least one is strong the four
   corners ``(+/- a_i, +/- a_j)``: their interaction ``k_i k_j``, ``k_i^2 k_j`` and
   ``k_i k_j^2``, with a point to spare. An interaction is of the order of the weaker effect
   times the relative change the stronger input makes to it; between two inputs that both
   change the result little it is left out, as is a weak input's cubic term (the "weak
   heredity" of Hamada and Wu 1992: interactions come with strong main effects).

Why these terms: the ball's COR dominates every shipped bat's spread under BBCOR; a lot's
liveliness moves BBCOR by about a twentieth over its band, not quite in a straight line, and
the effect of every other input changes with it. Over the 1000 draws of the shipped
aluminium-34 and ash-34 under ncaa-bbcor (least squares through all of them, solved by the
engine), a quadratic in the ``k`` misses some by 1.4e-4 and 2.1e-4, with the ``k_j^3`` terms
2.6e-5 and 3.0e-5, with all ``k_i^2 k_j`` terms 7e-6 and 3e-6, the full cubic 5e-6 and 3e-6:
about the engine's own scatter from draw to draw (1e-6 to 2e-6 along one input). The surface
fitted on this design (29 points for their five inputs; the COR is the one strong input)
misses the engine's results of all 1000 draws by at most 1.7e-5 and 5.5e-6 (with every
input's cubic, 37 points: 1.7e-5 and 5.2e-6; with all ten pairs' corners too, 61 points:
1.6e-5 and 3.5e-6; with three corners a pair: 1.7e-5 and 7.7e-6).

Whether it does, for this bat, these files and this protocol, is not assumed: the Monte Carlo
(:mod:`batcert.uncertainty.propagate`) solves a sample of the actual draws with the engine,
compares, and solves every draw with the engine when the surface misses by more than its bound
(JCGM 101:2008 judges a propagation by whether it reproduces the output's distribution to a
stated numerical tolerance; its clause 8 so compares the GUM framework with a Monte Carlo).

Pure numpy: no engine, no files.
"""

from __future__ import annotations

from dataclasses import dataclass
from itertools import combinations

import numpy as np

SURROGATE_CHECKED = 8  # actual draws solved by the engine to check the surface
EXTREMES = 4  # of them, at most so many chosen as extremes (the rest at random)
# an input is strong when its effect (the largest change of a result along its axis) is at
# least this share of the strongest input's; pairs with a strong input get corner points
STRONG = 0.1
CORNERS = ((1.0, 1.0), (1.0, -1.0), (-1.0, 1.0), (-1.0, -1.0))


def default_bound(metric: str) -> float:
    """The largest difference from the engine the surface may make on its checked draws, by
    default [metric unit]: one unit of the last digit the reports show of the metric
    (:data:`batcert.methods.metrics.METRICS`' ``digits``): 1e-4 for BBCOR, BESR, BPF and e_A
    (a tenth of the last digit of a limit stated to three decimals, BBCOR 0.500; for the
    shipped bats under 1 % of the result's standard deviation), 0.01 m/s for the exit speed
    (0.02 mph)."""
    from batcert.methods.metrics import METRICS
    return 10.0 ** -METRICS[metric].digits


def _point(d: int, at: dict[int, float]) -> np.ndarray:
    p = np.zeros(d)
    for j, v in at.items():
        p[j] = v
    return p


def axial(z: np.ndarray) -> np.ndarray:
    """The design's first stage for the draws ``z`` (samples, inputs), in standard
    uncertainties, shape (1 + 2 inputs, inputs): the centre, then each input alone at ``-a_j``
    and ``+a_j``, its largest drawn ``|k|``. Every point of the design lies within the draws'
    own range of each input, so it reaches no value of an input the draws do not."""
    a, d = np.abs(z).max(axis=0), z.shape[1]
    return np.array([np.zeros(d)] + [_point(d, {j: s * a[j]}) for j in range(d)
                                     for s in (-1.0, 1.0)])


def strong_inputs(values: np.ndarray) -> list[bool]:
    """Which inputs are strong (:data:`STRONG`) under any result, from the results ``values``
    (points, results) at the :func:`axial` points."""
    d = (values.shape[0] - 1) // 2
    effect = np.abs(values[1:].reshape(d, 2, -1) - values[0]).max(axis=1)  # (inputs, results)
    top = effect.max(axis=0)
    return [bool(s) for s in np.any(effect >= STRONG * np.where(top > 0, top, np.inf), axis=1)]


def strong_pairs(strong: list[bool]) -> list[tuple[int, int]]:
    """The pairs of inputs with at least one strong input: they get corner points and terms."""
    return [(i, j) for i, j in combinations(range(len(strong)), 2) if strong[i] or strong[j]]


def second_stage(z: np.ndarray, strong: list[bool]) -> np.ndarray:
    """The design's second stage: each strong input alone at ``+/- a_j / 2`` (its cubic term,
    with one point to spare), and for each pair of :func:`strong_pairs` the four points ``(+/-
    a_i, +/- a_j)`` (the others at 0), shape (points, inputs)."""
    a, d = np.abs(z).max(axis=0), z.shape[1]
    points = [_point(d, {j: s * 0.5 * a[j]}) for j in range(d) if strong[j] for s in (-1.0, 1.0)]
    points += [_point(d, {i: si * a[i], j: sj * a[j]}) for i, j in strong_pairs(strong)
               for si, sj in CORNERS]
    return np.array(points).reshape(-1, d)


def most_runs(inputs: int) -> int:
    """The most engine runs a surface for ``inputs`` inputs takes (every input strong): its
    design and its check."""
    return (1 + 4 * inputs + len(CORNERS) * inputs * (inputs - 1) // 2 + SURROGATE_CHECKED)


def _terms(u: np.ndarray, strong: list[bool]) -> np.ndarray:
    """The surface's terms of the scaled points ``u`` (rows): 1, each u_j and u_j^2, each strong
    input's u_j^3, and for each pair of :func:`strong_pairs` u_i u_j, u_i^2 u_j and u_i u_j^2."""
    d = u.shape[1]
    cols = [np.ones(u.shape[0])] + [u[:, j] ** n for j in range(d) for n in (1, 2)]
    cols += [u[:, j] ** 3 for j in range(d) if strong[j]]
    for i, j in strong_pairs(strong):
        cols += [u[:, i] * u[:, j], u[:, i] ** 2 * u[:, j], u[:, i] * u[:, j] ** 2]
    return np.column_stack(cols)


@dataclass(frozen=True)
class ResponseSurface:
    """A quadratic in each input's ``k``, cubic in a strong one's, with the interactions of the
    pairs with a strong input; one per column of results (one per protocol)."""

    scale: np.ndarray  # each input's a_j: the terms are in k_j / a_j [-]
    strong: list[bool]  # each input's
    coefficients: np.ndarray  # (terms, results)

    @classmethod
    def fit(cls, points: np.ndarray, values: np.ndarray, strong: list[bool]) -> ResponseSurface:
        """The least-squares surface through ``values`` (shape (points, results)) at
        ``points`` (:func:`axial` and :func:`second_stage`), in inputs scaled to [-1, 1]
        (conditioning). With no input ``strong``, the quadratic through the axial points."""
        scale = np.abs(points).max(axis=0)
        scale[scale == 0] = 1.0
        coefficients, *_ = np.linalg.lstsq(_terms(points / scale, strong), values, rcond=None)
        return cls(scale, strong, coefficients)

    def __call__(self, z: np.ndarray) -> np.ndarray:
        """The surface at the draws ``z`` (samples, inputs): shape (samples, results)."""
        return _terms(z / self.scale, self.strong) @ self.coefficients


def checked_draws(z: np.ndarray, predicted: np.ndarray, seed: int,
                  count: int = SURROGATE_CHECKED) -> list[int]:
    """The draws on which the surface is checked against the engine, sorted: up to
    :data:`EXTREMES` extremes (the draw farthest from the nominal inputs, where the surface
    extrapolates most, then each result's largest and smallest predicted value, where its
    curvature matters most and the pass probability's tail lies), the rest at random from the
    others, with a generator of its own from the run's ``seed`` (the same seed checks the same
    draws)."""
    n = z.shape[0]
    count = min(count, n)
    extremes = [int(np.argmax((z**2).sum(axis=1)))]
    for k in range(predicted.shape[1]):
        extremes += [int(np.argmax(predicted[:, k])), int(np.argmin(predicted[:, k]))]
    chosen = list(dict.fromkeys(extremes))[:min(EXTREMES, count)]
    rest = np.setdiff1d(np.arange(n), chosen)
    rng = np.random.default_rng([seed, 1])  # not the draws' own stream (seed alone)
    chosen += [int(i) for i in rng.choice(rest, count - len(chosen), replace=False)]
    return sorted(chosen)
