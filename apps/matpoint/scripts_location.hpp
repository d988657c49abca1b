// Where the plotting scripts (plot_history.py, plot_dispersion.py, plot_convergence.py) are.
#pragma once

#include <filesystem>

namespace matpoint {

/// The scripts folder, first found of: $MATPOINT_SCRIPTS_DIR; the installed layout beside this
/// binary (<prefix>/bin/matpoint -> <prefix>/share/matpoint/scripts, see `cmake --install`); the
/// source tree's scripts/ (a binary run from its build folder). Empty when none exists.
std::filesystem::path find_scripts_dir();

}  // namespace matpoint
