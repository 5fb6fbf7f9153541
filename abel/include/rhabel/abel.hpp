// rhabel/abel.hpp: umbrella header of the abel module (rhabel::abel).
//
// The generalized Abel operator of the paper (eq. 8), its forward application and its solvers
// for every index class, on one interval or on a union of disjoint intervals. All templates on
// Real (tested in double and cpp_bin_float_50). Overview of the public API:
//
//   abel_parameters<Real>(alpha, beta) / ::from_kappa(alpha, kappa)       alpha in [0,1), beta in (-1,1)
//       .kappa(), .one_minus_kappa_over_alpha(), .exponents(edge leading, edge trailing) -> {gam, del, nu}
//   abel_operator<Real>(alpha, beta, lo, hi)   (or (parameters, lo, hi))
//       .apply(jacobi_density, s)            A g(s), any s (outside [lo,hi]: surface slope, paper 27-28)
//       .apply_by_quadrature(S, gam, del, s) independent direct quadrature of the one-sided integrals
//       .eigenvalue(n, exponents)            lambda_n of the spectral relation
//       .eigenvalues(N, exponents)           lambda_0 .. lambda_{N-1} in O(N)
//       ::quadrature_evaluator               cached version of apply_by_quadrature
//   jacobi_density<Real>{lo, hi, gam, del, coefficients}: g(t), integral(), integral_to(t), moment(k),
//       integrate(f, breakpoints), intensity_leading(), intensity_trailing(), series(x)
//   solve(op, leading, trailing, F, solve_options)            smooth F (adaptive Chebyshev)
//   solve_polynomial(op, leading, trailing, monomial coefficients)
//   solve_image_series(op, leading, trailing, image coefficients)
//   solve_piecewise(op, leading, trailing, F, breakpoints)    exact piecewise projection
//     -> abel_solution{density, exponents, solvability_defect, homogeneous, residual,
//                      coefficient_tail, degree, status, with_load(P)}
//   solve_step(op, leading, trailing, F, t0)                  jump at t0 with singular enrichment
//                                                             (Moebius map for an apex near an edge)
//     -> enriched_solution{density: enriched_density (g(t), value_at_distance, value_with_offset,
//                                   evaluator(), integral(), integral_to(t), integral_from(t),
//                                   integrate(f, bps), integrate_between, intensities, mobius),
//                          exponents, solvability_defect, residual, coefficient_tail, degree, status,
//                          taylor_degree, rounding_floor};  apply(op, g, s)
//   solve_kinks(op, leading, trailing, F, {kink{position, order, jump}, ...})
//                                                             F' or F'' jumping at given points (a
//                                                             cubic spline's knots), each built in
//     -> kinked_solution{smooth: abel_solution (series, evidence), terms: enriched_density each,
//                        rounding_floor; g(t), integral(), integral_to(t), intensities}
//   kink_enrichment(op, leading, trailing, kink)              one kink's term C phi (empty series)
//   solve_union(parameters, intervals, F per interval, multi_solve_options)   paper 41
//     -> multi_solution{densities, exponents, solvability_defects, homogeneous, homogeneous_defects,
//                       residual, condition, degree, status};  apply_union(parameters, densities, s)
//   solve_elementary_abel(alpha, side, lo, hi, F), elementary_abel_primitive(alpha, side, lo, hi, F, x)
// The building blocks that the punch layer uses as well (each header documents accuracy and range):
//   numerics.hpp        plain_jacobi_values, cached_gauss_jacobi_rule, chebyshev_grid,
//                       chebyshev_coefficients, panel_integrator
//   far_field.hpp       cross_kernel, far_field (interpolative far field of many intervals)
//   cross_nodes.hpp     cross_nodes, make_cross_nodes, separated_cross_nodes
//   union_memory.hpp    union_memory_bytes, union_degree_limit, union_far_memory_bytes,
//                       union_far_degree_limit
//   gmres.hpp           gmres (restarted, right preconditioned)
//   broyden_matrix.hpp  broyden_matrix (factorised Jacobian plus Broyden's updates)
//   step_enrichment.hpp split_integrator, enrichment_image_any
#pragma once

#include "rhabel/quadrature.hpp"
#include "rhabel/abel/abel_operator.hpp"
#include "rhabel/abel/abel_solver.hpp"
#include "rhabel/abel/multi_interval.hpp"
#include "rhabel/abel/elementary.hpp"
#include "rhabel/abel/step_enrichment.hpp"
#include "rhabel/abel/broyden_matrix.hpp"
#include "rhabel/abel/cross_nodes.hpp"
#include "rhabel/abel/far_field.hpp"
#include "rhabel/abel/gmres.hpp"
#include "rhabel/abel/numerics.hpp"
#include "rhabel/abel/union_memory.hpp"
