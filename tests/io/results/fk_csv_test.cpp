// fk_csv (io/results/fk_csv.hpp): the exact text of `pkmopt fk`'s output for hand-made results.
#include "io/results/fk_csv.hpp"

#include <gtest/gtest.h>

#include <numbers>
#include <sstream>
#include <string>
#include <vector>

namespace {

TEST(FkCsv, ConvergedSolution) {
  pkmopt::FkResult r;
  r.pose.position = {0.1, -0.2, 0.95};
  r.converged = true;
  r.iterations = 4;
  r.residual = 1.5e-13;
  EXPECT_EQ(pkmopt::fk_csv(r),
            "x,y,z,rx,ry,rz,converged,iterations,residual\n"
            "0.1,-0.2,0.95,0,0,0,1,4,1.5e-13\n");
}

TEST(FkCsv, AnglesInDegreesAndAFailedSolve) {
  pkmopt::FkResult r;
  r.pose.angles = {std::numbers::pi / 6, -std::numbers::pi / 2, std::numbers::pi};
  r.converged = false;
  r.iterations = 100;
  r.residual = 0.25;
  const std::string csv = pkmopt::fk_csv(r);
  const std::string row = csv.substr(csv.find('\n') + 1);
  std::vector<std::string> fields;
  std::istringstream in(row.substr(0, row.size() - 1));
  for (std::string f; std::getline(in, f, ',');) fields.push_back(f);
  ASSERT_EQ(fields.size(), 9u);
  EXPECT_NEAR(std::stod(fields[3]), 30.0, 1e-12);
  EXPECT_NEAR(std::stod(fields[4]), -90.0, 1e-12);
  EXPECT_NEAR(std::stod(fields[5]), 180.0, 1e-12);
  EXPECT_EQ(fields[6], "0");
  EXPECT_EQ(fields[7], "100");
  EXPECT_EQ(fields[8], "0.25");
  EXPECT_EQ(row.back(), '\n');
}

}  // namespace
