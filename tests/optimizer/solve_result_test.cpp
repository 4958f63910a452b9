// Tests of optimizer/solve_result: the status names written to summary.json, when a result is
// usable, and its one-line summary.
#include "optimizer/solve_result.hpp"

#include <gtest/gtest.h>

#include <string>

namespace pkmopt {
namespace {

TEST(SolveResult, StatusNames) {
  EXPECT_EQ(to_string(SolveStatus::converged), "converged");
  EXPECT_EQ(to_string(SolveStatus::acceptable), "acceptable");
  EXPECT_EQ(to_string(SolveStatus::max_iterations), "max_iterations");
  EXPECT_EQ(to_string(SolveStatus::max_time), "max_time");
  EXPECT_EQ(to_string(SolveStatus::infeasible), "infeasible");
  EXPECT_EQ(to_string(SolveStatus::diverging), "diverging");
  EXPECT_EQ(to_string(SolveStatus::evaluation_error), "evaluation_error");
  EXPECT_EQ(to_string(SolveStatus::failed), "failed");
}

// Usable: converged or acceptable, evaluated, and feasible to 1e-6.
TEST(SolveResult, Usable) {
  SolveResult r;
  r.fitness = {1.0};
  for (SolveStatus s : {SolveStatus::converged, SolveStatus::acceptable}) {
    r.status = s;
    r.constraint_violation = 1e-6;
    EXPECT_TRUE(r.usable()) << to_string(s);
    r.constraint_violation = 2e-6;
    EXPECT_FALSE(r.usable()) << to_string(s);
  }
  r.constraint_violation = 0.0;
  for (SolveStatus s :
       {SolveStatus::max_iterations, SolveStatus::max_time, SolveStatus::infeasible,
        SolveStatus::diverging, SolveStatus::evaluation_error, SolveStatus::failed}) {
    r.status = s;
    EXPECT_FALSE(r.usable()) << to_string(s);
  }
  r.status = SolveStatus::converged;
  r.fitness.clear();  // never evaluated
  EXPECT_FALSE(r.usable());
}

TEST(SolveResult, Summary) {
  SolveResult r;
  r.solver = "nlopt:SLSQP";
  r.problem = "hs71";
  r.status = SolveStatus::converged;
  r.objective = 17.0140173;
  r.constraint_violation = 0.0;
  r.iterations = 9;
  r.fitness_evaluations = 40;
  r.gradient_evaluations = 10;
  r.seconds = 0.25;
  EXPECT_EQ(r.summary(),
            "nlopt:SLSQP on 'hs71': converged, f = 17.0140173, constraint violation 0, 9 "
            "iterations, 40 fitness and 10 gradient evaluations, 0.250 s");
  r.message = "Optimization terminated successfully";
  EXPECT_TRUE(r.summary().ends_with(", 0.250 s (Optimization terminated successfully)"))
      << r.summary();
}

}  // namespace
}  // namespace pkmopt
