// The JSON input reader and validator (docs/input.md is the user's reference for every key).
//
// Three small pieces do the work:
//   Issues  collects every problem (path, value, expected) instead of stopping at the first;
//   Value   one JSON value and its path: typed accessors return std::optional and record an issue
//           when the value is missing (if required) or of the wrong type or range;
//   Object  a JSON object with a fixed list of allowed keys: unknown keys are reported on sight.
// SpecReader walks the input section by section with them and fills a Spec. Defaults are the
// initial values of the Spec structs (or given with value_or); no exception is used to fill them.
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

namespace {

using nlohmann::json;

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr std::size_t kMaxValueChars = 200;  // longer values are cut in messages
constexpr double kMaxCells = 1e8;
constexpr double kCellCountTolerance = 1e-9;  // relative
constexpr double kInsideTolerance = 1e-12;    // relative to the domain size
constexpr double kMaxPlausibleSteps = 1e9;    // see check_step_count
constexpr int kMaxJsonDepth = 64;             // see parse_json; the deepest valid input needs about 6

// ---------------------------------------------------------------------------------------------
// Message text

std::string format_number(double x) {
  std::ostringstream out;
  out << std::setprecision(12) << x;
  return out.str();
}

/// The text itself, or its first kMaxValueChars characters and "...": every piece of the input
/// echoed in a message (a value, a key, a token the JSON parser stopped at) is cut this way.
std::string cut(std::string_view text) {
  if (text.size() <= kMaxValueChars) return std::string(text);
  return std::string(text.substr(0, kMaxValueChars)) + "...";
}

std::string dump_value(const json& j) {
  // A huge value is dumped whole first: bounded by the input's size, which the reader holds anyway.
  return cut(j.dump());
}

/// nlohmann's parse error without its "[json.exception...] " prefix and with the token it quotes
/// ("last read: '...'", which can be a whole unterminated comment or a 32 MB number) cut.
std::string parse_error_text(std::string what) {
  if (const auto end = what.find("] "); what.starts_with("[json.exception") && end != std::string::npos)
    what = what.substr(end + 2);
  const std::string_view marker = "last read: '";
  if (const auto start = what.find(marker); start != std::string::npos) {
    const auto token = start + marker.size();
    const auto close = what.rfind('\'');
    const auto length = close != std::string::npos && close >= token ? close - token : what.size() - token;
    what = what.substr(0, token) + cut(std::string_view(what).substr(token, length)) +
           (close != std::string::npos && close >= token ? what.substr(close) : "");
  }
  // The parser's own words are short; this bounds anything else it might quote.
  if (what.size() > 4 * kMaxValueChars) what = what.substr(0, 4 * kMaxValueChars) + "...";
  return what;
}

template <class Range>
std::string join(const Range& items, bool quoted) {
  std::string out;
  for (const auto& item : items) {
    if (!out.empty()) out += ", ";
    if (quoted) out += '"';
    out.append(std::string_view(item));
    if (quoted) out += '"';
  }
  return out;
}

/// A numeric range with open or closed ends; the default is every finite number.
struct Bounds {
  double lo = -kInf, hi = kInf;
  bool lo_open = false, hi_open = false;

  [[nodiscard]] bool contains(double x) const {
    if (!std::isfinite(x)) return false;
    const bool above = lo_open ? x > lo : x >= lo;
    const bool below = hi_open ? x < hi : x <= hi;
    return above && below;
  }
  /// " > 0", " in [0, 1)", or "" for any number: appended to "a number" or "numbers".
  [[nodiscard]] std::string suffix() const {
    const bool has_lo = lo > -kInf, has_hi = hi < kInf;
    if (has_lo && has_hi)
      return " in " + std::string(lo_open ? "(" : "[") + format_number(lo) + ", " + format_number(hi) +
             (hi_open ? ")" : "]");
    if (has_lo) return (lo_open ? " > " : " >= ") + format_number(lo);
    if (has_hi) return (hi_open ? " < " : " <= ") + format_number(hi);
    return "";
  }
};

constexpr Bounds kAnyNumber{};
constexpr Bounds kPositive{0, kInf, true, false};
constexpr Bounds kNonNegative{0, kInf, false, false};
constexpr Bounds kUnitInterval{0, 1, false, false};

std::string numbers_text(int dim, const Bounds& bounds) {
  const std::string count = dim == 0   ? "1 to 3 numbers"
                            : dim == 1 ? "1 number"
                                       : std::to_string(dim) + " numbers";
  return "an array of " + count + bounds.suffix();
}

/// A keyword of the input and the value it stands for.
template <class T>
struct Named {
  std::string_view name;
  T value;
};

template <class T, std::size_t N>
std::string choices_text(const std::array<Named<T>, N>& options) {
  std::vector<std::string_view> names;
  for (const auto& option : options) names.push_back(option.name);
  return "one of " + join(names, true);
}

/// The keyword of `value` among `options`.
template <class T, std::size_t N>
std::string_view name_of(const std::array<Named<T>, N>& options, T value) {
  for (const auto& option : options)
    if (option.value == value) return option.name;
  return "?";
}

constexpr std::array<Named<MaterialModel>, 7> kModels{{{"linear_elastic", MaterialModel::LinearElastic},
                                                       {"neo_hookean", MaterialModel::NeoHookean},
                                                       {"mie_gruneisen", MaterialModel::MieGruneisen},
                                                       {"rigid", MaterialModel::Rigid},
                                                       {"mohr_coulomb", MaterialModel::MohrCoulomb},
                                                       {"drucker_prager", MaterialModel::DruckerPrager},
                                                       {"von_mises", MaterialModel::VonMises}}};
constexpr std::array<Named<DruckerPragerMatch>, 3> kDruckerPragerMatches{
    {{"outer", DruckerPragerMatch::Outer},
     {"inner", DruckerPragerMatch::Inner},
     {"plane_strain", DruckerPragerMatch::PlaneStrain}}};
constexpr std::array<Named<ContactLaw>, 3> kContactLaws{{{"stick", ContactLaw::Stick},
                                                         {"frictionless", ContactLaw::Frictionless},
                                                         {"coulomb", ContactLaw::Coulomb}}};
constexpr std::array<Named<ContactNormals>, 3> kContactNormals{
    {{"mass_gradient", ContactNormals::MassGradient},
     {"average", ContactNormals::Average},
     {"logistic_regression", ContactNormals::Logistic}}};
constexpr std::array<Named<ContactFmpmMethod>, 2> kContactFmpmMethods{
    {{"net", ContactFmpmMethod::Net}, {"evolving", ContactFmpmMethod::Evolving}}};
constexpr std::array<Named<CheckKind>, 3> kCheckKinds{{{"verification", CheckKind::Verification},
                                                       {"regression", CheckKind::Regression},
                                                       {"guard", CheckKind::Guard}}};
constexpr std::array<Named<bool>, 2> kContactFields{{{"bodies", false}, {"materials", true}}};
constexpr std::array<Named<NeoHookeanVolumetric>, 2> kVolumetric{
    {{"log_j", NeoHookeanVolumetric::LogJ}, {"half_j_squared", NeoHookeanVolumetric::HalfJSquared}}};
constexpr std::array<Named<BodyShape>, 4> kShapes{{{"box", BodyShape::Box},
                                                   {"disk", BodyShape::Disk},
                                                   {"sphere", BodyShape::Disk},  // 3-D only
                                                   {"polygon", BodyShape::Polygon}}};
constexpr std::array<Named<ConditionKind>, 4> kConditionKinds{{{"fixed", ConditionKind::Fixed},
                                                               {"slip", ConditionKind::Slip},
                                                               {"velocity", ConditionKind::Velocity},
                                                               {"moving_wall", ConditionKind::MovingWall}}};
constexpr std::array<Named<bool>, 2> kMaterialSides{{{"below", true}, {"above", false}}};
constexpr std::array<Named<int>, 6> kFaces{
    {{"x-", 0}, {"x+", 1}, {"y-", 2}, {"y+", 3}, {"z-", 4}, {"z+", 5}}};  // axis = id / 2, side = id % 2
constexpr std::array<Named<int>, 3> kAxes{{{"x", 0}, {"y", 1}, {"z", 2}}};
constexpr std::array<Named<UpdateScheme>, 6> kSchemes{{{"usl", UpdateScheme::USL},
                                                       {"usf", UpdateScheme::USF},
                                                       {"musl", UpdateScheme::MUSL},
                                                       {"usl+", UpdateScheme::MUSL},
                                                       {"usavg", UpdateScheme::USAVG},
                                                       {"usavg+", UpdateScheme::USAVGPlus}}};
constexpr std::array<Named<VelocityTransfer>, 5> kTransfers{{{"flip", VelocityTransfer::FLIP},
                                                             {"pic", VelocityTransfer::PIC},
                                                             {"blend", VelocityTransfer::Blend},
                                                             {"fmpm", VelocityTransfer::FMPM},
                                                             {"xpic", VelocityTransfer::XPIC}}};
constexpr std::array<Named<FmpmMeasure>, 2> kFmpmMeasures{
    {{"means", FmpmMeasure::Means}, {"changes", FmpmMeasure::Changes}}};
constexpr std::array<Named<FmpmBoundaryMethod>, 2> kFmpmBoundaryMethods{
    {{"incremental", FmpmBoundaryMethod::Incremental}, {"combined", FmpmBoundaryMethod::Combined}}};
constexpr std::array<Named<FmpmRecursion>, 2> kFmpmRecursions{
    {{"incremental", FmpmRecursion::Incremental}, {"binomial", FmpmRecursion::Binomial}}};
constexpr int kMaxFmpmOrder = 1000;
constexpr std::array<Named<ShapeKind>, 9> kShapeKinds{{{"linear", ShapeKind::Linear},
                                                       {"bspline2", ShapeKind::BSpline2},
                                                       {"bspline3", ShapeKind::BSpline3},
                                                       {"ugimp", ShapeKind::UGIMP},
                                                       {"cpgimp", ShapeKind::CpGIMP},
                                                       {"cpdi1", ShapeKind::CPDI1},
                                                       {"cpdi2", ShapeKind::CPDI2},
                                                       {"b2gimp", ShapeKind::B2GIMP},
                                                       {"b2cpdi", ShapeKind::B2CPDI}}};
constexpr std::array<Named<Mapping>, 3> kMappings{
    {{"mpm", Mapping::MPM}, {"impm", Mapping::IMPM}, {"mls_velocity", Mapping::MlsVelocity}}};
constexpr std::array<Named<CellQuadrature>, 2> kCellQuadratures{
    {{"cell_centre", CellQuadrature::Centre}, {"gauss_2x2", CellQuadrature::Gauss2}}};
constexpr std::array<Named<CellVolume>, 2> kCellVolumes{
    {{"cell", CellVolume::Full}, {"particle_fraction", CellVolume::ParticleFraction}}};
constexpr std::array<Named<DeformationUpdate>, 2> kDeformationUpdates{
    {{"exponential", DeformationUpdate::Exponential}, {"linear", DeformationUpdate::Linear}}};

// ---------------------------------------------------------------------------------------------
// Issues, Value, Object

class Issues {
 public:
  void add(std::string path, std::string value, std::string expected) {
    list_.push_back({std::move(path), std::move(value), std::move(expected)});
  }

  /// An unknown key `key` of the object at `parent`: an issue now; where the key does belong is
  /// added by hint_misplaced_keys() once every object's keys are known.
  void add_unknown_key(const std::string& parent, const std::string& key, std::string value,
                       std::string expected) {
    unknown_.push_back({list_.size(), parent, key});
    add(parent.empty() ? cut(key) : parent + "." + cut(key), std::move(value), std::move(expected));
  }

  /// The keys the object at `path` allows (every object the reader looked at, present or not).
  void know_keys(const std::string& path, const std::vector<std::string_view>& keys) {
    for (const auto& key : keys) known_.emplace_back(path, key);
  }

  /// "gravity belongs under loads": an unknown key that another object of the input allows.
  void hint_misplaced_keys() {
    for (const auto& u : unknown_) {
      std::vector<std::string> places;
      for (const auto& [path, key] : known_) {
        if (key != u.key || path == u.parent) continue;
        const std::string place = path.empty() ? "the top level" : generic_path(path);
        if (std::find(places.begin(), places.end(), place) == places.end()) places.push_back(place);
      }
      if (!places.empty())
        list_[u.index].expected += "; " + cut(u.key) + " belongs under " + join(places, false);
    }
  }
  [[nodiscard]] std::size_t size() const { return list_.size(); }
  [[nodiscard]] bool empty() const { return list_.empty(); }
  [[nodiscard]] std::vector<InputIssue> take() { return std::move(list_); }

 private:
  struct UnknownKey {
    std::size_t index;  // in list_
    std::string parent, key;
  };

  /// "bodies[3].shape" -> "bodies[].shape": a place in any element of an array.
  static std::string generic_path(const std::string& path) {
    std::string out;
    for (std::size_t i = 0; i < path.size(); ++i) {
      out += path[i];
      if (path[i] == '[')
        while (i + 1 < path.size() && path[i + 1] != ']') ++i;
    }
    return out;
  }

  std::vector<UnknownKey> unknown_;
  std::vector<std::pair<std::string, std::string_view>> known_;
  std::vector<InputIssue> list_;
};

/// One JSON value (or the absence of one) at a path. Accessors return nullopt, and record an issue,
/// when the value is wrong; an absent value gives nullopt and an issue only when it is required.
class Value {
 public:
  Value(const json* j, std::string path, Issues& issues, bool required)
      : j_(j), path_(std::move(path)), issues_(&issues), required_(required) {}

  [[nodiscard]] bool present() const { return j_ != nullptr; }
  [[nodiscard]] const json& get() const { return *j_; }
  [[nodiscard]] const std::string& path() const { return path_; }
  [[nodiscard]] Issues& issues() const { return *issues_; }

  /// The member `key` of this value when it is an object (absent otherwise).
  [[nodiscard]] Value member(std::string_view key, bool required) const {
    const json* child = nullptr;
    if (j_ != nullptr && j_->is_object()) {
      const auto it = j_->find(std::string(key));
      if (it != j_->end()) child = &*it;
    }
    return {child, path_.empty() ? cut(key) : path_ + "." + cut(key), *issues_, required};
  }

  /// Element `index` of this value, which must be a present array.
  [[nodiscard]] Value element(std::size_t index) const {
    return {&(*j_)[index], path_ + "[" + std::to_string(index) + "]", *issues_, true};
  }

  /// Records "got <this value>, expected <expected>".
  void fail(const std::string& expected) const {
    issues_->add(path_.empty() ? "(root)" : path_, j_ != nullptr ? dump_value(*j_) : "missing", expected);
  }

  /// True when present; records "missing" when absent and required.
  [[nodiscard]] bool usable(const std::string& expected) const {
    if (j_ != nullptr) return true;
    if (required_) fail(expected);
    return false;
  }

  [[nodiscard]] bool expect_object(const std::string& expected) const {
    if (!usable(expected)) return false;
    if (j_->is_object()) return true;
    fail(expected);
    return false;
  }

  [[nodiscard]] std::optional<double> number(const Bounds& bounds = kAnyNumber) const {
    const std::string expected = "a number" + bounds.suffix();
    if (!usable(expected)) return std::nullopt;
    if (!j_->is_number() || !bounds.contains(j_->get<double>())) {
      fail(expected);
      return std::nullopt;
    }
    return j_->get<double>();
  }

  /// An integer in [lo, hi]; a number with a zero fractional part (such as 1e6) counts as one.
  [[nodiscard]] std::optional<long> integer(long lo, long hi = LONG_MAX) const {
    const std::string expected =
        hi == LONG_MAX ? "an integer >= " + std::to_string(lo)
                       : "an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
    if (!usable(expected)) return std::nullopt;
    const std::optional<long> value = integer_value();
    if (!value || *value < lo || *value > hi) {
      fail(expected);
      return std::nullopt;
    }
    return value;
  }

  [[nodiscard]] std::optional<bool> boolean() const {
    if (!usable("true or false")) return std::nullopt;
    if (j_->is_boolean()) return j_->get<bool>();
    fail("true or false");
    return std::nullopt;
  }

  [[nodiscard]] std::optional<std::string> string() const {
    if (!usable("a non-empty string")) return std::nullopt;
    if (j_->is_string() && !j_->get_ref<const std::string&>().empty()) return j_->get<std::string>();
    fail("a non-empty string");
    return std::nullopt;
  }

  template <class T, std::size_t N>
  [[nodiscard]] std::optional<T> choice(const std::array<Named<T>, N>& options) const {
    const std::string expected = choices_text(options);
    if (!usable(expected)) return std::nullopt;
    if (j_->is_string()) {
      const auto& text = j_->get_ref<const std::string&>();
      for (const auto& option : options)
        if (option.name == text) return option.value;
    }
    fail(expected);
    return std::nullopt;
  }

  /// An array of `dim` numbers within `bounds` (1 to 3 numbers when dim is 0, i.e. unknown),
  /// returned with zeros past its length.
  [[nodiscard]] std::optional<Triple> vector(int dim, const Bounds& bounds = kAnyNumber) const {
    const std::string expected = numbers_text(dim, bounds);
    if (!usable(expected)) return std::nullopt;
    const bool size_ok = j_->is_array() && (dim == 0 ? !j_->empty() && j_->size() <= 3
                                                     : j_->size() == static_cast<std::size_t>(dim));
    const bool all_ok = size_ok && std::all_of(j_->begin(), j_->end(), [&](const json& x) {
                          return x.is_number() && bounds.contains(x.get<double>());
                        });
    if (!all_ok) {
      fail(expected);
      return std::nullopt;
    }
    Triple out{};
    for (std::size_t a = 0; a < j_->size(); ++a) out[a] = (*j_)[a].get<double>();
    return out;
  }

  /// The elements of an array with at least `min_size` of them (empty and an issue otherwise).
  [[nodiscard]] std::vector<Value> elements(const std::string& expected, std::size_t min_size = 0) const {
    std::vector<Value> out;
    if (!usable(expected)) return out;
    if (!j_->is_array() || j_->size() < min_size) {
      fail(expected);
      return out;
    }
    for (std::size_t i = 0; i < j_->size(); ++i) out.push_back(element(i));
    return out;
  }

 private:
  [[nodiscard]] std::optional<long> integer_value() const {
    if (j_->is_number_unsigned()) {
      const auto u = j_->get<std::uint64_t>();
      if (u > static_cast<std::uint64_t>(LONG_MAX)) return std::nullopt;
      return static_cast<long>(u);
    }
    if (j_->is_number_integer()) return j_->get<long>();
    if (j_->is_number_float()) {
      const double x = j_->get<double>();
      if (!std::isfinite(x) || std::floor(x) != x || std::abs(x) > 9e18) return std::nullopt;
      return static_cast<long>(x);
    }
    return std::nullopt;
  }

  const json* j_;
  std::string path_;
  Issues* issues_;
  bool required_;
};

/// A JSON object whose keys must come from a fixed list. Unknown keys are reported when it is made;
/// a missing (required) or non-object value is reported once, and the Object is then not valid:
/// its members read as absent and record nothing, so one mistake gives one issue.
class Object {
 public:
  Object(const Value& value, std::initializer_list<std::string_view> keys)
      : value_(value), keys_(keys), valid_(value.expect_object("an object with the keys: " + keys_text())) {
    value.issues().know_keys(value.path(), keys_);
    if (!valid_) return;
    for (const auto& [key, child] : value.get().items())
      if (!allowed(key))
        value.issues().add_unknown_key(value.path(), key, dump_value(child),
                                       "one of the keys: " + keys_text());
  }

  [[nodiscard]] bool valid() const { return valid_; }
  [[nodiscard]] const Value& value() const { return value_; }
  [[nodiscard]] bool has(std::string_view key) const { return member(key, false).present(); }
  [[nodiscard]] Value required(std::string_view key) const { return member(key, true); }
  [[nodiscard]] Value optional(std::string_view key) const { return member(key, false); }

  /// Records that `key` is missing (for rules about combinations of keys).
  void missing(std::string_view key, const std::string& expected) const {
    if (valid_) value_.member(key, true).fail(expected);
  }

 private:
  [[nodiscard]] Value member(std::string_view key, bool required) const {
    assert(allowed(key) && "read a key that is not in the Object's key list");
    if (!valid_) return {nullptr, value_.path(), value_.issues(), false};
    return value_.member(key, required);
  }
  [[nodiscard]] bool allowed(std::string_view key) const {
    return std::find(keys_.begin(), keys_.end(), key) != keys_.end();
  }
  [[nodiscard]] std::string keys_text() const { return join(keys_, false); }

  Value value_;
  std::vector<std::string_view> keys_;
  bool valid_;
};

template <class T, class U>
void set_if(T& target, const std::optional<U>& value) {
  if (value) target = static_cast<T>(*value);
}

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
    for (const auto& frame : frames_)
      out += frame.is_object ? (out.empty() ? "" : ".") + cut(frame.key)
                             : "[" + std::to_string(frame.index) + "]";
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

// ---------------------------------------------------------------------------------------------
// The input format, section by section

class SpecReader {
 public:
  explicit SpecReader(Issues& issues) : issues_(issues) {}

  Spec read(const json& root_json) {
    const Value root(&root_json, "", issues_, true);
    const Object top(root, {"title", "units", "grid", "materials", "bodies", "boundary_conditions", "loads",
                            "solver", "output", "checks", "contact"});
    if (!top.valid()) return std::move(spec_);
    set_if(spec_.title, top.optional("title").string());
    read_units(Object(top.optional("units"), {"length", "time", "mass", "stress", "energy"}));
    read_grid(Object(top.required("grid"), {"dim", "min", "max", "cell_size"}));
    read_materials(top.required("materials"));
    read_bodies(top.required("bodies"));
    read_conditions(top.optional("boundary_conditions"));
    read_loads(Object(top.optional("loads"), {"gravity"}));
    read_solver(Object(top.required("solver"),
                       {"scheme", "transfer", "position_alpha", "flip_fraction", "fmpm", "xpic", "basis", "shape",
                        "mapping", "mls", "deformation_update", "dt", "courant", "end_time", "max_steps",
                        "mass_tolerance", "constrain_old_velocity", "artificial_viscosity", "max_energy_growth"}));
    check_one_sided_transfer(top.optional("boundary_conditions"));
    read_output(Object(top.optional("output"), {"every_steps", "every_time", "particles", "plots", "fields",
                                                "checkpoint", "probes"}));
    read_checks(top.optional("checks"));
    read_contact(top.optional("contact"));
    if (grid_ok_) check_stencil_fits();
    if (issues_.empty()) check_step_count();
    return std::move(spec_);
  }

 private:
  // --- units: names only, for the plots' axes (summary.json echoes them); nothing is converted ---

  void read_units(const Object& units) {
    for (const char* key : {"length", "time", "mass", "stress", "energy"}) (void)units.optional(key).string();
  }

  // --- grid ---

  void read_grid(const Object& grid) {
    const std::size_t issues_before = issues_.size();
    const auto dim = grid.required("dim").integer(1, 3);
    dim_ = static_cast<int>(dim.value_or(0));  // 0: unknown, vectors below then take 1 to 3 numbers
    const auto lo = grid.required("min").vector(dim_);
    const auto hi = grid.required("max").vector(dim_);
    const auto cell_size = read_cell_size(grid.required("cell_size"));
    if (!dim || !lo || !hi || !cell_size) return;
    GridSpec& g = spec_.grid;
    g.dim = dim_;
    g.min = *lo;
    g.max = *hi;
    g.cell_size = *cell_size;
    for (int a = 0; a < dim_; ++a)
      if (!(g.max[a] > g.min[a])) {
        grid.required("max").fail(numbers_text(dim_, kAnyNumber) + ", each greater than grid.min's");
        return;
      }
    read_cell_counts(grid.required("cell_size"));
    grid_ok_ = issues_.size() == issues_before;
  }

  /// A number (the same in every direction) or a vector, all > 0.
  std::optional<Triple> read_cell_size(const Value& v) const {
    const std::string expected = "a number > 0 or " + numbers_text(dim_, kPositive);
    if (!v.usable(expected)) return std::nullopt;
    if (v.get().is_number()) {
      const auto h = v.number(kPositive);
      if (!h) return std::nullopt;
      Triple out{};
      for (int a = 0; a < std::max(dim_, 1); ++a) out[a] = *h;
      return out;
    }
    if (!v.get().is_array()) {
      v.fail(expected);
      return std::nullopt;
    }
    return v.vector(dim_, kPositive);
  }

  /// cells = (max - min) / cell_size: a whole number >= 1 per direction, at most kMaxCells in all.
  void read_cell_counts(const Value& cell_size) {
    GridSpec& g = spec_.grid;
    Triple counts{};
    double total = 1;
    for (int a = 0; a < dim_; ++a) {
      const double n = (g.max[a] - g.min[a]) / g.cell_size[a];
      counts[a] = std::round(n);
      if (counts[a] < 1 || std::abs(n - counts[a]) > kCellCountTolerance * counts[a]) {
        cell_size.fail("cell_size dividing (max - min) into a whole number of cells");
        return;
      }
      total *= counts[a];
    }
    if (total > kMaxCells) {
      cell_size.fail("at most 1e8 cells");
      return;
    }
    for (int a = 0; a < dim_; ++a) g.cells[a] = static_cast<int>(counts[a]);
  }

  // --- materials ---

  void read_materials(const Value& list) {
    const auto items = list.elements("a non-empty array of material objects", 1);
    names_complete_ = !items.empty();
    for (const auto& item : items) spec_.materials.push_back(read_material(item));
  }

  MaterialSpec read_material(const Value& v) {
    const Object m(v, {"name", "model", "density", "E", "nu", "lambda", "mu", "volumetric", "bulk_sound_speed",
                       "hugoniot_slope", "gruneisen", "shear_modulus", "velocity", "cohesion", "friction_angle",
                       "dilation_angle", "softening", "match", "yield_stress", "hardening_modulus"});
    MaterialSpec out;
    if (!m.valid()) {
      names_complete_ = false;
      return out;
    }
    read_material_name(m.required("name"), out);
    const auto model = m.required("model").choice(kModels);
    set_if(out.model, model);
    set_if(out.density, m.required("density").number(kPositive));
    if (model) read_plasticity(m, *model, out);
    if (model == MaterialModel::MieGruneisen) return read_mie_gruneisen(m, out);
    if (model == MaterialModel::Rigid) {
      read_rigid(m, out);
      return out;
    }
    for (const char* key : {"bulk_sound_speed", "hugoniot_slope", "gruneisen", "shear_modulus"})
      if (m.has(key))
        m.optional(key).fail(std::string("no \"") + key + "\" unless model is \"mie_gruneisen\"");
    if (m.has("velocity")) m.optional("velocity").fail("no velocity unless model is \"rigid\"");
    read_elasticity(m, out);
    const Value volumetric = m.optional("volumetric");
    if (model && model != MaterialModel::NeoHookean && volumetric.present())
      volumetric.fail("no \"volumetric\" key for a " + std::string(name_of(kModels, *model)) +
                      " material (only neo_hookean has one)");
    else
      set_if(out.volumetric, volumetric.choice(kVolumetric));
    return out;
  }

  /// The plastic models' keys (material/mohr_coulomb.hpp, drucker_prager.hpp, von_mises.hpp);
  /// refuses them on the other models. Angles in degrees.
  static void read_plasticity(const Object& m, MaterialModel model, MaterialSpec& out) {
    const bool frictional = model == MaterialModel::MohrCoulomb || model == MaterialModel::DruckerPrager;
    const bool metal = model == MaterialModel::VonMises;
    for (const char* key : {"cohesion", "friction_angle", "dilation_angle", "softening"})
      if (!frictional && m.has(key))
        m.optional(key).fail(std::string("no \"") + key + "\" unless model is \"mohr_coulomb\" or \"drucker_prager\"");
    if (model != MaterialModel::DruckerPrager && m.has("match"))
      m.optional("match").fail("no \"match\" unless model is \"drucker_prager\"");
    for (const char* key : {"yield_stress", "hardening_modulus"})
      if (!metal && m.has(key)) m.optional(key).fail(std::string("no \"") + key + "\" unless model is \"von_mises\"");
    if (frictional) read_friction(m, out);
    if (model == MaterialModel::DruckerPrager) set_if(out.match, m.optional("match").choice(kDruckerPragerMatches));
    if (metal) {
      set_if(out.yield_stress, m.required("yield_stress").number(kPositive));
      // H < 0 would make the yield stress sigma_y + H eps_p negative at eps_p = sigma_y / |H|.
      set_if(out.hardening_modulus, m.optional("hardening_modulus").number(kNonNegative));
    }
  }

  /// Mohr-Coulomb strength: c >= 0, 0 < phi < 90 deg, 0 <= psi <= phi, optional linear softening
  /// {"cohesion": c_r, "friction_angle": phi_r, "plastic_strain": eps_s} with c_r <= c,
  /// psi <= phi_r <= phi.
  static void read_friction(const Object& m, MaterialSpec& out) {
    set_if(out.cohesion, m.required("cohesion").number(kNonNegative));
    const auto phi = m.required("friction_angle").number({0, 90, true, true});
    set_if(out.friction_angle, phi);
    const Value psi_value = m.optional("dilation_angle");
    const auto psi = psi_value.number(phi ? Bounds{0, *phi, false, false} : kNonNegative);
    set_if(out.dilation_angle, psi);
    out.residual_cohesion = out.cohesion;
    out.residual_friction_angle = out.friction_angle;
    const Object soft(m.optional("softening"), {"cohesion", "friction_angle", "plastic_strain"});
    if (!m.has("softening") || !soft.valid()) return;
    set_if(out.residual_cohesion, soft.required("cohesion").number({0, out.cohesion, false, false}));
    set_if(out.residual_friction_angle,
           soft.required("friction_angle").number({std::max(out.dilation_angle, 0.0), out.friction_angle,
                                                  out.dilation_angle == 0.0, false}));
    set_if(out.softening_strain, soft.required("plastic_strain").number(kPositive));
  }

  /// model "mie_gruneisen" (material/mie_gruneisen.hpp): C0, S, Gamma0 and an optional shear modulus.
  static MaterialSpec read_mie_gruneisen(const Object& m, MaterialSpec& out) {
    for (const char* key : {"E", "nu", "lambda", "mu", "volumetric"})
      if (m.has(key)) m.optional(key).fail(std::string("no \"") + key + "\" for a mie_gruneisen material");
    set_if(out.bulk_sound_speed, m.required("bulk_sound_speed").number(kPositive));
    set_if(out.hugoniot_slope, m.required("hugoniot_slope").number(kNonNegative));
    set_if(out.gruneisen, m.required("gruneisen").number(kNonNegative));
    set_if(out.mu, m.optional("shear_modulus").number(kNonNegative));
    // lambda + 2 mu / 3 = K = rho0 C0^2, so that lambda + 2 mu is the dilatational modulus
    out.lambda = out.density * out.bulk_sound_speed * out.bulk_sound_speed - 2.0 * out.mu / 3.0;
    return out;
  }

  /// A rigid material: only name, model, density and an optional prescribed velocity (one entry
  /// per axis, each a number or {"table": [[t, v], ...]}; zero by default).
  void read_rigid(const Object& m, MaterialSpec& out) const {
    for (const char* key : {"E", "nu", "lambda", "mu", "volumetric"})
      if (m.has(key)) m.optional(key).fail("no elastic constants for a rigid material");
    const Value v = m.optional("velocity");
    if (!v.present()) return;
    const std::string expected = "an array of " + std::string(dim_ == 0 ? "1 to 3" : std::to_string(dim_)) +
                                 " entries, each a number or {\"table\": [[t, v], ...]}";
    const bool size_ok = v.get().is_array() && (dim_ == 0 ? !v.get().empty() && v.get().size() <= 3
                                                          : v.get().size() == static_cast<std::size_t>(dim_));
    if (!size_ok) {
      v.fail(expected);
      return;
    }
    for (std::size_t a = 0; a < v.get().size(); ++a)
      if (auto f = read_time_function(v.element(a), expected)) out.rigid_velocity[a] = *f;
  }

  void read_material_name(const Value& v, MaterialSpec& out) {
    const auto name = v.string();
    if (!name) {
      names_complete_ = false;
      return;
    }
    for (const auto& other : spec_.materials)
      if (other.name == *name) {
        v.fail("a name not used by another material");
        return;
      }
    out.name = *name;
  }

  /// Exactly one pair: E and nu, or lambda and mu; the other pair is computed from it.
  static void read_elasticity(const Object& m, MaterialSpec& out) {
    const bool young = m.has("E") || m.has("nu");
    const bool lame = m.has("lambda") || m.has("mu");
    if (young && lame)
      m.optional(m.has("lambda") ? "lambda" : "mu")
          .fail("either E and nu, or lambda and mu, not keys of both pairs");
    else if (young)
      read_young(m, out);
    else if (lame)
      read_lame(m, out);
    else
      m.missing("E", "E and nu, or lambda and mu");
  }

  static void read_young(const Object& m, MaterialSpec& out) {
    const auto E = m.required("E").number(kPositive);
    const auto nu = m.required("nu").number({-1, 0.5, true, true});
    if (!E || !nu) return;
    out.youngs_modulus = *E;
    out.poisson_ratio = *nu;
    out.lambda = *E * *nu / ((1 + *nu) * (1 - 2 * *nu));
    out.mu = *E / (2 * (1 + *nu));
  }

  static void read_lame(const Object& m, MaterialSpec& out) {
    const auto lambda = m.required("lambda").number();
    const auto mu = m.required("mu").number(kPositive);
    if (!lambda || !mu) return;
    if (*lambda + 2 * *mu / 3 <= 0) {  // the bulk modulus must be positive
      m.required("lambda").fail("a number > -2 mu / 3 = " + format_number(-2 * *mu / 3) +
                                " (a positive bulk modulus)");
      return;
    }
    out.lambda = *lambda;
    out.mu = *mu;
    out.youngs_modulus = *mu * (3 * *lambda + 2 * *mu) / (*lambda + *mu);
    out.poisson_ratio = *lambda / (2 * (*lambda + *mu));
  }

  // --- bodies ---

  void read_bodies(const Value& list) {
    const auto items = list.elements("a non-empty array of body objects", 1);
    for (std::size_t i = 0; i < items.size(); ++i) spec_.bodies.push_back(read_body(items[i], i));
  }

  BodySpec read_body(const Value& v, std::size_t index) {
    const Object b(v, {"name", "material", "shape", "particles_per_cell", "velocity", "velocity_sine",
                       "velocity_gradient", "velocity_noise", "geostatic"});
    BodySpec out;
    out.name = "body" + std::to_string(index);
    if (!b.valid()) return out;
    set_if(out.name, b.optional("name").string());
    read_body_material(b.required("material"), out);
    read_shape(b.required("shape"), out);
    set_if(out.particles_per_cell, b.optional("particles_per_cell").integer(1, 10));
    set_if(out.velocity, b.optional("velocity").vector(dim_));
    read_sine(Object(b.optional("velocity_sine"), {"amplitude", "wave_vector", "phase"}), out);
    read_velocity_gradient(b.optional("velocity_gradient"), out);
    const Object noise(b.optional("velocity_noise"), {"amplitude", "seed"});
    if (noise.valid()) {
      set_if(out.noise_amplitude, noise.required("amplitude").number(kNonNegative));
      if (const auto seed = noise.optional("seed").integer(0, UINT_MAX))
        out.noise_seed = static_cast<unsigned>(*seed);
    }
    read_geostatic(b.optional("geostatic"), out);
    return out;
  }

  /// {"k0": K0 >= 0, "surface": height of the free surface}: an initial geostatic stress, held by
  /// a plastic material's history (the elastic models' stress is a function of F alone).
  void read_geostatic(const Value& v, BodySpec& out) const {
    const Object g(v, {"k0", "surface"});
    if (!v.present() || !g.valid()) return;
    out.geostatic = true;
    set_if(out.k0, g.required("k0").number(kNonNegative));
    set_if(out.geostatic_surface, g.required("surface").number());
    if (!names_complete_ || static_cast<std::size_t>(out.material) >= spec_.materials.size()) return;
    const MaterialModel model = spec_.materials[static_cast<std::size_t>(out.material)].model;
    if (model != MaterialModel::MohrCoulomb && model != MaterialModel::DruckerPrager &&
        model != MaterialModel::VonMises)
      v.fail("no geostatic stress for a " + std::string(name_of(kModels, model)) +
             " body (only mohr_coulomb, drucker_prager and von_mises materials hold an initial stress)");
  }

  void read_body_material(const Value& v, BodySpec& out) const {
    const auto name = v.string();
    if (!name || !names_complete_) return;  // an unnamed material is reported already
    for (std::size_t k = 0; k < spec_.materials.size(); ++k)
      if (spec_.materials[k].name == *name) {
        out.material = static_cast<int>(k);
        return;
      }
    std::vector<std::string> names;
    for (const auto& m : spec_.materials) names.push_back(m.name);
    v.fail("the name of a material: " + join(names, true));
  }

  void read_shape(const Value& v, BodySpec& out) const {
    if (!v.expect_object("an object with \"type\": " +
                         join(std::array{"box", "disk", "sphere", "polygon"}, true)))
      return;
    const std::size_t issues_before = issues_.size();
    const Value type = v.member("type", true);
    const auto kind = type.choice(kShapes);
    if (!kind) return;
    out.shape = *kind;
    switch (*kind) {
      case BodyShape::Box:
        read_box(Object(v, {"type", "min", "max"}), out);
        break;
      case BodyShape::Disk:  // "disk" in 1-D and 2-D (and, as before, in 3-D), "sphere" in 3-D
        if (dim_ != 0 && dim_ != 3 && type.get() == "sphere")
          type.fail("\"disk\" (\"sphere\" needs grid.dim 3)");
        else
          read_disk(Object(v, {"type", "center", "radius"}), out);
        break;
      case BodyShape::Polygon:
        if (dim_ != 0 && dim_ != 2)
          type.fail("\"box\" or \"disk\" (a polygon needs grid.dim 2)");
        else
          read_polygon(Object(v, {"type", "vertices"}), out);
        break;
    }
    if (grid_ok_ && issues_.size() == issues_before) check_inside_grid(v, out);
  }

  void read_box(const Object& s, BodySpec& out) const {
    const auto lo = s.required("min").vector(dim_);
    const auto hi = s.required("max").vector(dim_);
    if (!lo || !hi) return;
    out.min = *lo;
    out.max = *hi;
    for (int a = 0; a < dim_; ++a)
      if (!(out.max[a] > out.min[a])) {
        s.required("max").fail(numbers_text(dim_, kAnyNumber) + ", each greater than the box min's");
        return;
      }
  }

  void read_disk(const Object& s, BodySpec& out) const {
    set_if(out.center, s.required("center").vector(dim_));
    set_if(out.radius, s.required("radius").number(kPositive));
  }

  static void read_polygon(const Object& s, BodySpec& out) {
    const Value list = s.required("vertices");
    const auto items = list.elements("an array of at least 3 [x, y] points", 3);
    for (const auto& item : items) {
      const auto point = item.vector(2);
      if (!point) return;
      out.polygon.push_back({(*point)[0], (*point)[1]});
    }
    if (items.empty()) return;
    double twice_area = 0;  // shoelace formula
    for (std::size_t k = 0; k < out.polygon.size(); ++k) {
      const auto& p = out.polygon[k];
      const auto& q = out.polygon[(k + 1) % out.polygon.size()];
      twice_area += p[0] * q[1] - q[0] * p[1];
    }
    const auto [lo, hi] = bounding_box(out, 2);
    if (std::abs(twice_area) <= 1e-12 * (hi[0] - lo[0]) * (hi[1] - lo[1]))
      list.fail("the vertices of a polygon with nonzero area");
  }

  static std::pair<Triple, Triple> bounding_box(const BodySpec& body, int dim) {
    Triple lo{}, hi{};
    switch (body.shape) {
      case BodyShape::Box:
        return {body.min, body.max};
      case BodyShape::Disk:
        for (int a = 0; a < dim; ++a) {
          lo[a] = body.center[a] - body.radius;
          hi[a] = body.center[a] + body.radius;
        }
        return {lo, hi};
      case BodyShape::Polygon:
        lo = {kInf, kInf, 0};
        hi = {-kInf, -kInf, 0};
        for (const auto& p : body.polygon)
          for (int a = 0; a < 2; ++a) {
            lo[a] = std::min(lo[a], p[a]);
            hi[a] = std::max(hi[a], p[a]);
          }
        return {lo, hi};
    }
    return {lo, hi};
  }

  void check_inside_grid(const Value& shape, const BodySpec& body) const {
    const auto [lo, hi] = bounding_box(body, dim_);
    if (!box_inside_grid(lo, hi, kInsideTolerance))
      shape.fail("a shape inside the grid " + grid_box_text() + "; it " + overhang_text(lo, hi));
  }

  /// "reaches 0.2 beyond the x+ side (x = 1.2 > grid.max[0] = 1)": each side the box [lo, hi] crosses.
  [[nodiscard]] std::string overhang_text(const Triple& lo, const Triple& hi) const {
    const GridSpec& g = spec_.grid;
    std::vector<std::string> sides;
    for (int a = 0; a < dim_; ++a) {
      const std::string axis(1, "xyz"[a]), index = "[" + std::to_string(a) + "]";
      if (lo[a] < g.min[a])
        sides.push_back(format_number(g.min[a] - lo[a]) + " beyond the " + axis + "- side (" + axis + " = " +
                        format_number(lo[a]) + " < grid.min" + index + " = " + format_number(g.min[a]) + ")");
      if (hi[a] > g.max[a])
        sides.push_back(format_number(hi[a] - g.max[a]) + " beyond the " + axis + "+ side (" + axis + " = " +
                        format_number(hi[a]) + " > grid.max" + index + " = " + format_number(g.max[a]) + ")");
    }
    std::string out = "reaches ";
    for (std::size_t i = 0; i < sides.size(); ++i) out += (i == 0 ? "" : " and ") + sides[i];
    return out;
  }

  /// [lo, hi] lies in the grid's box, widened by `relative_tolerance` of its size.
  [[nodiscard]] bool box_inside_grid(const Triple& lo, const Triple& hi, double relative_tolerance) const {
    const GridSpec& g = spec_.grid;
    for (int a = 0; a < dim_; ++a) {
      const double tolerance = relative_tolerance * (g.max[a] - g.min[a]);
      if (lo[a] < g.min[a] - tolerance || hi[a] > g.max[a] + tolerance) return false;
    }
    return true;
  }

  [[nodiscard]] std::string grid_box_text() const {
    return "[min, max] (grid.min = " + vector_text(spec_.grid.min) +
           ", grid.max = " + vector_text(spec_.grid.max) + ")";
  }

  [[nodiscard]] std::string vector_text(const Triple& x) const {
    std::vector<std::string> parts;
    for (int a = 0; a < dim_; ++a) parts.push_back(format_number(x[a]));
    return "[" + join(parts, false) + "]";
  }

  /// A dim x dim matrix as an array of rows: V += G x.
  void read_velocity_gradient(const Value& v, BodySpec& out) const {
    if (!v.present()) return;
    const std::string expected =
        "an array of " + std::to_string(dim_) + " rows of " + numbers_text(dim_, kAnyNumber);
    const auto rows = v.elements(expected, 1);
    if (dim_ != 0 && rows.size() != static_cast<std::size_t>(dim_) && !rows.empty()) {
      v.fail(expected);
      return;
    }
    for (std::size_t r = 0; r < rows.size() && r < 3; ++r)
      if (const auto row = rows[r].vector(dim_)) out.velocity_gradient[r] = *row;
    out.has_velocity_gradient = true;
  }

  void read_sine(const Object& s, BodySpec& out) const {
    if (!s.valid()) return;
    out.has_sine_velocity = true;
    set_if(out.sine_amplitude, s.required("amplitude").vector(dim_));
    set_if(out.sine_wave_vector, s.required("wave_vector").vector(dim_));
    set_if(out.sine_phase, s.optional("phase").number());
  }

  // --- boundary conditions ---

  void read_conditions(const Value& list) {
    for (const auto& item : list.elements("an array of boundary condition objects")) {
      const bool wall = item.get().is_object() && item.get().value("type", json()) == "moving_wall";
      if (wall)
        spec_.conditions.push_back(read_moving_wall(
            Object(item, {"type", "axis", "position", "material", "velocity", "depth", "stretch_about"})));
      else
        spec_.conditions.push_back(
            read_condition(Object(item, {"face", "box", "type", "normal", "velocity", "one_sided"})));
    }
  }

  /// {"type": "moving_wall", "axis", "position", "material": "below"|"above", "velocity", "depth",
  ///  "stretch_about"} (Nairn 2026 §3.1).
  VelocityConditionSpec read_moving_wall(const Object& c) const {
    VelocityConditionSpec out;
    out.kind = ConditionKind::MovingWall;
    out.on_face = false;
    if (!c.valid()) return out;
    if (const auto axis = c.required("axis").choice(kAxes)) {
      out.normal_axis = *axis;
      if (dim_ != 0 && *axis >= dim_)
        c.required("axis").fail("an axis of the grid (" + std::to_string(dim_) + "-D)");
    }
    set_if(out.wall_position, c.required("position").number());
    set_if(out.material_below, c.required("material").choice(kMaterialSides));
    const std::string expected = "a number (a constant wall velocity) or {\"table\": [[t, v], ...]}";
    if (auto v = read_time_function(c.required("velocity"), expected)) out.wall_velocity = *v;
    set_if(out.depth, c.required("depth").number(kNonNegative));
    out.stretch_about = c.optional("stretch_about").number();
    return out;
  }

  VelocityConditionSpec read_condition(const Object& c) const {
    VelocityConditionSpec out;
    if (!c.valid()) return out;
    read_region(c, out);
    const auto kind = c.required("type").choice(kConditionKinds);
    set_if(out.kind, kind);
    if (!kind) return out;
    read_normal(c, *kind, out);
    const Value velocity = c.optional("velocity");
    if (*kind == ConditionKind::Velocity) {
      if (velocity.present())
        read_prescribed_velocity(velocity, out);
      else
        c.missing("velocity", prescribed_velocity_text());
    } else if (velocity.present()) {
      velocity.fail("no velocity unless type is \"velocity\"");
    }
    read_one_sided(c.optional("one_sided"), out);
    return out;
  }

  /// "one_sided": true on a fixed or slip face (slip with the face's own normal), not with FMPM/XPIC.
  void read_one_sided(const Value& v, VelocityConditionSpec& out) const {
    const auto one_sided = v.boolean();
    if (!one_sided || !*one_sided) return;
    const bool face_normal = out.kind == ConditionKind::Fixed || out.normal_axis == out.face_axis;
    if (!out.on_face || out.kind == ConditionKind::Velocity || !face_normal)
      v.fail("one_sided only on a \"fixed\" face or a \"slip\" face with the face's normal");
    else
      out.one_sided = true;
  }

  /// One-sided conditions decide per step which nodes they hold; the FMPM/XPIC increments would need
  /// that choice cached, so they are refused there.
  void check_one_sided_transfer(const Value& list) const {
    const auto t = spec_.solver.transfer;
    if (t != VelocityTransfer::FMPM && t != VelocityTransfer::XPIC) return;
    for (std::size_t i = 0; i < spec_.conditions.size(); ++i)
      if (spec_.conditions[i].one_sided)
        list.element(i)
            .member("one_sided", false)
            .fail("false (one_sided conditions need transfer flip, pic or blend)");
  }

  /// Exactly one of "face" and "box".
  void read_region(const Object& c, VelocityConditionSpec& out) const {
    const bool face = c.has("face"), box = c.has("box");
    if (face && box) {
      c.optional("box").fail("no box when a face is given (exactly one of face or box)");
    } else if (face) {
      const Value v = c.optional("face");
      const auto id = v.choice(kFaces);
      if (!id) return;
      out.on_face = true;
      out.face_axis = *id / 2;
      out.face_side = *id % 2;
      if (dim_ != 0 && out.face_axis >= dim_) v.fail(faces_text());
    } else if (box) {
      out.on_face = false;
      const Object b(c.optional("box"), {"min", "max"});
      const auto lo = b.required("min").vector(dim_);
      const auto hi = b.required("max").vector(dim_);
      if (!lo || !hi) return;
      out.box_min = *lo;
      out.box_max = *hi;
      for (int a = 0; a < dim_; ++a)
        if (out.box_max[a] < out.box_min[a]) {
          b.required("max").fail(numbers_text(dim_, kAnyNumber) + ", each at least the box min's");
          return;
        }
    } else {
      c.missing("face", "exactly one of \"face\" (" + faces_text() + ") or \"box\"");
    }
  }

  /// The faces of the grid's dimension, e.g. "one of "x-", "x+", "y-", "y+"".
  [[nodiscard]] std::string faces_text() const {
    std::vector<std::string_view> names;
    for (const auto& face : kFaces)
      if (dim_ == 0 || face.value / 2 < dim_) names.push_back(face.name);
    return "one of " + join(names, true);
  }

  void read_normal(const Object& c, ConditionKind kind, VelocityConditionSpec& out) const {
    const Value normal = c.optional("normal");
    if (kind != ConditionKind::Slip) {
      if (normal.present()) normal.fail("no normal unless type is \"slip\"");
      return;
    }
    out.normal_axis = out.face_axis;
    if (!normal.present()) {
      if (c.has("box") && !c.has("face"))
        c.missing("normal", "\"x\", \"y\" or \"z\": the constrained axis of a slip box");
      return;
    }
    const auto axis = normal.choice(kAxes);
    if (!axis) return;
    if (dim_ != 0 && *axis >= dim_) {
      std::vector<std::string_view> names;
      for (int a = 0; a < dim_; ++a) names.push_back(kAxes[static_cast<std::size_t>(a)].name);
      normal.fail("one of " + join(names, true) + " (an axis of the " + std::to_string(dim_) + "-D grid)");
      return;
    }
    out.normal_axis = *axis;
  }

  [[nodiscard]] std::string prescribed_velocity_text() const {
    const std::string count = dim_ == 0 ? "1 to 3" : std::to_string(dim_);
    return "an array of " + count + " entries, each a number, null (free) or {\"table\": [[t, v], ...]}";
  }

  void read_prescribed_velocity(const Value& v, VelocityConditionSpec& out) const {
    const std::string expected = prescribed_velocity_text();
    const bool size_ok = v.get().is_array() && (dim_ == 0 ? !v.get().empty() && v.get().size() <= 3
                                                          : v.get().size() == static_cast<std::size_t>(dim_));
    if (!size_ok) {
      v.fail(expected);
      return;
    }
    bool any_prescribed = false;
    for (std::size_t a = 0; a < v.get().size(); ++a) {
      const Value component = v.element(a);
      if (component.get().is_null()) continue;
      any_prescribed = true;
      out.velocity[a] = read_time_function(component, expected);
    }
    if (!any_prescribed) v.fail(expected + ", at least one not null");
  }

  /// A number (a constant) or {"table": [[t0, v0], [t1, v1], ...]} with strictly increasing t.
  static std::optional<TimeFunction> read_time_function(const Value& v, const std::string& expected) {
    if (!v.usable(expected)) return std::nullopt;  // absent: an issue when required (fuzzer finding)
    if (v.get().is_number()) {
      const auto x = v.number();
      if (!x) return std::nullopt;
      return TimeFunction{{}, {*x}};
    }
    if (!v.get().is_object()) {
      v.fail(expected);
      return std::nullopt;
    }
    const Object t(v, {"table"});
    const auto rows = t.required("table").elements("an array of [t, v] rows, at least one", 1);
    TimeFunction out;
    for (const auto& row : rows) {
      const auto tv = row.vector(2);
      if (!tv) return std::nullopt;
      if (!out.times.empty() && !((*tv)[0] > out.times.back())) {
        row.fail("a row whose time is greater than the previous row's");
        return std::nullopt;
      }
      out.times.push_back((*tv)[0]);
      out.values.push_back((*tv)[1]);
    }
    if (rows.empty()) return std::nullopt;
    return out;
  }

  // --- loads, solver, output, checks ---

  void read_loads(const Object& loads) {
    set_if(spec_.loads.gravity, loads.optional("gravity").vector(dim_));
  }

  void read_solver(const Object& s) {
    SolverSpec& out = spec_.solver;
    set_if(out.scheme, s.optional("scheme").choice(kSchemes));
    const auto transfer = s.optional("transfer").choice(kTransfers);
    set_if(out.transfer, transfer);
    if (out.transfer == VelocityTransfer::FMPM) out.position_alpha = 0.5;  // Nairn 2026 §2.1: consistent
    set_if(out.position_alpha, s.optional("position_alpha").number(kUnitInterval));
    read_fmpm(s, out);
    const Value flip_fraction = s.optional("flip_fraction");
    if (out.transfer == VelocityTransfer::Blend)
      out.flip_fraction = flip_fraction.number(kUnitInterval).value_or(0.99);
    else if (flip_fraction.present() && (transfer || !s.has("transfer")))
      flip_fraction.fail("no flip_fraction unless transfer is \"blend\"");
    // Without a basis: quadratic B-splines, the user guide's recommendation (no cell-crossing
    // noise); linear under mapping "impm", whose cell quadrature needs it (Gong 2015 §5.3).
    const bool impm = s.optional("mapping").present() && s.optional("mapping").get() == "impm";
    out.shape = impm ? ShapeKind::Linear : ShapeKind::BSpline2;
    set_if(out.shape, s.optional("basis").choice(kShapeKinds));
    if (s.has("shape"))  // the key's old name, easily confused with bodies[].shape (a body's geometry)
      s.optional("shape").fail(
          "no key shape here: the basis functions are solver.basis (renamed from solver.shape)");
    read_mapping(s, out);
    set_if(out.deformation_update, s.optional("deformation_update").choice(kDeformationUpdates));
    out.dt = s.optional("dt").number(kPositive);
    const Value courant = s.optional("courant");
    if (s.has("dt") && courant.present())
      courant.fail("no courant when dt is given (one of dt or courant)");
    else
      set_if(out.courant, courant.number({0, 1, true, false}));
    set_if(out.end_time, s.required("end_time").number(kPositive));
    set_if(out.max_steps, s.optional("max_steps").integer(0));
    set_if(out.mass_tolerance, s.optional("mass_tolerance").number({0, 1, false, true}));
    read_constrain_old_velocity(s.optional("constrain_old_velocity"), out);
    read_energy_guard(s.optional("max_energy_growth"), out);
    read_artificial_viscosity(Object(s.optional("artificial_viscosity"), {"linear", "quadratic"}), out);
  }

  /// solver.max_energy_growth: a number > 0 (explicit/energy_guard.hpp), or "off".
  static void read_energy_guard(const Value& growth, SolverSpec& out) {
    if (!growth.present()) return;
    const json& j = growth.get();
    if (j.is_string() && j.get_ref<const std::string&>() == "off")
      out.max_energy_growth.reset();
    else if (j.is_number() && j.get<double>() > 0 && std::isfinite(j.get<double>()))
      out.max_energy_growth = j.get<double>();
    else
      growth.fail("a number > 0, or \"off\"");
  }

  /// solver.constrain_old_velocity: Gong 2015's wall treatment (extraction A24): the velocity
  /// conditions also hold on the old node velocities v(1), so a = (v+ - v) / dt and the FLIP
  /// increment carry no wall reaction. The FMPM and XPIC loops apply the conditions themselves.
  static void read_constrain_old_velocity(const Value& v, SolverSpec& out) {
    set_if(out.constrain_old_velocity, v.boolean());
    if (out.constrain_old_velocity &&
        (out.transfer == VelocityTransfer::FMPM || out.transfer == VelocityTransfer::XPIC))
      v.fail(
          "false with transfer \"fmpm\" or \"xpic\" (their loops apply the velocity conditions to "
          "every increment, Nairn 2026 Table 2)");
  }

  /// solver.artificial_viscosity: {"linear": A1, "quadratic": A2}, NairnMPM's defaults 0.2 and 2.0.
  static void read_artificial_viscosity(const Object& a, SolverSpec& out) {
    if (!a.valid()) return;
    out.av_linear = a.optional("linear").number(kNonNegative).value_or(0.2);
    out.av_quadratic = a.optional("quadratic").number(kNonNegative).value_or(2.0);
  }

  /// solver.mapping and solver.mls: Gong 2015's IMPM (§5.4) and MLS velocity mapping (§6.6).
  void read_mapping(const Object& s, SolverSpec& out) const {
    const Value mapping = s.optional("mapping");
    set_if(out.mapping, mapping.choice(kMappings));
    const Value mls_value = s.optional("mls");
    if (out.mapping == Mapping::MPM) {
      if (mls_value.present()) mls_value.fail("no mls unless mapping is \"impm\" or \"mls_velocity\"");
      return;
    }
    if (out.mapping == Mapping::IMPM && out.shape != ShapeKind::Linear)
      mapping.fail(
          "\"impm\" with basis \"linear\" (the cell quadrature uses the bilinear N_i), or "
          "\"mls_velocity\" for the other bases");
    if (out.transfer == VelocityTransfer::FMPM || out.transfer == VelocityTransfer::XPIC)
      mapping.fail("\"mpm\" with transfer \"fmpm\" or \"xpic\" (their passes re-map the momentum by mass)");
    const Object mls(mls_value, {"degree", "quadrature", "cell_volume"});
    set_if(out.mls.degree, mls.optional("degree").integer(0, 1));
    for (const char* key : {"quadrature", "cell_volume"})
      if (out.mapping != Mapping::IMPM && mls.has(key))
        mls.optional(key).fail(std::string("no ") + key + " unless mapping is \"impm\"");
    set_if(out.mls.quadrature, mls.optional("quadrature").choice(kCellQuadratures));
    set_if(out.mls.cell_volume, mls.optional("cell_volume").choice(kCellVolumes));
  }

  /// solver.fmpm (transfer "fmpm") or solver.xpic (transfer "xpic"): Nairn 2026 §2.2-3.4.
  void read_fmpm(const Object& s, SolverSpec& out) const {
    const bool fmpm = out.transfer == VelocityTransfer::FMPM, xpic = out.transfer == VelocityTransfer::XPIC;
    for (const char* key : {"fmpm", "xpic"}) {
      const Value v = s.optional(key);
      if (v.present() && !(key == std::string_view("fmpm") ? fmpm : xpic))
        v.fail(std::string("no ") + key + " unless transfer is \"" + key + "\"");
    }
    if (xpic) {
      const Object x(s.optional("xpic"), {"order"});
      set_if(out.fmpm.order, x.optional("order").integer(1, kMaxFmpmOrder));
      return;
    }
    if (!fmpm) return;
    const Object f(s.optional("fmpm"),
                   {"order", "blend", "dynamic", "periodic", "boundary_method", "recursion"});
    FmpmSpec& k = out.fmpm;
    set_if(k.order, f.optional("order").integer(1, kMaxFmpmOrder));
    const Object blend(f.optional("blend"), {"with", "factor"});
    if (blend.valid()) {
      set_if(k.blend_with, blend.required("with").integer(1, 2));
      set_if(k.blend_factor, blend.required("factor").number(kUnitInterval));
    }
    const Object dynamic(f.optional("dynamic"), {"measure", "limit"});
    if (dynamic.valid()) {
      set_if(k.measure, dynamic.required("measure").choice(kFmpmMeasures));
      set_if(k.limit, dynamic.required("limit").number(kPositive));
    }
    const Object periodic(f.optional("periodic"), {"courant", "steps", "time"});
    if (periodic.valid()) {
      int given = 0;
      if (const auto c = periodic.optional("courant").number(kPositive)) {
        k.period = FmpmPeriod::Courant, k.period_value = *c, ++given;
      }
      if (const auto n = periodic.optional("steps").integer(1)) {
        k.period = FmpmPeriod::Steps, k.period_value = static_cast<double>(*n), ++given;
      }
      if (const auto t = periodic.optional("time").number(kPositive)) {
        k.period = FmpmPeriod::Time, k.period_value = *t, ++given;
      }
      if (given != 1) periodic.value().fail("an object with exactly one of the keys courant, steps or time");
    }
    set_if(k.boundary_method, f.optional("boundary_method").choice(kFmpmBoundaryMethods));
    set_if(k.recursion, f.optional("recursion").choice(kFmpmRecursions));
    if (k.recursion == FmpmRecursion::Binomial && (k.blend_with > 0 || k.measure != FmpmMeasure::None))
      f.optional("recursion").fail("\"incremental\" with blend or dynamic (eq. 4 has no per-increment step)");
  }

  /// The basis's stencil must fit on the grid (shape/stencil_width.hpp).
  void check_stencil_fits() {
    const int fewest = minimum_cells(spec_.solver.shape);
    for (int a = 0; a < dim_; ++a)
      if (spec_.grid.cells[a] < fewest) {
        issues_.add("grid.cell_size", format_number(spec_.grid.cell_size[a]),
                    "at least " + std::to_string(fewest) + " cells per direction for solver.basis \"" +
                        std::string(name_of(kShapeKinds, spec_.solver.shape)) + "\" (its stencil is " +
                        std::to_string(fewest + 1) + " nodes wide); the grid has " +
                        std::to_string(spec_.grid.cells[a]) + " along axis " + std::to_string(a));
        return;
      }
  }

  /// A run of more than kMaxPlausibleSteps steps without solver.max_steps is almost always a unit
  /// mix-up (end_time in ms against SI moduli, a cell size in m against a grid in mm, ...): refused
  /// with the estimate. dt from solver.dt, or the Courant number with the elastic wave speed
  /// sqrt((lambda + 2 mu) / rho) of the stiffest material (particle speeds are not known yet).
  void check_step_count() {
    const SolverSpec& solver = spec_.solver;
    if (solver.max_steps > 0) return;
    double dt = solver.dt.value_or(0.0);
    if (!solver.dt) {
      double speed = 0.0, h = kInf;
      for (const auto& m : spec_.materials)
        speed = std::max(speed, std::sqrt((m.lambda + 2.0 * m.mu) / m.density));
      for (int a = 0; a < dim_; ++a) h = std::min(h, spec_.grid.cell_size[a]);
      if (!(speed > 0.0)) return;
      dt = solver.courant * h / speed;
    }
    const double steps = solver.end_time / dt;
    if (steps <= kMaxPlausibleSteps) return;
    issues_.add("solver.end_time", format_number(solver.end_time),
                "a run of at most 1e9 time steps without solver.max_steps; this one needs about " +
                    format_number(std::round(steps)) + " steps of dt = " + format_number(dt) +
                    " (check the units of end_time, cell_size, E and density, or set solver.max_steps)");
  }

  void read_output(const Object& o) {
    OutputSpec& out = spec_.output;
    set_if(out.every_steps, o.optional("every_steps").integer(0));
    set_if(out.every_time, o.optional("every_time").number(kNonNegative));
    if (out.every_steps != 0 && out.every_time != 0)
      o.optional("every_time").fail("0 when every_steps is nonzero (one of every_steps or every_time)");
    set_if(out.particles, o.optional("particles").boolean());
    set_if(out.plots, o.optional("plots").boolean());
    std::vector<std::string_view> field_names;
    for (const auto& f : kParticleFields) field_names.push_back(f.name);
    const std::string fields_text = "one of the particle fields " + join(field_names, true);
    for (const auto& item : o.optional("fields").elements("an array of particle field names")) {
      const auto name = item.string();
      if (!name) continue;
      if (is_particle_field(*name))
        out.fields.push_back(*name);
      else
        item.fail(fields_text);
    }
    read_checkpoint_keys(Object(o.optional("checkpoint"), {"every_steps", "every_minutes"}));
    read_probes(o.optional("probes"));
  }

  /// output.probes: [{"name": "tip", "position": [x, y]}, ...] (docs/input.md#output).
  void read_probes(const Value& list) {
    std::set<std::string> names;
    for (const auto& item : list.elements("an array of probe objects {\"name\", \"position\"}")) {
      const Object p(item, {"name", "position"});
      if (!p.valid()) continue;
      ProbeSpec probe;
      const Value name = p.required("name");
      if (const auto text = name.string()) {
        const bool plain = std::all_of(text->begin(), text->end(), [](char c) {
          return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_' || c == '-';
        });
        if (!plain)
          name.fail("a name of letters, digits, '_' and '-' (it names history.csv columns)");
        else if (!names.insert(*text).second)
          name.fail("a name different from every other probe's");
        probe.name = *text;
      }
      const Value position = p.required("position");
      if (const auto x = position.vector(dim_)) {
        probe.position = *x;
        if (grid_ok_ && !box_inside_grid(*x, *x, 0.0))
          position.fail("a point inside the grid " + grid_box_text() + "; it " + overhang_text(*x, *x));
      }
      spec_.output.probes.push_back(probe);
    }
  }

  /// output.checkpoint: every N steps and/or every T wall-clock minutes (docs/input.md#output).
  void read_checkpoint_keys(const Object& c) {
    if (!c.valid()) return;
    CheckpointSpec& out = spec_.output.checkpoint;
    set_if(out.every_steps, c.optional("every_steps").integer(1));
    set_if(out.every_minutes, c.optional("every_minutes").number(kPositive));
    if (!c.has("every_steps") && !c.has("every_minutes"))
      c.value().fail("an object with every_steps (an integer >= 1) and/or every_minutes (a number > 0)");
  }

  void read_checks(const Value& list) {
    for (const auto& item : list.elements("an array of check objects")) {
      const Object c(item, {"name", "measure", "expected", "tolerance", "source", "kind"});
      if (!c.valid()) continue;
      CheckSpec check;
      set_if(check.name, c.required("name").string());
      read_measure(c.required("measure"), check);
      set_if(check.expected, c.required("expected").number());
      set_if(check.tolerance, c.required("tolerance").number(kNonNegative));
      set_if(check.source, c.required("source").string());
      set_if(check.kind, c.optional("kind").choice(kCheckKinds));
      spec_.checks.push_back(check);
    }
  }

  static void read_measure(const Value& v, CheckSpec& check) {
    std::vector<std::string_view> names;
    for (const auto& m : kMeasures) names.push_back(m.name);
    const std::string expected = "one of the measures " + join(names, true);
    if (!v.usable(expected)) return;
    if (!v.get().is_string() || !is_known_measure(v.get().get_ref<const std::string&>())) {
      v.fail(expected);
      return;
    }
    check.measure = v.get().get<std::string>();
  }

  // --- contact (Nairn 2026 §3.2; docs/theory/contact.md) ---

  void read_contact(const Value& v) {
    const bool has_rigid = std::any_of(spec_.materials.begin(), spec_.materials.end(),
                                       [](const MaterialSpec& m) { return m.model == MaterialModel::Rigid; });
    if (!v.present()) {
      if (has_rigid)
        v.fail("a \"contact\" object (a rigid material moves its own velocity field, which needs contact)");
      return;
    }
    const Object c(v, {"law", "friction", "normals", "separation", "fmpm_method", "fields", "pairs"});
    if (!c.valid()) return;
    ContactSpec& out = spec_.contact;
    out.enabled = true;
    set_if(out.by_material, c.optional("fields").choice(kContactFields));
    out.law = read_contact_law(c);
    set_if(out.normals, c.optional("normals").choice(kContactNormals));
    out.separation = c.optional("separation").number(kNonNegative);
    set_if(out.fmpm_method, c.optional("fmpm_method").choice(kContactFmpmMethods));
    const std::vector<std::string> names = field_names(out.by_material);
    if (names.size() < 2)
      c.value().fail(std::string("at least two ") + (out.by_material ? "materials" : "bodies") +
                     " for contact (one velocity field each); remove \"contact\" for a single body");
    read_contact_pairs(c.optional("pairs"), names, out);
    check_contact_solver(v);
  }

  /// "law" (default "stick") and "friction" (Coulomb only, required there).
  static ContactLawSpec read_contact_law(const Object& c) {
    ContactLawSpec law;
    set_if(law.law, c.optional("law").choice(kContactLaws));
    const Value friction = c.optional("friction");
    if (law.law == ContactLaw::Coulomb) {
      if (friction.present())
        set_if(law.friction, friction.number(kNonNegative));
      else
        c.missing("friction", "a number >= 0 (the Coulomb coefficient mu) with law \"coulomb\"");
    } else if (friction.present()) {
      friction.fail("no friction unless law is \"coulomb\"");
    }
    return law;
  }

  [[nodiscard]] std::vector<std::string> field_names(bool by_material) const {
    std::vector<std::string> names;
    if (by_material)
      for (const auto& m : spec_.materials) names.push_back(m.name);
    else
      for (const auto& b : spec_.bodies) names.push_back(b.name);
    return names;
  }

  /// [{"between": [name, name], "law", "friction"}, ...]: the law of one pair of fields.
  void read_contact_pairs(const Value& list, const std::vector<std::string>& names, ContactSpec& out) const {
    for (const auto& item : list.elements("an array of {\"between\": [name, name], \"law\", \"friction\"}")) {
      const Object p(item, {"between", "law", "friction"});
      if (!p.valid()) continue;
      ContactPairSpec pair;
      pair.law = read_contact_law(p);
      const Value between = p.required("between");
      const std::string expected = "two different names of " +
                                   std::string(out.by_material ? "materials" : "bodies") + ": " +
                                   join(names, true);
      const auto ends = between.elements(expected, 2);
      if (ends.empty()) continue;
      if (ends.size() != 2) {
        between.fail(expected);
        continue;
      }
      std::array<int, 2> index{-1, -1};
      for (int k = 0; k < 2; ++k) {
        const auto name = ends[k].string();
        const auto it = name ? std::find(names.begin(), names.end(), *name) : names.end();
        if (it == names.end()) {
          ends[k].fail(expected);
          continue;
        }
        index[k] = static_cast<int>(it - names.begin());
      }
      if (index[0] < 0 || index[1] < 0) continue;
      if (index[0] == index[1]) {
        between.fail(expected);
        continue;
      }
      pair.first = index[0];
      pair.second = index[1];
      out.pairs.push_back(pair);
    }
  }

  /// Contact runs on the explicit solver's per-increment FMPM path with fixed-domain bases.
  void check_contact_solver(const Value& v) const {
    const SolverSpec& s = spec_.solver;
    if (dim_ == 1) v.fail("no contact in a 1-D grid (contact needs grid.dim 2 or 3)");
    if (s.transfer == VelocityTransfer::XPIC)
      v.fail("no contact with transfer \"xpic\" (use \"fmpm\" or \"flip\")");
    if (s.transfer == VelocityTransfer::FMPM && s.fmpm.recursion == FmpmRecursion::Binomial)
      v.fail("no contact with fmpm.recursion \"binomial\" (eq. 4 has no per-increment contact step)");
    if (s.shape == ShapeKind::CPDI2)
      v.fail("no contact with solver.basis \"cpdi2\" (tracked corners); use \"cpdi1\"");
    if (s.mapping != Mapping::MPM) v.fail("no contact with solver.mapping other than \"mpm\"");
  }

  Issues& issues_;
  Spec spec_;
  int dim_ = 0;                  // grid.dim, 0 while unknown (missing or invalid)
  bool grid_ok_ = false;         // the grid has no issue: bodies can be checked against it
  bool names_complete_ = false;  // every material has a valid name: bodies' references can be checked
};

}  // namespace

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
