// `matpoint verify`: the built-in verification problems (analysis/verification.hpp) over a list of
// resolutions, with error norms, observed orders, plots and the checks against the papers.
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace matpoint {

class VerifyCommand {
 public:
  void add_to(CLI::App& app, std::string scripts_dir);
  [[nodiscard]] bool chosen() const { return command_ != nullptr && command_->parsed(); }
  [[nodiscard]] int run() const;

 private:
  CLI::App* command_ = nullptr;
  std::string scripts_dir_;
  std::vector<std::string> names_;
  std::string shape_;
  std::string method_;  // mpm, impm, improved-cpdi
  double amplitude_ = 0;
  std::string time_;  // "T" (one period) or "T/4"
  std::vector<int> cells_;
  int particles_per_cell_ = 2;
  std::string out_ = "out/verify";  // like `run`: results under out/, never loose in the current folder
  int threads_ = 1;
  bool json_ = false, full_ = false, plots_ = true, gong_walls_ = true;
};

}  // namespace matpoint
