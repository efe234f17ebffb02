"""The viscoelastic ball's parameters from ball tests: a weighted least-squares fit.

What a ball lab measures, and what the law predicts for it (all by integrating the ball against
a rigid surface, :func:`batcert.physics.balls.impact1d.body_impact`, except the quasi-static
compression):

* ``cor``: the COR against a rigid flat wall at a speed (ASTM F1887 at 60 mph; cannon tests);
* ``cylinder_cor``: against a rigid cylinder of a stated diameter (ASTM F2845's CCOR); the
  cylinder's contact is softer by Hertz's :func:`~batcert.physics.balls.footprint.stiffness_ratio`;
* ``peak_force``: the largest force of a rigid-wall (or cylinder) impact at a speed;
* ``collision_time``: the time over which the central 99 % of the impulse acts (Nathan 2000's
  definition), and ``contact_time``: first touch to separation, against a rigid wall;
* ``compression``: the force of a slow diametral squeeze between flat platens by a stated
  displacement (ASTM F1888: 0.25 in). Slow against ``tau``, so the relaxed stiffness holds; the
  two contacts are in series, each compressed by half the displacement:
  ``F = r k0 (d / 2)^a``.

The fit minimises ``sum ((model - value) / u)^2`` over the parameters ``log k0``, ``a``,
``logit r``, ``log tau`` (Levenberg-Marquardt with bounds, :func:`scipy.optimize.least_squares`,
from a start read off the data), and is refused (:class:`FitError`) when it cannot be trusted:
fewer tests than parameters, no COR or no stiffness-bearing test (time, force, compression),
parameters that the data do not determine (a singular Jacobian), a parameter at a bound of its
plausible range, or a test missed by more than ``MAX_RESIDUAL`` of its uncertainties. The
test blamed for a miss is the one the law fitted to the other tests misses most (a bad point
pulls the fit towards itself, so the largest residual of the full fit is often a good
neighbour's). The
parameters' standard uncertainties come from the Jacobian (``(J^T J)^-1``, scaled by the
reduced chi-square when it exceeds 1), and the parameters' change per unit shift of every COR
(a ball lot livelier or deader than the tested balls) from the same linearisation
(:attr:`BallFit.lot_direction`). Nothing about a bat enters. Units: SI.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from batcert.physics.balls import footprint
from batcert.physics.balls.fit_budget import Budget, Exhausted
from batcert.physics.balls.fit_checks import COR_KINDS, STIFFNESS_KINDS, FitError, check_tests
from batcert.physics.balls.fit_coordinates import SLOPE, bounds, law_of, theta_of
from batcert.physics.balls.fit_starts import starts
from batcert.physics.balls.impact1d import body_impact, contact_time_estimate
from batcert.physics.balls.viscoelastic import TwoTimeViscoelastic, Viscoelastic, ViscoelasticMarch

KINDS = ("cor", "cylinder_cor", "peak_force", "collision_time", "contact_time", "compression")
MAX_RESIDUAL = 3.0  # a test missed by more than this many standard uncertainties refuses the fit
FIT_STEPS = 150  # integration steps per contact time while fitting (COR to about 3e-6)
# plausible ranges: a fit at their edge is refused (the data do not hold the parameter)
BOUNDS = {"exponent": (1.0, 3.0), "relaxed_fraction": (0.01, 0.99),
          "relaxation_time": (1e-6, 0.1), "stiffness": (1e3, 1e13),
          "fast_share": (0.01, 0.99), "fast_relaxation_time": (1e-6, 0.1)}
PARAMETERS = Viscoelastic.PARAMETERS  # the one-time law's (the default law of a fit)
# the laws a ball's tests can be fitted to (each lists its PARAMETERS and their COORDINATES)
FITTED: dict[str, type[Viscoelastic]] = {Viscoelastic.name: Viscoelastic,
                                          TwoTimeViscoelastic.name: TwoTimeViscoelastic}


@dataclass(frozen=True)
class BallTest:
    """One measured ball property (module notes for the kinds).

    ``condition`` is the impact speed [m/s] (``compression``: the diametral displacement [m]);
    ``value`` in SI ([-], [N], [s]); ``uncertainty`` its standard uncertainty, same unit;
    ``surface_diameter`` the rigid cylinder's diameter [m] (``inf``: a flat)."""

    kind: str
    condition: float
    value: float
    uncertainty: float
    surface_diameter: float = float("inf")

    def __post_init__(self) -> None:
        if self.kind not in KINDS:
            raise ValueError(f"unknown ball test {self.kind!r} (one of {', '.join(KINDS)})")
        if not (self.condition > 0 and self.value > 0 and self.uncertainty >= 0):
            raise ValueError("a ball test needs a positive condition and value and an "
                             "uncertainty >= 0")


@dataclass(frozen=True)
class BallFit:
    """The fitted law and how well it reproduces the tests."""

    law: Viscoelastic
    tests: tuple[BallTest, ...]
    model: tuple[float, ...]  # the law's value of each test (SI)
    residuals: tuple[float, ...]  # (model - value) / uncertainty
    chi2: float
    dof: int
    uncertainty: dict[str, float]  # standard uncertainty of each parameter (SI)
    # change of the fit's coordinates (log k0, a, logit r, log tau) when every COR test moves
    # up by one of its standard uncertainties (a livelier ball lot)
    lot_direction: tuple[float, ...] = (0.0, 0.0, 0.0, 0.0)
    held: tuple[str, ...] = ()  # parameters held at given values, not fitted

    def moved(self, k: float) -> Viscoelastic:
        """The law of a ball lot whose every COR test lies ``k`` of its standard uncertainties
        above the tested balls' (:mod:`batcert.uncertainty`), by the fit's linearisation."""
        if k == 0.0:
            return self.law
        return law_of(theta_of(self.law) + k * np.asarray(self.lot_direction), type(self.law))


def predict(laws: list[Viscoelastic], tests: tuple[BallTest, ...], mass: float, radius: float,
            steps: int = FIT_STEPS) -> np.ndarray:
    """Each law's value of each test, (laws, tests): the impacts of every law integrated in one
    batch (module notes)."""
    dynamic = [i for i, t in enumerate(tests) if t.kind != "compression"]
    out = np.empty((len(laws), len(tests)))
    for i, t in enumerate(tests):
        if t.kind == "compression":
            for j, law in enumerate(laws):
                out[j, i] = law.quasi_static_force(0.5 * t.condition)
    if not dynamic:
        return out
    speed = np.array([tests[i].condition for i in dynamic])
    scale = np.array([footprint.stiffness_ratio(radius, 0.5 * tests[i].surface_diameter)
                      for i in dynamic])
    n_laws, n_dyn = len(laws), len(dynamic)
    which = np.repeat(np.arange(n_laws), n_dyn)
    state = ViscoelasticMarch.of(laws, [mass] * n_laws, which, np.tile(scale, n_laws))
    # one step size for every law (the first's): the finite differences of the fit's Jacobian
    # then see the parameters' change, not a change of the discretisation
    times = np.tile(contact_time_estimate(speed, mass, laws[0].relaxed_stiffness * scale,
                                          laws[0].exponent), n_laws)
    needs_history = any(tests[i].kind == "collision_time" for i in dynamic)
    res = body_impact(state, mass, np.tile(speed, n_laws), 0.0, times, steps=steps,
                      history=needs_history)
    column = {"cor": res.cor, "cylinder_cor": res.cor, "peak_force": res.peak_force,
              "collision_time": res.collision_time, "contact_time": res.contact_time}
    for k, i in enumerate(dynamic):
        out[:, i] = column[tests[i].kind].reshape(n_laws, n_dyn)[:, k]
    return out


def test_values(law, tests: tuple[BallTest, ...], mass: float, radius: float) -> np.ndarray:
    """What any contact law (not only a fitted one) gives for each test (SI), integrated to
    the default accuracy: ``inspect`` sets it beside the measured values."""
    out = np.empty(len(tests))
    for i, t in enumerate(tests):
        if t.kind == "compression":
            out[i] = float(law.quasi_static_force(0.5 * t.condition))
            continue
        scale = footprint.stiffness_ratio(radius, 0.5 * t.surface_diameter)
        res = law.body_impact(mass, np.array([t.condition]), 0.0, scale=scale,
                              history=t.kind == "collision_time")
        out[i] = {"cor": res.cor, "cylinder_cor": res.cor, "peak_force": res.peak_force,
                  "collision_time": res.collision_time,
                  "contact_time": res.contact_time}[t.kind][0]
    return out


def _solve(tests: tuple[BallTest, ...], mass: float, radius: float, fixed: Fixed = (),
           cls: type[Viscoelastic] = Viscoelastic, first: np.ndarray | None = None,
           budget: Budget | None = None):
    """The least-squares solution (module notes) over the parameters of ``cls`` not in
    ``fixed``: ``(theta, residuals, jacobian)``, ``theta`` all the coordinates, the Jacobian over
    the free ones; FitError when no start converges. ``first``: a start to try before those
    read off the data (a neighbouring fit's coordinates). ``budget``: the test evaluations it
    may make (:class:`~batcert.physics.balls.fit_budget.Exhausted` when spent)."""
    from scipy.optimize import least_squares  # lazy: only a fit needs it

    value = np.array([t.value for t in tests])
    sigma = np.array([t.uncertainty for t in tests])
    base, free = _split(fixed, cls)
    budget = Budget() if budget is None else budget

    def full(x) -> np.ndarray:
        theta = base.copy()
        theta[free] = x
        return theta

    def residuals_of(xs) -> np.ndarray:
        laws = [law_of(full(x), cls) for x in xs]
        budget.spend(len(laws) * len(tests))
        return (predict(laws, tests, mass, radius) - value) / sigma

    def fun(x):
        return residuals_of([x])[0]

    def jac(x):
        steps = 1e-3 * np.eye(free.size)
        r = residuals_of([x] + [x + d for d in steps])
        return ((r[1:] - r[0]) / 1e-3).T

    lower, upper = (b[free] for b in bounds(cls, BOUNDS))
    best = None
    costs: list[float] = []
    for start in ([] if first is None else [first]) + starts(tests, mass, cls):
        start = np.clip(start[free], lower + 1e-6, upper - 1e-6)
        try:
            res = least_squares(fun, start, jac=jac, bounds=(lower, upper), x_scale="jac",
                                xtol=1e-10, ftol=1e-10, max_nfev=60)
        except (ValueError, FloatingPointError):
            continue
        if best is None or res.cost < best.cost:
            best = res
        if best.cost <= 0.5 * max(len(tests) - free.size, 1):  # chi2/dof <= 1: good
            break
        # two starts that end at the best cost to 0.1 % found the same minimum: done
        if sum(abs(c - best.cost) <= 1e-3 * best.cost for c in costs + [res.cost]) >= 2:
            break
        costs.append(res.cost)
    if best is None:
        raise FitError(f"the fit of the {cls.name} ball to its tests did not converge")
    return full(best.x), fun(best.x), jac(best.x)


# parameters held at given values while the others are fitted: (name, SI value) pairs
Fixed = tuple[tuple[str, float], ...]


def _split(fixed: Fixed, cls: type[Viscoelastic] = Viscoelastic) -> tuple[np.ndarray, np.ndarray]:
    """The fit's coordinates with the fixed parameters set (the others placeholders), and the
    indices of the free ones."""
    given = dict(fixed)
    unknown = set(given) - set(cls.PARAMETERS)
    if unknown:
        raise ValueError(f"not parameters of the {cls.name} law: {sorted(unknown)}")
    # placeholders for the free ones: the middle of each plausible range (valid for the law)
    filled = {**{p: float(np.sqrt(BOUNDS[p][0] * BOUNDS[p][1])) if c == "log"
                 else 0.5 * (BOUNDS[p][0] + BOUNDS[p][1])
                 for p, c in zip(cls.PARAMETERS, cls.COORDINATES, strict=True)}, **given}
    base = theta_of(cls(*(filled[p] for p in cls.PARAMETERS)))
    return base, np.array([i for i, p in enumerate(cls.PARAMETERS) if p not in given], dtype=int)


def fit_ball(tests: tuple[BallTest, ...] | list[BallTest], mass: float, radius: float,
             fixed: Fixed = (), law: str = Viscoelastic.name,
             evaluations: int | None = None) -> BallFit:
    """Fit the viscoelastic law ``law`` (a name in :data:`FITTED`) to ``tests`` of a ball of
    ``mass`` [kg] and ``radius`` [m] (module notes), the parameters in ``fixed`` held at their
    given values (a ball known only by its marks: module notes); :class:`FitError` when the
    result cannot be trusted, or when no law is found within ``evaluations`` test evaluations
    (:data:`~batcert.physics.balls.fit_budget.MAX_EVALUATIONS` unless given)."""
    cls = FITTED[law]
    tests = tuple(tests)
    check_tests(tests, fixed, cls)
    n_free = len(cls.PARAMETERS) - len(fixed)
    value = np.array([t.value for t in tests])
    sigma = np.array([t.uncertainty for t in tests])
    budget = Budget(evaluations)
    try:
        theta, r, jm = _solve(tests, mass, radius, fixed, cls, budget=budget)
    except Exhausted:
        raise FitError(f"the fit of the {cls.name} ball to its {len(tests)} tests did not "
                       f"converge within its budget of {budget.limit:,} test evaluations: the "
                       "tests contradict one another (not of one ball), or an uncertainty is "
                       "too small", converged=False) from None
    fitted = replace(law_of(theta, cls), **dict(fixed))  # the held values exactly
    dof = len(tests) - n_free
    chi2 = float(r @ r)
    jtj = jm.T @ jm
    if np.linalg.cond(jtj) > 1e12:
        raise FitError("the ball tests do not determine the viscoelastic law's parameters "
                       "(the fit is singular): add a test of another kind or speed (COR at a "
                       "third speed, a contact or collision time, a peak force, a compression)")
    cov = np.linalg.inv(jtj) * max(1.0, chi2 / dof if dof > 0 else 1.0)
    _refuse_untrusted(tests, mass, radius, r, fixed, cls, fitted, theta, budget)
    # parameter uncertainties, in SI (through the transforms)
    _, free = _split(fixed, cls)
    su = np.zeros(len(cls.PARAMETERS))
    su[free] = np.sqrt(np.diag(cov))  # a held parameter: no uncertainty from the fit
    uncertainty = {p: float(SLOPE[c](getattr(fitted, p)) * su[i])
                   for i, (p, c) in enumerate(zip(cls.PARAMETERS, cls.COORDINATES, strict=True))}
    # a lot whose every COR test is one standard uncertainty higher: those residuals fall by 1
    dr = np.array([-1.0 if t.kind in COR_KINDS else 0.0 for t in tests])
    step = np.zeros(len(cls.PARAMETERS))
    step[free] = -np.linalg.solve(jtj, jm.T @ dr)
    direction = tuple(float(x) for x in step)
    model = value + r * sigma
    return BallFit(fitted, tests, tuple(float(x) for x in model), tuple(float(x) for x in r),
                   chi2, dof, uncertainty, direction, tuple(k for k, _ in fixed))


def _refuse_untrusted(tests, mass, radius, r, fixed, cls, fitted, theta, budget: Budget) -> None:
    """FitError when a parameter lands on the edge of its plausible range or a test is missed
    by more than :data:`MAX_RESIDUAL`; a test out of line (which can also push a parameter to
    its edge: a COR of 0.9 at 58 m/s drives the fast branch's share to 0.01) is named
    (:func:`_blame`, within the fit's ``budget``)."""
    at_edge = _at_bounds(fitted)
    if np.max(np.abs(r)) > MAX_RESIDUAL:
        worst, miss, model_value, cut = _blame(tests, mass, radius, r, fixed, cls, theta, budget)
        edge = (f"the fit puts the viscoelastic ball's {at_edge} at the edge of its plausible "
                "range, and the law" if at_edge else "the viscoelastic law")
        which = "fitted to the other tests misses this one"
        if cut:
            n_missed = int(np.sum(np.abs(r) > MAX_RESIDUAL))
            which = (f"fitted to all {len(tests)} tests misses {n_missed} of them by more than "
                     f"{MAX_RESIDUAL:g} standard uncertainties, this one most,")
        note = (f" (the search for the test at fault stopped at the fit's budget of "
                f"{budget.limit:,} test evaluations)" if cut else "")
        raise FitError(f"{edge} {which} by {miss:+.1f} standard uncertainties (model "
                       f"{_show(tests[worst], model_value)} against "
                       f"{_show(tests[worst], tests[worst].value)}): the tests are not of one "
                       f"ball, or an uncertainty is too small{note}", worst)
    if at_edge:
        raise FitError(f"the fit puts the viscoelastic ball's {at_edge} at the edge of its "
                       "plausible range: the tests do not hold it (or are not of one ball)")


def _blame(tests: tuple[BallTest, ...], mass: float, radius: float, r: np.ndarray,
           fixed: Fixed, cls: type[Viscoelastic],
           near: np.ndarray | None, budget: Budget) -> tuple[int, float, float, bool]:
    """The test at fault in a refused fit, ``(index, miss, model value, cut)``: the one without
    which the others fit best (the smallest chi-square of the fit to the rest), its miss being
    how far that fit is from it, in its standard uncertainties. Where the rest fit equally well
    (with as many tests as parameters they fit exactly), the one missed by most in the standard
    uncertainty of the miss (its own and the prediction's: its externally studentised residual,
    so that a test the others hardly constrain is not blamed for their extrapolation). A test
    without which the rest cannot be fitted (too few, or no COR or stiffness-bearing test left)
    is not a candidate; with no candidate, the full fit's largest residual. ``cut``: the search
    spent ``budget`` (test evaluations) before it ended, and the full fit's largest residual is
    returned."""
    k = int(np.argmax(np.abs(r)))
    best = (k, float(r[k]), tests[k].value + float(r[k]) * tests[k].uncertainty)
    score = np.inf
    n = len(cls.PARAMETERS)
    for i, test in enumerate(tests):
        rest = tests[:i] + tests[i + 1:]
        kinds = {t.kind for t in rest}
        if (len(rest) < n - len(fixed) or not kinds & set(COR_KINDS)
                or not kinds & set(STIFFNESS_KINDS)):
            continue
        try:
            # from the full fit's coordinates: one start usually serves (a leave-one-out refit)
            theta, r_rest, jm = _solve(rest, mass, radius, fixed, cls, near, budget)
            cov = np.zeros((n, n))
            free = _split(fixed, cls)[1]
            cov[np.ix_(free, free)] = np.linalg.inv(jm.T @ jm)
            budget.spend(n + 1)  # the test's value and its gradient, below
        except (FitError, np.linalg.LinAlgError):
            continue
        except Exhausted:
            return (k, float(r[k]), tests[k].value + float(r[k]) * tests[k].uncertainty, True)
        steps = 1e-3 * np.eye(n)
        values = [float(test_values(law_of(th, cls), (test,), mass, radius)[0])
                  for th in (theta, *(theta + d for d in steps))]
        gradient = (np.array(values[1:]) - values[0]) / 1e-3
        spread = np.sqrt(test.uncertainty**2 + max(float(gradient @ cov @ gradient), 0.0))
        studentised = (values[0] - test.value) / spread
        rest_chi2 = round(float(r_rest @ r_rest), 3)  # ties: the rest fit exactly
        if rest_chi2 - 1e-6 * studentised**2 < score:
            score = rest_chi2 - 1e-6 * studentised**2
            best = (i, (values[0] - test.value) / test.uncertainty, values[0])
    return (*best, False)


def _at_bounds(law: Viscoelastic) -> str | None:
    for name, coordinate in zip(law.PARAMETERS, law.COORDINATES, strict=True):
        lo, hi = BOUNDS[name]
        x = getattr(law, name)
        if coordinate == "log":
            near = np.log(x / lo) < 1e-3 or np.log(hi / x) < 1e-3
        else:
            near = x - lo < 1e-4 * (hi - lo) or hi - x < 1e-4 * (hi - lo)
        if near:
            return name.replace("_", " ")
    return None


def check_given(law: Viscoelastic, tests: tuple[BallTest, ...], mass: float,
                radius: float) -> None:
    """FitError naming the test that a law with every parameter given (no fit) misses by more
    than :data:`MAX_RESIDUAL` of its standard uncertainty (tests without one are not judged):
    a ball whose parameters contradict its own tests must not run without a word."""
    judged = [i for i, t in enumerate(tests) if t.uncertainty > 0]
    if not judged:
        return
    values = predict([law], tuple(tests[i] for i in judged), mass, radius)[0]
    miss = [(values[j] - tests[i].value) / tests[i].uncertainty for j, i in enumerate(judged)]
    worst = int(np.argmax(np.abs(miss)))
    if abs(miss[worst]) > MAX_RESIDUAL:
        test = tests[judged[worst]]
        raise FitError(f"the {type(law).name} law with the parameters given misses this test "
                       f"by {miss[worst]:+.1f} standard uncertainties (model "
                       f"{_show(test, values[worst])} against {_show(test, test.value)}): "
                       "the parameters are not of this ball, or leave one out to fit it",
                       judged[worst])


def _show(test: BallTest, x: float) -> str:
    unit = {"cor": "", "cylinder_cor": "", "peak_force": " N", "collision_time": " s",
            "contact_time": " s", "compression": " N"}[test.kind]
    return f"{x:.4g}{unit}"
