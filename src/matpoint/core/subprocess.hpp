// Starting helper programs (the plotting scripts) without a shell: the arguments travel as an
// argv, so quotes, spaces and `$` in a path are just characters.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace matpoint {

/// Runs argv[0] (searched on PATH when it has no '/') with the arguments argv, waits for it, and
/// returns "" on exit status 0; otherwise a one-paragraph reason: the program could not be
/// started (with the system's reason), or it exited non-zero or was killed, followed by the end
/// of what it wrote to stderr. Its stdout is discarded.
std::string run_program(const std::vector<std::string>& argv);

/// Runs a Python script: Debian's /usr/bin/python3 first (python3-matplotlib installs there,
/// whatever else is on PATH), else python3 from PATH. Returns "" on success, else the reason.
std::string run_python_script(const std::filesystem::path& script, const std::vector<std::string>& args);

}  // namespace matpoint
