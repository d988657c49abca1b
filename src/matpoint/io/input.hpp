// The JSON input reader: input.json -> Spec (DESIGN.md data flow). The format is documented in
// docs/input.md. Every problem is reported with its JSON path, the value found and what was expected,
// and all problems are collected before anything is thrown.
#pragma once

#include <filesystem>
#include <string>

#include "matpoint/io/spec.hpp"

namespace matpoint {

/// Parses and validates the text of an input file (JSON; // and /* */ comments allowed).
/// Throws InputError listing every problem found; the returned Spec holds the parsed JSON in `echo`.
[[nodiscard]] Spec parse_spec(const std::string& json_text);

/// Reads `file` and parses it with parse_spec. A missing or unreadable file is an InputError whose
/// single issue has the file name as its path.
[[nodiscard]] Spec load_spec(const std::filesystem::path& file);

}  // namespace matpoint
