// Tests of optimizer/ipopt_solver on Hock–Schittkowski 71 and Rosenbrock.
#include "optimizer/ipopt_solver.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

#include "problems/benchmarks/benchmarks.hpp"

namespace pkmopt {
namespace {

// HS71 optimum (Hock & Schittkowski 1981, problem 71; also Ipopt's own example).
constexpr double kHs71Optimum = 17.0140173;
const std::vector<double> kHs71X{1.0, 4.7429994, 3.8211503, 1.3794082};

// The same problem with its gradient hidden, so Ipopt must use finite differences.
class WithoutGradient : public Problem {
 public:
  explicit WithoutGradient(const Problem& inner) : inner_(inner) {}
  Bounds bounds() const override { return inner_.bounds(); }
  std::size_t num_objectives() const override { return inner_.num_objectives(); }
  std::size_t num_equality() const override { return inner_.num_equality(); }
  std::size_t num_inequality() const override { return inner_.num_inequality(); }
  std::vector<double> fitness(const std::vector<double>& x) const override {
    return inner_.fitness(x);
  }
  std::string name() const override { return inner_.name() + " (no gradient)"; }

 private:
  const Problem& inner_;
};

TEST(Ipopt, Hs71WithExactGradient) {
  Hs71 problem;
  const SolveResult result = solve_with_ipopt(problem, {1.0, 5.0, 5.0, 1.0});
  ASSERT_EQ(result.status, SolveStatus::converged) << result.summary();
  EXPECT_TRUE(result.usable());
  EXPECT_NEAR(result.objective, kHs71Optimum, 1e-6);
  for (std::size_t j = 0; j < 4; ++j) EXPECT_NEAR(result.x[j], kHs71X[j], 1e-6);
  EXPECT_LT(result.constraint_violation, 1e-7);
  EXPECT_GT(result.gradient_evaluations, 0);
}

TEST(Ipopt, Hs71WithFiniteDifferences) {
  Hs71 exact;
  WithoutGradient problem(exact);
  const SolveResult result = solve_with_ipopt(problem, {1.0, 5.0, 5.0, 1.0});
  ASSERT_TRUE(result.usable()) << result.summary();
  EXPECT_NEAR(result.objective, kHs71Optimum, 1e-5);
  for (std::size_t j = 0; j < 4; ++j) EXPECT_NEAR(result.x[j], kHs71X[j], 1e-4);
  EXPECT_EQ(result.gradient_evaluations, 0);
}

TEST(Ipopt, Rosenbrock) {
  Rosenbrock problem(5);
  const SolveResult result = solve_with_ipopt(problem, {-1.2, 1.0, -1.2, 1.0, -1.2});
  ASSERT_TRUE(result.usable()) << result.summary();
  EXPECT_NEAR(result.objective, 0.0, 1e-10);
  for (double v : result.x) EXPECT_NEAR(v, 1.0, 1e-5);
}

TEST(Ipopt, NonConvergenceIsAResult) {
  Rosenbrock problem(5);
  IpoptOptions options;
  options.max_iterations = 3;
  const SolveResult result = solve_with_ipopt(problem, {-1.2, 1.0, -1.2, 1.0, -1.2}, options);
  EXPECT_EQ(result.status, SolveStatus::max_iterations);
  EXPECT_FALSE(result.usable());
  EXPECT_NE(result.summary().find("max_iterations"), std::string::npos);
}

TEST(Ipopt, RejectedExtraOptionIsAResult) {
  Hs71 problem;
  IpoptOptions options;
  options.extra_options = {{"no_such_option", "3"}};
  const SolveResult result = solve_with_ipopt(problem, {1.0, 5.0, 5.0, 1.0}, options);
  EXPECT_EQ(result.status, SolveStatus::failed);
  EXPECT_NE(result.message.find("no_such_option"), std::string::npos);
}

TEST(Ipopt, OptionsAreValidated) {
  IpoptOptions options;
  EXPECT_FALSE(options.validate().has_value());
  options.tolerance = -1.0;
  ASSERT_TRUE(options.validate().has_value());
  EXPECT_EQ(*options.validate(),
            "IpoptOptions::tolerance = -1. Violated constraint: tolerance > 0");
  Hs71 problem;
  EXPECT_THROW(solve_with_ipopt(problem, {1, 5, 5, 1}, options), std::invalid_argument);
}

TEST(Ipopt, ExplainsMultiObjective) {
  const auto zdt1 = make_benchmark("zdt1", 5);
  const auto reason = ipopt_explain_unsupported(*zdt1);
  ASSERT_TRUE(reason.has_value());
  EXPECT_NE(reason->find("2 objectives"), std::string::npos);
  EXPECT_FALSE(ipopt_explain_unsupported(Hs71()).has_value());
}

}  // namespace
}  // namespace pkmopt
