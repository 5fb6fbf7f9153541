// scene/src/material.cpp: see rhabel/scene/material.hpp.
#include "rhabel/scene/material.hpp"

#include "rhabel/scene/error.hpp"

#include <cmath>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <variant>

namespace rhabel::scene {
namespace {

using ordered_json = nlohmann::ordered_json;

std::mutex cache_mutex;
std::map<std::string, std::shared_ptr<const materials::master_curve>> cache;

std::shared_ptr<const materials::master_curve> read_cached(const std::string& path, const std::string& command) {
  std::lock_guard lock(cache_mutex);
  if (const auto it = cache.find(path); it != cache.end()) return it->second;
  try {
    auto curve = std::make_shared<const materials::master_curve>(materials::read_master_curve(path));
    cache.emplace(path, curve);
    return curve;
  } catch (const std::invalid_argument& e) {
    throw input_error(command + ": material.master_curve: " + one_line(e.what()));
  }
}

// The length L of omega0 = U/L of one indentor: its contact length, but a flat punch's width. The
// flat's face is what deforms the material; at and above alpha + beta/2 = 1/2 it rides on its
// leading corner (contact length 0), which would leave no contact frequency.
double fit_length(const indentor_spec& indentor, const punch::indentor_result& solved) {
  return indentor.shape == shape_kind::flat ? indentor.width : solved.contact_length;
}

// The L of omega0 = U/L: the mean over the indentors of fit_length; for a sampled profile, the
// load-weighted mean width of the contacts found: contact_length of the spectral search's, the
// pressure_width (4 standard deviations of the pressure) of the boundary-element solver's patches,
// which, unlike their panel edges, moves continuously with the material, so that the fixed point
// converges (measured: with the panel edges it cycled for 60 solves at acceptance 1e-3).
double mean_contact_length(const scene_spec& scene, const run_outcome& outcome) {
  double sum = 0, weight = 0;
  const auto add = [&](double w, double length) {
    sum += w * length;
    weight += w;
  };
  if (const auto* bem = std::get_if<punch::profile_bem_result>(&outcome.solved)) {
    for (const auto& p : bem->patches) add(p.load.value, p.pressure_width);
  } else if (const auto* profile = std::get_if<punch::profile_result>(&outcome.solved)) {
    for (const auto& c : profile->contacts) add(c.load, c.contact_length);
  } else {
    const auto& r = std::get<punch::scene_result>(outcome.solved);
    for (std::size_t i = 0; i < r.indentors.size(); ++i) add(1.0, fit_length(scene.indentors.at(i), r.indentors[i]));
  }
  return weight > 0 ? sum / weight : 0.0;
}

}  // namespace

materials::master_curve load_master_curve(const master_curve_spec& spec, const std::string& command) {
  const auto curve = read_cached(spec.resolved_path, command);
  if (!spec.shifted) return *curve;
  try {
    return materials::shift_to_temperature(*curve, {spec.C1, spec.C2, spec.T_ref}, spec.temperature);
  } catch (const std::domain_error& e) {
    throw input_error(command + ": material.temperature = " + std::to_string(spec.temperature) + ": " + e.what());
  }
}

fitted_material fit_material(const material_fit_request& request) {
  fitted_material out;
  try {
    out.curve = materials::read_master_curve(request.curve_path);
  } catch (const std::invalid_argument& e) {
    throw input_error(std::string("fit-material: ") + one_line(e.what()));
  }
  if (request.wlf) {
    if (!(request.wlf->C1 > 0) || !(request.wlf->C2 > 0)) throw input_error("fit-material: --wlf C1 and C2 must be > 0");
    try {
      out.log10_aT = materials::wlf_log10_shift(*request.wlf, request.temperature);
    } catch (const std::domain_error& e) {
      throw input_error(std::string("fit-material: ") + e.what());
    }
    out.curve = materials::shift_to_temperature(out.curve, *request.wlf, request.temperature);
  }
  materials::fit_options options;
  options.half_window_decades = request.window_decades;
  options.warning_threshold = request.threshold;
  out.fit = materials::fit_at(out.curve, request.speed / request.length, options);
  return out;
}

nlohmann::ordered_json fitted_material_json(const material_fit_request& request, const fitted_material& fitted) {
  const auto& f = fitted.fit;
  ordered_json doc = {{"alpha", f.alpha}, {"E1", f.E1}, {"omega0", f.omega0},
                      {"alpha_slope", f.alpha_slope}, {"alpha_tan_delta", f.alpha_tan_delta},
                      {"modulus", f.modulus}, {"window", {f.window_lo, f.window_hi}},
                      {"status", materials::to_string(f.status)}, {"warning", f.warning},
                      {"master_curve", request.curve_path}, {"points", fitted.curve.omega.size()}};
  if (fitted.log10_aT) {
    doc["temperature"] = request.temperature;
    doc["log10_aT"] = *fitted.log10_aT;
  }
  return doc;
}

nlohmann::ordered_json material_fit_json(const master_curve_spec& spec, const material_fit_report& report) {
  ordered_json fit = {{"master_curve", spec.path}};
  if (spec.shifted) {
    fit["temperature"] = spec.temperature;
    fit["log10_aT"] = *report.log10_aT;
  }
  fit["alpha"] = report.fit.alpha;
  fit["E1"] = report.fit.E1;
  fit["omega0"] = report.fit.omega0;
  fit["alpha_slope"] = report.fit.alpha_slope;
  fit["alpha_tan_delta"] = report.fit.alpha_tan_delta;
  fit["modulus"] = report.fit.modulus;
  fit["window"] = {report.fit.window_lo, report.fit.window_hi};
  fit["contact_length"] = report.contact_length;
  fit["iterations"] = report.iterations;
  fit["status"] = materials::to_string(report.status);
  fit["warning"] = report.warning;
  return fit;
}

material_fit_report fit_scene_material(const scene_spec& scene, const run_request& request) {
  if (!scene.material.curve) throw std::invalid_argument("fit_scene_material: the scene's material is not a master curve");
  const auto& spec = *scene.material.curve;
  const auto curve = load_master_curve(spec, "solve");
  scene_spec trial = scene;
  run_request fit_request;  // the fixed point's trial solves: no samples, the run's tolerance
  fit_request.tolerance = request.tolerance;
  fit_request.interrupt = request.interrupt;
  // A profile's trial solves: its contact search at the run's acceptance and time limit (a
  // profile's contacts are only verified to what its data is worth: 1e-9 would never be ok).
  if (scene.profile) {
    fit_request.acceptance = request.acceptance;
    fit_request.time_limit = request.time_limit;
  }
  auto length = [&](const materials::local_fit& f) {
    trial.material.alpha = f.alpha;
    trial.material.E1 = f.E1;
    return mean_contact_length(trial, run_scene(trial, fit_request));
  };
  materials::fixed_point_fit fp;
  try {
    std::optional<double> start;
    if (scene.indentors.size() > 1) {
      // Several indentors: the coupled solve can be slow at a trial material far from the answer
      // (seconds instead of milliseconds), so the fixed point is first found with each indentor
      // solved alone (mean of their contact lengths), then refined on the whole scene from there.
      auto alone = [&](const materials::local_fit& f) {
        double sum = 0;
        for (const auto& ind : scene.indentors) {
          if (ind.shape == shape_kind::flat) {  // its width, whatever the material
            sum += ind.width;
            continue;
          }
          scene_spec single = scene;
          single.indentors = {ind};
          // An isolated indentor's contact length does not depend on its apex; at apex 0 the punch
          // solver is also fast for contacts far smaller than |apex| (1.5e-8 m at apex 0.02 m: 5.6 s).
          single.indentors[0].apex = 0;
          single.material.alpha = f.alpha;
          single.material.E1 = f.E1;
          sum += mean_contact_length(single, run_scene(single, fit_request));
        }
        return sum / static_cast<double>(scene.indentors.size());
      };
      const auto first = materials::fit_fixed_point(curve, scene.speed, alone);
      start = first.contact_length;
    }
    fp = materials::fit_fixed_point(curve, scene.speed, length, {}, start);
  } catch (const std::domain_error& e) {
    throw input_error(std::string("solve: material.master_curve '") + one_line(spec.path) + "': " + e.what());
  }
  material_fit_report report;
  report.fit = fp.fit;
  report.contact_length = fp.contact_length;
  report.iterations = fp.iterations;
  if (spec.shifted) report.log10_aT = materials::wlf_log10_shift({spec.C1, spec.C2, spec.T_ref}, spec.temperature);
  report.status = fp.converged ? fp.fit.status : materials::fit_status::not_converged;
  report.warning = fp.converged ? fp.fit.warning
                                : "the fixed point omega0 = U/L did not converge in " + std::to_string(fp.iterations) +
                                      " solves";
  return report;
}

run_outcome run_scene_with_material(const scene_spec& scene, const run_request& request, std::string* warning) {
  if (warning) warning->clear();
  if (!scene.material.curve) return run_scene(scene, request);
  const auto& spec = *scene.material.curve;
  material_fit_report report = fit_scene_material(scene, request);
  scene_spec trial = scene;
  trial.material.alpha = report.fit.alpha;
  trial.material.E1 = report.fit.E1;
  run_outcome out = run_scene(trial, request);
  out.result["material_fit"] = material_fit_json(spec, report);
  if (report.status != materials::fit_status::ok) {
    out.ok = false;
    if (warning) *warning = std::string(materials::to_string(report.status)) + ": " + report.warning;
  }
  out.fit = std::move(report);
  return out;
}

}  // namespace rhabel::scene
