#include "stability_scan_command.hpp"

#include <cstdio>
#include <fstream>
#include <sstream>

#include "matpoint/core/errors.hpp"

namespace matpoint {

void StabilityScanCommand::add_to(CLI::App& app) {
  command_ = app.add_subcommand(
      "stability-scan",
      "find the largest stable value of an input parameter (the Courant number) by bisection");
  command_->add_option("input", input_, "input file (JSON, comments allowed)")->required();
  command_->add_option("--parameter", options_.parameter, "dot path of the scanned number")
      ->capture_default_str();
  command_->add_option("--lo", options_.lo, "a stable value (checked first)")->capture_default_str();
  command_->add_option("--hi", options_.hi, "an unstable value (checked second)")->capture_default_str();
  command_->add_option("--tolerance", options_.tolerance, "half-width of the final bracket")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  command_
      ->add_option("--growth", options_.growth,
                   "unstable when the velocity scale (sqrt of kinetic energy) grows by more than this factor")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  command_->add_option(
      "--set", sets_,
      "PATH=JSON: set an input value before the scan, e.g. solver.fmpm.order=4 (null removes it)");
  command_->add_option("--threads", options_.threads, "OpenMP threads per run")->capture_default_str();
  command_->add_flag("--json", json_, "print the result as JSON");
}

int StabilityScanCommand::run() const {
  ScanOptions options = options_;
  for (const auto& set : sets_) {
    const auto eq = set.find('=');
    if (eq == std::string::npos || eq == 0) {
      std::fprintf(stderr, "input error: --set %s: expected PATH=JSON, e.g. solver.fmpm.order=4\n",
                   set.c_str());
      return kExitBadInput;
    }
    const std::string value = set.substr(eq + 1);
    if (!nlohmann::json::accept(value)) {
      std::fprintf(stderr, "input error: --set %s: the value %s is not JSON (quote strings: '\"fmpm\"')\n",
                   set.c_str(), value.c_str());
      return kExitBadInput;
    }
    options.overrides.emplace_back(set.substr(0, eq), value);
  }
  if (!(options.lo < options.hi)) {
    std::fprintf(stderr, "input error: --lo %g --hi %g: expected lo < hi\n", options.lo, options.hi);
    return kExitBadInput;
  }
  std::ifstream file(input_);
  if (!file) {
    std::fprintf(stderr, "input error: %s: cannot read the file\n", input_.c_str());
    return kExitBadInput;
  }
  std::stringstream text;
  text << file.rdbuf();
  nlohmann::json input;
  try {
    input = nlohmann::json::parse(text.str(), nullptr, true, /*ignore_comments=*/true);
  } catch (const nlohmann::json::exception& e) {
    std::fprintf(stderr, "input error: (json): %s\n", e.what());
    return kExitBadInput;
  }
  try {
    const auto result = stability_scan(input, options, [&](const ScanRun& r) {
      if (!json_)
        std::printf("  %s = %.5f  %s%s%s\n", options.parameter.c_str(), r.value,
                    r.stable ? "stable" : "unstable", r.stable ? "" : ": ", r.reason.c_str());
      std::fflush(stdout);
    });
    if (json_) {
      nlohmann::json j = {
          {"parameter", options.parameter}, {"bracketed", result.bracketed},
          {"stable", result.stable},        {"unstable", result.unstable},
          {"limit", result.limit()},        {"tolerance", 0.5 * (result.unstable - result.stable)},
          {"runs", nlohmann::json::array()}};
      for (const auto& r : result.runs)
        j["runs"].push_back({{"value", r.value}, {"stable", r.stable}, {"reason", r.reason}});
      std::printf("%s\n", j.dump(2).c_str());
    } else if (result.bracketed) {
      std::printf("%s limit: %.4f +/- %.4f (largest stable %.4f, smallest unstable %.4f)\n",
                  options.parameter.c_str(), result.limit(), 0.5 * (result.unstable - result.stable),
                  result.stable, result.unstable);
    } else {
      std::printf("not bracketed: --lo %g must be stable and --hi %g unstable\n", options.lo, options.hi);
    }
    return result.bracketed ? kExitOk : kExitOther;
  } catch (const InputError& error) {
    for (const auto& issue : error.issues())
      std::fprintf(stderr, "input error: %s\n", issue.message().c_str());
    return kExitBadInput;
  }
}

}  // namespace matpoint
