// python/src/bindings.hpp: shared pieces of the pybind11 extension rhabel._rhabel.
//
// Conventions of the bindings (python/README.md):
// - Library errors keep their C++ message and become Python exceptions through pybind11's
//   standard translation: std::invalid_argument, std::domain_error -> ValueError,
//   std::overflow_error -> OverflowError (tests/python/test_errors.py pins it).
// - Work in C++ runs without the GIL (py::gil_scoped_release after the inputs are converted).
//   A Python callable handed to a solver is wrapped by python_function: each call re-acquires
//   the GIL, and the reference to the callable is shared through a std::shared_ptr whose
//   deleter takes the GIL, so that the C++ side may copy the std::function freely without it.
// - Vectors go to NumPy without a per-element copy: the std::vector is moved to the heap and
//   owned by a capsule (to_numpy).
#pragma once

#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace rhabel::python {

namespace py = pybind11;

void bind_punch(py::module_& m);
void bind_quadrature(py::module_& m);
void bind_abel(py::module_& m);
void bind_riemann(py::module_& m);

/// A NumPy array that takes ownership of the vector's buffer (no element copy).
inline py::array_t<double> to_numpy(std::vector<double>&& values) {
  auto* owned = new std::vector<double>(std::move(values));
  py::capsule owner(owned, [](void* p) { delete static_cast<std::vector<double>*>(p); });
  return py::array_t<double>(static_cast<py::ssize_t>(owned->size()), owned->data(), owner);
}

/// A C-contiguous double array from any array-like (a copy only if the input is not one already).
using double_array = py::array_t<double, py::array::c_style | py::array::forcecast>;

/// out[i] = f(x[i]) for every element of x, with the GIL released; the result has x's shape and
/// is a Python float when x is a scalar (0-d).
template <class F>
py::object map_array(const double_array& x, F&& f) {
  double_array out(std::vector<py::ssize_t>(x.shape(), x.shape() + x.ndim()));
  const double* in = x.data();
  double* o = out.mutable_data();
  const auto n = static_cast<std::size_t>(x.size());
  {
    py::gil_scoped_release nogil;
    for (std::size_t i = 0; i < n; ++i) o[i] = f(in[i]);
  }
  if (x.ndim() == 0) return py::float_(o[0]);
  return out;
}

/// A Python callable float -> float usable from C++ without the GIL held (see the top).
/// `what` names the callable in the TypeError raised when it returns something that is not a
/// real number.
inline std::function<double(double)> python_function(const py::function& f, std::string what) {
  std::shared_ptr<py::function> held(new py::function(f), [](py::function* p) {
    py::gil_scoped_acquire gil;
    delete p;
  });
  return [held, what = std::move(what)](double x) -> double {
    py::gil_scoped_acquire gil;
    py::object value = (*held)(x);
    try {
      return value.cast<double>();
    } catch (const py::cast_error&) {
      throw py::type_error(what + " must return a real number, got " +
                           std::string(py::str(py::type::of(value).attr("__name__"))));
    }
  };
}

/// A polynomial sum_k c[k] s^k (monomial coefficients, Horner) as a callable: the data of a
/// solver without any Python call.
inline std::function<double(double)> polynomial_function(std::vector<double> c) {
  return [c = std::move(c)](double s) {
    double v = 0;
    for (std::size_t k = c.size(); k-- > 0;) v = v * s + c[k];
    return v;
  };
}

}  // namespace rhabel::python
