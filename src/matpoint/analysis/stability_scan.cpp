#include "matpoint/analysis/stability_scan.hpp"

#include <unistd.h>

#include <atomic>
#include <cmath>
#include <filesystem>
#include <sstream>

#include "matpoint/core/errors.hpp"
#include "matpoint/run/runner.hpp"
#include "matpoint/io/input.hpp"

namespace matpoint {

void set_json_path(nlohmann::json& root, const std::string& path, const nlohmann::json& value) {
  std::stringstream keys(path);
  std::string key;
  std::vector<std::string> parts;
  while (std::getline(keys, key, '.')) parts.push_back(key);
  nlohmann::json* node = &root;
  if (value.is_null()) {  // null removes the key
    for (std::size_t k = 0; k + 1 < parts.size() && node != nullptr; ++k) {
      const auto& part = parts[k];
      if (node->is_array() && part.find_first_not_of("0123456789") == std::string::npos &&
          std::stoul(part) < node->size())
        node = &(*node)[std::stoul(part)];
      else if (node->is_object() && node->contains(part))
        node = &(*node)[part];
      else
        node = nullptr;
    }
    if (node != nullptr && node->is_object()) node->erase(parts.back());
    return;
  }
  for (const auto& part : parts) {
    const bool index = !part.empty() && part.find_first_not_of("0123456789") == std::string::npos;
    if (index && node->is_array() && std::stoul(part) < node->size()) {
      node = &(*node)[std::stoul(part)];  // an element of an existing array, e.g. bodies.0
      continue;
    }
    if (!node->is_object()) *node = nlohmann::json::object();
    node = &(*node)[part];
  }
  *node = value;
}

ScanRun classify_run(const nlohmann::json& input, const ScanOptions& options, double value) {
  nlohmann::json j = input;
  for (const auto& [path, text] : options.overrides) set_json_path(j, path, nlohmann::json::parse(text));
  set_json_path(j, options.parameter, value);
  j.erase("checks");
  if (j.contains("solver") && j["solver"].is_object()) j["solver"].erase("dt");  // the Courant number sets it
  nlohmann::json output = j.value("output", nlohmann::json::object());
  output["particles"] = false;
  output["plots"] = false;
  if (!output.contains("every_steps") && !output.contains("every_time")) output["every_steps"] = 10;
  j["output"] = output;
  Spec spec = parse_spec(j.dump());
  spec.output.exact_times = false;  // the scanned Courant number must be every step's (none shortened)

  RunOptions run;
  run.progress = false;
  run.threads = options.threads;
  static std::atomic<int> counter{0};  // a folder per run: scans may run side by side
  run.out_dir = std::filesystem::temp_directory_path() /
                ("matpoint_scan_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
  const RunResult result = run_explicit(spec, run);
  std::error_code ignored;
  std::filesystem::remove_all(run.out_dir, ignored);

  ScanRun out;
  out.value = value;
  if (result.exit_code != kExitOk) {
    out.reason = result.message;
    return out;
  }
  const auto& samples = result.history.samples;
  const double initial = samples.front().kinetic_energy;
  for (const auto& s : samples)
    if (!(s.kinetic_energy <= options.growth * options.growth * initial)) {
      std::ostringstream why;
      why << "kinetic energy grew by a factor " << s.kinetic_energy / initial << " by t = " << s.time;
      out.reason = why.str();
      return out;
    }
  out.stable = true;
  return out;
}

ScanResult stability_scan(const nlohmann::json& input, const ScanOptions& options,
                          const std::function<void(const ScanRun&)>& on_run) {
  ScanResult result;
  auto run = [&](double value) {
    result.runs.push_back(classify_run(input, options, value));
    if (on_run) on_run(result.runs.back());
    return result.runs.back().stable;
  };
  double lo = options.lo, hi = options.hi;
  const bool lo_stable = run(lo);
  const bool hi_stable = run(hi);
  result.bracketed = lo_stable && !hi_stable;
  if (result.bracketed)
    while (hi - lo > 2.0 * options.tolerance) {
      const double mid = 0.5 * (lo + hi);
      (run(mid) ? lo : hi) = mid;
    }
  result.stable = lo;
  result.unstable = hi;
  return result;
}

}  // namespace matpoint
