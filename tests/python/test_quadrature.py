"""rhabel.gauss_jacobi against the Beta-function moments, and rhabel.jacobi_p against the explicit
sum DLMF 18.5.8 in exact rational arithmetic (no code shared with the library)."""

import math
from fractions import Fraction

import numpy as np
import pytest

import rhabel
from conftest import EPS

# The weights and the complements 1 -+ x are within 45 eps (the accuracy contract of
# gauss_jacobi.hpp for p, q in (-1, 5]); a positive sum of products, summed with fsum, adds one
# rounding per product and the reference B(.,.) from three gamma values a few more. The power
# (1 +- x)^j multiplies the rounding of the complement (half an ulp) by j.
MOMENT_TOLERANCE = 64 * EPS


def moment_tolerance(j):
    return MOMENT_TOLERANCE + j * EPS

RULES = [(1, 0.0, 0.0), (5, 0.25, -0.5), (16, -0.999, 0.5), (40, -0.9, 0.3), (41, 0.3, 0.7), (100, 5.0, 0.5),
         (1000, -0.5, 2.2)]


def beta_function(a, b):
    return math.gamma(a) * math.gamma(b) / math.gamma(a + b)


@pytest.mark.parametrize("n,p,q", RULES)
def test_rule_integrates_polynomials_exactly(n, p, q):
    x, one_minus_x, one_plus_x, w = rhabel.gauss_jacobi(n, p, q)
    assert x.shape == one_minus_x.shape == one_plus_x.shape == w.shape == (n,)
    assert np.all(np.diff(x) > 0) and np.all(w > 0)
    # int (1-x)^p (1+x)^(q+j) dx = 2^(p+q+j+1) B(p+1, q+j+1), exact for j <= 2n - 1 (and mirrored).
    for j in range(0, min(2 * n - 1, 60) + 1):
        exact = 2 ** (p + q + j + 1) * beta_function(p + 1, q + j + 1)
        assert math.fsum(w * one_plus_x ** j) == pytest.approx(exact, rel=moment_tolerance(j)), j
        exact = 2 ** (p + q + j + 1) * beta_function(p + j + 1, q + 1)
        assert math.fsum(w * one_minus_x ** j) == pytest.approx(exact, rel=moment_tolerance(j)), j


def test_mapped_rule_and_no_copy():
    lo, hi, n, p, q = 2.0, 5.0, 12, 0.25, -0.5
    rule = rhabel.gauss_jacobi(n, p, q, lo, hi)
    # The node is the rounded lo + (x - lo) or hi - (hi - x): within an ulp of x of its distances.
    assert np.max(np.abs((rule.x - lo) - rule.x_minus_lo)) <= 2 * EPS * hi
    assert np.max(np.abs((hi - rule.x) - rule.hi_minus_x)) <= 2 * EPS * hi
    for j in range(2 * n):
        exact = (hi - lo) ** (p + q + j + 1) * beta_function(p + 1, q + j + 1)
        assert math.fsum(rule.weight * rule.x_minus_lo ** j) == pytest.approx(exact, rel=moment_tolerance(j))
    # The arrays wrap the C++ vectors (owned by a capsule), they are not copies.
    for a in rule:
        assert a.dtype == np.float64 and not a.flags.owndata and a.base is not None
    x, _, _, w = rhabel.gauss_jacobi(10, 0.0, 0.0)  # unpacks as a tuple
    assert math.fsum(w) == pytest.approx(2.0, rel=MOMENT_TOLERANCE)


def exact_jacobi(n, p, q, x):
    """P_n^(p,q)(x) = sum_s C(n+p, n-s) C(n+q, s) ((x-1)/2)^s ((x+1)/2)^(n-s) (DLMF 18.5.8), in
    rationals: p, q, x are converted exactly."""
    p, q, x = Fraction(p), Fraction(q), Fraction(x)

    def binom(z, k):
        out = Fraction(1)
        for i in range(k):
            out *= (z - i) / (i + 1)
        return out

    return sum(binom(n + p, n - s) * binom(n + q, s) * ((x - 1) / 2) ** s * ((x + 1) / 2) ** (n - s)
               for s in range(n + 1))


@pytest.mark.parametrize("n,p,q", [(0, 0.5, 0.5), (1, 0.25, -0.5), (3, 0.5, 0.5), (7, -0.9, 0.3), (12, 2.0, 0.75),
                                   (25, -0.5, -0.5)])
def test_jacobi_p_matches_explicit_sum(n, p, q):
    xs = np.concatenate([np.linspace(-1, 1, 33), [-1 + 2 ** -30, 1 - 2 ** -30, 0.3333, 1.5, -2.0]])
    got = rhabel.jacobi_p(n, p, q, xs)
    assert isinstance(got, np.ndarray) and got.shape == xs.shape
    exact = [float(exact_jacobi(n, p, q, x)) for x in xs]
    # Relative O(n eps) away from the zeros, absolute O(n eps) max|P_n| near them (header:
    # <= 0.3 (n + 10) eps relative to the local scale); the scale here: max |P_n| on the points.
    scale = max(abs(v) for v in exact)
    assert np.max(np.abs(got - exact)) <= 4 * (n + 10) * EPS * scale
    assert isinstance(rhabel.jacobi_p(n, p, q, 0.25), float)  # a float in, a float out
    assert rhabel.jacobi_p(n, p, q, xs.reshape(2, -1)).shape == (2, xs.size // 2)
