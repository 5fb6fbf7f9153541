"""rhabel.abel.solve and rhabel.riemann.solve_abel_rh against closed forms and against each other
(two independent methods: spectral relation and Riemann-Hilbert problem)."""

import math

import numpy as np
import pytest

import rhabel
from conftest import EPS
from test_solve import parabola_closed_form


def test_carleman_closed_form():
    """alpha = beta = 0: PV int_{-1}^{1} sqrt(1 - t^2)/(t - s) dt = -pi s, so F = -pi s gives
    g = sqrt(1 - t^2) in the class bounded at both ends (defect 0)."""
    t = np.linspace(-0.99, 0.99, 23)
    exact = np.sqrt(1 - t ** 2)
    for data in ([0.0, -math.pi], lambda s: -math.pi * s):
        sol = rhabel.abel.solve(0.0, 0.0, -1.0, 1.0, "bounded", "bounded", data)
        assert sol.status == "converged" and sol.exponents == (0.5, 0.5, -1)
        assert abs(sol.solvability_defect) <= 16 * EPS
        assert np.max(np.abs(sol.density(t) - exact)) <= 16 * EPS  # a few roundings of the series
        assert sol.density.integral() == pytest.approx(math.pi / 2, rel=16 * EPS)
        # Intensity factors: g / (1 -+ t)^(1/2) -> sqrt(2) at both ends.
        assert sol.density.intensity_leading() == pytest.approx(math.sqrt(2), rel=16 * EPS)
        assert sol.density.intensity_trailing() == pytest.approx(math.sqrt(2), rel=16 * EPS)
        assert sol.residual < 1e-14 and sol.homogeneous is None
        rh = rhabel.riemann.solve_abel_rh(0.0, 0.0, -1.0, 1.0, data)
        values, errors = rh.density(t)
        assert np.max(np.abs(values - exact)) <= 1e-13 and np.all(errors < 1e-13)
        assert rh.total()[0] == pytest.approx(math.pi / 2, rel=64 * EPS)


@pytest.mark.parametrize("alpha,k", [(0.2, 0.0), (0.3, 0.5), (0.45, 2.0)])
def test_parabola_density_on_its_contact(alpha, k):
    """On the exact contact interval of a parabola, F = f'(s)/Gamma(1 - alpha) =
    -(s - apex)/(R Gamma(1 - alpha)) satisfies the orthogonality condition: the bounded solution
    exists (defect ~ 0) and int g is the closed form. Both solvers."""
    nu, R, apex = 0.3, 0.01, 0.0
    c = parabola_closed_form(alpha, 1.0, nu, k, 1.0, R, 1.0, apex)
    beta, a, b = c["beta"], c["a"], c["b"]
    integral = 1.0 / (math.pi / 2 * c["E_U"])  # load 1 = (pi/2) E_U int g
    coefficients = [apex / (R * math.gamma(1 - alpha)), -1 / (R * math.gamma(1 - alpha))]
    sol = rhabel.abel.solve(alpha, beta, a, b, "bounded", "bounded", coefficients)
    scale_F = (b - a) / (R * math.gamma(1 - alpha))
    assert abs(sol.solvability_defect) <= 1e-13 * scale_F
    assert sol.density.integral() == pytest.approx(integral, rel=1e-13)
    rh = rhabel.riemann.solve_abel_rh(alpha, beta, a, b, coefficients)
    assert rh.index == -1 and rh.status == "converged"
    assert rh.total()[0] == pytest.approx(integral, rel=1e-13)
    # Pointwise agreement of the two methods inside (header of riemann/abel_solver.hpp: <= 50 eps
    # relative to max(|g|, int g / L) at least 0.14 L from the ends for alpha <= 0.6).
    y = a + (b - a) * np.linspace(0.15, 0.85, 9)
    g_rh, _ = rh.density(y)
    g_spectral = sol.density(y)
    assert np.max(np.abs(g_rh - g_spectral)) <= 1e-12 * max(np.max(np.abs(g_spectral)), integral / (b - a))
    # int_a^y g by both.
    assert np.allclose(sol.density.integral_to(y), rh.integral(y)[0], rtol=1e-12, atol=1e-14 * integral)


def test_nu_plus_one_load_and_step_data():
    alpha, beta = 0.3, 0.2
    # nu = +1: the free constant fixed by int g = load.
    sol = rhabel.abel.solve(alpha, beta, -1.0, 2.0, "unbounded", "unbounded", [1.0, 0.5], load=3.0)
    assert sol.exponents[2] == 1 and sol.density.integral() == pytest.approx(3.0, rel=16 * EPS)
    assert sol.homogeneous.integral() == pytest.approx(1.0, rel=16 * EPS)
    assert sol.with_load(5.0).integral() == pytest.approx(5.0, rel=16 * EPS)
    rh = rhabel.riemann.solve_abel_rh(alpha, beta, -1.0, 2.0, [1.0, 0.5], "unbounded", "unbounded", load=3.0)
    assert rh.total()[0] == pytest.approx(3.0, rel=64 * EPS)
    y = np.array([-0.5, 0.0, 0.7, 1.5])
    assert np.allclose(rh.density(y)[0], sol.density(y), rtol=1e-11)
    # Step data (a wedge's F): piecewise spectral solve against the Riemann-Hilbert route; int g
    # is exact in both (c_0 of the series; the moment formula).
    gf = math.gamma(1 - alpha)
    S1, S2, t0 = 0.1, 0.2, 0.25
    spectral = rhabel.abel.solve(alpha, beta, -1.0, 1.0, "bounded", "unbounded",
                                 lambda s: (S1 - (S1 + S2) * (s > t0)) / gf, breakpoints=[t0])
    rh = rhabel.riemann.solve_abel_rh(alpha, beta, -1.0, 1.0, [S1 / gf], "bounded", "unbounded",
                                      steps=[(t0, -(S1 + S2) / gf)])
    assert spectral.density.integral() == pytest.approx(rh.total()[0], rel=1e-13)


def test_riemann_integral_and_scalars():
    rh = rhabel.riemann.solve_abel_rh(0.25, 0.1, 0.0, 1.0, lambda s: 1 + s * s, "bounded", "unbounded")
    value, error = rh.integral(0.5)
    assert isinstance(value, float) and isinstance(error, float)
    values, errors = rh.integral(np.array([0.0, 0.5, 1.0]))
    assert values[0] == 0 and values[1] == value and values[2] == rh.total()[0]
    assert rh.orthogonality_defect == (0.0, 0.0) and rh.leading == "bounded" and rh.trailing == "unbounded"
    with pytest.raises(ValueError, match="density: y = 1"):
        rh.density(1.0)
