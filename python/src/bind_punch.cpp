// python/src/bind_punch.cpp: the compiled part of rhabel.solve and rhabel.trial_interval,
// _rhabel._solve(scene, ...) and _rhabel._trial_interval(scene, a, b, tolerance).
//
// The scene arrives already validated by python/rhabel/_scene.py (the schema of
// examples/README.md: every required field present, no unknown field, numbers in range) and is
// mapped to rhabel::punch::scene here; the result goes back as nested Records (dicts with
// attribute access, python/rhabel/_record.py) whose keys are those of the command line's JSON
// result (scene/src/solve.cpp). The conversion of a contact's result is written once, in
// add_contact: a new field of punch's indentor_result is added there and nowhere else.
#include "bindings.hpp"

#include <rhabel/punch/contact.hpp>
#include <rhabel/punch/profile.hpp>
#include <rhabel/punch/profile_bem.hpp>

#include <cmath>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace rhabel::python {
namespace {

double number(const py::handle& object, const char* key) { return object[key].cast<double>(); }

punch::material to_material(const py::dict& material) {
  punch::material m;
  m.alpha = number(material, "alpha");
  m.E1 = number(material, "E1");
  m.poisson = number(material, "nu");
  m.coulomb = number(material, "coulomb");
  return m;
}

punch::indentor to_indentor(const py::dict& d) {
  punch::indentor ind;
  if (d.contains("load")) ind.load = number(d, "load");
  if (d.contains("height")) ind.height = number(d, "height");
  ind.apex = number(d, "apex");
  const auto shape = d["shape"].cast<std::string>();
  if (shape == "parabolic") {
    ind.shape = punch::parabolic{number(d, "radius")};
  } else if (shape == "wedge") {
    ind.shape = punch::wedge{number(d, "slope_leading"), number(d, "slope_trailing")};
  } else if (shape == "flat") {
    ind.shape = punch::flat{number(d, "width")};
  } else {
    throw py::value_error("rhabel: unknown shape '" + shape + "' (the scene was not validated)");
  }
  return ind;
}

punch::scene to_scene(const py::dict& spec) {
  punch::scene s;
  s.material = to_material(spec["material"]);
  s.speed = number(spec, "speed");
  if (spec.contains("body")) s.body = punch::rigid_body{number(spec["body"], "load")};
  for (const py::handle item : spec["indentors"].cast<py::list>()) {
    s.indentors.push_back(to_indentor(py::reinterpret_borrow<py::dict>(item)));
  }
  return s;
}

const char* side_name(punch::edge_side side) { return side == punch::edge_side::leading ? "leading" : "trailing"; }

/// An empty rhabel._record.Record (a dict subclass with attribute access): the result is built
/// from Records directly, no second pass in Python.
py::dict record() {
  static const py::object* type = nullptr;  // the GIL serialises the first call
  if (type == nullptr) type = new py::object(py::module_::import("rhabel._record").attr("Record"));
  return (*type)();
}

/// One contact's result into `out`, keys as in the JSON result (examples/README.md).
void add_contact(py::dict& out, punch::indentor_result&& r) {
  out["contact"] = py::make_tuple(r.a, r.b);
  out["contact_length"] = r.contact_length;
  if (r.epsilon) out["epsilon"] = *r.epsilon;
  out["load"] = r.load;
  if (!std::isnan(r.approach)) out["approach"] = r.approach;
  out["hysteretic_friction"] = r.hysteretic_friction;
  out["total_friction"] = r.total_friction;
  // As the command line: an unbounded pressure is None with peak_pressure_singular = True.
  const bool singular = std::isinf(r.peak_pressure) && r.peak_pressure > 0;
  out["peak_pressure"] = singular ? py::object(py::none()) : py::object(py::float_(r.peak_pressure));
  out["peak_pressure_singular"] = singular;
  out["peak_pressure_at"] = r.peak_pressure_at;
  py::list edges;
  for (const auto& e : r.edges) {
    py::dict edge = record();
    edge["side"] = side_name(e.side);
    edge["at"] = e.position;
    edge["singular"] = e.singular;
    edge["exponent"] = e.exponent;
    edge["intensity_factor"] = e.intensity_factor;
    edges.append(std::move(edge));
  }
  out["edges"] = std::move(edges);
  out["residual"] = r.residual;
  out["error_estimate"] = r.error_estimate;
  out["degree"] = r.degree;
  out["status"] = punch::to_string(r.code);
  out["status_message"] = r.status;
  if (!r.grid_x.empty()) {
    py::dict pressure = record();
    pressure["x"] = to_numpy(std::move(r.grid_x));
    pressure["p"] = to_numpy(std::move(r.pressure));
    out["pressure"] = std::move(pressure);
  }
  if (!r.displacement_x.empty()) {
    py::dict displacement = record();
    displacement["x"] = to_numpy(std::move(r.displacement_x));
    displacement["w"] = to_numpy(std::move(r.displacement));
    out["displacement"] = std::move(displacement);
  }
}

/// One indentor's result; shape and name are the scene's (`spec`: the validated indentor dict).
py::dict to_python(punch::indentor_result&& r, const py::dict& spec) {
  py::dict out = record();
  out["shape"] = spec["shape"];
  if (spec.contains("name")) out["name"] = spec["name"];
  add_contact(out, std::move(r));
  return out;
}

/// The head of a result document: the material's friction parameter, kappa, regime and E_U.
template <class Result>
py::dict result_head(const Result& r, double effective_modulus) {
  py::dict out = record();
  out["beta"] = r.beta;
  out["kappa"] = r.kappa;
  out["regime"] = r.regime;
  out["effective_modulus"] = effective_modulus;
  return out;
}

/// The whole result, keys as in the JSON result (without "scene", added in Python).
py::dict to_python(punch::scene_result&& r, const py::dict& spec, double effective_modulus) {
  py::dict out = result_head(r, effective_modulus);
  if (r.body_approach) out["body_approach"] = *r.body_approach;
  py::list indentors;
  const auto specs = spec["indentors"].cast<py::list>();
  for (std::size_t i = 0; i < r.indentors.size(); ++i) {
    indentors.append(to_python(std::move(r.indentors[i]), specs[i].cast<py::dict>()));
  }
  out["indentors"] = std::move(indentors);
  py::dict diagnostics = record();
  diagnostics["residual"] = r.diagnostics.residual;
  diagnostics["seconds"] = r.diagnostics.seconds;
  diagnostics["status"] = punch::to_string(r.diagnostics.code);
  diagnostics["status_message"] = r.diagnostics.status;
  diagnostics["iterations"] = r.diagnostics.iterations;
  out["diagnostics"] = std::move(diagnostics);
  return out;
}

punch::solve_options make_options(std::size_t grid, bool displacement, double tolerance, bool residual,
                                  double acceptance, std::size_t threads, double time_limit, double layered_below) {
  punch::solve_options options;
  options.grid_points = grid;
  options.displacement = displacement;
  options.tolerance = tolerance;
  options.residual = residual;
  options.acceptance = acceptance;
  options.threads = threads;
  options.time_limit = time_limit;
  options.layered_below = layered_below;
  return options;
}

py::dict solve(const py::dict& spec, std::size_t grid, bool displacement, double tolerance, bool residual,
               double acceptance, std::size_t threads, double time_limit, double layered_below) {
  const punch::scene s = to_scene(spec);
  punch::solve_options options =
      make_options(grid, displacement, tolerance, residual, acceptance, threads, time_limit, layered_below);
  punch::scene_result result = run_interruptible(options, [&] { return punch::solve(s, options); });
  return to_python(std::move(result), spec, s.material.effective_modulus(s.speed));
}

/// The punch scene of a validated scene dict with a "profile".
punch::profile_scene profile_scene_of(const py::dict& spec) {
  punch::profile_scene ps;
  ps.material = to_material(spec["material"]);
  ps.speed = number(spec, "speed");
  ps.load = number(spec["body"], "load");
  const py::dict profile = spec["profile"];
  ps.profile.x = profile["x"].cast<std::vector<double>>();
  ps.profile.z = profile["z"].cast<std::vector<double>>();
  ps.profile.corners = profile["corners"].cast<std::vector<double>>();
  if (profile.contains("period")) ps.profile.period = profile["period"].cast<double>();
  return ps;
}

/// punch::solve_profile for a validated scene with a "profile"; keys as in the JSON result.
py::dict solve_profile(const py::dict& spec, std::size_t grid, bool displacement, double tolerance, bool residual,
                       double acceptance, std::size_t threads, double time_limit, double layered_below) {
  const punch::profile_scene ps = profile_scene_of(spec);
  punch::solve_options options =
      make_options(grid, displacement, tolerance, residual, acceptance, threads, time_limit, layered_below);
  punch::profile_result r = run_interruptible(options, [&] { return punch::solve_profile(ps, options); });
  py::dict out = result_head(r, ps.material.effective_modulus(ps.speed));
  if (!std::isnan(r.body_approach)) out["body_approach"] = r.body_approach;
  py::list contacts;
  for (std::size_t i = 0; i < r.contacts.size(); ++i) {
    py::dict item = record();
    item["tip"] = r.tips[i];
    add_contact(item, std::move(r.contacts[i]));
    contacts.append(std::move(item));
  }
  out["contacts"] = std::move(contacts);
  if (!std::isnan(r.clearance)) {
    py::dict clearance = record();
    clearance["min"] = r.clearance;
    clearance["at"] = r.clearance_at;
    out["clearance"] = std::move(clearance);
  }
  out["penetrations"] = py::cast(r.penetrations);
  py::dict diagnostics = record();
  diagnostics["residual"] = r.diagnostics.residual;
  diagnostics["seconds"] = r.diagnostics.seconds;
  diagnostics["rounds"] = r.diagnostics.rounds;
  diagnostics["iterations"] = r.diagnostics.iterations;
  diagnostics["status"] = punch::to_string(r.diagnostics.code);
  diagnostics["status_message"] = r.diagnostics.status;
  diagnostics["load_fraction"] = r.diagnostics.load_fraction;
  out["diagnostics"] = std::move(diagnostics);
  return out;
}

/// A value with its error estimate: Record {value, error}, as in the JSON result.
py::dict estimate_record(const punch::bem_estimate& e) {
  py::dict out = record();
  out["value"] = e.value;
  out["error"] = e.error;
  return out;
}

/// punch::solve_profile_bem for a validated scene with a "profile" and profile.solver
/// "boundary_element"; keys as in the JSON result.
py::dict solve_profile_bem(const py::dict& spec, double acceptance, double time_limit) {
  const punch::profile_scene ps = profile_scene_of(spec);
  punch::solve_options options;
  options.acceptance = acceptance;
  options.time_limit = time_limit;
  punch::bem_options bem;
  if (const py::dict profile = spec["profile"]; profile.contains("max_panels"))
    bem.max_panels = profile["max_panels"].cast<std::size_t>();
  const punch::profile_bem_result r =
      run_interruptible(options, [&] { return punch::solve_profile_bem(ps, options, bem); });
  py::dict out = result_head(r, ps.material.effective_modulus(ps.speed));
  py::list patches;
  for (const auto& p : r.patches) {
    py::dict item = record();
    item["contact"] = py::make_tuple(p.a, p.b);
    item["edge_error"] = p.edge_error;
    item["load"] = estimate_record(p.load);
    item["hysteretic_friction"] = estimate_record(p.hysteretic_friction);
    item["peak_pressure"] = p.peak_pressure;
    item["pressure_width"] = p.pressure_width;
    patches.append(std::move(item));
  }
  out["patches"] = std::move(patches);
  out["hysteretic_friction"] = estimate_record(r.hysteretic_friction);
  out["total_friction"] = r.total_friction;
  out["mean_pressure"] = r.mean_pressure;
  out["contact_fraction"] = estimate_record(r.contact_fraction);
  py::dict diagnostics = record();
  diagnostics["seconds"] = r.diagnostics.seconds;
  diagnostics["panels"] = r.diagnostics.panels;
  diagnostics["active_set_steps"] = r.diagnostics.active_set_steps;
  diagnostics["level_panels"] = py::cast(r.diagnostics.level_panels);
  diagnostics["level_patches"] = py::cast(r.diagnostics.level_patches);
  diagnostics["level_friction"] = py::cast(r.diagnostics.level_friction);
  diagnostics["status"] = punch::to_string(r.diagnostics.code);
  diagnostics["status_message"] = r.diagnostics.status;
  out["diagnostics"] = std::move(diagnostics);
  return out;
}

/// punch::trial_interval for the scene's single indentor on [a, b]; a Record {load,
/// hysteretic_friction, error_estimate}.
py::dict trial_interval(const py::dict& spec, double a, double b, double tolerance) {
  const punch::scene s = to_scene(spec);
  punch::solve_options options;
  options.tolerance = tolerance;
  punch::trial_result result;
  {
    py::gil_scoped_release nogil;
    result = punch::trial_interval(s.material, s.speed, s.indentors.front(), a, b, options);
  }
  py::dict out = record();
  out["load"] = result.load;
  out["hysteretic_friction"] = result.hysteretic_friction;
  out["error_estimate"] = result.error_estimate;
  return out;
}

}  // namespace

void bind_punch(py::module_& m) {
  m.def("_solve", &solve, py::arg("scene"), py::arg("grid"), py::arg("displacement"), py::arg("tolerance"),
        py::arg("residual"), py::arg("acceptance"), py::arg("threads"), py::arg("time_limit"), py::arg("layered_below"),
        "Solves a VALIDATED scene dict (rhabel.solve validates first). Returns nested Records.");
  m.def("_solve_profile", &solve_profile, py::arg("scene"), py::arg("grid"), py::arg("displacement"),
        py::arg("tolerance"), py::arg("residual"), py::arg("acceptance"), py::arg("threads"), py::arg("time_limit"),
        py::arg("layered_below"), "Solves a VALIDATED scene dict with a sampled profile (rhabel.solve validates first).");
  m.def("_solve_profile_bem", &solve_profile_bem, py::arg("scene"), py::arg("acceptance"), py::arg("time_limit"),
        "Solves a VALIDATED scene dict with a sampled profile by the boundary-element method (rhabel.solve "
        "validates first).");
  m.def("_trial_interval", &trial_interval, py::arg("scene"), py::arg("a"), py::arg("b"), py::arg("tolerance"),
        "punch::trial_interval for a VALIDATED one-indentor scene dict (rhabel.trial_interval validates "
        "first). Returns a Record {load, hysteretic_friction, error_estimate}.");
}

}  // namespace rhabel::python
