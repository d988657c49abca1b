// `matpoint dispersion`: the linearised 1-D stability / dispersion analysis of Gong 2015 ch. 7
// (src/matpoint/analysis/dispersion.hpp, docs/theory/stability.md).
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <string>

namespace matpoint {

struct DispersionCommand {
  CLI::App* app;             ///< the subcommand: true after parsing when it was given
  std::function<int()> run;  ///< prints the table and bounds, writes the CSV and plots; returns the exit code
};

/// Registers the `dispersion` subcommand on `app`; plots are drawn with scripts_dir/plot_dispersion.py.
DispersionCommand add_dispersion_command(CLI::App& app, const std::string& scripts_dir);

}  // namespace matpoint
