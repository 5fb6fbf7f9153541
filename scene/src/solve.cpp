// scene/src/solve.cpp: a validated scene -> rhabel::punch::solve -> the result document.
//
// The result document (schema in examples/README.md) keeps the names of the issue: beta, regime,
// indentors[i].{contact, contact_length, epsilon (wedges only), load, hysteretic_friction,
// total_friction, peak_pressure, peak_pressure_at, edges}, diagnostics.{residual, seconds}, and adds
// the evidence of the solver (kappa, effective modulus, per-indentor residual, error estimate,
// degree, status) and an echo of the validated scene.
//
// No NaN or Inf ever reaches the output: the punch layer reports an infinite peak pressure when an
// edge is singular; that is written as "peak_pressure": null with "peak_pressure_singular": true
// (the edge itself carries its exponent and intensity factor). Every other number is checked and a
// non-finite one is a solver failure (std::runtime_error, exit code 1, nothing printed).
#include "rhabel/scene/solve.hpp"

#include "rhabel/scene/error.hpp"

#include <rhabel/punch/contact.hpp>
#include <rhabel/punch/profile.hpp>
#include <rhabel/punch/profile_bem.hpp>

#include <cmath>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

namespace rhabel::scene {
namespace {

using ordered_json = nlohmann::ordered_json;

punch::material to_punch(const material_spec& m) {
  punch::material out;
  out.alpha = m.alpha;
  out.E1 = m.E1;
  out.poisson = m.nu;
  out.coulomb = m.coulomb;
  return out;
}

// Every number of the document must be finite: nlohmann-json would print NaN and Inf as null,
// silently. The path of the first offender goes into the message.
void require_finite(const ordered_json& value, const std::string& path) {
  if (value.is_number_float() && !std::isfinite(value.get<double>())) {
    throw std::runtime_error("solve: the solver produced a non-finite value at " + path);
  }
  if (value.is_object()) {
    for (const auto& item : value.items()) require_finite(item.value(), path + "." + item.key());
  } else if (value.is_array()) {
    for (std::size_t i = 0; i < value.size(); ++i) require_finite(value[i], path + "[" + std::to_string(i) + "]");
  }
}

// The same for a sampled array (kept out of the document, see run_outcome).
void require_finite(const std::vector<double>& values, const std::string& path) {
  for (std::size_t k = 0; k < values.size(); ++k)
    if (!std::isfinite(values[k]))
      throw std::runtime_error("solve: the solver produced a non-finite value at " + path + "[" + std::to_string(k) + "]");
}

// A placeholder prefix no scene text can contain by chance: a control character (escaped as
// \u001f in the dump, as it would be in any string of the scene) and 64 random bits.
std::string make_grid_token() {
  std::random_device device;
  std::ostringstream os;
  os << '\x1f' << "rhabel-grid-" << std::hex << device() << device() << ':';
  return os.str();
}

ordered_json edge_json(const punch::edge_report& e) {
  return {{"side", e.side == punch::edge_side::leading ? "leading" : "trailing"},
          {"at", e.position},
          {"singular", e.singular},
          {"exponent", e.exponent},
          {"intensity_factor", e.intensity_factor}};
}

// Runs a solver, its refusals as input errors (exit code 2).
template <class Solve>
auto solve_or_refuse(Solve&& solve) {
  try {
    return solve();
  } catch (const std::invalid_argument& e) {  // the solver rejected the scene as posed
    throw input_error(std::string("solve: the scene was rejected: ") + e.what());
  } catch (const std::domain_error& e) {  // e.g. overlapping contacts, no contact interval
    throw input_error(std::string("solve: the scene has no solution: ") + e.what());
  }
}

// The surface of several contacts on one grid, when sampled: "surface": {"x", "w"} and the table.
void add_surface(run_outcome& out, std::vector<double>&& x, std::vector<double>&& w) {
  if (x.empty()) return;
  if (x.size() != w.size()) throw std::runtime_error("solve: the solver returned a surface grid of mismatched sizes");
  require_finite(x, "result.surface.x");
  require_finite(w, "result.surface.w");
  out.result["surface"] = {{"x", out.grid_token + "s0x"}, {"w", out.grid_token + "s0v"}};
  out.surface.columns = {"x", "displacement"};
  out.surface.fields.push_back({0, std::move(x), std::move(w)});
}

// The head of a result document: the material's regime and the effective modulus.
template <class Result>
void begin_document(run_outcome& out, const run_request& request, const Result& r, double effective_modulus) {
  if (request.grid > 0) out.grid_token = make_grid_token();
  out.result["beta"] = r.beta;
  out.result["kappa"] = r.kappa;
  out.result["regime"] = punch::to_string(r.regime);
  out.result["effective_modulus"] = effective_modulus;
}

// What every result document ends with: the status that decides the exit code, the echo of the
// scene; every number checked finite.
void finish_document(run_outcome& out, const scene_spec& spec, punch::status_code code) {
  out.ok = code == punch::status_code::ok;
  out.result["scene"] = scene_json(spec);
  require_finite(out.result, "result");
}

// The tail of a result document: the diagnostics (with `rounds` and `load_fraction` for a
// profile's search: the fields its diagnostics have), then finish_document.
template <class Diagnostics>
void end_document(run_outcome& out, const scene_spec& spec, const run_request& request, const Diagnostics& d) {
  ordered_json diagnostics = {{"residual", request.residual ? ordered_json(d.residual) : ordered_json(nullptr)},
                              {"seconds", d.seconds}};
  if constexpr (requires { d.rounds; }) diagnostics["rounds"] = d.rounds;
  diagnostics["iterations"] = d.iterations;
  diagnostics["status"] = punch::to_string(d.code);
  diagnostics["status_message"] = d.status;
  if constexpr (requires { d.load_fraction; }) diagnostics["load_fraction"] = d.load_fraction;
  out.result["diagnostics"] = std::move(diagnostics);
  finish_document(out, spec, d.code);
}

// The fields of one contact's result (an indentor's, or a contact of a profile); its sampled
// arrays go to out's tables as field `index`, the document holding their placeholders
// (run_outcome::array).
ordered_json contact_item(punch::indentor_result& ir, std::size_t index, const std::string& where, const run_request& request,
                          run_outcome& out) {
  auto placeholder = [&](char table, char part) {
    return out.grid_token + table + std::to_string(index) + part;
  };
  ordered_json item;
  item["contact"] = {ir.a, ir.b};
  item["contact_length"] = ir.contact_length;
  if (ir.epsilon) item["epsilon"] = *ir.epsilon;
  item["load"] = ir.load;
  if (!std::isnan(ir.approach)) item["approach"] = ir.approach;
  item["hysteretic_friction"] = ir.hysteretic_friction;
  item["total_friction"] = ir.total_friction;
  const bool singular_peak = !std::isfinite(ir.peak_pressure);
  if (singular_peak && !(ir.peak_pressure > 0))
    throw std::runtime_error("solve: the solver produced a NaN peak pressure for " + where);
  item["peak_pressure"] = singular_peak ? ordered_json(nullptr) : ordered_json(ir.peak_pressure);
  item["peak_pressure_singular"] = singular_peak;
  item["peak_pressure_at"] = ir.peak_pressure_at;
  ordered_json edges = ordered_json::array();
  for (const auto& e : ir.edges) edges.push_back(edge_json(e));
  item["edges"] = std::move(edges);
  // Not computed (run_request::residual false): null, as JSON has no NaN.
  item["residual"] = request.residual ? ordered_json(ir.residual) : ordered_json(nullptr);
  item["error_estimate"] = ir.error_estimate;
  item["degree"] = ir.degree;
  item["status"] = punch::to_string(ir.code);
  item["status_message"] = ir.status;
  if (request.grid > 0) {
    if (ir.grid_x.size() != ir.pressure.size() || ir.displacement_x.size() != ir.displacement.size()) {
      throw std::runtime_error("solve: the solver returned grids of mismatched sizes");
    }
    const std::string prefix = "result." + where + ".";
    require_finite(ir.grid_x, prefix + "pressure.x");
    require_finite(ir.pressure, prefix + "pressure.p");
    item["pressure"] = {{"x", placeholder('p', 'x')}, {"p", placeholder('p', 'v')}};
    out.pressure.fields.push_back({index, std::move(ir.grid_x), std::move(ir.pressure)});
    if (request.displacement) {
      require_finite(ir.displacement_x, prefix + "displacement.x");
      require_finite(ir.displacement, prefix + "displacement.w");
      item["displacement"] = {{"x", placeholder('d', 'x')}, {"w", placeholder('d', 'v')}};
      out.displacement.fields.push_back({index, std::move(ir.displacement_x), std::move(ir.displacement)});
    }
  }
  return item;
}

punch::profile_scene profile_scene_of(const scene_spec& spec) {
  punch::profile_scene ps;
  ps.material = to_punch(spec.material);
  ps.speed = spec.speed;
  ps.load = *spec.body_load;
  ps.profile = {spec.profile->x, spec.profile->z, spec.profile->corners, spec.profile->period};
  return ps;
}

ordered_json estimate_json(const punch::bem_estimate& e) { return {{"value", e.value}, {"error", e.error}}; }

// A sampled profile by the boundary-element method (profile.solver): its patches, no sampled
// fields (punch::solve_profile_bem has none; --grid is refused for it by the command).
run_outcome run_profile_bem(const scene_spec& spec, const run_request& request, const punch::solve_options& options) {
  if (request.grid > 0)
    throw input_error("solve: " + request.grid_option + ": sampled fields come from profile.solver \"spectral\"; the "
                      "boundary-element solver reports its patches only");
  const punch::profile_scene ps = profile_scene_of(spec);
  punch::bem_options bem;
  if (spec.profile->max_panels > 0) bem.max_panels = spec.profile->max_panels;
  punch::profile_bem_result r = solve_or_refuse([&] { return punch::solve_profile_bem(ps, options, bem); });
  run_outcome out;
  auto& doc = out.result;
  begin_document(out, request, r, ps.material.effective_modulus(spec.speed));
  ordered_json patches = ordered_json::array();
  for (const auto& p : r.patches)
    patches.push_back({{"contact", {p.a, p.b}},
                       {"edge_error", p.edge_error},
                       {"load", estimate_json(p.load)},
                       {"hysteretic_friction", estimate_json(p.hysteretic_friction)},
                       {"peak_pressure", p.peak_pressure},
                       {"pressure_width", p.pressure_width}});
  doc["patches"] = std::move(patches);
  doc["hysteretic_friction"] = estimate_json(r.hysteretic_friction);
  doc["total_friction"] = r.total_friction;
  doc["mean_pressure"] = r.mean_pressure;
  doc["contact_fraction"] = estimate_json(r.contact_fraction);
  const auto& d = r.diagnostics;
  doc["diagnostics"] = {{"seconds", d.seconds},
                        {"panels", d.panels},
                        {"active_set_steps", d.active_set_steps},
                        {"level_panels", d.level_panels},
                        {"level_patches", d.level_patches},
                        {"level_friction", d.level_friction},
                        {"status", punch::to_string(d.code)},
                        {"status_message", d.status}};
  finish_document(out, spec, d.code);
  out.solved = std::move(r);
  return out;
}

// A sampled profile: its contacts as found by punch::solve_profile.
run_outcome run_profile(const scene_spec& spec, const run_request& request, const punch::solve_options& options) {
  const punch::profile_scene ps = profile_scene_of(spec);
  punch::profile_result r = solve_or_refuse([&] { return punch::solve_profile(ps, options); });
  run_outcome out;
  auto& doc = out.result;
  begin_document(out, request, r, ps.material.effective_modulus(spec.speed));
  if (!std::isnan(r.body_approach)) doc["body_approach"] = r.body_approach;
  out.pressure.columns = {"contact", "x", "pressure"};
  out.displacement.columns = {"contact", "x", "displacement"};
  ordered_json contacts = ordered_json::array();
  for (std::size_t i = 0; i < r.contacts.size(); ++i) {
    ordered_json item;
    item["tip"] = r.tips[i];
    item.update(contact_item(r.contacts[i], i, "contacts[" + std::to_string(i) + "]", request, out));
    contacts.push_back(std::move(item));
  }
  doc["contacts"] = std::move(contacts);
  doc["hysteretic_friction"] = r.hysteretic_friction;
  doc["total_friction"] = r.total_friction;
  doc["mean_pressure"] = r.mean_pressure;
  doc["contact_fraction"] = r.contact_fraction;
  if (spec.profile->period > 0) doc["window"] = {r.window_start, r.window_start + spec.profile->period};
  add_surface(out, std::move(r.surface_x), std::move(r.surface));
  if (!std::isnan(r.clearance)) doc["clearance"] = {{"min", r.clearance}, {"at", r.clearance_at}};
  if (!std::isnan(r.level_mismatch)) doc["level_mismatch"] = {{"max", r.level_mismatch}, {"at", r.level_mismatch_at}};
  doc["penetrations"] = r.penetrations;
  end_document(out, spec, request, r.diagnostics);
  out.solved = std::move(r);
  return out;
}

}  // namespace

double default_acceptance(const scene_spec& scene) {
  return scene.profile && scene.profile->boundary_element ? 1e-4 : 1e-9;
}

punch::scene punch_scene(const scene_spec& spec) {
  punch::scene s;
  s.material = to_punch(spec.material);
  s.speed = spec.speed;
  if (spec.body_load) s.body = punch::rigid_body{*spec.body_load};
  for (const auto& d : spec.indentors) {
    punch::indentor ind;
    if (!spec.body_load) ind.load = d.load;
    ind.apex = d.apex;
    ind.height = d.height;
    switch (d.shape) {
      case shape_kind::parabolic: ind.shape = punch::parabolic{d.radius}; break;
      case shape_kind::wedge: ind.shape = punch::wedge{d.slope_leading, d.slope_trailing}; break;
      case shape_kind::flat: ind.shape = punch::flat{d.width}; break;
    }
    s.indentors.push_back(std::move(ind));
  }
  return s;
}

ordered_json scene_json(const scene_spec& spec, bool samples) {
  ordered_json material = {{"alpha", spec.material.alpha},
                           {"E1", spec.material.E1},
                           {"nu", spec.material.nu},
                           {"coulomb", spec.material.coulomb}};
  if (!spec.material.name.empty()) material["name"] = spec.material.name;
  ordered_json indentors = ordered_json::array();
  for (const auto& d : spec.indentors) {
    ordered_json item = {{"shape", shape_name(d.shape)}};
    if (!d.name.empty()) item["name"] = d.name;
    switch (d.shape) {
      case shape_kind::parabolic: item["radius"] = d.radius; break;
      case shape_kind::wedge:
        item["slope_leading"] = d.slope_leading;
        item["slope_trailing"] = d.slope_trailing;
        break;
      case shape_kind::flat: item["width"] = d.width; break;
    }
    if (spec.body_load) {
      item["height"] = d.height;
    } else {
      item["load"] = d.load;
    }
    item["apex"] = d.apex;
    indentors.push_back(std::move(item));
  }
  ordered_json out;
  if (!spec.description.empty()) out["description"] = spec.description;
  out["material"] = std::move(material);
  out["speed"] = spec.speed;
  if (spec.body_load) out["body"] = {{"load", *spec.body_load}};
  if (spec.profile) {
    // The samples themselves are the input's (a measured profile has thousands): their count,
    // range and file stand for them.
    ordered_json profile;
    if (!spec.profile->file.empty()) profile["file"] = spec.profile->file;
    if (samples) {
      profile["x"] = spec.profile->x;
      profile["z"] = spec.profile->z;
    } else {
      profile["samples"] = spec.profile->x.size();
      if (!spec.profile->x.empty()) profile["x_range"] = {spec.profile->x.front(), spec.profile->x.back()};
    }
    profile["corners"] = spec.profile->corners;
    if (spec.profile->period > 0) profile["period"] = spec.profile->period;
    profile["solver"] = spec.profile->boundary_element ? "boundary_element" : "spectral";
    if (spec.profile->max_panels > 0) profile["max_panels"] = spec.profile->max_panels;
    out["profile"] = std::move(profile);
  } else {
    out["indentors"] = std::move(indentors);
  }
  return out;
}

const std::vector<double>* run_outcome::array(std::string_view text) const {
  if (grid_token.empty() || text.size() < grid_token.size() + 3 || text.substr(0, grid_token.size()) != grid_token)
    return nullptr;
  const std::string_view rest = text.substr(grid_token.size());
  const sampled_table* table = rest.front() == 'p'   ? &pressure
                               : rest.front() == 'd' ? &displacement
                               : rest.front() == 's' ? &surface
                                                     : nullptr;
  const char part = rest.back();
  if (!table || (part != 'x' && part != 'v')) return nullptr;
  std::size_t index = 0;
  for (const char c : rest.substr(1, rest.size() - 2)) {
    if (c < '0' || c > '9') return nullptr;
    index = 10 * index + static_cast<std::size_t>(c - '0');
  }
  for (const auto& field : table->fields)
    if (field.indentor == index) return part == 'x' ? &field.x : &field.value;
  return nullptr;
}

std::vector<double>* run_outcome::array(std::string_view text) {
  return const_cast<std::vector<double>*>(std::as_const(*this).array(text));
}

run_outcome run_scene(const scene_spec& spec, const run_request& request) {
  punch::solve_options options;
  options.grid_points = request.grid;
  options.acceptance = request.acceptance > 0 ? request.acceptance : default_acceptance(spec);
  options.threads = request.threads;
  options.time_limit = request.time_limit;
  options.tolerance = request.tolerance;
  options.displacement = request.displacement;
  options.spacing = request.spacing;
  options.residual = request.residual;
  options.layered_below = request.layered_below;
  options.profile_knots = request.profile_knots;
  if (request.interrupt) options.interrupt = request.interrupt;
  if (spec.profile)
    return spec.profile->boundary_element ? run_profile_bem(spec, request, options) : run_profile(spec, request, options);
  punch::scene_result r = solve_or_refuse([&] { return punch::solve(punch_scene(spec), options); });
  run_outcome out;
  auto& doc = out.result;
  begin_document(out, request, r, to_punch(spec.material).effective_modulus(spec.speed));
  if (r.body_approach) doc["body_approach"] = *r.body_approach;
  ordered_json indentors = ordered_json::array();
  out.pressure.columns = {"indentor", "x", "pressure"};
  out.displacement.columns = {"indentor", "x", "displacement"};
  for (std::size_t i = 0; i < r.indentors.size(); ++i) {
    const auto& spec_i = spec.indentors.at(i);
    ordered_json item;
    item["shape"] = shape_name(spec_i.shape);
    if (!spec_i.name.empty()) item["name"] = spec_i.name;
    item.update(contact_item(r.indentors[i], i, "indentors[" + std::to_string(i) + "]", request, out));
    indentors.push_back(std::move(item));
  }
  doc["indentors"] = std::move(indentors);
  add_surface(out, std::move(r.surface_x), std::move(r.surface));
  end_document(out, spec, request, r.diagnostics);
  out.solved = std::move(r);
  return out;
}

void write_document(const run_outcome& outcome, bool compact, const std::function<void(std::string_view)>& write) {
  const std::string text = compact ? outcome.result.dump() : outcome.result.dump(2);
  if (outcome.grid_token.empty()) {
    write(text);
    return;
  }
  const std::string dumped = ordered_json(outcome.grid_token).dump();  // "\u001frhabel-grid-...:"
  const std::string marker = dumped.substr(0, dumped.size() - 1);      // without the closing quote
  std::string buffer;
  std::size_t done = 0;
  for (std::size_t at = text.find(marker); at != std::string::npos; at = text.find(marker, done)) {
    const std::size_t close = text.find('"', at + marker.size());
    const std::vector<double>* array =
        outcome.array(outcome.grid_token + text.substr(at + marker.size(), close - at - marker.size()));
    if (!array) throw std::logic_error("write_document: a placeholder without its array");
    buffer.assign(text, done, at - done);
    // nlohmann's layout of a non-empty array: "[" then, indented, one element a line ("\n" +
    // indent + 2 spaces before each), "\n" + indent + "]"; compact: "[a,b,...]".
    const std::size_t line = text.rfind('\n', at) + 1;
    const std::size_t indent = text.find_first_not_of(' ', line) - line;
    const std::string separator = compact ? "," : ",\n" + std::string(indent + 2, ' ');
    const std::vector<double>& values = *array;
    buffer += '[';
    if (!compact && !values.empty()) buffer += "\n" + std::string(indent + 2, ' ');
    char number[64];
    for (std::size_t k = 0; k < values.size(); ++k) {
      if (k) buffer += separator;
      buffer.append(number, nlohmann::detail::to_chars(number, number + sizeof number, values[k]));
      if (buffer.size() > (1u << 20)) {
        write(buffer);
        buffer.clear();
      }
    }
    if (!compact && !values.empty()) buffer += "\n" + std::string(indent, ' ');
    buffer += ']';
    write(buffer);
    done = close + 1;
  }
  write(std::string_view(text).substr(done));
}

}  // namespace rhabel::scene
