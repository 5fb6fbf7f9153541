// python/src/bind_quadrature.cpp: Gauss-Jacobi rules and Jacobi polynomials (rhabel::quadrature,
// double precision). Docstrings of the public names: python/rhabel/__init__.py.
#include "bindings.hpp"

#include <rhabel/quadrature/gauss_jacobi.hpp>
#include <rhabel/quadrature/jacobi_polynomial.hpp>

#include <utility>

namespace rhabel::python {

void bind_quadrature(py::module_& m) {
  m.def(
      "gauss_jacobi",
      [](std::size_t n, double p, double q, double lo, double hi) {
        check_size("rhabel.gauss_jacobi", "n", n, max_quadrature_nodes, "32 bytes a node");
        quadrature::quadrature_rule<double> rule;
        {
          py::gil_scoped_release nogil;
          rule = (lo == -1 && hi == 1) ? quadrature::gauss_jacobi<double>(n, p, q)
                                       : quadrature::gauss_jacobi<double>(n, p, q, lo, hi);
        }
        return py::make_tuple(to_numpy(std::move(rule.x)), to_numpy(std::move(rule.hi_minus_x)),
                              to_numpy(std::move(rule.x_minus_lo)), to_numpy(std::move(rule.weight)));
      },
      py::arg("n"), py::arg("p"), py::arg("q"), py::arg("lo") = -1.0, py::arg("hi") = 1.0,
      "(x, hi_minus_x, x_minus_lo, weight) of the n-point Gauss-Jacobi rule (see rhabel.gauss_jacobi).");
  m.def(
      "jacobi_p",
      [](std::size_t n, double p, double q, const double_array& x) {
        check_size("rhabel.jacobi_p", "n", n, max_quadrature_nodes, "O(n) a point");
        return map_array(x, [n, p, q](double t) { return quadrature::jacobi_p<double>(n, p, q, t); });
      },
      py::arg("n"), py::arg("p"), py::arg("q"), py::arg("x"),
      "P_n^(p,q)(x), elementwise over x (see rhabel.jacobi_p).");
}

}  // namespace rhabel::python
