// Empirical stability limit of an input: bisection on a numeric input parameter (the Courant
// number by default) between a stable and an unstable value. A run is stable when it reaches its
// end without a numerical guard tripping (NaN, det F <= 0, a particle leaving the grid) and its
// kinetic energy never exceeds growth^2 times the initial one (a velocity growth factor, so that a
// run seeded with tiny noise counts as unstable long before it overflows). Used for Nairn 2026
// §3.3 (bisection to +/-0.005) and the Gong 2015 extraction's scan S1.
#pragma once

#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

namespace matpoint {

struct ScanOptions {
  std::string parameter = "solver.courant";  // dot path of the scanned number
  double lo = 0.05, hi = 1.5;                // the bracket; lo must be stable and hi unstable
  double tolerance = 0.005;                  // stop when hi - lo <= 2 tolerance
  double growth = 1e6;                       // unstable when max |V| grows beyond this factor (via energy)
  int threads = 1;
  std::vector<std::pair<std::string, std::string>> overrides;  // (dot path, JSON value) set before the scan
};

struct ScanRun {
  double value = 0;
  bool stable = false;
  std::string reason;  // why it counts as unstable ("" when stable)
};

struct ScanResult {
  double stable = 0, unstable = 0;  // the final bracket
  bool bracketed = false;           // lo was stable and hi unstable
  std::vector<ScanRun> runs;        // in the order run
  [[nodiscard]] double limit() const { return 0.5 * (stable + unstable); }
};

/// Sets `path` (keys separated by dots, array elements by their index; objects created when
/// missing) of `root` to `value`; a null value removes the key instead.
void set_json_path(nlohmann::json& root, const std::string& path, const nlohmann::json& value);

/// Runs the bisection; throws InputError when the input (with its overrides) is invalid.
/// `on_run` (optional) is called after each run, e.g. to print progress.
ScanResult stability_scan(const nlohmann::json& input, const ScanOptions& options,
                          const std::function<void(const ScanRun&)>& on_run = {});

/// One run of the input at `value` of the scanned parameter, classified.
ScanRun classify_run(const nlohmann::json& input, const ScanOptions& options, double value);

}  // namespace matpoint
