// Tests of models/serial/five_axis_ik: for table-table, head-head and table-head chains (one with
// an inclined, nutating axis), every solution puts the tool where forward kinematics (the chain's
// own product) says, the axis values a pose came from are among the solutions, the singular
// configuration (A = 0 of 641236) frees the C axis, directions outside a nutating head's
// hemisphere have no solution, and chains that are not 5-axis are refused.
#include "models/serial/five_axis_ik.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "tests/sample_machines.hpp"

namespace pkmopt {
namespace {

using sample_machines::Uniform;

constexpr double kPi = std::numbers::pi;

struct Family {
  const char* code;
  int spindle;
};

// The distance of two angles on the circle.
double angle_gap(double a, double b) { return std::abs(std::remainder(a - b, 2.0 * kPi)); }

TEST(FiveAxisIk, EverySolutionReachesThePoseAndTheOriginalIsAmongThem) {
  const Eigen::Vector3d r_tool(0.01, -0.02, 0.12), a_tool(0, 0, 1);
  for (const Family f :
       {Family{"641236", 5}, Family{"123646", 5}, Family{"612356", 5},
        Family{"123 6 4:0.7853981633974483 5 6", 5},
        Family{"123 6 5:0.7853981633974483 6 5:-0.7853981633974483 6", 5}, Family{"12345", -1}}) {
    const SerialChain chain = SerialChain::from_code(f.code);
    Uniform u(7);
    for (int trial = 0; trial < 50; ++trial) {
      Eigen::VectorXd q(chain.num_variables());
      int k = 0;
      for (const ChainElement& e : chain.elements()) {
        if (!e.variable) continue;
        q(k) = k == f.spindle ? 0.0 : e.motion >= 4 ? u(-3.0, 3.0) : u(-0.5, 0.5);
        ++k;
      }
      const Eigen::Matrix4d T = chain.transform(q);
      const Eigen::Vector3d r0 = (T * r_tool.homogeneous()).head<3>();
      const Eigen::Vector3d a0 = T.topLeftCorner<3, 3>() * a_tool;
      const std::vector<FiveAxisSolution> solutions =
          five_axis_inverse_kinematics(chain, f.spindle, r_tool, a_tool, r0, a0);
      ASSERT_FALSE(solutions.empty()) << f.code;
      EXPECT_LE(solutions.size(), 2u);
      bool original = false;
      for (const FiveAxisSolution& s : solutions) {
        const Eigen::Matrix4d S = chain.transform(s.q);
        EXPECT_LT(((S * r_tool.homogeneous()).head<3>() - r0).norm(), 1e-10) << f.code;
        EXPECT_LT((S.topLeftCorner<3, 3>() * a_tool - a0).norm(), 1e-10) << f.code;
        bool same = true;
        int j = 0;
        for (const ChainElement& e : chain.elements()) {
          if (!e.variable) continue;
          same = same && (e.motion >= 4 ? angle_gap(s.q(j), q(j)) : std::abs(s.q(j) - q(j))) < 1e-8;
          ++j;
        }
        original = original || same;
      }
      EXPECT_TRUE(original) << f.code << " q = " << q.transpose();
    }
  }
}

// 641236 by hand: the tool axis Rz(C) Rx(A) e_z = (sin C sin A, -cos C sin A, cos A), so the
// two branches are (A, C) and (-A, C + pi); at A = 0 C turns without moving the axis.
TEST(FiveAxisIk, TableTableBranchesAndItsSingularity) {
  const SerialChain chain = SerialChain::from_code("641236");
  const Eigen::Vector3d r_tool(0, 0, 0.1), a_tool(0, 0, 1);
  const double A = 0.6, C = -1.1;
  const Eigen::Vector3d a0(std::sin(C) * std::sin(A), -std::cos(C) * std::sin(A), std::cos(A));
  const auto solutions =
      five_axis_inverse_kinematics(chain, 5, r_tool, a_tool, Eigen::Vector3d(0.2, 0.1, -0.3), a0);
  ASSERT_EQ(solutions.size(), 2u);
  std::vector<std::pair<double, double>> found;
  for (const auto& s : solutions) found.emplace_back(s.q(1), s.q(0));
  const bool first = angle_gap(found[0].first, A) < 1e-12;
  const auto& plus = first ? found[0] : found[1];
  const auto& minus = first ? found[1] : found[0];
  EXPECT_NEAR(plus.first, A, 1e-12);
  EXPECT_LT(angle_gap(plus.second, C), 1e-12);
  EXPECT_NEAR(minus.first, -A, 1e-12);
  EXPECT_LT(angle_gap(minus.second, C + kPi), 1e-12);
  for (const auto& s : solutions) EXPECT_FALSE(s.singular);

  const auto vertical = five_axis_inverse_kinematics(
      chain, 5, r_tool, a_tool, Eigen::Vector3d(0.2, 0.1, -0.3), Eigen::Vector3d(0, 0, 1), 0.4);
  ASSERT_EQ(vertical.size(), 1u);
  EXPECT_TRUE(vertical[0].singular);
  EXPECT_DOUBLE_EQ(vertical[0].q(0), 0.4);  // C takes the free angle
  EXPECT_NEAR(vertical[0].q(1), 0.0, 1e-12);
}

// A nutating head: C, then a second axis inclined 45 deg from it (Ry(45) Rz(B) Ry(-45)), the tool
// along z at B = 0. Its axis is (1 - cos B, -sin B, 1 + cos B) / 2 turned by C, so it reaches the
// upper half-space only.
TEST(FiveAxisIk, NutatingHeadReachesItsHemisphereOnly) {
  const SerialChain chain =
      SerialChain::from_code("123 6 5:0.7853981633974483 6 5:-0.7853981633974483 6");
  const Eigen::Vector3d r_tool(0, 0, 0.15), a_tool(0, 0, 1);
  const auto up = five_axis_inverse_kinematics(chain, 5, r_tool, a_tool, Eigen::Vector3d::Zero(),
                                               Eigen::Vector3d(0.1, 0.2, 0.9).normalized());
  ASSERT_FALSE(up.empty());
  for (const auto& s : up) {
    const double B = s.q(4);
    EXPECT_NEAR(0.5 * (1.0 + std::cos(B)), Eigen::Vector3d(0.1, 0.2, 0.9).normalized().z(), 1e-12);
  }
  EXPECT_TRUE(five_axis_inverse_kinematics(chain, 5, r_tool, a_tool, Eigen::Vector3d::Zero(),
                                           Eigen::Vector3d(0.1, 0.2, -0.9).normalized())
                  .empty());
}

TEST(FiveAxisIk, ChainsThatAreNotFiveAxisAreRefused) {
  const Eigen::Vector3d zero = Eigen::Vector3d::Zero(), z(0, 0, 1);
  for (const char* code : {"1236", "664123", "44123"}) {
    try {
      five_axis_inverse_kinematics(SerialChain::from_code(code), -1, zero, z, zero, z);
      ADD_FAILURE() << code << " was accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(code), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace pkmopt
