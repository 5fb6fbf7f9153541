// scene/src/scene.cpp: parsing and validation of the scene file (see rhabel/scene/scene.hpp).
#include "rhabel/scene/scene.hpp"

#include "rhabel/scene/error.hpp"

#include <nlohmann/json.hpp>
#include <rhabel/materials/text_file.hpp>

#include <cmath>
#include <cstddef>
#include <initializer_list>
#include <filesystem>
#include <fstream>
#include <set>
#include <system_error>
#include <sstream>
#include <string>
#include <vector>

namespace rhabel::scene {

const char* shape_name(shape_kind shape) noexcept {
  switch (shape) {
    case shape_kind::parabolic: return "parabolic";
    case shape_kind::wedge: return "wedge";
    case shape_kind::flat: return "flat";
  }
  return "unknown";
}

namespace {

using json = nlohmann::json;

// A message must stay on one line whatever the input contained (commands.hpp: one_line).
[[noreturn]] void fail_scene(const std::string& message) { throw input_error("solve: " + one_line(message)); }

// What nlohmann-json does not check safely, found by one pass over the bytes before parsing:
// - a NUL byte: nlohmann's lexer takes it for the end of the input and accepted
//   "SCENE\0 garbage {{{" as SCENE (issue 14), so the rest of the input was never read;
// - nesting deeper than max_scene_depth: a value nested ~75,000 deep crashed the program with a
//   stack overflow (recursive dump and destruction of the value; issue 14). The scan counts
//   [ and { outside strings only, so it refuses before any value exists.
// Byte offsets count from 0.
void check_bytes(std::string_view text, const std::string& source) {
  std::size_t depth = 0;
  bool in_string = false, escaped = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '\0') {
      fail_scene("scene " + source + " contains a NUL byte at byte offset " + std::to_string(i) +
           " (the whole input must be one JSON object)");
    }
    if (in_string) {
      if (escaped) {
        escaped = false;
      } else if (c == '\\') {
        escaped = true;
      } else if (c == '"') {
        in_string = false;
      }
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > max_scene_depth) {
        fail_scene("scene " + source + " nests arrays and objects deeper than the limit of " +
             std::to_string(max_scene_depth) + " levels (at byte offset " + std::to_string(i) + ")");
      }
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
    }
  }
}

// A value (at nesting level `level`, the top-level being 1) nested deeper than max_scene_depth;
// the recursion stops there, so it is bounded whatever the value.
bool nested_deeper(const json& value, std::size_t level) {
  if (!value.is_structured()) return false;
  if (level > max_scene_depth) return true;
  for (const auto& item : value) {
    if (nested_deeper(item, level + 1)) return true;
  }
  return false;
}

// The scene's syntax is checked by nlohmann-json; this callback adds what it does not check:
// duplicate keys. It tracks the path of the value being parsed so that the message can name it.
class duplicate_key_guard {
 public:
  bool operator()(int /*depth*/, json::parse_event_t event, json& parsed) {
    switch (event) {
      case json::parse_event_t::object_start: frames_.push_back(frame{true, {}, 0, {}}); break;
      case json::parse_event_t::array_start: frames_.push_back(frame{false, {}, 0, {}}); break;
      case json::parse_event_t::key: {
        auto& top = frames_.back();
        const auto key = parsed.get<std::string>();
        if (!top.keys.insert(key).second) {
          top.key = key;
          fail_scene(path() + " appears twice in the same object (duplicate keys are rejected: which one was meant?)");
        }
        top.key = key;
        break;
      }
      case json::parse_event_t::value: element_done(); break;
      case json::parse_event_t::object_end:
      case json::parse_event_t::array_end:
        frames_.pop_back();
        element_done();
        break;
    }
    return true;  // keep everything
  }

  // Path of the value being parsed now (valid also after the lexer threw).
  std::string path() const {
    std::string out;
    for (const auto& f : frames_) {
      if (f.object) {
        if (!out.empty()) out += '.';
        out += f.key;
      } else {
        out += '[' + std::to_string(f.index) + ']';
      }
    }
    return out.empty() ? "(top level)" : out;
  }
 private:
  struct frame {
    bool object;
    std::string key;          // current key (object)
    std::size_t index;        // elements completed so far (array)
    std::set<std::string> keys;
  };
  void element_done() {
    if (!frames_.empty() && !frames_.back().object) ++frames_.back().index;
  }
  std::vector<frame> frames_;
};

std::string type_of(const json& value) {
  if (value.is_null()) return "null";
  if (value.is_boolean()) return "a boolean";
  if (value.is_string()) return "a string";
  if (value.is_array()) return "an array";
  if (value.is_object()) return "an object";
  return "a number";
}

std::string show(const json& value) {
  if (value.is_number_float() && !std::isfinite(value.get<double>())) {
    return value.get<double>() > 0 ? "+inf" : "-inf";
  }
  std::string text = value.dump();
  if (text.size() > 40) text = text.substr(0, 37) + "...";
  return text;
}

std::string child(const std::string& parent, const std::string& key) {
  return parent.empty() ? key : parent + "." + key;
}

// Valid ranges of the numeric fields, with their printed form.
struct range {
  double lo, hi;
  bool lo_open, hi_open;
  const char* text;
  bool contains(double x) const {
    return (lo_open ? x > lo : x >= lo) && (hi_open ? x < hi : x <= hi);
  }
};
constexpr double inf = HUGE_VAL;
constexpr range positive{0, inf, true, true, "(0, inf)"};
constexpr range non_negative{0, inf, false, true, "[0, inf)"};
constexpr range any_finite{-inf, inf, true, true, "(-inf, inf)"};
constexpr range alpha_range{0, 1, false, true, "[0, 1)"};
constexpr range poisson_range{0, 0.5, false, false, "[0, 0.5]"};
constexpr range max_panels_range{256, 8388608, false, false, "[256, 8388608]"};

// Checks that `object` (at `path`) has only the listed keys.
void only_keys(const json& object, const std::string& path, std::initializer_list<const char*> allowed,
               const std::string& context = {}) {
  for (const auto& item : object.items()) {
    bool known = false;
    std::string list;
    for (const char* name : allowed) {
      known = known || item.key() == name;
      list += list.empty() ? name : std::string(", ") + name;
    }
    if (!known) {
      fail_scene(child(path, item.key()) + " is not a known field" + context + " (known: " + list + ")");
    }
  }
}

const json& require(const json& object, const std::string& path, const char* key, const std::string& what) {
  const auto it = object.find(key);
  if (it == object.end()) fail_scene(child(path, key) + " is missing: " + what);
  return *it;
}

double number(const json& value, const std::string& path, const range& valid, const std::string& what) {
  if (!value.is_number()) {
    fail_scene(path + " must be a number in " + valid.text + " (" + what + "), got " + type_of(value) + " " + show(value));
  }
  const double x = value.get<double>();
  if (!std::isfinite(x)) {
    fail_scene(path + " = " + show(value) + " overflows a double; valid range " + valid.text + " (" + what + ")");
  }
  if (!valid.contains(x)) {
    fail_scene(path + " = " + show(value) + " is outside the valid range " + valid.text + " (" + what + ")");
  }
  return x;
}

double required_number(const json& object, const std::string& path, const char* key, const range& valid,
                       const std::string& what) {
  const auto& value =
      require(object, path, key, std::string("a number in ") + valid.text + " is required (" + what + ")");
  return number(value, child(path, key), valid, what);
}

std::string optional_string(const json& object, const std::string& path, const char* key) {
  const auto it = object.find(key);
  if (it == object.end()) return {};
  if (!it->is_string()) fail_scene(child(path, key) + " must be a string, got " + type_of(*it) + " " + show(*it));
  return it->get<std::string>();
}

void require_object(const json& value, const std::string& path) {
  if (!value.is_object()) fail_scene(path + " must be a JSON object {...}, got " + type_of(value) + " " + show(value));
}

material_spec parse_material(const json& value, const std::string& base_dir) {
  const std::string path = "material";
  require_object(value, path);
  if (value.contains("master_curve")) {
    only_keys(value, path, {"master_curve", "temperature", "wlf", "nu", "coulomb", "name"},
              " of a master-curve material (alpha and E1 are fitted from the curve)");
    material_spec m;
    master_curve_spec c;
    const auto& file = value.at("master_curve");
    if (!file.is_string() || file.get<std::string>().empty()) {
      fail_scene("material.master_curve must be a non-empty string (a CSV file name), got " + type_of(file) + " " + show(file));
    }
    c.path = file.get<std::string>();
    // A NUL byte ends the name for the operating system: "c.csv\u0000junk" would read c.csv.
    if (c.path.find('\0') != std::string::npos) {
      fail_scene("material.master_curve = " + show(file) + " contains a NUL byte (\\u0000): not a file name");
    }
    c.resolved_path = base_dir.empty() || c.path.front() == '/' ? c.path : base_dir + "/" + c.path;
    const bool has_t = value.contains("temperature"), has_wlf = value.contains("wlf");
    if (has_t != has_wlf) {
      fail_scene(std::string("material.") + (has_t ? "wlf" : "temperature") + " is missing: \"temperature\" and \"wlf\" " +
           "go together (the WLF shift of the master curve to that temperature)");
    }
    if (has_t) {
      c.shifted = true;
      c.temperature = number(value.at("temperature"), "material.temperature", any_finite, "temperature, same unit as wlf.T_ref");
      const auto& wlf = value.at("wlf");
      require_object(wlf, "material.wlf");
      only_keys(wlf, "material.wlf", {"C1", "C2", "T_ref"});
      c.C1 = required_number(wlf, "material.wlf", "C1", positive, "WLF constant C1");
      c.C2 = required_number(wlf, "material.wlf", "C2", positive, "WLF constant C2, a temperature difference");
      c.T_ref = required_number(wlf, "material.wlf", "T_ref", any_finite, "reference temperature of the master curve");
    }
    m.nu = required_number(value, path, "nu", poisson_range, "Poisson ratio");
    m.coulomb = required_number(value, path, "coulomb", non_negative, "Coulomb friction coefficient");
    m.name = optional_string(value, path, "name");
    m.curve = std::move(c);
    return m;
  }
  only_keys(value, path, {"alpha", "E1", "nu", "coulomb", "name"});  // or the master-curve form above
  material_spec m;
  m.alpha = required_number(value, path, "alpha", alpha_range, "power-law exponent of E(t) = E1 t^-alpha");
  m.E1 = required_number(value, path, "E1", positive, "modulus coefficient of E(t) = E1 t^-alpha");
  m.nu = required_number(value, path, "nu", poisson_range, "Poisson ratio");
  m.coulomb = required_number(value, path, "coulomb", non_negative, "Coulomb friction coefficient");
  m.name = optional_string(value, path, "name");
  return m;
}

indentor_spec parse_indentor(const json& value, const std::string& path, bool body) {
  require_object(value, path);
  indentor_spec d;
  const auto& shape = require(value, path, "shape", "one of \"parabolic\", \"wedge\", \"flat\" is required");
  if (!shape.is_string()) {
    fail_scene(child(path, "shape") + " must be one of \"parabolic\", \"wedge\", \"flat\", got " + type_of(shape) + " " +
         show(shape));
  }
  const auto name = shape.get<std::string>();
  const std::string context = " for shape \"" + name + "\"";
  // Python's rhabel/_scene.py mirrors these checks and their order (the messages are compared).
  if (name == "parabolic" || name == "wedge" || name == "flat") {
    if (body && value.contains("load"))
      fail_scene(child(path, "load") + " is not used on a rigid body (the body's load is split over the indentors): remove it");
    if (!body && value.contains("height"))
      fail_scene(child(path, "height") + " needs a rigid body (\"body\": {\"load\": ...}): remove it or add the body");
  }
  const char* own = body ? "height" : "load";
  if (name == "parabolic") {
    d.shape = shape_kind::parabolic;
    only_keys(value, path, {"shape", own, "apex", "name", "radius"}, context);
    d.radius = required_number(value, path, "radius", positive, "radius of curvature of the parabola");
  } else if (name == "wedge") {
    d.shape = shape_kind::wedge;
    only_keys(value, path, {"shape", own, "apex", "name", "slope_leading", "slope_trailing"}, context);
    d.slope_leading = required_number(value, path, "slope_leading", positive, "slope of the face at x < apex");
    d.slope_trailing = required_number(value, path, "slope_trailing", positive, "slope of the face at x > apex");
  } else if (name == "flat") {
    d.shape = shape_kind::flat;
    only_keys(value, path, {"shape", own, "apex", "name", "width"}, context);
    d.width = required_number(value, path, "width", positive, "width of the flat face");
  } else {
    fail_scene(child(path, "shape") + " = " + show(shape) + " is not a known shape (valid: \"parabolic\", \"wedge\", \"flat\")");
  }
  if (body) {
    if (const auto it = value.find("height"); it != value.end())
      d.height = number(*it, child(path, "height"), any_finite, "height of the apex on the body");
  } else {
    d.load = required_number(value, path, "load", positive, "normal force per unit length");
  }
  if (const auto it = value.find("apex"); it != value.end()) {
    d.apex = number(*it, child(path, "apex"), any_finite, "apex position");
  }
  d.name = optional_string(value, path, "name");
  return d;
}

std::vector<double> number_array(const json& value, const std::string& path, const std::string& what) {
  if (!value.is_array()) fail_scene(path + " must be an array of numbers (" + what + "), got " + type_of(value) + " " + show(value));
  std::vector<double> out;
  out.reserve(value.size());
  for (std::size_t i = 0; i < value.size(); ++i)
    out.push_back(number(value[i], path + "[" + std::to_string(i) + "]", any_finite, what));
  return out;
}

// The two-column CSV of a profile: x,z per line (comma, semicolon, tab or blanks between them);
// an optional first line that is not numeric (a header) and lines starting with # are skipped.
void read_profile_csv(const std::string& path, const std::string& shown, profile_spec& p) {
  std::string text;
  try {  // only a regular file, with a bound: a device (/dev/zero) or a pipe would be read forever
    text = materials::read_text_file(path, "profile.file");
  } catch (const std::invalid_argument& e) {
    fail_scene("profile.file = \"" + shown + "\" is not a readable regular file (" + e.what() + ")");
  }
  std::istringstream in{std::string(materials::without_bom(text))};
  std::string line;
  std::size_t number_of_line = 0;
  while (std::getline(in, line)) {
    ++number_of_line;
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    for (char& c : line)
      if (c == ',' || c == ';' || c == '\t' || c == '\r') c = ' ';
    std::istringstream fields(line);
    double x = 0, z = 0;
    std::string rest;
    const bool numeric = static_cast<bool>(fields >> x >> z);
    if (!numeric && p.x.empty() && number_of_line == 1) continue;  // a header
    if (!numeric || (fields >> rest) || !std::isfinite(x) || !std::isfinite(z))
      fail_scene("profile.file = \"" + shown + "\" line " + std::to_string(number_of_line) +
           ": expected two finite numbers x,z, got \"" + line.substr(0, 80) + "\"");
    p.x.push_back(x);
    p.z.push_back(z);
  }
}

profile_spec parse_profile(const json& value, const std::string& base_dir) {
  require_object(value, "profile");
  profile_spec p;
  if (value.contains("file")) {
    only_keys(value, "profile", {"file", "corners", "period", "solver", "max_panels"}, " with a file");
    p.file = optional_string(value, "profile", "file");
    const std::filesystem::path path(p.file);
    read_profile_csv(path.is_absolute() || base_dir.empty() ? p.file : (std::filesystem::path(base_dir) / path).string(),
                     p.file, p);
  } else {
    only_keys(value, "profile", {"x", "z", "corners", "period", "solver", "max_panels"});
    p.x = number_array(require(value, "profile", "x", "the sample abscissae (or \"file\")"), "profile.x", "sample abscissa");
    p.z = number_array(require(value, "profile", "z", "the sample heights"), "profile.z", "sample height");
  }
  if (const auto it = value.find("corners"); it != value.end())
    p.corners = number_array(*it, "profile.corners", "abscissa of a slope jump");
  if (const auto it = value.find("period"); it != value.end())
    p.period = number(*it, "profile.period", positive, "the period: the samples lie in [x_0, x_0 + period)");
  // The solver: the spectral contact search or the boundary-element method, both finite or
  // periodic; the boundary-element method by default with a period (it takes any load and any
  // number of patches; the spectral search is the accurate one where it succeeds: README).
  const std::string solver = optional_string(value, "profile", "solver");
  if (solver.empty()) {
    p.boundary_element = p.period > 0;
  } else if (solver == "boundary_element") {
    p.boundary_element = true;
  } else if (solver == "spectral") {
    p.boundary_element = false;
  } else {
    fail_scene("profile.solver = \"" + solver.substr(0, 40) + "\" is not a solver (known: spectral, boundary_element)");
  }
  if (const auto it = value.find("max_panels"); it != value.end()) {
    if (!p.boundary_element)
      fail_scene("profile.max_panels bounds the grids of profile.solver \"boundary_element\"; the spectral solver has none");
    const double m = number(*it, "profile.max_panels", max_panels_range,
                            "the finest grid's panels, ~130 bytes each; a whole number");
    if (m != std::floor(m)) fail_scene("profile.max_panels = " + show(*it) + " must be a whole number of panels");
    p.max_panels = static_cast<std::size_t>(m);
  }
  return p;
}

// The scene of a parsed value whose nesting is bounded: its fields validated.
scene_spec scene_of(const json& root, const std::string& source, const std::string& base_dir) {
  if (!root.is_object()) fail_scene("scene " + source + ": the top level must be a JSON object {...}, got " + type_of(root));
  only_keys(root, "", {"description", "material", "speed", "body", "indentors", "profile"});

  scene_spec scene;
  scene.description = optional_string(root, "", "description");
  scene.material = parse_material(require(root, "", "material", "an object {alpha, E1, nu, coulomb} is required"), base_dir);
  scene.speed = required_number(root, "", "speed", positive, "sliding speed");
  if (const auto it = root.find("body"); it != root.end()) {
    require_object(*it, "body");
    only_keys(*it, "body", {"load"});
    scene.body_load = required_number(*it, "body", "load", positive, "total normal force per unit length");
  }
  if (const auto it = root.find("profile"); it != root.end()) {
    if (root.contains("indentors")) fail_scene("indentors and profile are exclusive: give one of them");
    if (!scene.body_load) fail_scene("profile needs a rigid body with its total load: add \"body\": {\"load\": ...}");
    scene.profile = parse_profile(*it, base_dir);
    return scene;
  }
  const auto& list = require(root, "", "indentors", "a non-empty array of indentors is required");
  if (!list.is_array()) fail_scene("indentors must be a non-empty array [...], got " + type_of(list) + " " + show(list));
  if (list.empty()) fail_scene("indentors is empty: at least one indentor is required");
  for (std::size_t i = 0; i < list.size(); ++i) {
    scene.indentors.push_back(parse_indentor(list[i], "indentors[" + std::to_string(i) + "]", scene.body_load.has_value()));
  }
  return scene;
}

}  // namespace

scene_spec parse_scene(std::string_view text, const std::string& source, const std::string& base_dir) {
  check_bytes(text, source);
  json root;
  duplicate_key_guard guard;
  try {
    root = json::parse(text.begin(), text.end(),
                       [&guard](int depth, json::parse_event_t event, json& parsed) {
                         return guard(depth, event, parsed);
                       });
  } catch (const json::parse_error& e) {
    // nlohmann's message: "[json.exception.parse_error.101] parse error at line 1, column 3: ..."
    std::string what = e.what();
    if (const auto at = what.find("] "); at != std::string::npos) what = what.substr(at + 2);
    // e.byte counts the bytes read, the offending one included: its offset is e.byte - 1.
    const std::size_t offset = e.byte > 0 ? e.byte - 1 : 0;
    fail_scene("scene " + source + " is not valid JSON: " + what + " (byte offset " + std::to_string(offset) + ")");
  } catch (const json::out_of_range& e) {
    // nlohmann-json 3.11 refuses a number beyond the double range ("number overflow parsing
    // '1e400'"); the guard still knows which value was being read.
    std::string what = e.what();
    if (const auto at = what.find("] "); at != std::string::npos) what = what.substr(at + 2);
    fail_scene(guard.path() + " is out of range: " + what + " (numbers must be finite doubles)");
  }
  return scene_of(root, source, base_dir);  // check_bytes has bounded the nesting
}

scene_spec parse_scene_value(const nlohmann::json& root, const std::string& source, const std::string& base_dir) {
  if (nested_deeper(root, 1))
    fail_scene("scene " + source + " nests arrays and objects deeper than the limit of " + std::to_string(max_scene_depth) +
               " levels");
  return scene_of(root, source, base_dir);
}

}  // namespace rhabel::scene
