#include "matpoint/io/output_folder.hpp"

#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>
#include <system_error>

#include "matpoint/core/errors.hpp"

namespace matpoint {

namespace {

namespace fs = std::filesystem;

/// The file names a run writes directly in its folder (run_outputs.hpp, runner.cpp, checkpoint.hpp).
bool is_run_file(const std::string& name) {
  static const std::regex pattern(
      R"(((particles|domains)_\d{6}\.vtu|results\.pvd|domains\.pvd|history\.csv|summary\.json|)"
      R"(checkpoint(\.previous|\.s\d{8,}\.r\d{4,})?\.h5)(\.partial.*)?)");
  return std::regex_match(name, pattern);
}

/// The plot names plot_history.py writes into plots/.
bool is_plot_file(const std::string& name) {
  static const std::regex pattern(R"((energy|momentum|probes|final_state)(\.partial)?\.png)");
  return std::regex_match(name, pattern);
}

void add_matching(const fs::path& dir, bool (*matches)(const std::string&), std::vector<fs::path>& out) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return;
  for (const auto& entry : fs::directory_iterator(dir, ec))
    if (entry.is_regular_file(ec) && matches(entry.path().filename().string())) out.push_back(entry.path());
}

}  // namespace

std::vector<fs::path> run_files_in(const fs::path& dir) {
  std::vector<fs::path> out;
  add_matching(dir, is_run_file, out);
  add_matching(dir / "plots", is_plot_file, out);
  std::sort(out.begin(), out.end());
  return out;
}

std::string describe_run_files(const std::vector<fs::path>& files) {
  std::map<std::string, int> series;  // particles_*.vtu -> count
  std::vector<std::string> singles;
  for (const auto& file : files) {
    std::string name = file.filename().string();
    if (file.parent_path().filename() == "plots") name = "plots/" + name;
    static const std::regex numbered(R"((\w+_)\d{6}(\.vtu.*))");
    std::smatch m;
    if (std::regex_match(name, m, numbered))
      ++series[m[1].str() + "*" + m[2].str()];
    else
      singles.push_back(name);
  }
  std::vector<std::string> parts;
  for (const auto& [pattern, count] : series) parts.push_back(std::to_string(count) + " " + pattern);
  const std::size_t shown = std::min<std::size_t>(singles.size(), 6);
  parts.insert(parts.end(), singles.begin(), singles.begin() + static_cast<long>(shown));
  if (singles.size() > shown) parts.push_back(std::to_string(singles.size() - shown) + " more");
  std::string out;
  for (std::size_t i = 0; i < parts.size(); ++i)
    out += (i == 0 ? "" : i + 1 == parts.size() ? " and " : ", ") + parts[i];
  return out;
}

std::size_t remove_run_files(const fs::path& dir) {
  std::size_t removed = 0;
  for (const auto& file : run_files_in(dir)) removed += fs::remove(file) ? 1 : 0;
  std::error_code ec;
  if (fs::is_empty(dir / "plots", ec) && !ec) fs::remove(dir / "plots", ec);
  return removed;
}

void refuse_stale_checkpoint(const fs::path& checkpoint, long checkpoint_step) {
  const fs::path summary_file = checkpoint.parent_path() / "summary.json";
  std::ifstream in(summary_file);
  if (!in) return;
  const auto summary = nlohmann::json::parse(in, nullptr, /*allow_exceptions=*/false);
  if (!summary.is_object() || summary.value("status", "") != "ok") return;
  const auto steps = summary.find("steps");
  if (steps == summary.end() || !steps->is_number_integer()) return;
  const long finished_step = steps->get<long>();
  if (finished_step <= checkpoint_step) return;
  throw InputError(
      {{checkpoint.string(),
        "a checkpoint of step " + std::to_string(checkpoint_step) + ", older than the run that finished in " +
            checkpoint.parent_path().string() + " at step " + std::to_string(finished_step) +
            " (summary.json): restarting would go back and overwrite its later outputs",
        "the checkpoint of that run's last step: set output.checkpoint so that a run writes one when "
        "it finishes, and run again (docs/output.md \"Checkpoints and restart\")"}});
}

}  // namespace matpoint
