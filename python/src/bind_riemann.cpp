// python/src/bind_riemann.cpp: the Riemann-Hilbert route to the generalized Abel equation
// (rhabel::riemann, double precision): _rhabel.riemann.solve_abel_rh and RHSolution. Docstrings
// of the public names: python/rhabel/riemann.py.
#include "bindings.hpp"

#include <rhabel/riemann/abel_solver.hpp>

#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace rhabel::python {
namespace {

using solution = riemann::abel_rh_solution<double>;
using estimated = riemann::estimated<double>;

riemann::edge edge_from(const std::string& name, const char* parameter) {
  if (name == "bounded") return riemann::edge::bounded;
  if (name == "unbounded") return riemann::edge::unbounded;
  throw py::value_error(std::string("rhabel.riemann.solve_abel_rh: ") + parameter + " = '" + name +
                        "' is not a valid edge class (valid: 'bounded', 'unbounded')");
}

const char* edge_name(riemann::edge e) { return e == riemann::edge::bounded ? "bounded" : "unbounded"; }

const char* status_name(riemann::abel_status s) {
  switch (s) {
    case riemann::abel_status::converged: return "converged";
    case riemann::abel_status::orthogonality_not_satisfied: return "orthogonality_not_satisfied";
    case riemann::abel_status::not_converged: return "not_converged";
  }
  return "unknown";
}

py::tuple pair(const estimated& e) { return py::make_tuple(e.value, e.error_estimate); }

solution solve(double alpha, double beta, double a, double b, const py::object& data, const std::string& leading,
               const std::string& trailing, const std::vector<std::pair<double, double>>& steps, std::size_t order,
               std::optional<double> load, double tolerance) {
  const riemann::edge lead = edge_from(leading, "leading"), trail = edge_from(trailing, "trailing");
  constexpr const char* fn = "rhabel.riemann.solve_abel_rh";
  check_size(fn, "order", order, max_panel_order, "Gauss nodes per panel");
  check_size(fn, "len(steps)", steps.size(), max_breakpoints, "a panel each");
  if (!(tolerance > 0) || !std::isfinite(tolerance)) {
    throw py::value_error(std::string(fn) + ": tolerance = " + std::string(py::repr(py::float_(tolerance))) +
                          " must be finite and > 0");
  }
  if (load) check_finite(fn, "load", *load);
  riemann::piecewise_function<double> F;
  if (PyCallable_Check(data.ptr())) {
    F.smooth = python_function(py::reinterpret_borrow<py::function>(data), "rhabel.riemann.solve_abel_rh: data(s)");
  } else if (!data.is_none()) {
    try {
      auto coefficients = data.cast<std::vector<double>>();
      check_size(fn, "len(data)", coefficients.size(), max_expansion_degree, "polynomial coefficients");
      for (const double c : coefficients) check_finite(fn, "a coefficient of data", c);
      F.smooth = polynomial_function(std::move(coefficients));
    } catch (const py::cast_error&) {
      throw py::type_error(
          "rhabel.riemann.solve_abel_rh: data must be a callable F(s), a sequence of monomial coefficients of F, "
          "or None (steps only)");
    }
  }
  for (const auto& [position, size] : steps) {
    F.steps.push_back({check_finite(fn, "a step's position", position), check_finite(fn, "a step's size", size)});
  }
  riemann::abel_rh_options<double> options;
  options.order = order;
  options.load = load;
  options.tolerance = tolerance;
  py::gil_scoped_release nogil;  // python_function takes the GIL back for each call of data
  return riemann::solve_abel_rh(alpha, beta, a, b, std::move(F), lead, trail, options);
}

/// (value, error_estimate) of f(y) for a scalar y, or two arrays of y's shape for an array.
template <class F>
py::tuple estimates(const double_array& y, F&& f) {
  std::vector<py::ssize_t> shape(y.shape(), y.shape() + y.ndim());
  double_array values(shape), errors(shape);
  const auto n = static_cast<std::size_t>(y.size());
  const double* in = y.data();
  double* value = values.mutable_data();
  double* error = errors.mutable_data();
  {
    py::gil_scoped_release nogil;
    for (std::size_t i = 0; i < n; ++i) {
      const estimated e = f(in[i]);
      value[i] = e.value;
      error[i] = e.error_estimate;
    }
  }
  if (y.ndim() == 0) return py::make_tuple(value[0], error[0]);
  return py::make_tuple(values, errors);
}

}  // namespace

void bind_riemann(py::module_& m) {
  py::class_<solution>(m, "RHSolution",
                       "Solution of the generalized Abel equation by the Riemann-Hilbert route "
                       "(rhabel::riemann::abel_rh_solution). Every value comes with an error estimate.")
      .def_property_readonly("index", &solution::index, "nu in {-1, 0, +1}")
      .def_property_readonly("leading", [](const solution& s) { return edge_name(s.leading()); }, "class at a")
      .def_property_readonly("trailing", [](const solution& s) { return edge_name(s.trailing()); }, "class at b")
      .def_property_readonly(
          "status", [](const solution& s) { return status_name(s.status()); },
          "'converged', 'orthogonality_not_satisfied' (nu = -1, no bounded solution) or 'not_converged'")
      .def(
          "integral", [](const solution& s, const double_array& y) { return estimates(y, [&s](double t) { return s.integral(t); }); },
          py::arg("y"), "(int_a^y g, error estimate), elementwise for an array y in [a, b].")
      .def(
          "density",
          [](const solution& s, const double_array& y) -> py::tuple {
            if (y.ndim() == 0) return estimates(y, [&s](double t) { return s.density(t); });
            // Many points: one interpolant of A~ per order (abel_rh_solution::densities).
            std::vector<double> ys(y.data(), y.data() + y.size());
            std::vector<estimated> out;
            {
              py::gil_scoped_release nogil;
              out = s.densities(ys);
            }
            std::vector<py::ssize_t> shape(y.shape(), y.shape() + y.ndim());
            double_array values(shape), errors(shape);
            for (std::size_t i = 0; i < out.size(); ++i) {
              values.mutable_data()[i] = out[i].value;
              errors.mutable_data()[i] = out[i].error_estimate;
            }
            return py::make_tuple(values, errors);
          },
          py::arg("y"), "(g(y), error estimate) for y in (a, b) off the steps; arrays use the batch algorithm.")
      .def(
          "total",
          [](const solution& s) {
            estimated e{};
            {
              py::gil_scoped_release nogil;
              e = s.total();
            }
            return pair(e);
          },
          "(int_a^b g, error estimate).")
      .def_property_readonly(
          "orthogonality_defect", [](const solution& s) { return pair(s.orthogonality_defect()); },
          "nu = -1: (normalised orthogonality defect, error estimate); (0, 0) otherwise")
      .def(
          "homogeneous",
          [](const solution& s, const double_array& y) { return map_array(y, [&s](double t) { return s.homogeneous(t); }); },
          py::arg("y"), "nu = +1: g_h(y) = (y-a)^(-(1+2 alpha+beta)/2) (b-y)^((beta-1)/2), elementwise.")
      .def_property_readonly("homogeneous_constant", &solution::homogeneous_constant, "nu = +1: C in g = g_0 + C g_h")
      .def("__repr__", [](const solution& s) {
        return "RHSolution(index=" + std::to_string(s.index()) + ", status='" + status_name(s.status()) + "')";
      });

  m.def("solve_abel_rh", &solve, py::arg("alpha"), py::arg("beta"), py::arg("a"), py::arg("b"),
        py::arg("data") = py::none(), py::arg("leading") = "bounded", py::arg("trailing") = "bounded", py::kw_only(),
        py::arg("steps") = std::vector<std::pair<double, double>>{}, py::arg("order") = 0,
        py::arg("load") = py::none(), py::arg("tolerance") = 1000 * std::numeric_limits<double>::epsilon(),
        "Compiled part of rhabel.riemann.solve_abel_rh (see there).");
}

}  // namespace rhabel::python
