// Issues, Value and Object: the three pieces the input reader is built from (see input.cpp), with
// the message helpers they share. Internal to io/input*.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "matpoint/core/errors.hpp"
#include "matpoint/io/spec.hpp"

namespace matpoint::input_detail {

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

std::string format_number(double x);

/// The text itself, or its first kMaxValueChars characters and "...": every piece of the input
/// echoed in a message (a value, a key, a token the JSON parser stopped at) is cut this way.
std::string cut(std::string_view text);

std::string dump_value(const json& j);

/// nlohmann's parse error without its "[json.exception...] " prefix and with the token it quotes
/// ("last read: '...'", which can be a whole unterminated comment or a 32 MB number) cut.
std::string parse_error_text(std::string what);

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

std::string numbers_text(int dim, const Bounds& bounds);

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

}  // namespace matpoint::input_detail
