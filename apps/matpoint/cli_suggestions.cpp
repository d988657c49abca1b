#include "cli_suggestions.hpp"

#include <algorithm>
#include <cstdio>
#include <numeric>

namespace matpoint {

namespace {

std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  std::iota(row.begin(), row.end(), 0);
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

std::vector<std::string> command_names(const CLI::App& app) {
  std::vector<std::string> names;
  for (const auto* sub : app.get_subcommands([](const CLI::App*) { return true; }))
    names.push_back(sub->get_name());
  return names;
}

std::vector<std::string> long_options(const CLI::App& app) {
  std::vector<std::string> names;
  for (const auto* option : app.get_options())
    for (const auto& name : option->get_lnames()) names.push_back("--" + name);
  return names;
}

std::string with_suggestion(const std::string& what, const std::optional<std::string>& nearest) {
  return nearest ? what + "; did you mean '" + *nearest + "'?" : what;
}

}  // namespace

std::optional<std::string> nearest_name(const std::string& word, const std::vector<std::string>& candidates) {
  std::optional<std::string> best;
  std::size_t best_distance = 3;
  for (const auto& candidate : candidates) {
    const std::size_t d = edit_distance(word, candidate);
    if (d < best_distance && 2 * d < word.size()) best = candidate, best_distance = d;
  }
  if (!best && word.size() >= 2)
    for (const auto& candidate : candidates)
      if (candidate.starts_with(word)) return candidate;
  return best;
}

std::optional<int> handle_command_word(CLI::App& app, int argc, char** argv) {
  if (argc < 2) return std::nullopt;
  const std::string word = argv[1];
  if (word.empty() || word[0] == '-') return std::nullopt;
  const auto names = command_names(app);
  if (word == "help") {
    if (argc == 2) {
      std::fputs(app.help().c_str(), stdout);
      return 0;
    }
    const std::string topic = argv[2];
    if (std::find(names.begin(), names.end(), topic) != names.end()) {
      std::fputs(app.get_subcommand(topic)->help().c_str(), stdout);
      return 0;
    }
    std::fprintf(stderr, "error: %s\n",
                 with_suggestion("no command '" + topic + "'", nearest_name(topic, names)).c_str());
    return 2;
  }
  if (std::find(names.begin(), names.end(), word) != names.end()) return std::nullopt;
  std::string list;
  for (const auto& name : names) list += (list.empty() ? "" : ", ") + name;
  std::fprintf(stderr, "error: %s\ncommands: %s (matpoint help COMMAND for its options)\n",
               with_suggestion("unknown command '" + word + "'", nearest_name(word, names)).c_str(),
               list.c_str());
  return 2;
}

std::string describe_extras(const CLI::App& app) {
  const CLI::App* command = &app;
  for (const auto* sub : app.get_subcommands()) command = sub;  // the command that was given
  const std::string name = command == &app ? "matpoint" : command->get_name();
  std::string out;
  for (const auto& arg : command->remaining(true)) {
    if (!out.empty()) out += "\n";
    if (arg.starts_with("-")) {
      const std::string option = arg.substr(0, arg.find('='));
      out += "error: " + with_suggestion("unknown option '" + option + "' for '" + name + "'",
                                         nearest_name(option, long_options(*command)));
    } else {
      out += "error: unexpected argument '" + arg + "' for '" + name + "'";
    }
  }
  return out + "\nRun 'matpoint help" + (command == &app ? "" : " " + name) + "' for the options.";
}

}  // namespace matpoint
