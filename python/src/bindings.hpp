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

#include <rhabel/punch/contact.hpp>

#include <chrono>
#include <cmath>
#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace rhabel::python {

namespace py = pybind11;

void bind_punch(py::module_& m);
void bind_quadrature(py::module_& m);
void bind_abel(py::module_& m);
void bind_riemann(py::module_& m);
void bind_scene(py::module_& m);

// ---- limits on sizes given from Python ------------------------------------------------------
// Checked before anything is allocated or computed, so that a wrong size (10**9) is a ValueError
// naming the argument and its limit at once, not minutes of work or a MemoryError after gigabytes.
// Each is far above what an accurate double-precision result needs.

/// Gauss-Jacobi nodes (gauss_jacobi n), the degree of jacobi_p: 10^6 nodes are 32 MB and under a
/// second (the rules are O(n)); no double-precision rule needs more.
inline constexpr std::size_t max_quadrature_nodes = 1'000'000;
/// Image coefficients of rhabel.abel.solve (degree, max_degree, piecewise_degree, the number of
/// polynomial coefficients): the conversions are O(n^2) (16384: about a second); smooth data
/// converges below 1000, and piecewise data only algebraically, so more buys little.
inline constexpr std::size_t max_expansion_degree = 16384;
/// Points of the independent residual (each an adaptive quadrature of A g): 8 by default.
inline constexpr std::size_t max_residual_points = 1024;
/// Breakpoints of piecewise data (each adds a panel of piecewise_degree / 2 + 24 nodes).
inline constexpr std::size_t max_breakpoints = 1024;
/// JacobiDensity.moment(k): t^k of a double overflows long before (|t| > 1.0001 at k = 10^7).
inline constexpr std::size_t max_moment_order = 100'000;
/// Gauss nodes per panel of rhabel.riemann.solve_abel_rh (default 26; the error is at rounding
/// level from 40).
inline constexpr std::size_t max_panel_order = 1024;

/// ValueError "<function>: <name> = <value> is above the limit of <limit> (<why>)" unless
/// value <= limit.
inline void check_size(const char* function, const char* name, std::size_t value, std::size_t limit,
                       const char* why) {
  if (value > limit) {
    throw py::value_error(std::string(function) + ": " + name + " = " + std::to_string(value) +
                          " is above the limit of " + std::to_string(limit) + " (" + why + ")");
  }
}

/// ValueError "<function>: <name> = <value> must be a finite number" unless x is finite.
inline double check_finite(const char* function, const char* name, double x) {
  if (!std::isfinite(x)) {
    throw py::value_error(std::string(function) + ": " + name + " = " + std::string(py::repr(py::float_(x))) +
                          " must be a finite number");
  }
  return x;
}

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
/// real number, and in the ValueError raised when it returns NaN or an infinity.
inline std::function<double(double)> python_function(const py::function& f, std::string what) {
  std::shared_ptr<py::function> held(new py::function(f), [](py::function* p) {
    py::gil_scoped_acquire gil;
    delete p;
  });
  return [held, what = std::move(what)](double x) -> double {
    py::gil_scoped_acquire gil;
    py::object value = (*held)(x);
    double v = 0;
    try {
      v = value.cast<double>();
    } catch (const py::cast_error&) {
      throw py::type_error(what + " must return a real number, got " +
                           std::string(py::str(py::type::of(value).attr("__name__"))));
    }
    // A NaN or an infinity would pass through the solver's arithmetic (a NaN density reported as
    // converged): refused where it appears, naming the callable and the point.
    if (!std::isfinite(v)) {
      throw py::value_error(what + " returned " + std::string(py::repr(value)) + " at s = " +
                            std::string(py::repr(py::float_(x))) + ": it must return finite numbers");
    }
    return v;
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

// ---- Ctrl-C ---------------------------------------------------------------------------------
/// Ctrl-C during a solve (punch::solve_options::interrupt). The solve runs without the GIL, so
/// Python's SIGINT handler cannot run until it returns; this polls the handlers
/// (PyErr_CheckSignals, the GIL taken back for the call) from the calling thread, at most every
/// 50 ms. Once the handler has raised (KeyboardInterrupt, or whatever a user's handler raises),
/// the solve stops at its next time-limit check (punch::interrupted) and `run` raises that
/// exception instead. Other threads of the solve never poll (Python runs signal
/// handlers in the main thread only), so only the calling thread touches the state.
class ctrl_c {
 public:
  ctrl_c() : state_(std::make_shared<state>()) { state_->thread = std::this_thread::get_id(); }

  std::function<bool()> poll() const {
    return [s = state_] {
      if (std::this_thread::get_id() != s->thread) return false;
      const auto now = std::chrono::steady_clock::now();
      if (now - s->last < std::chrono::milliseconds(50)) return false;
      s->last = now;
      py::gil_scoped_acquire gil;
      if (PyErr_CheckSignals() == 0) return false;
      s->fired = true;  // the handler's exception is now Python's error indicator
      return true;
    };
  }

  /// solve() without the GIL (threads may solve other scenes meanwhile); the handler's exception
  /// in place of punch::interrupted.
  template <class Solve>
  auto run(Solve&& solve) const {
    try {
      py::gil_scoped_release nogil;
      return solve();
    } catch (const punch::interrupted&) {
      if (state_->fired) throw py::error_already_set();  // the GIL is held again here
      throw;
    }
  }

 private:
  struct state {
    std::thread::id thread;
    std::chrono::steady_clock::time_point last{};
    bool fired = false;
  };
  std::shared_ptr<state> state_;
};

/// solve() (which reads `options`) with options.interrupt polling Ctrl-C (ctrl_c::run).
template <class Options, class Solve>
auto run_interruptible(Options& options, Solve&& solve) {
  const ctrl_c interrupt;
  options.interrupt = interrupt.poll();
  return interrupt.run(std::forward<Solve>(solve));
}

}  // namespace rhabel::python
