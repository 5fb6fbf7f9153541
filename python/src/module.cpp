// python/src/module.cpp: the extension module rhabel._rhabel. The public API is the Python
// package python/rhabel/ (it re-exports and documents what is bound here; python/README.md).
#include "bindings.hpp"

#include <rhabel/punch/contact.hpp>

PYBIND11_MODULE(_rhabel, m) {
  m.doc() = "Compiled core of the Python package rhabel (use `import rhabel`, not this module).";
  m.attr("__version__") = rhabel::punch::version();
  rhabel::python::bind_punch(m);
  rhabel::python::bind_quadrature(m);
  rhabel::python::bind_scene(m);
  auto abel = m.def_submodule("abel", "Generalized Abel equation: the spectral solver (rhabel::abel).");
  rhabel::python::bind_abel(abel);
  auto riemann = m.def_submodule("riemann", "Generalized Abel equation: the Riemann-Hilbert route (rhabel::riemann).");
  rhabel::python::bind_riemann(riemann);
}
