"""The generalized Abel equation on [lo, hi] = [a, b] and its spectral solver (rhabel::abel):

    F(s) = int_s^b g(t) (t - s)^(alpha-1) dt - kappa int_a^s g(t) (s - t)^(alpha-1) dt,
    kappa = cos((alpha + beta/2) pi) / cos(beta pi/2),

alpha in [0, 1) (alpha = 0: the Carleman operator PV int g/(t-s) dt + pi tan(beta pi/2) g(s)),
beta in (-1, 1). The solution is sought in an index class given by its behaviour at each edge,
g ~ (t - a)^gam at a and (b - t)^del at b:

    leading  "bounded":   gam = (1 - 2 alpha - beta)/2     "unbounded": gam = -(1 + 2 alpha + beta)/2
    trailing "bounded":   del = (1 + beta)/2               "unbounded": del = (beta - 1)/2

with index nu = -(gam + del + alpha): -1 (bounded at both ends: exists iff F satisfies one
orthogonality condition, reported as solvability_defect), 0, or +1 (unbounded at both: one free
constant, fixed by ``load`` = int g). "unbounded" at the leading edge needs 2 alpha + beta < 1.
Theory and measured accuracy: the header rhabel/abel/abel_solver.hpp of the C++ library.
"""

from ._rhabel import abel as _abel

JacobiDensity = _abel.JacobiDensity
AbelSolution = _abel.AbelSolution

__all__ = ["solve", "JacobiDensity", "AbelSolution"]


def solve(alpha, beta, lo, hi, leading, trailing, data, *, breakpoints=None, degree=0, max_degree=1024,
          tolerance=3.552713678800501e-15, residual_points=8, load=None, piecewise_degree=256):
    """Solve A g = F on [lo, hi] in the class (leading, trailing), each "bounded" or "unbounded".

    data
        * a callable F(s) -> float, F smooth on [lo, hi] (rhabel::abel::solve): F is
          interpolated at Chebyshev points, 17, 33, 65, ... until the last eighth of its
          Chebyshev coefficients is below ``tolerance`` x max|F| (or ``max_degree`` is reached:
          status "not_converged"); spectral accuracy (smooth data: <= 1e-14 from 12 points for
          alpha <= 0.5). With ``breakpoints`` (interior points where F jumps or kinks):
          rhabel::abel::solve_piecewise, ``piecewise_degree`` image coefficients by Gauss-Jacobi
          on each piece (exact for piecewise polynomials; needs gam + nu > -1).
          The callable is called from C++ (with the GIL); an exception it raises propagates.
        * a sequence of monomial coefficients [c0, c1, ...] of F(s) = sum c_k s^k
          (rhabel::abel::solve_polynomial: exact up to rounding, no Python call at all).

    degree (0: adaptive), max_degree, tolerance (relative Chebyshev tail, default 16 eps),
    residual_points (0: skip the independent residual), load (nu = +1: prescribe int g) and
    piecewise_degree are the fields of rhabel::abel::solve_options.

    Returns an AbelSolution:
        density             g, a JacobiDensity: callable (vectorised), integral(),
                            integral_to(t), moment(k), intensity_leading(), intensity_trailing()
                            (the edge intensity factors K = lim g / distance^exponent), lo, hi,
                            gam, del_, coefficients
        exponents           (gam, del, nu)
        solvability_defect  nu = -1: the image-P_0 coefficient of (L/2)^(-alpha) F (0 iff the
                            bounded solution exists; g then solves A g = F - (L/2)^alpha defect)
        homogeneous         nu = +1: unit-integral homogeneous solution; else None
        residual            max |A g - F| / max |F| at interior points, A g by direct quadrature
                            (independent of the spectral relation); an estimate; NaN if skipped
        coefficient_tail    relative size of the discarded tail: an error estimate
        degree, status      "converged" or "not_converged"
        with_load(load)     nu = +1: the density with int g = load

    status is "converged" only with a finite density and residual; with ``breakpoints`` only with
    a residual of at most 1e-2 (piecewise data converge algebraically in piecewise_degree).

    Raises ValueError for alpha outside [0, 1), beta outside (-1, 1), lo >= hi, a class that
    does not exist, a callable returning NaN or an infinity (naming it and the point), non-finite
    coefficients, tolerance or load, polynomial data beyond the double range, piecewise_degree 0,
    or a size above its limit (degree, max_degree, piecewise_degree and len(data) 16384,
    residual_points 1024, len(breakpoints) 1024), checked before any work. Releases the GIL while
    computing (re-acquired for each call of a Python callable).

    Example (alpha = beta = 0: PV int_{-1}^{1} g(t)/(t - s) dt = -pi s, g = sqrt(1 - t^2))::

        sol = rhabel.abel.solve(0, 0, -1, 1, "bounded", "bounded", [0.0, -math.pi])
        sol.density(0.5)   # 0.866...
    """
    return _abel.solve(alpha, beta, lo, hi, leading, trailing, data, breakpoints=breakpoints, degree=degree,
                       max_degree=max_degree, tolerance=tolerance, residual_points=residual_points, load=load,
                       piecewise_degree=piecewise_degree)
