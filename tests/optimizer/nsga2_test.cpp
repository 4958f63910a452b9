// Tests of optimizer/nsga2 on ZDT1/ZDT2/ZDT3 and constrained problems, and reproducibility.
#include "optimizer/nsga2.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

#include "optimizer/indicators.hpp"
#include "problems/benchmarks/benchmarks.hpp"

namespace pkmopt {
namespace {

Nsga2Options small_run(std::uint64_t seed = 1) {
  Nsga2Options options;
  options.population = 60;
  options.generations = 150;
  options.seed = seed;
  options.threads = 1;
  return options;
}

// IGD+ of the NSGA-II front against 500 points of the analytic front.
double igd_of_run(const BenchmarkProblem& problem, const Nsga2Options& options) {
  const FrontResult front = run_nsga2(problem, options);
  EXPECT_FALSE(front.x.empty()) << front.message;
  EXPECT_EQ(front.fitness_evaluations,
            static_cast<long long>(options.population * (options.generations + 1)));
  return igd_plus(front.objectives(), problem.reference_front(500));
}

TEST(Nsga2, ConvexFrontZdt1) {
  Zdt problem(1, 10);
  EXPECT_LT(igd_of_run(problem, small_run()), 0.01);
}

TEST(Nsga2, ConcaveFrontZdt2) {
  Zdt problem(2, 10);
  EXPECT_LT(igd_of_run(problem, small_run()), 0.01);
}

TEST(Nsga2, DisconnectedFrontZdt3) {
  Zdt problem(3, 10);
  EXPECT_LT(igd_of_run(problem, small_run()), 0.01);
}

TEST(Nsga2, ConstrainedBnhAndTnk) {
  Bnh bnh;
  const FrontResult front = run_nsga2(bnh, small_run());
  for (const auto& f : front.fitness) EXPECT_LE(constraint_violation(bnh, f), 0.0);
  // BNH objectives span ~0..140 and ~0..50: IGD+ relative to that scale.
  EXPECT_LT(igd_plus(front.objectives(), bnh.reference_front(500)), 0.5);
  Tnk tnk;
  const FrontResult tnk_front = run_nsga2(tnk, small_run());
  for (const auto& f : tnk_front.fitness) EXPECT_LE(constraint_violation(tnk, f), 0.0);
  EXPECT_LT(igd_plus(tnk_front.objectives(), tnk.reference_front(500)), 0.01);
}

TEST(Nsga2, SameSeedSameFrontForOneAndTwoThreads) {
  Zdt problem(1, 10);
  Nsga2Options options = small_run(7);
  options.generations = 40;
  const FrontResult one = run_nsga2(problem, options);
  options.threads = 2;
  const FrontResult two = run_nsga2(problem, options);
  ASSERT_FALSE(one.x.empty());
  EXPECT_EQ(one.x, two.x);  // bit-identical
  EXPECT_EQ(one.fitness, two.fitness);
  options.seed = 8;
  EXPECT_NE(run_nsga2(problem, options).x, one.x);
}

TEST(Nsga2, SearchInStepsEqualsOneRun) {
  // advance(7) then advance(13) is run_nsga2 with 20 generations, bit for bit, for the same
  // seed, and the evaluation count is population * (generations + 1).
  Zdt problem(2, 8);
  Nsga2Options options;
  options.population = 24;
  options.generations = 20;
  options.seed = 11;
  const FrontResult whole = run_nsga2(problem, options);
  Nsga2Search search(problem, options);
  EXPECT_EQ(search.generations(), 0u);
  EXPECT_EQ(search.fitness_evaluations(), 24);
  search.advance(7);
  search.advance(0);
  search.advance(13);
  EXPECT_EQ(search.generations(), 20u);
  const FrontResult stepped = search.front();
  EXPECT_EQ(stepped.fitness_evaluations, whole.fitness_evaluations);
  EXPECT_EQ(stepped.fitness_evaluations, 24 * 21);
  EXPECT_EQ(stepped.x, whole.x);
  EXPECT_EQ(stepped.fitness, whole.fitness);
  // A different split gives the same population too; a different seed does not.
  Nsga2Search other(problem, options);
  for (int g = 0; g < 20; ++g) other.advance(1);
  EXPECT_EQ(other.front().x, whole.x);
  options.seed = 12;
  Nsga2Search reseeded(problem, options);
  reseeded.advance(20);
  EXPECT_NE(reseeded.front().x, whole.x);
}

TEST(Nsga2, InitialPopulationIsUsed) {
  Zdt problem(1, 5);
  Nsga2Options options = small_run();
  options.generations = 0;
  options.initial_population = {{0.0, 0.0, 0.0, 0.0, 0.0}};  // a Pareto-optimal design
  const FrontResult front = run_nsga2(problem, options);
  ASSERT_FALSE(front.fitness.empty());
  EXPECT_EQ(front.fitness.front(), (std::vector<double>{0.0, 1.0}));
}

TEST(Nsga2, OptionsAreValidated) {
  Nsga2Options options;
  options.population = 7;
  ASSERT_TRUE(options.validate().has_value());
  EXPECT_NE(options.validate()->find("population"), std::string::npos);
  EXPECT_THROW(run_nsga2(Zdt(1, 5), options), std::invalid_argument);
}

}  // namespace
}  // namespace pkmopt
