// python/src/bind_scene.cpp: the scene layer (rhabel/scene.hpp) for the Python package:
// _rhabel._fit_scene_material(text, tolerance, acceptance, time_limit), the master-curve fixed
// point of a scene given as JSON text, by the same code as `rhabel solve` (the command line then
// solves the scene with the fitted power law, and so does rhabel.solve).
#include "bindings.hpp"

#include <rhabel/scene.hpp>

#include <string>

namespace rhabel::python {
namespace {

py::dict fit_scene_material(const std::string& text, double tolerance, double acceptance, double time_limit) {
  scene::scene_spec spec;
  try {
    // A relative master_curve is relative to the working directory (rhabel.load_scene makes it
    // absolute against the scene file's directory, as the command line does).
    spec = scene::parse_scene(text, "scene", "");
  } catch (const scene::input_error& e) {
    throw py::value_error(e.what());
  }
  scene::run_request request;
  request.tolerance = tolerance;
  request.acceptance = acceptance;
  request.time_limit = time_limit;
  scene::material_fit_report report;
  try {
    report = run_interruptible(request, [&] { return scene::fit_scene_material(spec, request); });
  } catch (const scene::input_error& e) {
    throw py::value_error(e.what());
  }
  const auto& curve = *spec.material.curve;
  py::dict out;
  out["master_curve"] = curve.path;
  if (curve.shifted) {
    out["temperature"] = curve.temperature;
    out["log10_aT"] = *report.log10_aT;
  }
  out["alpha"] = report.fit.alpha;
  out["E1"] = report.fit.E1;
  out["omega0"] = report.fit.omega0;
  out["alpha_slope"] = report.fit.alpha_slope;
  out["alpha_tan_delta"] = report.fit.alpha_tan_delta;
  out["modulus"] = report.fit.modulus;
  out["window"] = py::make_tuple(report.fit.window_lo, report.fit.window_hi);
  out["contact_length"] = report.contact_length;
  out["iterations"] = report.iterations;
  out["status"] = report.status;
  out["warning"] = report.warning;
  return out;
}

}  // namespace

void bind_scene(py::module_& m) {
  m.def("_fit_scene_material", &fit_scene_material, py::arg("text"), py::arg("tolerance"), py::arg("acceptance"),
        py::arg("time_limit"));
}

}  // namespace rhabel::python
