// Files are written to a temporary name in the same folder and renamed into place, so a killed run
// leaves either the previous complete file or the new complete file, never a torn one.
#pragma once

#include <filesystem>
#include <string_view>

namespace matpoint {

/// Writes content to path atomically; throws std::runtime_error naming the path on failure.
void write_file_atomically(const std::filesystem::path& path, std::string_view content);

}  // namespace matpoint
