#include "models/acceleration_capability.hpp"

namespace pkmopt {

bool acceleration_force_bound(const Machine& machine, MachineData& data, const Pose& pose,
                              const Wrench& wrench, double a_max, Eigen::VectorXd& bound) {
  Wrench gravity;
  Matrix6d M;
  if (!machine.dynamic_wrench(data, pose, Vector6d::Zero(), Vector6d::Zero(), gravity) ||
      !machine.mass_matrix(data, pose, M)) {
    return false;
  }
  // Only forces are needed: the four static solves skip the compliance metrics.
  const bool compliance = data.compliance_metrics;
  data.compliance_metrics = false;
  PoseMetrics m;
  machine.analyze(data, pose, wrench + gravity, m);
  bool ok = !m.singular && m.tau.allFinite();
  Eigen::VectorXd result = m.tau.cwiseAbs();
  Eigen::VectorXd g_squared = Eigen::VectorXd::Zero(result.size());
  for (int k = 0; k < 3 && ok; ++k) {
    machine.analyze(data, pose, M.col(k), m);  // tau(M e_k): the column k of G
    ok = !m.singular && m.tau.allFinite();
    if (ok) g_squared += m.tau.cwiseAbs2();
  }
  data.compliance_metrics = compliance;
  if (!ok) return false;
  bound = result + a_max * g_squared.cwiseSqrt();
  return true;
}

}  // namespace pkmopt
