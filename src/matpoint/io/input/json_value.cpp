// The message helpers of the input reader (json_value.hpp).
#include "matpoint/io/input/json_value.hpp"

#include <iomanip>

namespace matpoint::input_detail {

std::string format_number(double x) {
  std::ostringstream out;
  out << std::setprecision(12) << x;
  return out.str();
}

std::string cut(std::string_view text) {
  if (text.size() <= kMaxValueChars) return std::string(text);
  return std::string(text.substr(0, kMaxValueChars)) + "...";
}

std::string dump_value(const json& j) {
  // A huge value is dumped whole first: bounded by the input's size, which the reader holds anyway.
  return cut(j.dump());
}

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

std::string numbers_text(int dim, const Bounds& bounds) {
  const std::string count = dim == 0   ? "1 to 3 numbers"
                            : dim == 1 ? "1 number"
                                       : std::to_string(dim) + " numbers";
  return "an array of " + count + bounds.suffix();
}

}  // namespace matpoint::input_detail
