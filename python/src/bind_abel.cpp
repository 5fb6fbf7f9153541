// python/src/bind_abel.cpp: the spectral solver of the generalized Abel equation (rhabel::abel,
// double precision): _rhabel.abel.solve, JacobiDensity, AbelSolution. Docstrings of the public
// names: python/rhabel/abel.py.
#include "bindings.hpp"

#include <rhabel/abel/abel_solver.hpp>

#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace rhabel::python {
namespace {

using density = abel::jacobi_density<double>;
using solution = abel::abel_solution<double>;

abel::edge edge_from(const std::string& name, const char* parameter) {
  if (name == "bounded") return abel::edge::bounded;
  if (name == "unbounded") return abel::edge::unbounded;
  throw py::value_error(std::string("rhabel.abel.solve: ") + parameter + " = '" + name +
                        "' is not a valid edge class (valid: 'bounded', 'unbounded')");
}

const char* status_name(abel::solve_status s) {
  return s == abel::solve_status::converged ? "converged" : "not_converged";
}

solution solve(double alpha, double beta, double lo, double hi, const std::string& leading,
               const std::string& trailing, const py::object& data, std::optional<std::vector<double>> breakpoints,
               std::size_t degree, std::size_t max_degree, double tolerance, std::size_t residual_points,
               std::optional<double> load, std::size_t piecewise_degree) {
  const abel::edge lead = edge_from(leading, "leading"), trail = edge_from(trailing, "trailing");
  constexpr const char* fn = "rhabel.abel.solve";
  check_size(fn, "degree", degree, max_expansion_degree, "O(n^2) conversions");
  check_size(fn, "max_degree", max_degree, max_expansion_degree, "O(n^2) conversions");
  check_size(fn, "piecewise_degree", piecewise_degree, max_expansion_degree, "O(n^2) per piece");
  check_size(fn, "residual_points", residual_points, max_residual_points, "a quadrature each");
  if (!(tolerance >= 0) || !std::isfinite(tolerance)) {
    throw py::value_error("rhabel.abel.solve: tolerance = " + std::string(py::repr(py::float_(tolerance))) +
                          " must be finite and >= 0 (relative Chebyshev tail)");
  }
  if (load) check_finite(fn, "load", *load);
  if (breakpoints) {
    check_size(fn, "len(breakpoints)", breakpoints->size(), max_breakpoints, "a panel each");
    for (const double b : *breakpoints) check_finite(fn, "a breakpoint", b);
  }
  abel::solve_options<double> options;
  options.degree = degree;
  options.max_degree = max_degree;
  options.tolerance = tolerance;
  options.residual_points = residual_points;
  options.load = load;
  options.piecewise_degree = piecewise_degree;
  const bool callable = PyCallable_Check(data.ptr()) != 0;
  std::function<double(double)> f;
  std::vector<double> coefficients;
  if (callable) {
    f = python_function(py::reinterpret_borrow<py::function>(data), "rhabel.abel.solve: data(s)");
  } else {
    try {
      coefficients = data.cast<std::vector<double>>();
    } catch (const py::cast_error&) {
      throw py::type_error(
          "rhabel.abel.solve: data must be a callable F(s) or a sequence of monomial coefficients of F");
    }
    if (breakpoints) throw py::value_error("rhabel.abel.solve: breakpoints need data given as a callable");
    check_size(fn, "len(data)", coefficients.size(), max_expansion_degree, "polynomial coefficients");
    for (const double c : coefficients) check_finite(fn, "a coefficient of data", c);
  }
  py::gil_scoped_release nogil;  // python_function takes the GIL back for each call of data
  const abel::abel_operator<double> op(alpha, beta, lo, hi);
  try {
    if (!callable) return abel::solve_polynomial(op, lead, trail, coefficients, options);
    if (breakpoints) return abel::solve_piecewise(op, lead, trail, f, *breakpoints, options);
    return abel::solve(op, lead, trail, f, options);
  } catch (const std::overflow_error& e) {  // data near the double range: bad input, named
    throw py::value_error(std::string("rhabel.abel.solve: data takes values beyond the double range on [lo, hi] (") +
                          e.what() + ")");
  }
}

}  // namespace

void bind_abel(py::module_& m) {
  py::class_<density>(m, "JacobiDensity",
                      "g(t) = (1 - x)^del (1 + x)^gam sum_n c_n P_n^(del,gam)(x) on [lo, hi], "
                      "x = (2t - lo - hi)/(hi - lo) (rhabel::abel::jacobi_density).")
      .def_readonly("lo", &density::lo, "left end (the leading edge a)")
      .def_readonly("hi", &density::hi, "right end (the trailing edge b)")
      .def_readonly("gam", &density::gam, "exponent at lo: g ~ (t - lo)^gam")
      .def_readonly("del_", &density::del, "exponent at hi: g ~ (hi - t)^del")
      .def_property_readonly(
          "coefficients", [](const density& d) { return to_numpy(std::vector<double>(d.coefficients)); },
          "c_n, the coefficients in P_n^(del,gam) (a copy)")
      .def(
          "__call__", [](const density& d, const double_array& t) { return map_array(t, [&d](double s) { return d(s); }); },
          py::arg("t"), "g(t), elementwise (0 outside [lo, hi]; +-inf at an end where the exponent is negative).")
      .def(
          "series", [](const density& d, const double_array& x) { return map_array(x, [&d](double y) { return d.series(y); }); },
          py::arg("x"), "S(x) = sum_n c_n P_n^(del,gam)(x), the smooth factor in the reference variable x in [-1, 1].")
      .def("integral", &density::integral, "int_lo^hi g(t) dt (exact for the series).")
      .def(
          "integral_to",
          [](const density& d, const double_array& t) {
            for (py::ssize_t i = 0; i < t.size(); ++i) check_finite("JacobiDensity.integral_to", "t", t.data()[i]);
            return map_array(t, [&d](double s) { return d.integral_to(s); });
          },
          py::arg("t"), "int_lo^t g, elementwise (exact for the series: incomplete beta + Rodrigues form).")
      .def(
          "moment",
          [](const density& d, std::size_t k) {
            check_size("JacobiDensity.moment", "k", k, max_moment_order, "t^k overflows a double long before");
            return d.moment(k);
          },
          py::arg("k"), "int_lo^hi t^k g(t) dt (Gauss-Jacobi, exact for the series).")
      .def("intensity_leading", &density::intensity_leading, "K_a = lim_{t->lo+} g(t) (t - lo)^(-gam).")
      .def("intensity_trailing", &density::intensity_trailing, "K_b = lim_{t->hi-} g(t) (hi - t)^(-del).")
      .def("__repr__", [](const density& d) {
        return "JacobiDensity(lo=" + std::string(py::repr(py::float_(d.lo))) + ", hi=" +
               std::string(py::repr(py::float_(d.hi))) + ", gam=" + std::string(py::repr(py::float_(d.gam))) +
               ", del_=" + std::string(py::repr(py::float_(d.del))) + ", terms=" + std::to_string(d.coefficients.size()) +
               ")";
      });

  py::class_<solution>(m, "AbelSolution", "Solution of A g = F and its evidence (rhabel::abel::abel_solution).")
      .def_readonly("density", &solution::density, "g, a JacobiDensity")
      .def_property_readonly(
          "exponents",
          [](const solution& s) { return py::make_tuple(s.exponents.gam, s.exponents.del, s.exponents.nu); },
          "(gam, del, nu): edge exponents and index of the class")
      .def_readonly("solvability_defect", &solution::solvability_defect,
                    "nu = -1: image-P_0 coefficient of (L/2)^(-alpha) F (0 iff F satisfies the orthogonality condition)")
      .def_property_readonly(
          "homogeneous",
          [](const solution& s) -> py::object {
            if (s.homogeneous.coefficients.empty()) return py::none();
            return py::cast(s.homogeneous);
          },
          "nu = +1: the unit-integral homogeneous solution (a JacobiDensity); None otherwise")
      .def_readonly("residual", &solution::residual,
                    "independent relative residual of A g = F at interior points (NaN if not computed); an estimate")
      .def_readonly("coefficient_tail", &solution::coefficient_tail,
                    "relative size of the discarded Chebyshev tail: an estimate of the relative error")
      .def_readonly("degree", &solution::degree, "number of image coefficients used")
      .def_property_readonly(
          "status", [](const solution& s) { return status_name(s.status); }, "'converged' or 'not_converged'")
      .def(
          "with_load",
          [](const solution& s, double load) { return s.with_load(check_finite("AbelSolution.with_load", "load", load)); },
          py::arg("load"),
           "nu = +1 only: the solution with int g = load (a JacobiDensity).")
      .def("__repr__", [](const solution& s) {
        return "AbelSolution(status='" + std::string(status_name(s.status)) + "', degree=" + std::to_string(s.degree) +
               ", nu=" + std::to_string(s.exponents.nu) + ", residual=" + std::string(py::repr(py::float_(s.residual))) +
               ")";
      });

  m.def("solve", &solve, py::arg("alpha"), py::arg("beta"), py::arg("lo"), py::arg("hi"), py::arg("leading"),
        py::arg("trailing"), py::arg("data"), py::kw_only(), py::arg("breakpoints") = py::none(),
        py::arg("degree") = 0, py::arg("max_degree") = 1024,
        py::arg("tolerance") = 16 * std::numeric_limits<double>::epsilon(), py::arg("residual_points") = 8,
        py::arg("load") = py::none(), py::arg("piecewise_degree") = 256,
        "Compiled part of rhabel.abel.solve (see there).");
}

}  // namespace rhabel::python
