// Tests of models/serial/serial_chain: elementary motions, the 641236 five-axis machine against its
// closed form, tool-point Jacobians against finite differences, code parsing and the
// structure class.
#include "models/serial/serial_chain.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "models/core/pose.hpp"
#include "tests/sample_machines.hpp"

namespace pkmopt {
namespace {

TEST(SerialChain, ElementaryMotionsAreTheBaseRotationsAndTranslations) {
  for (double v : {-2.0, -0.3, 0.0, 0.7, 3.0}) {
    for (int k = 1; k <= 3; ++k) {
      Eigen::Matrix4d expected = Eigen::Matrix4d::Identity();
      expected(k - 1, 3) = v;
      EXPECT_EQ(elementary_motion<double>(k, v), expected);
    }
    for (int k = 4; k <= 6; ++k) {
      Eigen::Vector3d angles = Eigen::Vector3d::Zero();
      angles(k - 4) = v;
      Eigen::Matrix4d expected = Eigen::Matrix4d::Identity();
      expected.topLeftCorner<3, 3>() = rotation_zyx<double>(angles);  // Rx, Ry or Rz alone
      EXPECT_TRUE(elementary_motion<double>(k, v).isApprox(expected, 1e-15)) << k;
    }
  }
  EXPECT_THROW(elementary_motion<double>(7, 0.0), std::invalid_argument);
}

// The 5-axis milling machine with code 641236 (table C about z and A about x, then X, Y, Z,
// then the spindle about z): its transform written out by hand,
//   T = [Rz(psi) Rx(theta) Rz(phi),  Rz(psi) Rx(theta) (x, y, z)^T; 0 0 0 1],
//   Rz(psi) Rx(theta) = [c_psi, -s_psi c_th,  s_psi s_th;
//                        s_psi,  c_psi c_th, -c_psi s_th;
//                        0,      s_th,        c_th].
TEST(SerialChain, FiveAxisMachine641236MatchesItsClosedForm) {
  const SerialChain chain = SerialChain::from_code("641236");
  EXPECT_EQ(chain.code(), "641236");
  EXPECT_EQ(chain.num_variables(), 6);
  EXPECT_EQ(chain.num_translations(), 3);
  EXPECT_EQ(chain.num_rotations(), 3);
  sample_machines::Uniform rng(641236);
  for (int trial = 0; trial < 50; ++trial) {
    const double psi = rng(-M_PI, M_PI), th = rng(-1.5, 1.5), x = rng(-0.5, 0.5),
                 y = rng(-0.5, 0.5), z = rng(-0.5, 0.5), phi = rng(-M_PI, M_PI);
    const double cp = std::cos(psi), sp = std::sin(psi), ct = std::cos(th), st = std::sin(th);
    Eigen::Matrix3d M;
    M << cp, -sp * ct, sp * st, sp, cp * ct, -cp * st, 0.0, st, ct;
    const Eigen::Matrix3d Rphi = (Eigen::Matrix3d() << std::cos(phi), -std::sin(phi), 0,
                                  std::sin(phi), std::cos(phi), 0, 0, 0, 1)
                                     .finished();
    Eigen::Matrix4d expected = Eigen::Matrix4d::Identity();
    expected.topLeftCorner<3, 3>() = M * Rphi;
    expected.topRightCorner<3, 1>() = M * Eigen::Vector3d(x, y, z);
    Eigen::VectorXd q(6);
    q << psi, th, x, y, z, phi;
    EXPECT_TRUE(chain.transform(q).isApprox(expected, 1e-14)) << trial;
    // A tool point on the spindle axis does not move with the spindle angle.
    const Eigen::Vector3d tip(0.0, 0.0, -0.1);
    Eigen::VectorXd q2 = q;
    q2(5) += 1.0;
    EXPECT_TRUE(chain.tool_point(q, tip).isApprox(chain.tool_point(q2, tip), 1e-14));
  }
}

TEST(SerialChain, ToolPointJacobianMatchesFiniteDifferences) {
  sample_machines::Uniform rng(7);
  for (const char* code : {"641236", "12345", "3:0.4 5 1 2:-0.2 6 4:0.3 3", "66 11 45"}) {
    const SerialChain chain = SerialChain::from_code(code);
    for (int trial = 0; trial < 10; ++trial) {
      Eigen::VectorXd q(chain.num_variables());
      for (int i = 0; i < q.size(); ++i) q(i) = rng(-1.0, 1.0);
      const Eigen::Vector3d r(rng(-0.2, 0.2), rng(-0.2, 0.2), rng(-0.2, 0.2));
      const Eigen::MatrixXd J = chain.tool_point_jacobian(q, r);
      const double h = 1e-6;
      for (int i = 0; i < q.size(); ++i) {
        Eigen::VectorXd qp = q, qm = q;
        qp(i) += h;
        qm(i) -= h;
        const Eigen::Vector3d fd = (chain.tool_point(qp, r) - chain.tool_point(qm, r)) / (2 * h);
        EXPECT_LT((J.col(i) - fd).norm(), 1e-8) << code << " column " << i;
      }
    }
  }
}

// The twist Jacobian: its position rows are the tool-point Jacobian, and its rotation rows the
// angular velocity of the tool frame, omega^ = dR/dq R^T, by central differences.
TEST(SerialChain, TwistJacobianMatchesFiniteDifferences) {
  sample_machines::Uniform rng(11);
  for (const char* code : {"641236", "12345", "3:0.4 5 1 2:-0.2 6 4:0.3 3", "66 11 45"}) {
    const SerialChain chain = SerialChain::from_code(code);
    for (int trial = 0; trial < 10; ++trial) {
      Eigen::VectorXd q(chain.num_variables());
      for (int i = 0; i < q.size(); ++i) q(i) = rng(-1.0, 1.0);
      const Eigen::Vector3d r(rng(-0.2, 0.2), rng(-0.2, 0.2), rng(-0.2, 0.2));
      const Eigen::MatrixXd J = chain.twist_jacobian(q, r);
      EXPECT_LT((J.topRows(3) - chain.tool_point_jacobian(q, r)).norm(), 1e-12) << code;
      const Eigen::Matrix3d R = chain.transform(q).topLeftCorner<3, 3>();
      const double h = 1e-6;
      for (int i = 0; i < q.size(); ++i) {
        Eigen::VectorXd qp = q, qm = q;
        qp(i) += h;
        qm(i) -= h;
        const Eigen::Matrix3d W = (chain.transform(qp).topLeftCorner<3, 3>() -
                                   chain.transform(qm).topLeftCorner<3, 3>()) /
                                  (2 * h) * R.transpose();
        const Eigen::Vector3d omega(W(2, 1), W(0, 2), W(1, 0));
        EXPECT_LT((J.col(i).tail<3>() - omega).norm(), 1e-8) << code << " column " << i;
        EXPECT_LT((W + W.transpose()).norm(), 1e-8) << code;  // skew: a rotation rate
      }
    }
  }
}

TEST(SerialChain, ConstantsEnterTheProduct) {
  const SerialChain chain = SerialChain::from_code("1, 3:0.25, 4:1.5707963267948966");
  EXPECT_EQ(chain.num_variables(), 1);
  EXPECT_EQ(chain.code(), "134");
  Eigen::VectorXd q(1);
  q << 0.1;
  // x 0.1, z 0.25, then a quarter turn about x: the point (0, 1, 0) goes to (0, 0, 1).
  EXPECT_TRUE(chain.tool_point(q, Eigen::Vector3d(0, 1, 0))
                  .isApprox(Eigen::Vector3d(0.1, 0.0, 1.25), 1e-15));
}

TEST(SerialChain, BadCodesAreRejectedWithThePosition) {
  auto message = [](const std::string& code) {
    try {
      SerialChain::from_code(code);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message("6412x6"),
            "coordinate code '6412x6': expected a motion digit 1..6 at position 5, found 'x'");
  EXPECT_EQ(message("647"),
            "coordinate code '647': expected a motion digit 1..6 at position 3, found '7'");
  EXPECT_EQ(message("3:abc"),
            "coordinate code '3:abc': expected a finite number after ':' at position 3, found "
            "'abc'");
  EXPECT_EQ(message(" , "), "coordinate code ' , ': expected at least one motion digit 1..6");
  const SerialChain chain = SerialChain::from_code("12");
  EXPECT_THROW(chain.transform(Eigen::VectorXd::Zero(3)), std::invalid_argument);
}

TEST(SerialChain, StructureClassFollowsTheSeedsNotation) {
  EXPECT_EQ(structure_class(5, 0), "P5\u04170");  // traditional 5-axis machine
  EXPECT_EQ(structure_class(0, 6), "P0\u04176");  // hexapod
  EXPECT_EQ(structure_class(2, 3), "P2\u04173");  // gantry X/Y with a 3-PRS head
  EXPECT_EQ(structure_class(1, 6), "P1\u04176");  // long axis carrying a hexapod
  EXPECT_EQ(structure_class(0, 6), "P0З6");
}

}  // namespace
}  // namespace pkmopt
