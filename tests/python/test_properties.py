"""Property-based tests of the Python API (Debian's python3-hypothesis; skipped without it).

Whatever the arguments, a call either raises ValueError or TypeError (never a crash, MemoryError,
OverflowError, RecursionError or SystemError) or returns a result whose evidence is honest: status
"converged" only with a finite density and, for piecewise data, a residual within the acceptance.
Deterministic for CI: derandomize=True (the examples are a function of the test alone), no example
database, a bounded number of examples and no deadline (the run time is bounded by max_examples
and the size limits, not by the wall clock)."""

import math

import pytest

hypothesis = pytest.importorskip("hypothesis")
from hypothesis import given, settings, strategies as st  # noqa: E402

import rhabel  # noqa: E402

PIECEWISE_RESIDUAL_ACCEPTANCE = 1e-2  # abel_solver.hpp: piecewise_residual_acceptance
REFUSALS = (ValueError, TypeError)

settings.register_profile("rhabel", derandomize=True, database=None, deadline=None, max_examples=60,
                          suppress_health_check=list(hypothesis.HealthCheck))
settings.load_profile("rhabel")

any_float = st.floats(allow_nan=True, allow_infinity=True)
small_float = st.floats(min_value=-1e3, max_value=1e3, allow_nan=False)
edge = st.sampled_from(["bounded", "unbounded", "neither"])
size = st.one_of(st.integers(min_value=0, max_value=64), st.integers(min_value=-2, max_value=10**12))


def finite_density(sol):
    return all(math.isfinite(c) for c in sol.density.coefficients)


@given(alpha=any_float, beta=any_float, lo=any_float, hi=any_float, leading=edge, trailing=edge,
       coefficients=st.lists(any_float, max_size=6), degree=size, tolerance=any_float)
def test_abel_polynomial_data_refused_or_honest(alpha, beta, lo, hi, leading, trailing, coefficients, degree,
                                                 tolerance):
    try:
        sol = rhabel.abel.solve(alpha, beta, lo, hi, leading, trailing, coefficients, degree=degree,
                                tolerance=tolerance, residual_points=4)
    except REFUSALS:
        return
    assert sol.status in ("converged", "not_converged")
    if sol.status == "converged":
        assert finite_density(sol)


@given(alpha=st.floats(min_value=0, max_value=0.45), beta=st.floats(min_value=-0.5, max_value=0.5),
       breakpoints=st.lists(st.floats(min_value=-1.5, max_value=1.5), min_size=1, max_size=3),
       piecewise_degree=st.integers(min_value=0, max_value=48), power=st.sampled_from([0, 1, 2]),
       trailing=st.sampled_from(["bounded", "unbounded"]))
def test_abel_piecewise_converged_only_within_the_acceptance(alpha, beta, breakpoints, piecewise_degree, power,
                                                             trailing):
    kink = breakpoints[0]
    try:
        sol = rhabel.abel.solve(alpha, beta, -1.0, 1.0, "bounded", trailing, lambda s: abs(s - kink) ** power,
                                breakpoints=breakpoints, piecewise_degree=piecewise_degree, residual_points=6)
    except REFUSALS:
        return
    if sol.status == "converged":
        assert sol.residual <= PIECEWISE_RESIDUAL_ACCEPTANCE and finite_density(sol)


@given(value=any_float, call=st.integers(min_value=1, max_value=40))
def test_callable_values_are_finite_or_refused(value, call):
    calls = [0]

    def data(s):
        calls[0] += 1
        return value if calls[0] == call else 1.0 + s
    try:
        sol = rhabel.riemann.solve_abel_rh(0.3, 0.1, -1.0, 1.0, data)
    except ValueError as e:
        assert "data(s)" in str(e) and not math.isfinite(value)
        return
    assert sol.status != "converged" or math.isfinite(sol.total()[0])


@given(n=size, p=any_float, q=any_float)
def test_gauss_jacobi_refused_or_finite(n, p, q):
    try:
        rule = rhabel.gauss_jacobi(n, p, q)
    except REFUSALS:
        return
    assert all(math.isfinite(w) for w in rule.weight)


@given(a=any_float, b=any_float)
def test_trial_interval_refused_or_finite(a, b):
    scene = {"material": {"alpha": 0.3, "E1": 1.0, "nu": 0.5, "coulomb": 0}, "speed": 1.0,
             "indentors": [{"shape": "parabolic", "radius": 1.0, "load": 1.0}]}
    try:
        t = rhabel.trial_interval(scene, a, b)
    except REFUSALS:
        return
    assert math.isfinite(t.load) and math.isfinite(t.hysteretic_friction)


json_values = st.recursive(
    st.none() | st.booleans() | any_float | st.integers() | st.text(max_size=8),
    lambda inner: st.lists(inner, max_size=3) | st.dictionaries(st.text(max_size=8), inner, max_size=3),
    max_leaves=12)
scene_keys = st.sampled_from(["description", "material", "speed", "body", "indentors", "profile", "x"])


@given(scene=st.dictionaries(scene_keys, json_values, max_size=5))
def test_validate_scene_refuses_with_value_error(scene):
    try:
        rhabel.validate_scene(scene)
    except ValueError:
        pass
