#include "models/dynamics/mass_model.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>

#include "models/core/require.hpp"

namespace pkmopt {

Eigen::Matrix3d inertia_tensor(const std::array<double, 6>& c) {
  Eigen::Matrix3d I;
  I << c[0], c[3], c[4], c[3], c[1], c[5], c[4], c[5], c[2];
  return I;
}

std::array<double, 6> inertia_components(const Eigen::Matrix3d& I) {
  return {I(0, 0), I(1, 1), I(2, 2), I(0, 1), I(0, 2), I(1, 2)};
}

namespace {

void check_link(const LinkMass& link, const std::string& where) {
  for (const double v : {link.mass, link.centre, link.inertia})
    require(std::isfinite(v) && v >= 0.0,
            where + ": mass, centre and inertia must be finite numbers >= 0");
}

}  // namespace

void check_mass_model(const MassModel& m, const std::string& where) {
  const RigidBody& p = m.platform;
  require(std::isfinite(p.mass) && p.mass > 0.0, where + "platform.mass must be > 0 (kg)");
  require(p.centre_of_mass.allFinite(), where + "platform.centre_of_mass must be finite");
  require(p.inertia.allFinite() && (p.inertia - p.inertia.transpose()).norm() == 0.0,
          where + "platform.inertia must be finite and symmetric");
  const Eigen::Vector3d principal =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(p.inertia, Eigen::EigenvaluesOnly)
          .eigenvalues();
  require(principal.minCoeff() > 0.0,
          where + "platform.inertia must be positive definite (every principal moment > 0)");
  // A real body's principal moments satisfy I_a + I_b >= I_c (a small tolerance for rounding).
  const double slack = 1e-9 * principal.sum();
  require(principal(0) + principal(1) + slack >= principal(2),
          where + "platform.inertia: the principal moments violate I1 + I2 >= I3 (no body has it)");
  check_link(m.legs.cylinder, where + "legs.cylinder");
  check_link(m.legs.rod, where + "legs.rod");
  check_link(m.legs.link, where + "legs.link");
  check_link(m.legs.crank, where + "legs.crank");
  require(std::isfinite(m.legs.carriage) && m.legs.carriage >= 0.0,
          where + "legs.carriage must be a finite number >= 0 (kg)");
  require(m.gravity.allFinite(), where + "gravity must be finite");
}

}  // namespace pkmopt
