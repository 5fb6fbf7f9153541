"""The Riemann-Hilbert route to the generalized Abel equation (rhabel::riemann):

    F(s) = int_s^b g(t) (t - s)^(alpha-1) dt - kappa int_a^s g(t) (s - t)^(alpha-1) dt,  a < s < b,

solved through a scalar Riemann-Hilbert problem with Cauchy integrals and an elementary Abel
inversion: independent of rhabel.abel by its method (no spectral relation, no Jacobi expansion of
F), so the two solvers check each other. F = smooth part + steps (the wedge is one step). Every
value is returned with an error estimate (|value at order n - value at order 3n/2|: an estimate,
not a bound). Theory and measured accuracy: the header rhabel/riemann/abel_solver.hpp of the C++
library.
"""

from ._rhabel import riemann as _riemann

RHSolution = _riemann.RHSolution

__all__ = ["solve_abel_rh", "RHSolution"]


def solve_abel_rh(alpha, beta, a, b, data=None, leading="bounded", trailing="bounded", *, steps=(), order=0,
                  load=None, tolerance=2.220446049250313e-13):
    """Solve the generalized Abel equation on [a, b] for g in the class (leading, trailing),
    each "bounded" or "unbounded" (see rhabel.abel for the classes; "unbounded" at a needs
    alpha + beta/2 < 1/2). alpha in [0, 1), beta in [0, 1).

    data
        the smooth part of F: a callable F(s) -> float (analytic near [a, b]; called from C++
        with the GIL, also later by density()), a sequence of monomial coefficients
        [c0, c1, ...] (no Python call), or None (steps only).
    steps
        sequence of (position, size): F jumps by ``size`` at ``position`` in (a, b)
        (F = smooth + sum size [s > position]). A wedge with slopes S1, S2 and apex t0 is
        data = [S1 / Gamma(1 - alpha)], steps = [(t0, -(S1 + S2) / Gamma(1 - alpha))].
    order
        Gauss nodes per panel (0: the default, 26 in double; at least 4).
    load
        nu = +1: int g = load fixes the free constant (else 0).
    tolerance
        for the status only (default 1000 eps).

    Returns an RHSolution:
        total()                  (int_a^b g, error estimate)
        integral(y)              (int_a^y g, error estimate), y in [a, b]; arrays elementwise
        density(y)               (g(y), error estimate), y in (a, b) off the steps; an array y
                                 uses the batch algorithm (one interpolant per call)
        orthogonality_defect     nu = -1: (normalised defect, estimate): ~0 iff the bounded
                                 solution exists
        index, leading, trailing, status ("converged", "orthogonality_not_satisfied",
                                 "not_converged"), homogeneous(y), homogeneous_constant

    Measured accuracy (header): int g and int_a^y g to a few eps relative to int g for smooth F;
    g(y) to <= 50 eps for y >= 0.14 L from both ends (alpha <= 0.6), worse towards the ends.
    Raises ValueError for parameters outside their ranges, y outside the domain, a callable
    returning NaN or an infinity (naming it), a tolerance not finite and > 0, or order or
    len(steps) above 1024. Releases the
    GIL while computing (re-acquired for each call of a Python callable).
    """
    return _riemann.solve_abel_rh(alpha, beta, a, b, data, leading, trailing, steps=list(steps), order=order,
                                  load=load, tolerance=tolerance)
