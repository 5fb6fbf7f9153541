// scene/src/sweep.cpp: sweep files and rows (see rhabel/scene/sweep.hpp).
#include "rhabel/scene/sweep.hpp"

#include "rhabel/scene/error.hpp"
#include "rhabel/scene/material.hpp"
#include "rhabel/scene/scene.hpp"
#include "rhabel/scene/solve.hpp"

#include "rhabel/materials.hpp"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <utility>
#include <variant>

namespace rhabel::scene {
namespace {

using json = nlohmann::json;
namespace fs = std::filesystem;

[[noreturn]] void fail_sweep(const std::string& message) { throw input_error("sweep: " + one_line(message)); }

std::string read_text(const std::string& path, const char* what) {
  try {
    return materials::read_text_file(path, what);
  } catch (const std::invalid_argument& e) {
    fail_sweep(e.what());
  }
}

json parse_json(const std::string& text, const std::string& source) {
  try {
    return json::parse(text);
  } catch (const json::exception& e) {
    std::string what = e.what();
    if (const auto at = what.find("] "); at != std::string::npos) what = what.substr(at + 2);
    fail_sweep(source + " is not valid JSON: " + what);
  }
}

constexpr std::size_t max_index_digits = 9;

// "indentors[0].load" -> /indentors/0/load
json::json_pointer to_pointer(const std::string& path, const std::string& where) {
  std::string pointer;
  std::size_t i = 0;
  auto bad = [&] {
    fail_sweep(where + " = \"" + path + "\" is not a field path like speed, indentors[0].load, material.temperature");
  };
  if (path.empty()) bad();
  // A scene's field names are letters, digits and underscores: anything else (a NUL, a control
  // character, JSON pointer's own ~ and /) cannot name one and would reach the CSV header.
  for (const char c : path) {
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.' || c == '[' || c == ']')) bad();
  }
  while (i < path.size()) {
    std::size_t j = i;
    while (j < path.size() && path[j] != '.' && path[j] != '[') ++j;
    if (j == i) bad();
    pointer += '/';
    pointer.append(path, i, j - i);
    while (j < path.size() && path[j] == '[') {
      const auto close = path.find(']', j);
      if (close == std::string::npos || close == j + 1) bad();
      const std::string index = path.substr(j + 1, close - j - 1);
      // At most max_index_digits digits, without leading zeros: JSON pointer's array indices (a
      // longer one overflowed inside the JSON library); no scene has 10^9 indentors.
      if (index.find_first_not_of("0123456789") != std::string::npos || index.size() > max_index_digits ||
          (index.size() > 1 && index.front() == '0')) {
        bad();
      }
      pointer += '/';
      pointer += index;
      j = close + 1;
    }
    if (j < path.size()) {
      if (path[j] != '.' || j + 1 == path.size()) bad();
      ++j;
    }
    i = j;
  }
  return json::json_pointer(pointer);
}

double range_number(const json& object, const std::string& where, const char* key) {
  const auto it = object.find(key);
  if (it == object.end() || !it->is_number() || !std::isfinite(it->get<double>())) {
    fail_sweep(where + "." + key + " must be a finite number");
  }
  return it->get<double>();
}

std::vector<json> expand_range(const json& spec, const std::string& where, bool logarithmic) {
  if (!spec.is_object()) fail_sweep(where + " must be an object {\"from\": .., \"to\": .., \"count\": ..}");
  for (const auto& item : spec.items()) {
    if (item.key() != "from" && item.key() != "to" && item.key() != "count") {
      fail_sweep(where + "." + item.key() + " is not a known field (known: from, to, count)");
    }
  }
  const double from = range_number(spec, where, "from"), to = range_number(spec, where, "to");
  const auto c = spec.find("count");
  if (c == spec.end() || !c->is_number_integer() || c->get<long long>() < 1 ||
      c->get<long long>() > static_cast<long long>(max_sweep_rows)) {
    fail_sweep(where + ".count must be an integer in [1, " + std::to_string(max_sweep_rows) + "]");
  }
  const auto n = static_cast<std::size_t>(c->get<long long>());
  if (logarithmic && !(from > 0 && to > 0)) fail_sweep(where + ": from and to must be > 0 for a log_range");
  std::vector<json> values;
  for (std::size_t i = 0; i < n; ++i) {
    double v;
    if (i == 0) {
      v = from;
    } else if (i + 1 == n) {
      v = to;
    } else {
      const double t = static_cast<double>(i) / static_cast<double>(n - 1);
      // (1 - t) from + t to, not from + t (to - from): the difference overflows for ends near
      // +-1.8e308 (-1e308 .. 1e308 has the middle 0).
      v = logarithmic ? std::exp((1 - t) * std::log(from) + t * std::log(to)) : (1 - t) * from + t * to;
    }
    values.emplace_back(v);
  }
  return values;
}

// Makes a relative master_curve path absolute against `dir`.
// The scene's file names (material.master_curve, profile.file) made absolute against the
// directory of the scene they were written in: each row's scene is parsed without a directory.
void absolutize_paths(json& scene, const fs::path& dir) {
  if (!scene.is_object()) return;
  auto absolutize = [&](json& value) {
    if (!value.is_string()) return;
    const fs::path p = value.get<std::string>();
    if (!p.empty() && p.is_relative()) value = fs::absolute(dir / p).lexically_normal().string();
  };
  if (const auto m = scene.find("material"); m != scene.end() && m->is_object())
    if (const auto c = m->find("master_curve"); c != m->end()) absolutize(*c);
  if (const auto pr = scene.find("profile"); pr != scene.end() && pr->is_object())
    if (const auto f = pr->find("file"); f != pr->end()) absolutize(*f);
}

std::string number_text(double x) { return json(x).dump(); }  // shortest round trip

std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"") == std::string::npos && !text.empty()) return text;
  std::string out = "\"";
  for (const char c : text) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + "\"";
}

std::string value_text(const json& v, row_format format) {
  if (format == row_format::jsonl) return v.dump();
  return v.is_string() ? csv_field(one_line(v.get<std::string>())) : v.dump();
}

}  // namespace

sweep_spec read_sweep(const std::string& path) {
  return parse_sweep(read_text(path, "sweep file"), "sweep file '" + path + "'", fs::path(path).parent_path().string());
}

sweep_spec parse_sweep(const std::string& text, const std::string& source, const std::string& directory) {
  const json doc = parse_json(text, source);
  if (!doc.is_object()) fail_sweep(source + ": the top level must be an object");
  for (const auto& item : doc.items()) {
    if (item.key() != "description" && item.key() != "scene" && item.key() != "axes" && item.key() != "combine") {
      fail_sweep(item.key() + " is not a known field of a sweep (known: description, scene, axes, combine)");
    }
  }
  const fs::path dir = directory;
  sweep_spec sweep;
  const auto s = doc.find("scene");
  if (s == doc.end()) fail_sweep("scene is missing: a scene object or the name of a scene file is required");
  fs::path scene_dir = dir;
  if (s->is_string()) {
    const fs::path scene_path = dir / s->get<std::string>();
    sweep.base = parse_json(read_text(scene_path.string(), "scene file"), "scene file '" + scene_path.string() + "'");
    scene_dir = scene_path.parent_path();
  } else if (s->is_object()) {
    sweep.base = *s;
  } else {
    fail_sweep("scene must be an object or a file name");
  }
  absolutize_paths(sweep.base, scene_dir);
  // The base scene must be valid by itself (its errors name the field: "sweep: scene: ...").
  try {
    const auto spec = parse_scene_value(sweep.base, "(base scene)");
    sweep.indentors = spec.indentors.size();
    sweep.profile = spec.profile.has_value();
    // A bad master curve is bad input of the whole sweep (exit 2), not a failed row each time.
    if (spec.material.curve) {
      try {
        (void)materials::read_master_curve(spec.material.curve->resolved_path);
      } catch (const std::invalid_argument& e) {
        fail_sweep(std::string("scene: material.master_curve: ") + e.what());
      }
    }
  } catch (const input_error& e) {
    std::string what = e.what();
    if (what.starts_with("solve: ")) what = what.substr(7);
    fail_sweep("scene: " + what);
  }
  if (const auto c = doc.find("combine"); c != doc.end()) {
    if (*c == "zip") sweep.zip = true;
    else if (*c != "product") fail_sweep("combine = " + c->dump() + " is not known (valid: \"product\", \"zip\")");
  }
  const auto a = doc.find("axes");
  if (a == doc.end() || !a->is_array() || a->empty()) fail_sweep("axes must be a non-empty array of {path, values|range|log_range}");
  for (std::size_t k = 0; k < a->size(); ++k) {
    const json& item = (*a)[k];
    const std::string where = "axes[" + std::to_string(k) + "]";
    if (!item.is_object()) fail_sweep(where + " must be an object");
    sweep_axis axis;
    int kinds = 0;
    for (const auto& field : item.items()) {
      if (field.key() == "path") continue;
      if (field.key() == "values") {
        ++kinds;
        if (!field.value().is_array() || field.value().empty()) fail_sweep(where + ".values must be a non-empty array");
        for (std::size_t i = 0; i < field.value().size(); ++i) {
          const auto& v = field.value()[i];
          if (!(v.is_number() || v.is_string() || v.is_boolean())) {
            fail_sweep(where + ".values[" + std::to_string(i) + "] must be a number, string or boolean");
          }
          axis.values.push_back(v);
        }
      } else if (field.key() == "range" || field.key() == "log_range") {
        ++kinds;
        axis.values = expand_range(field.value(), where + "." + field.key(), field.key() == "log_range");
      } else {
        fail_sweep(where + "." + field.key() + " is not a known field (known: path, values, range, log_range)");
      }
    }
    if (kinds != 1) fail_sweep(where + " needs exactly one of values, range, log_range");
    const auto p = item.find("path");
    if (p == item.end() || !p->is_string()) fail_sweep(where + ".path is missing: the JSON path of a scene field, e.g. speed");
    axis.path = p->get<std::string>();
    axis.pointer = to_pointer(axis.path, where + ".path");
    const auto parent = axis.pointer.parent_pointer();
    if (!sweep.base.contains(parent) || !(sweep.base.at(parent).is_object() || sweep.base.at(parent).is_array())) {
      fail_sweep(where + ".path = \"" + axis.path + "\": its parent does not exist in the base scene");
    }
    if (sweep.base.at(parent).is_array() && !sweep.base.contains(axis.pointer)) {
      fail_sweep(where + ".path = \"" + axis.path + "\": index out of range in the base scene");
    }
    if (sweep.base.contains(axis.pointer) && !sweep.base.at(axis.pointer).is_primitive()) {
      fail_sweep(where + ".path = \"" + axis.path + "\" is not a scalar field of the scene");
    }
    if (!sweep.base.contains(axis.pointer)) {
      // A field the base scene does not have (material.temperature, an indentor's apex) must be
      // one the scene knows: otherwise every row would be invalid_scene.
      json trial = sweep.base;
      trial[axis.pointer] = axis.values.front();
      try {
        (void)parse_scene_value(trial, "(base scene with " + axis.path + ")");
      } catch (const input_error& e) {
        const std::string what = e.what();
        if (what.find(" " + axis.path + " is not a known field") != std::string::npos) {
          fail_sweep(where + ".path = \"" + axis.path + "\" is not a field of the scene (" +
                     what.substr(what.find(axis.path)) + ")");
        }
      }
    }
    for (const auto& other : sweep.axes) {
      if (other.pointer == axis.pointer) fail_sweep(where + ".path = \"" + axis.path + "\" is swept twice");
    }
    sweep.axes.push_back(std::move(axis));
  }
  std::size_t rows = sweep.zip ? sweep.axes.front().values.size() : 1;
  for (const auto& axis : sweep.axes) {
    if (sweep.zip) {
      if (axis.values.size() != rows) {
        fail_sweep("combine \"zip\" needs axes of one length: " + axis.path + " has " + std::to_string(axis.values.size()) +
             " values, " + sweep.axes.front().path + " has " + std::to_string(rows));
      }
    } else {
      if (rows > max_sweep_rows / axis.values.size()) fail_sweep("more than " + std::to_string(max_sweep_rows) + " rows");
      rows *= axis.values.size();
    }
  }
  sweep.rows = rows;
  return sweep;
}

std::vector<json> row_values(const sweep_spec& sweep, std::size_t row) {
  std::vector<json> out(sweep.axes.size());
  if (sweep.zip) {
    for (std::size_t k = 0; k < sweep.axes.size(); ++k) out[k] = sweep.axes[k].values[row];
    return out;
  }
  for (std::size_t k = sweep.axes.size(); k-- > 0;) {  // the last axis varies fastest
    const auto n = sweep.axes[k].values.size();
    out[k] = sweep.axes[k].values[row % n];
    row /= n;
  }
  return out;
}

json row_scene(const sweep_spec& sweep, std::size_t row) {
  json scene = sweep.base;
  const auto values = row_values(sweep, row);
  for (std::size_t k = 0; k < values.size(); ++k) scene[sweep.axes[k].pointer] = values[k];
  return scene;
}

std::vector<std::string> row_columns(const sweep_spec& sweep) {
  std::vector<std::string> cols{"row"};
  for (const auto& axis : sweep.axes) cols.push_back(axis.path);
  for (const char* c : {"tolerance", "acceptance"}) cols.emplace_back(c);  // row_options
  if (sweep.profile) cols.emplace_back("profile_knots");
  for (const char* c : {"status", "alpha", "E1", "omega0", "alpha_tan_delta"}) cols.emplace_back(c);
  for (std::size_t i = 0; i < sweep.indentors; ++i) {
    const std::string p = "ind" + std::to_string(i) + "_";
    for (const char* c : {"a", "b", "contact_length", "load", "C_f", "total_friction"}) cols.push_back(p + c);
  }
  // A sampled profile: its contacts' count and the body's friction and contact fraction.
  if (sweep.profile)
    for (const char* c : {"contacts", "C_f", "C_f_error", "total_friction", "contact_fraction"}) cols.emplace_back(c);
  for (const char* c : {"residual", "seconds", "message"}) cols.emplace_back(c);
  return cols;
}

std::string header_line(const sweep_spec& sweep, row_format format) {
  if (format == row_format::jsonl) return {};
  std::string line;
  for (const auto& c : row_columns(sweep)) {
    if (!line.empty()) line += ',';  // (a + "," + b: GCC 12 -Wrestrict false positive at -O3, its bug 105329)
    line += csv_field(c);
  }
  return line + "\n";
}

std::string row_prefix(const sweep_spec& sweep, std::size_t row, row_format format) {
  const auto values = row_values(sweep, row);
  std::string out;
  if (format == row_format::csv) {
    out = std::to_string(row) + ",";
    for (const auto& v : values) out += value_text(v, format) + ",";
  } else {
    out = "{\"row\":" + std::to_string(row) + ",";
    for (std::size_t k = 0; k < values.size(); ++k) out += json(sweep.axes[k].path).dump() + ":" + values[k].dump() + ",";
  }
  return out;
}

std::string row_options(const sweep_spec& sweep, row_format format, const run_request& request) {
  std::vector<std::pair<const char*, std::string>> fields{
      {"tolerance", number_text(request.tolerance)},
      {"acceptance", request.acceptance > 0 ? number_text(request.acceptance) : std::string()}};
  if (sweep.profile) fields.emplace_back("profile_knots", request.profile_knots ? "true" : "false");
  std::string out;
  for (const auto& [name, text] : fields) {
    if (format == row_format::csv) out += text + ",";
    else out += json(name).dump() + ":" + (text.empty() ? "null" : text) + ",";
  }
  return out;
}

bool is_complete_row(const sweep_spec& sweep, row_format format, std::string_view line) {
  if (line.size() < 2 || line.back() != '\n') return false;
  line.remove_suffix(1);
  const auto columns = row_columns(sweep);
  if (format == row_format::jsonl) {
    const json row = json::parse(line.begin(), line.end(), nullptr, false);
    if (!row.is_object() || row.size() != columns.size()) return false;
    for (const auto& c : columns) {
      if (!row.contains(c)) return false;
    }
    return true;
  }
  std::size_t fields = 1;
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (c == '\n' || c == '\r') return false;
    if (quoted) {
      if (c == '"') {
        if (i + 1 < line.size() && line[i + 1] == '"') ++i;
        else quoted = false;
      }
    } else if (c == '"') {
      if (i > 0 && line[i - 1] != ',') return false;  // a quote only opens a field
      quoted = true;
    } else if (c == ',') {
      ++fields;
    }
  }
  return !quoted && fields == columns.size();
}

std::string solve_row(const sweep_spec& sweep, std::size_t row, row_format format, bool& ok, const run_request& request) {
  const auto columns = row_columns(sweep);
  // The columns from the status on (those before are row_prefix's and row_options').
  const auto status_column = std::find(columns.begin() + 1 + static_cast<std::ptrdiff_t>(sweep.axes.size()),
                                       columns.end(), std::string("status"));
  const auto first_output = static_cast<std::size_t>(status_column - columns.begin());
  std::vector<std::string> fields(columns.size() - first_output);  // status .. message, as text ("" = empty)
  auto set = [&](const std::string& column, const std::string& text) {
    for (std::size_t j = first_output; j < columns.size(); ++j) {
      if (columns[j] == column) fields[j - first_output] = text;
    }
  };
  std::string status = "ok", message;
  const auto start = std::chrono::steady_clock::now();
  try {
    scene_spec scene;
    try {
      scene = parse_scene_value(row_scene(sweep, row), "(row " + std::to_string(row) + ")");
    } catch (const input_error& e) {
      status = "invalid_scene";
      throw;
    }
    std::string warning;
    const run_outcome outcome = run_scene_with_material(scene, request, &warning);
    // The row's fields from the typed result (the same doubles as the result document's).
    const auto diagnostics = [&](const auto& d) {
      status = punch::to_string(d.code);
      message = status == "ok" ? std::string() : d.status;
    };
    std::visit([&](const auto& r) { diagnostics(r.diagnostics); }, outcome.solved);
    set("alpha", number_text(outcome.fit ? outcome.fit->fit.alpha : scene.material.alpha));
    set("E1", number_text(outcome.fit ? outcome.fit->fit.E1 : scene.material.E1));
    if (outcome.fit) {
      set("omega0", number_text(outcome.fit->fit.omega0));
      set("alpha_tan_delta", number_text(outcome.fit->fit.alpha_tan_delta));
      if (status == "ok" && outcome.fit->status != materials::fit_status::ok) {
        status = materials::to_string(outcome.fit->status);
        message = outcome.fit->warning;
      }
    }
    if (const auto* r = std::get_if<punch::profile_bem_result>(&outcome.solved)) {  // profile.solver "boundary_element"
      set("contacts", std::to_string(r->patches.size()));
      set("C_f", number_text(r->hysteretic_friction.value));
      set("C_f_error", number_text(r->hysteretic_friction.error));
      set("total_friction", number_text(r->total_friction));
      set("contact_fraction", number_text(r->contact_fraction.value));
    } else if (const auto* p = std::get_if<punch::profile_result>(&outcome.solved)) {
      // The spectral search: the body's values (load-weighted over the contacts; per period).
      set("contacts", std::to_string(p->contacts.size()));
      double load = 0;
      for (const auto& c : p->contacts) load += c.load;
      if (load > 0) set("C_f", number_text(p->hysteretic_friction)), set("total_friction", number_text(p->total_friction));
      set("contact_fraction", number_text(p->contact_fraction));
    } else {
      const auto& r = std::get<punch::scene_result>(outcome.solved);
      for (std::size_t i = 0; i < r.indentors.size(); ++i) {
        const std::string prefix = "ind" + std::to_string(i) + "_";
        const auto& ind = r.indentors[i];
        set(prefix + "a", number_text(ind.a));
        set(prefix + "b", number_text(ind.b));
        set(prefix + "contact_length", number_text(ind.contact_length));
        set(prefix + "load", number_text(ind.load));
        set(prefix + "C_f", number_text(ind.hysteretic_friction));
        set(prefix + "total_friction", number_text(ind.total_friction));
      }
    }
    std::visit(
        [&](const auto& r) {
          if constexpr (requires { r.diagnostics.residual; }) set("residual", number_text(r.diagnostics.residual));
        },
        outcome.solved);
  } catch (const input_error& e) {
    if (status == "ok") status = "no_solution";
    message = e.what();
  } catch (const std::exception& e) {
    status = "error";
    message = e.what();
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", seconds);
  set("seconds", buf);
  set("status", status);
  set("message", one_line(message));
  ok = status == "ok";

  std::string line = row_prefix(sweep, row, format) + row_options(sweep, format, request);
  for (std::size_t j = 0; j < fields.size(); ++j) {
    const auto& name = columns[first_output + j];
    const auto& text = fields[j];
    const bool is_string = name == "status" || name == "message";
    if (format == row_format::csv) {
      line += (j ? "," : "") + (is_string ? csv_field(text) : text);
    } else {
      line += (j ? "," : "") + json(name).dump() + ":" + (is_string ? json(text).dump() : text.empty() ? "null" : text);
    }
  }
  return line + (format == row_format::csv ? "\n" : "}\n");
}

sweep_pool::sweep_pool(const sweep_spec& sweep, row_format format, std::vector<std::size_t> rows, std::size_t threads,
                       const run_request& request)
    : sweep_(sweep), format_(format), rows_(std::move(rows)), request_(request) {
  threads = std::max<std::size_t>(1, std::min(threads, rows_.size()));
  if (rows_.empty()) return;
  for (std::size_t t = 0; t < threads; ++t) workers_.emplace_back([this] { work(); });
}

sweep_pool::~sweep_pool() {
  stop_ = true;
  for (auto& w : workers_) w.join();
}

std::vector<finished_row> sweep_pool::take(std::chrono::milliseconds wait) {
  std::unique_lock lock(mutex_);
  ready_.wait_for(lock, wait, [this] { return !done_.empty(); });
  std::vector<finished_row> out(std::make_move_iterator(done_.begin()), std::make_move_iterator(done_.end()));
  done_.clear();
  return out;
}

void sweep_pool::work() {
  for (;;) {
    const std::size_t k = next_.fetch_add(1);
    if (k >= rows_.size() || stop_) return;
    bool ok = false;
    std::string line = solve_row(sweep_, rows_[k], format_, ok, request_);
    {
      std::lock_guard lock(mutex_);
      done_.push_back({rows_[k], std::move(line)});
    }
    ready_.notify_one();
  }
}

}  // namespace rhabel::scene
