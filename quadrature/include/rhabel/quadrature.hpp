// rhabel/quadrature.hpp: umbrella header of the quadrature module (rhabel::quadrature).
// Gauss-Jacobi rules, Jacobi polynomials, and Cauchy and Abel product rules for
// Jacobi-weighted densities.
#pragma once

#include "rhabel/quadrature/jacobi_polynomial.hpp"
#include "rhabel/quadrature/gauss_jacobi.hpp"
#include "rhabel/quadrature/detail/jacobi_projection.hpp"  // jacobi_coefficients (public)
#include "rhabel/quadrature/cauchy_transform.hpp"
#include "rhabel/quadrature/abel_integral.hpp"
