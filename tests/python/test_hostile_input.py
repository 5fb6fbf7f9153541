"""Hostile input to the Python API (issue 31): each case a ValueError/TypeError naming the argument,
raised before any large allocation, or a correct result; a solver's status is "converged" only on
its own evidence (residual within the acceptance, finite density)."""

import math

import pytest

import rhabel

# The limits of python/src/bindings.hpp and abel_solver.hpp (named there with their reasons).
MAX_QUADRATURE_NODES = 1_000_000
MAX_EXPANSION_DEGREE = 16384
PIECEWISE_RESIDUAL_ACCEPTANCE = 1e-2
HUGE = 10**9  # a size that used to allocate gigabytes or run for minutes

PARABOLA = {"material": {"alpha": 0.3, "E1": 1.0, "nu": 0.5, "coulomb": 0}, "speed": 1.0,
            "indentors": [{"shape": "parabolic", "radius": 1.0, "load": 1.0}]}


def solve_kink(**options):
    return rhabel.abel.solve(.3, .1, -1, 1, "bounded", "unbounded", lambda s: abs(s), breakpoints=[0.], **options)


def test_piecewise_degree_0_is_refused_not_a_crash():
    with pytest.raises(ValueError, match="piecewise_degree = 0"):
        solve_kink(piecewise_degree=0)


# (s^2 is a polynomial: from 4 coefficients on its projection is exact, and converged.)
@pytest.mark.parametrize("data, degree", [(abs, 1), (abs, 2), (abs, 4), (lambda s: s * s, 1), (lambda s: s * s, 2)],
                         ids=["abs-1", "abs-2", "abs-4", "square-1", "square-2"])
def test_piecewise_few_coefficients_not_converged(data, degree):
    sol = rhabel.abel.solve(.3, .1, -1, 1, "bounded", "unbounded", data, breakpoints=[0.], piecewise_degree=degree)
    assert sol.residual > PIECEWISE_RESIDUAL_ACCEPTANCE
    assert sol.status == "not_converged"


def test_piecewise_default_converged_on_its_residual():
    sol = solve_kink()
    assert sol.status == "converged" and sol.residual <= PIECEWISE_RESIDUAL_ACCEPTANCE


def nan_on_call(n):
    """A callable returning s, but NaN on its n-th call."""
    calls = [0]

    def f(s):
        calls[0] += 1
        return float("nan") if calls[0] == n else s
    return f


@pytest.mark.parametrize("bad", [float("nan"), float("inf")])
def test_callable_returning_nan_is_an_error_naming_it(bad):
    with pytest.raises(ValueError, match=r"rhabel.riemann.solve_abel_rh: data\(s\) returned"):
        rhabel.riemann.solve_abel_rh(.3, .1, -1, 1, lambda s: bad)
    with pytest.raises(ValueError, match=r"rhabel.abel.solve: data\(s\) returned nan"):
        rhabel.abel.solve(.3, .1, -1, 1, "bounded", "unbounded", nan_on_call(3))
    with pytest.raises(ValueError, match=r"rhabel.abel.solve: data\(s\) returned nan"):
        rhabel.abel.solve(.3, .1, -1, 1, "bounded", "unbounded", nan_on_call(5), breakpoints=[0.])


@pytest.mark.parametrize("call, words", [
    (lambda: rhabel.abel.solve(.3, .1, -1, 1, "bounded", "unbounded", abs, max_degree=HUGE), "max_degree"),
    (lambda: rhabel.abel.solve(.3, .1, -1, 1, "bounded", "unbounded", abs, degree=HUGE), "degree"),
    (lambda: rhabel.abel.solve(.3, .1, -1, 1, "bounded", "unbounded", abs, residual_points=HUGE), "residual_points"),
    (lambda: solve_kink(piecewise_degree=HUGE), "piecewise_degree"),
    (lambda: rhabel.abel.solve(.3, .1, -1, 1, "bounded", "unbounded", [0.0] * (MAX_EXPANSION_DEGREE + 1)),
     "len(data)"),
    (lambda: rhabel.abel.solve(.3, .1, -1, 1, "bounded", "unbounded", abs,
                               breakpoints=[0.5 * i / 100_000 for i in range(1, 100_000)]), "len(breakpoints)"),
    (lambda: rhabel.gauss_jacobi(HUGE, 0, 0), "n"),
    (lambda: rhabel.gauss_jacobi(MAX_QUADRATURE_NODES + 1, 0, 0), "n"),
    (lambda: rhabel.jacobi_p(HUGE, 0, 0, 0.5), "n"),
    (lambda: rhabel.riemann.solve_abel_rh(.3, .1, -1, 1, [1.0], order=HUGE), "order"),
    (lambda: rhabel.abel.solve(0, 0, -1, 1, "bounded", "bounded", [0.0, -math.pi]).density.moment(HUGE), "k"),
], ids=["max_degree", "degree", "residual_points", "piecewise_degree", "coefficients", "breakpoints",
        "gauss_jacobi", "gauss_jacobi_limit", "jacobi_p", "rh_order", "moment"])
def test_sizes_beyond_the_limits_refused_at_once(call, words):
    with pytest.raises(ValueError, match=r"\b" + words.replace("(", r"\(").replace(")", r"\)") + r" = \d+ is above the limit"):
        call()


@pytest.mark.parametrize("tolerance", [float("nan"), -1.0, float("inf")])
def test_bad_tolerances_refused(tolerance):
    with pytest.raises(ValueError, match="tolerance"):
        rhabel.abel.solve(.3, .1, -1, 1, "bounded", "unbounded", abs, tolerance=tolerance)
    with pytest.raises(ValueError, match="tolerance"):
        rhabel.riemann.solve_abel_rh(.3, .1, -1, 1, [1.0], tolerance=tolerance)
    with pytest.raises(ValueError, match="tolerance"):
        rhabel.solve(PARABOLA, tolerance=tolerance)


def test_non_finite_arguments_of_densities_refused():
    free = rhabel.abel.solve(0, 0, -1, 1, "unbounded", "unbounded", [1.0])
    with pytest.raises(ValueError, match="with_load: load = nan"):
        free.with_load(float("nan"))
    g = rhabel.abel.solve(0, 0, -1, 1, "bounded", "bounded", [0.0, -math.pi]).density
    with pytest.raises(ValueError, match="integral_to: t = nan"):
        g.integral_to(float("nan"))
    with pytest.raises(ValueError, match="integral_to: t = inf"):
        g.integral_to([0.0, float("inf")])


def test_non_finite_steps_refused():
    with pytest.raises(ValueError, match="a step's size = nan"):
        rhabel.riemann.solve_abel_rh(.3, .1, -1, 1, [1.0], steps=[(0.0, float("nan"))])
    with pytest.raises(ValueError, match="a step's position = inf"):
        rhabel.riemann.solve_abel_rh(.3, .1, -1, 1, [1.0], steps=[(float("inf"), 1.0)])


def test_coefficients_near_the_double_range_are_a_value_error():
    with pytest.raises(ValueError, match="data"):
        rhabel.abel.solve(.3, .1, -1, 1, "bounded", "unbounded", [1e308, 1e308])
    with pytest.raises(ValueError, match="a coefficient of data = nan"):
        rhabel.abel.solve(.3, .1, -1, 1, "bounded", "unbounded", [1.0, float("nan")])


@pytest.mark.parametrize("a, b", [(-1e300, 1e300), (0.0, 5e-324), (-1e308, 1e308)])
def test_trial_interval_beyond_the_double_range_refused(a, b):
    with pytest.raises(ValueError, match=r"trial_interval: .*(interval|b - a)"):
        rhabel.trial_interval(PARABOLA, a, b)


def test_deeply_nested_description_is_a_value_error():
    deep = []
    for _ in range(100_000):
        deep = [deep]
    with pytest.raises(ValueError, match="deeper than"):
        rhabel.validate_scene({**PARABOLA, "description": deep})


def test_profile_csv_byte_order_mark_is_skipped(tmp_path):
    samples = "0,-4e-6\n0.001,-1e-6\n0.002,0\n0.003,-1e-6\n0.004,-4e-6\n"
    (tmp_path / "bom.csv").write_bytes(b"\xef\xbb\xbf" + samples.encode())
    (tmp_path / "plain.csv").write_text(samples)
    base = {"material": {"alpha": 0.3, "E1": 1e6, "nu": 0.5, "coulomb": 0}, "speed": 0.01, "body": {"load": 10}}
    bom = rhabel.validate_scene({**base, "profile": {"file": str(tmp_path / "bom.csv")}})
    plain = rhabel.validate_scene({**base, "profile": {"file": str(tmp_path / "plain.csv")}})
    assert bom["profile"]["x"] == plain["profile"]["x"] and len(bom["profile"]["x"]) == 5


@pytest.mark.parametrize("name", ["/dev/zero", "directory", "with\0nul.csv"])
def test_profile_file_that_is_not_a_regular_file_refused(tmp_path, name):
    path = str(tmp_path) if name == "directory" else name
    base = {"material": {"alpha": 0.3, "E1": 1e6, "nu": 0.5, "coulomb": 0}, "speed": 0.01, "body": {"load": 10}}
    with pytest.raises(ValueError, match="profile.file .* is not a readable regular file"):
        rhabel.validate_scene({**base, "profile": {"file": path}})
