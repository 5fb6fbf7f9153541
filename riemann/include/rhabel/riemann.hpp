// rhabel/riemann.hpp: umbrella header of the riemann module (rhabel::riemann).
//
// The Riemann-Hilbert route, an independent second solver of the generalized Abel equation
// (independent of rhabel::abel by its method: Riemann problem + Cauchy integrals + Abel
// inversion; its Gauss-Jacobi rules are rhabel::quadrature::gauss_jacobi):
//   riemann/cauchy_integral.hpp  Cauchy integrals and principal values of Jacobi-weighted,
//                                piecewise smooth densities (product integration)
//   riemann/riemann_problem.hpp  Phi_+ = G Phi_- + g1 on a segment: canonical function, general
//                                solution of index -1, 0, +1, Plemelj limits, orthogonality defect
//   riemann/abel_solver.hpp      solve_abel_rh: the generalized Abel equation (paper eq. 8) for all
//                                index classes through the Riemann problem and Abel's inversion
#pragma once

#include "rhabel/quadrature.hpp"
#include "rhabel/riemann/abel_solver.hpp"
#include "rhabel/riemann/cauchy_integral.hpp"
#include "rhabel/riemann/riemann_problem.hpp"
