// python/src/bind_scene.cpp: the scene layer (rhabel/scene.hpp) for the Python package, the same
// code as the command line's:
//   _rhabel._fit_scene_material(text, tolerance, acceptance, time_limit): the master-curve fixed
//     point of a scene given as JSON text (`rhabel solve` then solves the scene with the fitted
//     power law, and so does rhabel.solve);
//   _rhabel._fit_material(curve, speed, length, temperature, wlf, window_decades, threshold): the
//     local power law of a master curve at omega0 = U/L, the JSON of `rhabel fit-material --json`;
//   _rhabel._Sweep(text, source, directory): a sweep file parsed and validated; .run(...) solves its
//     rows on a pool of threads (into a resumable output file or not) and returns their lines, the
//     lines of `rhabel sweep`.
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
#include <vector>

namespace rhabel::python {
namespace {

/// A JSON value of the scene layer's document as Python objects (objects as dicts, arrays as lists).
py::object to_python(const nlohmann::ordered_json& value) {
  if (value.is_object()) {
    py::dict out;
    for (const auto& [key, item] : value.items()) out[py::str(key)] = to_python(item);
    return out;
  }
  if (value.is_array()) {
    py::list out;
    for (const auto& item : value) out.append(to_python(item));
    return out;
  }
  if (value.is_string()) return py::str(value.get<std::string>());
  if (value.is_boolean()) return py::bool_(value.get<bool>());
  if (value.is_number_unsigned()) return py::int_(value.get<std::size_t>());
  if (value.is_number_integer()) return py::int_(value.get<long long>());
  if (value.is_number()) return py::float_(value.get<double>());
  return py::none();
}

py::object fit_scene_material(const std::string& text, double tolerance, double acceptance, double time_limit) {
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
  return to_python(scene::material_fit_json(*spec.material.curve, report));
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
    return to_python(scene::fitted_material_json(request, scene::fit_material(request)));
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
    return scene::row_scene(spec_, row);
  }

  /// Solves the rows (those missing from `out` when it is given: resumed as by `rhabel sweep`) on
  /// `threads` threads; progress(done, total) from this thread after each batch; Ctrl-C (or an
  /// exception of progress) stops the rows under way and raises, the rows done kept in `out`.
  /// Returns every row's line, in row order.
  std::vector<std::string> run(const std::string& out, bool jsonl, std::size_t threads, double tolerance,
                               double acceptance, double time_limit, const py::object& progress) {
    const auto format = jsonl ? scene::row_format::jsonl : scene::row_format::csv;
    std::optional<scene::sweep_output> output;
    std::map<std::size_t, std::string> lines;
    std::vector<std::size_t> todo;
    if (!out.empty()) {
      try {
        output.emplace(spec_, format, out);
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
    const auto stop = std::make_shared<std::atomic<bool>>(false);
    scene::run_request request;  // grid 0, one thread per row (the rows run in parallel)
    request.tolerance = tolerance;
    request.acceptance = acceptance;
    request.time_limit = time_limit;
    request.interrupt = [stop] { return stop->load(); };
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
           py::arg("acceptance"), py::arg("time_limit"), py::arg("progress"));
  m.def("_fit_scene_material", &fit_scene_material, py::arg("text"), py::arg("tolerance"), py::arg("acceptance"),
        py::arg("time_limit"));
}

}  // namespace rhabel::python
