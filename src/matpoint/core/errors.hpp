// Error types and the exit codes of the command line (DESIGN.md: 0 ok, 2 bad input, 3 numerical failure).
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

namespace matpoint {

enum ExitCode : int { kExitOk = 0, kExitOther = 1, kExitBadInput = 2, kExitNumerical = 3 };

/// One problem found in the input: where (JSON path), what was there, what was expected.
struct InputIssue {
  std::string path;
  std::string value;
  std::string expected;
  [[nodiscard]] std::string message() const { return path + ": got " + value + ", expected " + expected; }
};

/// Thrown after validation when the input has one or more problems; carries all of them.
class InputError : public std::runtime_error {
 public:
  explicit InputError(std::vector<InputIssue> issues);
  [[nodiscard]] const std::vector<InputIssue>& issues() const { return issues_; }

 private:
  std::vector<InputIssue> issues_;
};

/// A run that became numerically invalid: names the step, time and entity (particle or node).
class NumericalFailure : public std::runtime_error {
 public:
  NumericalFailure(long step, double time, std::string entity, const std::string& what);
  [[nodiscard]] long step() const { return step_; }
  [[nodiscard]] double time() const { return time_; }
  [[nodiscard]] const std::string& entity() const { return entity_; }

 private:
  long step_;
  double time_;
  std::string entity_;
};

}  // namespace matpoint
