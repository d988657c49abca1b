#include "scripts_location.hpp"

#include <cstdlib>
#include <system_error>

// Set by CMakeLists.txt: the scripts folder relative to the installed binary's folder, and the
// source tree's scripts folder (the fallback for a binary that was built but not installed).
#ifndef MATPOINT_INSTALLED_SCRIPTS_RELATIVE
#define MATPOINT_INSTALLED_SCRIPTS_RELATIVE "../share/matpoint/scripts"
#endif
#ifndef MATPOINT_SOURCE_SCRIPTS_DIR
#define MATPOINT_SOURCE_SCRIPTS_DIR ""
#endif

namespace matpoint {

namespace {

bool has_plot_script(const std::filesystem::path& dir) {
  std::error_code ec;
  return !dir.empty() && std::filesystem::is_regular_file(dir / "plot_history.py", ec);
}

}  // namespace

std::filesystem::path find_scripts_dir() {
  if (const char* env = std::getenv("MATPOINT_SCRIPTS_DIR"); env != nullptr && *env != '\0') return env;
  std::error_code ec;
  const auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const auto installed = (exe.parent_path() / MATPOINT_INSTALLED_SCRIPTS_RELATIVE).lexically_normal();
    if (has_plot_script(installed)) return installed;
  }
  if (has_plot_script(MATPOINT_SOURCE_SCRIPTS_DIR)) return MATPOINT_SOURCE_SCRIPTS_DIR;
  return {};
}

}  // namespace matpoint
