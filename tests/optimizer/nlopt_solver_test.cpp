// Tests of optimizer/nlopt_solver on Hock–Schittkowski 71 and Rosenbrock.
#include "optimizer/nlopt_solver.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

#include "problems/benchmarks/benchmarks.hpp"

namespace pkmopt {
namespace {

constexpr double kHs71Optimum = 17.0140173;  // Hock & Schittkowski 1981, problem 71

SolveResult run(const Problem& problem, const std::vector<double>& x0, const std::string& name) {
  NloptOptions options;
  options.algorithm = name;
  return solve_with_nlopt(problem, x0, options);
}

TEST(Nlopt, Hs71WithSlsqp) {
  const SolveResult result = run(Hs71(), {1.0, 5.0, 5.0, 1.0}, "SLSQP");
  ASSERT_TRUE(result.usable()) << result.summary();
  EXPECT_NEAR(result.objective, kHs71Optimum, 1e-6);
  EXPECT_NEAR(result.x[1], 4.7429994, 1e-5);
  EXPECT_EQ(result.solver, "nlopt:SLSQP");
}

TEST(Nlopt, Hs71WithCobylaWithoutDerivatives) {
  NloptOptions options;
  options.algorithm = "cobyla";
  options.max_evaluations = 3000;
  // COBYLA handles the equality as two inequalities and keeps shrinking its trust region
  // without meeting xtol_rel: it ends on its budget, at the optimum.
  const SolveResult result = solve_with_nlopt(Hs71(), {1.0, 5.0, 5.0, 1.0}, options);
  EXPECT_LT(result.constraint_violation, 1e-6) << result.summary();
  EXPECT_NEAR(result.objective, kHs71Optimum, 1e-4);
  EXPECT_EQ(result.gradient_evaluations, 0);
}

TEST(Nlopt, RosenbrockLocal) {
  for (const char* name : {"LBFGS", "SLSQP", "BOBYQA"}) {
    const SolveResult result = run(Rosenbrock(4), {-1.2, 1.0, -1.2, 1.0}, name);
    ASSERT_TRUE(result.usable()) << result.summary();
    EXPECT_NEAR(result.objective, 0.0, 1e-7) << name;
    for (double v : result.x) EXPECT_NEAR(v, 1.0, 1e-3) << name;
  }
}

TEST(Nlopt, RosenbrockGlobal) {
  NloptOptions options;
  options.algorithm = "DIRECT_L";
  options.max_evaluations = 3000;
  const SolveResult result = solve_with_nlopt(Rosenbrock(2), {0.0, 0.0}, options);
  EXPECT_TRUE(result.usable()) << result.summary();
  EXPECT_LT(result.objective, 1e-3);
}

TEST(Nlopt, IsresHandlesConstraints) {
  NloptOptions options;
  options.algorithm = "ISRES";
  options.max_evaluations = 20000;
  options.seed = 3;
  const SolveResult result = solve_with_nlopt(Hs71(), {1.0, 5.0, 5.0, 1.0}, options);
  // A stochastic global search: near the optimum, within a loose band.
  EXPECT_LT(result.constraint_violation, 1e-3) << result.summary();
  EXPECT_LT(result.objective, 18.0) << result.summary();
}

TEST(Nlopt, ExplainsUnsupportedConstraints) {
  NloptOptions options;
  options.algorithm = "BOBYQA";
  const auto reason = nlopt_explain_unsupported(Hs71(), options);
  ASSERT_TRUE(reason.has_value());
  EXPECT_NE(reason->find("equality constraints"), std::string::npos);
  EXPECT_THROW(solve_with_nlopt(Hs71(), {1, 5, 5, 1}, options), std::invalid_argument);
  options.algorithm = "MMA";  // inequalities only
  ASSERT_TRUE(nlopt_explain_unsupported(Hs71(), options).has_value());
  options.algorithm = "NO_SUCH";
  const auto unknown = nlopt_explain_unsupported(Hs71(), options);
  ASSERT_TRUE(unknown.has_value());
  EXPECT_NE(unknown->find("SLSQP"), std::string::npos);
}

TEST(Nlopt, BudgetExhaustedIsAResult) {
  NloptOptions options;
  options.algorithm = "NELDERMEAD";
  options.max_evaluations = 10;
  const SolveResult result = solve_with_nlopt(Rosenbrock(4), {-1.2, 1.0, -1.2, 1.0}, options);
  EXPECT_EQ(result.status, SolveStatus::max_iterations);
  EXPECT_FALSE(result.usable());
}

}  // namespace
}  // namespace pkmopt
