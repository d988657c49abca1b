// The JSON input reader and validator (docs/input.md is the user's reference for every key).
//
// Three small pieces do the work:
//   Issues  collects every problem (path, value, expected) instead of stopping at the first;
//   Value   one JSON value and its path: typed accessors return std::optional and record an issue
//           when the value is missing (if required) or of the wrong type or range;
//   Object  a JSON object with a fixed list of allowed keys: unknown keys are reported on sight.
// (all three in io/input/json_value.hpp; the keywords in io/input/keywords.hpp.)
// SpecReader (io/input/spec_reader.hpp) walks the input section by section with them and fills a
// Spec; each section has its file, io/input/read_SECTION.cpp, and SpecReader::read below names the
// sections in order. Defaults are the initial values of the Spec structs (or given with value_or);
// no exception is used to fill them.
#include "matpoint/io/input.hpp"

#include <algorithm>
#include <cassert>
#include <cctype>
#include <climits>
#include <cmath>
#include <fstream>
#include <initializer_list>
#include <iomanip>
#include <limits>
#include <set>
#include <sstream>
#include <string_view>
#include <utility>

#include "matpoint/analysis/measures.hpp"
#include "matpoint/core/errors.hpp"
#include "matpoint/io/input/keywords.hpp"
#include "matpoint/io/input/spec_reader.hpp"
#include "matpoint/io/memory_estimate.hpp"
#include "matpoint/io/particle_fields.hpp"
#include "matpoint/shape/stencil_width.hpp"

namespace matpoint {

double TimeFunction::operator()(double t) const {
  if (times.empty()) return values.empty() ? 0.0 : values.front();
  if (t <= times.front()) return values.front();
  if (t >= times.back()) return values.back();
  const auto k = static_cast<std::size_t>(std::upper_bound(times.begin(), times.end(), t) - times.begin());
  const double s = (t - times[k - 1]) / (times[k] - times[k - 1]);  // times[k-1] <= t < times[k]
  return values[k - 1] + s * (values[k] - values[k - 1]);
}

double TimeFunction::integral(double t) const {
  if (times.empty()) return (values.empty() ? 0.0 : values.front()) * t;
  double sum = 0.0, t0 = 0.0;
  auto add = [&](double a, double b) {  // integral over [a, b] of the interpolant, a < b
    if (b > a) sum += 0.5 * ((*this)(a) + (*this)(b)) * (b - a);
  };
  for (double knot : times) {
    if (knot >= t) break;
    if (knot > t0) {
      add(t0, knot);
      t0 = knot;
    }
  }
  add(t0, t);
  return sum;
}

namespace input_detail {

// ---------------------------------------------------------------------------------------------
// Parsing: JSON syntax and repeated keys

/// A parser callback that reports keys given twice in one object (nlohmann::json keeps the last).
class RepeatedKeyFinder {
 public:
  explicit RepeatedKeyFinder(Issues& issues) : issues_(issues) {}

  bool on_event(json::parse_event_t event, const json& parsed) {
    switch (event) {
      case json::parse_event_t::object_start:
        frames_.push_back({true, {}, 0, {}});
        break;
      case json::parse_event_t::array_start:
        frames_.push_back({false, {}, 0, {}});
        break;
      case json::parse_event_t::key:
        on_key(parsed.get<std::string>());
        break;
      case json::parse_event_t::object_end:
      case json::parse_event_t::array_end:
        frames_.pop_back();
        element_done();
        break;
      case json::parse_event_t::value:
        element_done();
        break;
    }
    return true;
  }

 private:
  struct Frame {
    bool is_object;
    std::string key;             // current key (objects)
    std::size_t index;           // current index (arrays)
    std::set<std::string> keys;  // keys seen so far (objects)
  };

  void on_key(const std::string& key) {
    Frame& top = frames_.back();
    top.key = key;
    if (!top.keys.insert(key).second)
      issues_.add(path(), "a repeated key", "each key at most once in an object");
  }
  void element_done() {
    if (!frames_.empty() && !frames_.back().is_object) ++frames_.back().index;
  }
  [[nodiscard]] std::string path() const {
    std::string out;
    // Appended piece by piece: "[" + std::to_string(...) trips a GCC 12 -Wrestrict false positive.
    for (const auto& frame : frames_) {
      if (frame.is_object) {
        if (!out.empty()) out += '.';
        out += cut(frame.key);
      } else {
        out += '[';
        out += std::to_string(frame.index);
        out += ']';
      }
    }
    return out;
  }

  Issues& issues_;
  std::vector<Frame> frames_;
};

/// Thrown by the parser callback when arrays/objects nest deeper than kMaxJsonDepth: deeper values
/// are refused before anything walks them recursively (dumping one for a message would overflow
/// the stack; found by the fuzzer, tests/inputs/bad/deeply_nested.json).
struct TooDeep {};

/// Parses the text (comments allowed); a syntax error becomes an issue and nullopt.
std::optional<json> parse_json(const std::string& text, Issues& issues) {
  RepeatedKeyFinder finder(issues);
  const json::parser_callback_t callback = [&finder](int depth, json::parse_event_t event, json& parsed) {
    const bool opens =
        event == json::parse_event_t::object_start || event == json::parse_event_t::array_start;
    if (opens && depth >= kMaxJsonDepth) throw TooDeep{};
    return finder.on_event(event, parsed);
  };
  try {
    return json::parse(text, callback, /*allow_exceptions=*/true, /*ignore_comments=*/true);
  } catch (const TooDeep&) {
    issues.add("(json)", "arrays or objects nested more than " + std::to_string(kMaxJsonDepth) + " deep",
               "an input nested at most " + std::to_string(kMaxJsonDepth) + " levels deep");
    return std::nullopt;
  } catch (const json::exception& e) {
    // "[json.exception.parse_error.101] parse error at line 3, column 7: ...; last read: '...'"
    issues.add("(json)", parse_error_text(e.what()), "valid JSON (comments allowed)");
    return std::nullopt;
  }
}

Spec SpecReader::read(const json& root_json) {
  const Value root(&root_json, "", issues_, true);
  const Object top(root, {"title", "units", "grid", "mesh", "materials", "bodies", "boundary_conditions",
                          "loads", "solver", "output", "checks", "contact", "heat", "fe_bodies"});
  if (!top.valid()) return std::move(spec_);
  set_if(spec_.title, top.optional("title").string());
  read_units(Object(top.optional("units"), {"length", "time", "mass", "stress", "energy"}));
  if (top.has("mesh") && top.has("grid"))
    top.optional("grid").fail("no grid with a mesh (an implicit run's particles are seeded on its mesh)");
  else if (top.has("mesh"))
    read_mesh(Object(top.required("mesh"), {"element", "min", "max", "cells", "ratio", "lines", "diagonal",
                                            "refine", "file", "dim"}));
  else
    read_grid(Object(top.required("grid"), {"dim", "min", "max", "cell_size"}));
  read_materials(top.required("materials"));
  read_bodies(top.required("bodies"), top.has("fe_bodies") ? 0 : 1);
  read_conditions(top.optional("boundary_conditions"));
  read_loads(Object(top.optional("loads"), {"gravity", "gravity_scale", "tractions"}));
  read_solver(Object(top.required("solver"), {"scheme",
                                              "transfer",
                                              "position_alpha",
                                              "flip_fraction",
                                              "fmpm",
                                              "xpic",
                                              "basis",
                                              "shape",
                                              "mapping",
                                              "mls",
                                              "deformation_update",
                                              "dt",
                                              "courant",
                                              "end_time",
                                              "max_steps",
                                              "mass_tolerance",
                                              "constrain_old_velocity",
                                              "artificial_viscosity",
                                              "max_energy_growth",
                                              "rebalance",
                                              "type",
                                              "implicit",
                                              "meshfree"}));
  check_one_sided_transfer(top.optional("boundary_conditions"));
  read_output(Object(top.optional("output"), {"every_steps", "every_time", "particles", "plots", "fields",
                                              "checkpoint", "probes", "node_probes"}));
  read_checks(top.optional("checks"));
  read_contact(top.optional("contact"));
  read_heat(top.optional("heat"));
  read_fe_bodies(top.optional("fe_bodies"));
  if (grid_ok_ && !spec_.mesh.enabled) check_stencil_fits();
  if (issues_.empty()) check_step_count();
  return std::move(spec_);
}

}  // namespace input_detail

using input_detail::Issues;
using input_detail::json;
using input_detail::parse_json;
using input_detail::SpecReader;

Spec parse_spec(const std::string& json_text) {
  Issues issues;
  std::optional<json> root = parse_json(json_text, issues);
  if (!root) throw InputError(issues.take());
  Spec spec = SpecReader(issues).read(*root);
  issues.hint_misplaced_keys();
  if (!issues.empty()) throw InputError(issues.take());
  check_memory(spec);  // refuse, with the estimate, what would end in an out-of-memory kill
  spec.echo = std::move(*root);
  return spec;
}

namespace {

/// What a path that is not a regular file is, for the message.
const char* file_kind(std::filesystem::file_type type) {
  switch (type) {
    case std::filesystem::file_type::not_found:
      return "no such file";
    case std::filesystem::file_type::directory:
      return "a folder";
    case std::filesystem::file_type::fifo:
      return "a named pipe";
    case std::filesystem::file_type::socket:
      return "a socket";
    case std::filesystem::file_type::character:
    case std::filesystem::file_type::block:
      return "a device";
    default:
      return "not a regular file";
  }
}

}  // namespace

Spec load_spec(const std::filesystem::path& file) {
  // The type is tested before the file is opened: opening a named pipe with no writer would wait
  // for one forever, and a device can be endless.
  std::error_code error;
  const auto type = std::filesystem::status(file, error).type();
  if (type != std::filesystem::file_type::regular)
    throw InputError({{file.string(), file_kind(type), "a readable JSON input file"}});
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError({{file.string(), "a file that cannot be read", "a readable JSON input file"}});
  std::ostringstream text;
  text << in.rdbuf();
  return parse_spec(text.str());
}

}  // namespace matpoint
