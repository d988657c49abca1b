// The output folder of a run: which files in it are matpoint's (docs/output.md "Files"), so that a
// new run does not mix its files with an earlier run's, and a restart does not go back in time.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace matpoint {

/// The files in `dir` that a run writes (particles_NNNNNN.vtu, domains_NNNNNN.vtu, results.pvd,
/// domains.pvd, history.csv, summary.json, checkpoint*.h5, plots/*.png and their .partial
/// temporaries); empty when `dir` does not exist. Other files are not listed.
std::vector<std::filesystem::path> run_files_in(const std::filesystem::path& dir);

/// "results.pvd, history.csv and 41 particles_*.vtu": a short description of run_files_in's list.
std::string describe_run_files(const std::vector<std::filesystem::path>& files);

/// Deletes run_files_in(dir) (and an emptied plots/); returns how many files were deleted.
std::size_t remove_run_files(const std::filesystem::path& dir);

/// Throws InputError when the run that last wrote the checkpoint's folder finished (summary.json
/// status "ok") at a later step than `checkpoint_step`: restarting from it would silently go back
/// and overwrite that run's later outputs. Names both steps.
void refuse_stale_checkpoint(const std::filesystem::path& checkpoint, long checkpoint_step);

}  // namespace matpoint
