// `matpoint stability-scan`: the empirical stability limit of an input (analysis/stability_scan.hpp).
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "matpoint/analysis/stability_scan.hpp"

namespace matpoint {

class StabilityScanCommand {
 public:
  void add_to(CLI::App& app);
  [[nodiscard]] bool chosen() const { return command_ != nullptr && command_->parsed(); }
  [[nodiscard]] int run() const;

 private:
  CLI::App* command_ = nullptr;
  std::string input_;
  ScanOptions options_;
  std::vector<std::string> sets_;
  bool json_ = false;
};

}  // namespace matpoint
