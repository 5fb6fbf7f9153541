"""rhabel.trial_interval (the trial fields of the paper's Section 4) against closed forms that share
no code with the solver:

- the parabola on ANY interval [a, b]: its data F = f'/Gamma(1 - alpha) is linear, so by the spectral
  relation (docs/theory.md section 4, index nu = 0) the trial density is the weight times a polynomial
  of degree 1 whose two coefficients are F's coefficients divided by lambda_0 and lambda_1; its load and
  C_f are then moments of a Beta weight (closed form below);
- the wedge on [a, apex] (constant data S1): the closed form of docs/theory.md section 5, C_f = S1;
- at the true contact interval (parabola, and the wedge below the boundary, whose eps and L are
  explicit) the trial field carries the true load.
"""

import math

import pytest

import rhabel
from conftest import EPS, SOLVE_TOLERANCE
from test_solve import parabola_closed_form

# Tolerances (named, with the reason):
# The parabola's data is a polynomial of degree 1: the expansion is exact after two terms, so the
# trial field's load and C_f agree with the closed form to rounding (a few hundred eps for the
# Jacobi sums and the Gamma functions of the closed form; measured <= 45 eps).
CLOSED_FORM = 256 * EPS
# The wedge with its apex inside the interval: the apex singularity is built in and the smooth rest
# expanded to the requested tolerance (rhabel.solve's default 1e-12), as in rhabel.solve.
EXPANSION = 10 * SOLVE_TOLERANCE


def material(alpha, beta, E1=1.0):
    """nu = 0 and k = 2 tan(beta pi/2) give the friction parameter beta exactly."""
    return {"alpha": alpha, "E1": E1, "nu": 0.0, "coulomb": 2 * math.tan(beta * math.pi / 2)}


def one(alpha, beta, indentor, speed=1.0, E1=1.0):
    return {"material": material(alpha, beta, E1), "speed": speed, "indentors": [indentor]}


def effective_modulus(alpha, E1, speed):
    return E1 * math.gamma(1 - alpha) * speed ** alpha  # nu = 0


def parabola_trial(alpha, beta, E_U, R, apex, a, b):
    """Load and C_f of the index-0 solution of (8) on [a, b] for f' = -(x - apex)/R.

    With x = (2t - a - b)/L, h = L/2, the weight w = (1 - x)^del (1 + x)^gam (gam = (1-2alpha-beta)/2,
    del = (beta-1)/2) and the spectral relation A[w P_n^(del,gam)] = h^alpha lambda_n P_n^(gam,del),
    lambda_n = -pi (1-alpha)_n / (n! sin(pi del)): F = F0 P_0 + F1 P_1^(gam,del) gives
    g = h^-alpha w (F0/lambda_0 + F1/lambda_1 P_1^(del,gam)). P_1^(p,q)(x) = ((p - q) + (p + q + 2) x)/2.
    Moments of w: u = (1 + x)/2 has the Beta(gam + 1, del + 1) law."""
    gam, dl = (1 - 2 * alpha - beta) / 2, (beta - 1) / 2
    h, d = (b - a) / 2, (a + b) / 2 - apex
    G = math.gamma(1 - alpha)
    s = gam + dl + 2
    # F(x) = -(d + h x)/(R G), and x = (2 P_1^(gam,del) - (gam - del))/s
    F1 = -(h / (R * G)) * 2 / s
    F0 = -(d / (R * G)) + (h / (R * G)) * (gam - dl) / s
    sin_dl = math.sin(math.pi * dl)
    c0, c1 = F0 / (-math.pi / sin_dl), F1 / (-math.pi * (1 - alpha) / sin_dl)
    A, B = c0 + c1 * (dl - gam) / 2, c1 * s / 2  # g = h^-alpha w (A + B x)
    m0 = 2 ** (dl + gam + 1) * math.gamma(gam + 1) * math.gamma(dl + 1) / math.gamma(s)
    Eu, Eu2 = (gam + 1) / s, (gam + 1) * (gam + 2) / (s * (s + 1))
    Ex, Ex2 = 2 * Eu - 1, 4 * Eu2 - 4 * Eu + 1
    integral = h ** (1 - alpha) * m0 * (A + B * Ex)
    slope_moment = -h ** (1 - alpha) * m0 / R * (d * A + (d * B + h * A) * Ex + h * B * Ex2)
    return math.pi / 2 * E_U * integral, slope_moment / integral


def rel(x, y):
    return abs(x - y) / abs(y)


@pytest.mark.parametrize("alpha", [0.0, 0.3, 0.5, 0.7])
@pytest.mark.parametrize("beta", [0.0, 0.3])
@pytest.mark.parametrize("interval", [(-1.0, 0.4), (-0.3, 1.2), (0.5, 2.0), (-3.0, -2.5)])
def test_parabola_on_any_interval(alpha, beta, interval):
    """Intervals around, behind and ahead of the vertex; the apex is moved off 0 as well."""
    R, apex, E1, speed = 0.7, 0.25, 3.0, 2.0
    a, b = interval
    sc = one(alpha, beta, {"shape": "parabolic", "radius": R, "load": 1.0, "apex": apex}, speed, E1)
    t = rhabel.trial_interval(sc, a, b)
    load, cf = parabola_trial(alpha, beta, effective_modulus(alpha, E1, speed), R, apex, a, b)
    assert rel(t.load, load) <= CLOSED_FORM
    assert abs(t.hysteretic_friction - cf) <= CLOSED_FORM * max(abs(cf), (b - a) / R)
    assert 0 <= t.error_estimate <= SOLVE_TOLERANCE


@pytest.mark.parametrize("alpha", [0.0, 0.2, 0.45, 0.7])
@pytest.mark.parametrize("k", [0.0, 0.5])
def test_parabola_at_the_true_interval(alpha, k):
    """At the closed-form contact the trial field is the true one: the requested load and C_f."""
    nu, E1, speed, R, P, apex = 0.3, 2.0, 0.5, 0.01, 0.25, 1e-3
    exact = parabola_closed_form(alpha, E1, nu, k, speed, R, P, apex)
    sc = {"material": {"alpha": alpha, "E1": E1, "nu": nu, "coulomb": k}, "speed": speed,
          "indentors": [{"shape": "parabolic", "radius": R, "load": P, "apex": apex}]}
    t = rhabel.trial_interval(sc, exact["a"], exact["b"])
    assert rel(t.load, P) <= CLOSED_FORM
    assert abs(t.hysteretic_friction - exact["C_f"]) <= CLOSED_FORM * exact["L"] / R


@pytest.mark.parametrize("alpha", [0.0, 0.25, 0.6])
@pytest.mark.parametrize("beta", [0.0, 0.4])
def test_wedge_ending_at_its_apex(alpha, beta):
    """[a, apex]: only the leading face, data S1/Gamma(1 - alpha) (docs/theory.md section 5):
    load = E_U S1 cos(beta pi/2) B(gam + 1, del + 1) L^(1-alpha) / (2 Gamma(1 - alpha)), C_f = S1."""
    S1, S2, apex, L = 0.2, 0.05, 0.3, 1.7
    sc = one(alpha, beta, {"shape": "wedge", "slope_leading": S1, "slope_trailing": S2, "load": 1.0, "apex": apex})
    t = rhabel.trial_interval(sc, apex - L, apex)
    gam, dl = (1 - 2 * alpha - beta) / 2, (beta - 1) / 2
    B = math.gamma(gam + 1) * math.gamma(dl + 1) / math.gamma(gam + dl + 2)
    load = effective_modulus(alpha, 1.0, 1.0) * S1 * math.cos(beta * math.pi / 2) * B * L ** (1 - alpha) / (
        2 * math.gamma(1 - alpha))
    assert rel(t.load, load) <= CLOSED_FORM
    assert rel(t.hysteretic_friction, S1) <= CLOSED_FORM


# eps = (apex - a)/L below the boundary solves I_eps(del, gam) = S2/(S1 + S2) (docs/theory.md section 5).
# Cases where it is known in closed form (beta = 0, del = 1/2): alpha = 0 (gam = 1/2), where
# I_eps(1/2, 1/2) = (2/pi) arcsin(sqrt(eps)); alpha = 1/4 (gam = 1/4) with S1 = S2, where
# I_eps(1/2, 1/4) = 1/2 at eps = 2 (sqrt 2 - 1) (mpmath's betainc at 30 digits: 0.5 exactly).
WEDGE_CASES = [(0.0, 1.0, 0.5),
               (0.0, 3.0, math.sin(3 * math.pi / 8) ** 2),
               (0.25, 1.0, 2 * (math.sqrt(2) - 1))]


@pytest.mark.parametrize("alpha, ratio, eps", WEDGE_CASES)
def test_wedge_below_the_boundary_at_the_true_interval(alpha, ratio, eps):
    """The true interval from the explicit eps and L (docs/theory.md section 5; beta = 0):
    load = E_U (S1 + S2) eps^del (1 - eps)^gam L^(1-alpha) / (2 Gamma(2 - alpha)). The trial field on
    it carries the load, and its C_f is rhabel.solve's."""
    S1, P, apex = 0.1, 1.0, 0.4
    S2 = ratio * S1
    gam, dl = (1 - 2 * alpha) / 2, 0.5
    E_U = effective_modulus(alpha, 1.0, 1.0)
    L = (2 * math.gamma(2 - alpha) * P / (E_U * (S1 + S2) * eps ** dl * (1 - eps) ** gam)) ** (1 / (1 - alpha))
    wedge = {"shape": "wedge", "slope_leading": S1, "slope_trailing": S2, "load": P, "apex": apex}
    sc = one(alpha, 0.0, wedge)
    t = rhabel.trial_interval(sc, apex - eps * L, apex + (1 - eps) * L)
    assert rel(t.load, P) <= EXPANSION
    assert -EXPANSION * S1 <= t.hysteretic_friction < S1
    if alpha == 0:  # elastic frictionless: C_f = 0 (docs/theory.md section 8)
        assert abs(t.hysteretic_friction) <= EXPANSION * S1
    solved = rhabel.solve(sc).indentors[0]
    assert solved.epsilon == pytest.approx(eps, rel=CLOSED_FORM)
    assert abs(t.hysteretic_friction - solved.hysteretic_friction) <= EXPANSION * S1


def test_errors():
    parabola = {"shape": "parabolic", "radius": 1.0, "load": 1.0}
    with pytest.raises(ValueError, match="flat punch has no trial family"):
        rhabel.trial_interval(one(0.3, 0.0, {"shape": "flat", "width": 1.0, "load": 1.0}), -1, 1)
    with pytest.raises(ValueError, match="need finite a < b"):
        rhabel.trial_interval(one(0.3, 0.0, parabola), 1.0, -1.0)
    with pytest.raises(ValueError, match="exactly one"):
        sc = one(0.3, 0.0, parabola)
        sc["indentors"] = [parabola, dict(parabola, apex=5.0)]
        rhabel.trial_interval(sc, -1, 1)
    with pytest.raises(ValueError, match="finite"):
        rhabel.trial_interval(one(0.3, 0.0, parabola), float("nan"), 1.0)
    with pytest.raises(ValueError, match="radius"):
        rhabel.trial_interval(one(0.3, 0.0, dict(parabola, radius=-1.0)), -1, 1)
