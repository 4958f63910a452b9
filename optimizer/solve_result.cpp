#include "optimizer/solve_result.hpp"

#include <fmt/format.h>

namespace pkmopt {

std::string_view to_string(SolveStatus status) {
  switch (status) {
    case SolveStatus::converged:
      return "converged";
    case SolveStatus::acceptable:
      return "acceptable";
    case SolveStatus::max_iterations:
      return "max_iterations";
    case SolveStatus::max_time:
      return "max_time";
    case SolveStatus::infeasible:
      return "infeasible";
    case SolveStatus::diverging:
      return "diverging";
    case SolveStatus::evaluation_error:
      return "evaluation_error";
    case SolveStatus::failed:
      return "failed";
  }
  return "failed";
}

bool SolveResult::usable() const {
  return (status == SolveStatus::converged || status == SolveStatus::acceptable) &&
         !fitness.empty() && constraint_violation <= 1e-6;
}

std::string SolveResult::summary() const {
  return fmt::format(
      "{} on '{}': {}, f = {:.10g}, constraint violation {:.3g}, {} iterations, {} fitness and "
      "{} gradient evaluations, {:.3f} s{}{}",
      solver, problem, to_string(status), objective, constraint_violation, iterations,
      fitness_evaluations, gradient_evaluations, seconds, message.empty() ? "" : " (",
      message.empty() ? std::string() : message + ")");
}

}  // namespace pkmopt
