// Files are written to a temporary name in the same folder and renamed into place, so a killed run
// leaves either the previous complete file or the new complete file, never a torn one.
#pragma once

#include <filesystem>
#include <string_view>

namespace matpoint {

/// Writes content to path atomically; throws std::runtime_error naming the path on failure.
void write_file_atomically(const std::filesystem::path& path, std::string_view content);

/// Flushes a file's (or a folder's) data to the disk (fsync); throws std::runtime_error on failure.
/// Checkpoints call it before their rename, so that a power cut cannot leave a renamed empty file.
void sync_to_disk(const std::filesystem::path& path);

}  // namespace matpoint
