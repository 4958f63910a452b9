#include "models/dynamics/acceleration_capability.hpp"

#include "models/core/capabilities.hpp"

namespace pkmopt {

bool acceleration_force_bound(const Machine& machine, MachineData& data, const Pose& pose,
                              const Wrench& wrench, double a_max, Eigen::VectorXd& bound) {
  // Only forces are needed: the static solves skip the compliance metrics.
  const bool compliance = data.compliance_metrics;
  data.compliance_metrics = false;
  PoseMetrics m;
  const Vector6d at_rest = Vector6d::Zero();
  const Capability<Dynamics> dynamics = machine.dynamics();
  bool ok = dynamics && dynamics->inverse_dynamics(data, pose, at_rest, at_rest, wrench, m) &&
            !m.singular && m.tau.allFinite();
  const Eigen::VectorXd tau0 = ok ? m.tau : Eigen::VectorXd();
  Eigen::VectorXd g_squared = Eigen::VectorXd::Zero(tau0.size());
  for (int k = 0; k < 3 && ok; ++k) {
    // Column k of G: the forces per unit TCP acceleration along axis k (linear at rest).
    Vector6d unit = Vector6d::Zero();
    unit(k) = 1.0;
    ok = dynamics->inverse_dynamics(data, pose, at_rest, unit, wrench, m) && !m.singular &&
         m.tau.allFinite();
    if (ok) g_squared += (m.tau - tau0).cwiseAbs2();
  }
  data.compliance_metrics = compliance;
  if (!ok) return false;
  bound = tau0.cwiseAbs() + a_max * g_squared.cwiseSqrt();
  return true;
}

}  // namespace pkmopt
