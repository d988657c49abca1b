// "Did you mean ...?" for the command line: a mistyped command or option gets the nearest name.
#pragma once

#include <CLI/CLI.hpp>
#include <optional>
#include <string>
#include <vector>

namespace matpoint {

/// The candidate closest to `word` by edit distance, if it is close enough to be a typo (at most
/// 2 edits, and fewer than half of the word's letters), or a candidate that starts with `word`.
std::optional<std::string> nearest_name(const std::string& word, const std::vector<std::string>& candidates);

/// Handles what CLI11 reports badly, before parsing: `matpoint help [COMMAND]` prints the help
/// and returns 0; an unknown first word gets "did you mean" and returns 2. nullopt: parse as usual.
std::optional<int> handle_command_word(CLI::App& app, int argc, char** argv);

/// The message for arguments that no option took (CLI::ExtrasError): each unknown option with the
/// nearest option of the command it was given to.
std::string describe_extras(const CLI::App& app);

}  // namespace matpoint
