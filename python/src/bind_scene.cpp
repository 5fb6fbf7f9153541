// python/src/bind_scene.cpp: the scene layer (rhabel/scene.hpp) for the Python package, the same
// code as the command line's:
//   _rhabel._fit_material(curve, speed, length, temperature, wlf, window_decades, threshold): the
//     local power law of a master curve at omega0 = U/L, the JSON of `rhabel fit-material --json`;
//   _rhabel._Sweep(text, source, directory): a sweep file parsed and validated; .run(...) solves its
//     rows on a pool of threads (into a resumable output file or not) and returns their lines, the
//     lines of `rhabel sweep`;
//   _rhabel._solve_scene(text, directory, ...): `rhabel solve`: the scene parsed and validated,
//     solved (a master curve's fixed point first) and its result document as nested Records, the
//     sampled fields as NumPy arrays;
//   _rhabel._validate_scene(text, directory): the validated scene, as the document echoes it;
//   _rhabel._trial_interval(text, directory, a, b, tolerance): punch::trial_interval for the
//     scene's one indentor.
// Scenes arrive as JSON text (python/rhabel/_scene.py turns a dict into it), so that one parser
// with its one-line messages serves the command line and Python.
#include "bindings.hpp"

#include <rhabel/scene.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <variant>
#include <vector>

namespace rhabel::python {
namespace {

/// The message of the scene layer's input_error without the command's "solve: " prefix (the
/// command line prints "rhabel: solve: " before it; Python raises it as it is).
std::string without_command(const char* what) {
  const std::string_view text(what), prefix("solve: ");
  return std::string(text.substr(0, prefix.size()) == prefix ? text.substr(prefix.size()) : text);
}

/// A scene parsed by the scene layer; its refusal a ValueError. Relative files (a profile's CSV,
/// a master curve) are relative to `directory`.
scene::scene_spec parse(const std::string& text, const std::string& directory) {
  try {
    return scene::parse_scene(text, "(dict)", directory);
  } catch (const scene::input_error& e) {
    throw py::value_error(without_command(e.what()));
  }
}

/// The classes of rhabel._record: Record (a dict with attribute access) and Contact (a contact's
/// Record, with pressure_at).
struct record_classes {
  py::object record, contact;
};
const record_classes& records() {
  static const record_classes* classes = nullptr;  // the GIL serialises the first call
  if (classes == nullptr) {
    const py::module_ module = py::module_::import("rhabel._record");
    classes = new record_classes{module.attr("Record"), module.attr("Contact")};
  }
  return *classes;
}

/// A JSON value of the scene layer (a result document, a fit, a validated scene) as Python
/// objects: objects as Records, those of the result's "indentors" and "contacts" as Contacts
/// (`top`: value is the document itself), arrays as lists, a contact's interval (a, b) as a
/// tuple, and the placeholders of sampled fields as the NumPy arrays themselves (moved out of
/// `outcome`, when given). An object is made as `type` (default: Record).
py::object to_records(const nlohmann::ordered_json& value, scene::run_outcome* outcome, bool top = false,
                      const py::object* type = nullptr) {
  if (value.is_object()) {
    py::object out = type ? (*type)() : records().record();
    for (const auto& [key, item] : value.items()) {
      if (key == "contact" && item.is_array() && item.size() == 2) {
        out[py::str(key)] = py::make_tuple(item[0].get<double>(), item[1].get<double>());
      } else if (top && item.is_array() && (key == "indentors" || key == "contacts")) {
        py::list contacts;
        for (const auto& c : item) contacts.append(to_records(c, outcome, false, &records().contact));
        out[py::str(key)] = std::move(contacts);
      } else {
        out[py::str(key)] = to_records(item, outcome);
      }
    }
    return out;
  }
  if (value.is_array()) {
    py::list out;
    for (const auto& item : value) out.append(to_records(item, outcome));
    return out;
  }
  if (value.is_string()) {
    const auto& text = value.get_ref<const std::string&>();
    if (std::vector<double>* array = outcome ? outcome->array(text) : nullptr) return to_numpy(std::move(*array));
    return py::str(text);
  }
  if (value.is_boolean()) return py::bool_(value.get<bool>());
  if (value.is_number_unsigned()) return py::int_(value.get<std::size_t>());
  if (value.is_number_integer()) return py::int_(value.get<long long>());
  if (value.is_number()) return py::float_(value.get<double>());
  return py::none();
}

/// The solved pressure of each contact (`key`: "indentors" or "contacts") on its Contact.
void attach_pressure(py::object& result, const char* key, const std::vector<punch::indentor_result>& solved) {
  if (!result.contains(key)) return;
  const py::list items = result[key];
  for (std::size_t i = 0; i < solved.size() && i < items.size(); ++i)
    items[i].attr("_pressure") = py::cast(solved[i].pressure_at);
}

py::object solve_scene(const std::string& text, const std::string& directory, std::size_t grid, bool displacement,
                       double tolerance, bool residual, double acceptance, std::size_t threads, double time_limit,
                       double layered_below, bool graded, bool profile_knots) {
  const scene::scene_spec spec = parse(text, directory);
  scene::run_request request;
  request.grid = grid;
  request.grid_option = "grid";
  request.displacement = displacement;
  request.tolerance = tolerance;
  request.residual = residual;
  request.acceptance = acceptance;
  request.threads = threads;
  request.time_limit = time_limit;
  request.layered_below = layered_below;
  request.profile_knots = profile_knots;
  request.spacing = graded ? punch::sample_spacing::graded : punch::sample_spacing::uniform;
  scene::run_outcome outcome;
  try {
    outcome = run_interruptible(request, [&] { return scene::run_scene_with_material(spec, request); });
  } catch (const scene::input_error& e) {
    throw py::value_error(without_command(e.what()));
  }
  py::object result = to_records(outcome.result, &outcome, true);
  if (const auto* r = std::get_if<punch::scene_result>(&outcome.solved)) attach_pressure(result, "indentors", r->indentors);
  if (const auto* r = std::get_if<punch::profile_result>(&outcome.solved)) attach_pressure(result, "contacts", r->contacts);
  return result;
}

/// punch::trial_interval for the scene's single indentor on [a, b] (checked by the caller: one
/// indentor, a < b finite); a Record {load, hysteretic_friction, error_estimate}.
py::object trial_interval(const std::string& text, const std::string& directory, double a, double b, double tolerance) {
  const punch::scene s = scene::punch_scene(parse(text, directory));
  punch::solve_options options;
  options.tolerance = tolerance;
  punch::trial_result result;
  {
    py::gil_scoped_release nogil;
    result = punch::trial_interval(s.material, s.speed, s.indentors.front(), a, b, options);
  }
  py::object out = records().record();
  out["load"] = result.load;
  out["hysteretic_friction"] = result.hysteretic_friction;
  out["error_estimate"] = result.error_estimate;
  return out;
}

py::object validate_scene(const std::string& text, const std::string& directory) {
  return to_records(scene::scene_json(parse(text, directory), true), nullptr);
}

/// `rhabel fit-material --json` (the scene layer's fit_material); arguments checked by the caller.
py::object fit_material(const std::string& curve, double speed, double length, std::optional<double> temperature,
                        std::optional<std::vector<double>> wlf, double window_decades, double threshold) {
  scene::material_fit_request request;
  request.curve_path = curve;
  request.speed = speed;
  request.length = length;
  if (wlf && temperature) {
    request.wlf = materials::wlf_shift{(*wlf).at(0), (*wlf).at(1), (*wlf).at(2)};
    request.temperature = *temperature;
  }
  request.window_decades = window_decades;
  request.threshold = threshold;
  try {
    return to_records(scene::fitted_material_json(request, scene::fit_material(request)), nullptr);
  } catch (const scene::input_error& e) {
    throw py::value_error(e.what());
  }
}

/// A parsed sweep and the run of its rows.
class sweep_handle {
 public:
  sweep_handle(const std::string& text, const std::string& source, const std::string& directory) {
    try {
      spec_ = scene::parse_sweep(text, source, directory);
    } catch (const scene::input_error& e) {
      throw py::value_error(e.what());
    }
  }
  std::size_t rows() const { return spec_.rows; }
  std::vector<std::string> columns() const { return scene::row_columns(spec_); }
  std::string row_scene(std::size_t row) const {
    if (row >= spec_.rows) throw py::index_error("row " + std::to_string(row) + " of " + std::to_string(spec_.rows));
    return scene::row_scene(spec_, row).dump();
  }

  /// Solves the rows (those missing from `out` when it is given: resumed as by `rhabel sweep`) on
  /// `threads` threads; progress(done, total) from this thread after each batch; Ctrl-C (or an
  /// exception of progress) stops the rows under way and raises, the rows done kept in `out`.
  /// Returns every row's line, in row order.
  std::vector<std::string> run(const std::string& out, bool jsonl, std::size_t threads, double tolerance,
                               double acceptance, double time_limit, bool profile_knots, const py::object& progress) {
    const auto format = jsonl ? scene::row_format::jsonl : scene::row_format::csv;
    std::optional<scene::sweep_output> output;
    std::map<std::size_t, std::string> lines;
    std::vector<std::size_t> todo;
    const auto stop = std::make_shared<std::atomic<bool>>(false);
    scene::run_request request;  // grid 0, one thread per row (the rows run in parallel)
    request.tolerance = tolerance;
    request.acceptance = acceptance;
    request.time_limit = time_limit;
    request.profile_knots = profile_knots;
    request.interrupt = [stop] { return stop->load(); };
    if (!out.empty()) {
      try {
        output.emplace(spec_, format, out, request);
      } catch (const scene::input_error& e) {
        throw py::value_error(e.what());
      } catch (const scene::write_error& e) {
        PyErr_SetString(PyExc_OSError, e.what());
        throw py::error_already_set();
      }
      todo = output->missing();
    } else {
      for (std::size_t i = 0; i < spec_.rows; ++i) todo.push_back(i);
    }
    if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
    std::optional<scene::sweep_pool> pool;
    pool.emplace(spec_, format, todo, threads, request);
    const auto join = [&] {
      stop->store(true);
      py::gil_scoped_release nogil;
      pool.reset();
    };
    try {
      std::size_t done = 0;
      while (done < todo.size()) {
        std::vector<scene::finished_row> batch;
        {
          py::gil_scoped_release nogil;
          batch = pool->take(std::chrono::milliseconds(100));
        }
        for (auto& r : batch) {
          if (output) {
            output->append(std::move(r));
          } else {
            lines.emplace(r.row, std::move(r.line));
          }
          ++done;
        }
        if (!progress.is_none()) progress(done, todo.size());
        if (PyErr_CheckSignals() != 0) throw py::error_already_set();
      }
    } catch (...) {
      join();
      throw;
    }
    join();
    if (output) {
      try {
        output->finish();
      } catch (const scene::write_error& e) {
        PyErr_SetString(PyExc_OSError, e.what());
        throw py::error_already_set();
      }
    }
    const auto& all = output ? output->lines() : lines;
    std::vector<std::string> result;
    result.reserve(all.size());
    for (const auto& [row, line] : all) result.push_back(line);
    return result;
  }

 private:
  scene::sweep_spec spec_;
};

}  // namespace

void bind_scene(py::module_& m) {
  m.def("_fit_material", &fit_material, py::arg("curve"), py::arg("speed"), py::arg("length"), py::arg("temperature"),
        py::arg("wlf"), py::arg("window_decades"), py::arg("threshold"));
  py::class_<sweep_handle>(m, "_Sweep")
      .def(py::init<const std::string&, const std::string&, const std::string&>(), py::arg("text"), py::arg("source"),
           py::arg("directory"))
      .def_property_readonly("rows", &sweep_handle::rows)
      .def("columns", &sweep_handle::columns)
      .def("row_scene", &sweep_handle::row_scene, py::arg("row"))
      .def("run", &sweep_handle::run, py::arg("out"), py::arg("jsonl"), py::arg("threads"), py::arg("tolerance"),
           py::arg("acceptance"), py::arg("time_limit"), py::arg("profile_knots"), py::arg("progress"));
  m.def("_solve_scene", &solve_scene, py::arg("text"), py::arg("directory"), py::arg("grid"), py::arg("displacement"),
        py::arg("tolerance"), py::arg("residual"), py::arg("acceptance"), py::arg("threads"), py::arg("time_limit"),
        py::arg("layered_below"), py::arg("graded"), py::arg("profile_knots"));
  m.def("_validate_scene", &validate_scene, py::arg("text"), py::arg("directory"));
  m.def("_trial_interval", &trial_interval, py::arg("text"), py::arg("directory"), py::arg("a"), py::arg("b"),
        py::arg("tolerance"));
}

}  // namespace rhabel::python
