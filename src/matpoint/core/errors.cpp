#include "matpoint/core/errors.hpp"

#include <sstream>

namespace matpoint {

namespace {
std::string join_issues(const std::vector<InputIssue>& issues) {
  std::ostringstream out;
  for (const auto& issue : issues) out << issue.message() << '\n';
  return out.str();
}

std::string describe_failure(long step, double time, const std::string& entity, const std::string& what) {
  std::ostringstream out;
  out << "numerical failure at step " << step << ", time " << time << ", " << entity << ": " << what;
  return out.str();
}
}  // namespace

InputError::InputError(std::vector<InputIssue> issues)
    : std::runtime_error(join_issues(issues)), issues_(std::move(issues)) {}

NumericalFailure::NumericalFailure(long step, double time, std::string entity, const std::string& what)
    : std::runtime_error(describe_failure(step, time, entity, what)),
      step_(step),
      time_(time),
      entity_(std::move(entity)) {}

}  // namespace matpoint
