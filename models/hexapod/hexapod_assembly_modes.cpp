// Hexapod::all_forward_kinematics: the assembly modes of models/hexapod/assembly_modes.hpp as
// TCP poses with their residual, Jacobian determinant, reachability and distances.
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <memory>
#include <mutex>

#include "models/hexapod/assembly_modes.hpp"
#include "models/hexapod/hexapod.hpp"

namespace pkmopt {
namespace {

// sqrt(|dp|^2 + (rho theta)^2), theta the angle of R_a^T R_b.
double pose_distance(const Pose& a, const Pose& b, double rho) {
  const Eigen::Matrix3d Ra = rotation_zyx(a.angles), Rb = rotation_zyx(b.angles);
  const double c = std::clamp(((Ra.transpose() * Rb).trace() - 1.0) / 2.0, -1.0, 1.0);
  const double theta = std::acos(c);
  return std::hypot((a.position - b.position).norm(), rho * theta);
}

}  // namespace

struct Hexapod::AssemblyModeCache {
  std::once_flag made;
  std::unique_ptr<AssemblyModeSolver> solver;
};

std::shared_ptr<Hexapod::AssemblyModeCache> Hexapod::new_assembly_mode_cache() {
  return std::make_shared<AssemblyModeCache>();
}

ForwardSolutions Hexapod::all_forward_kinematics(const Eigen::VectorXd& q,
                                                 const std::optional<Pose>& guess) const {
  const Eigen::Matrix<double, 6, 1> lengths = q.head<6>();
  const Pose reference = guess ? *guess : home_pose_for(lengths);
  // The solver's own start: the lengths of the centred platform at mid-stroke.
  std::call_once(assembly_modes_->made, [&] {
    const Vec6<double> mid =
        Vec6<double>::Constant(0.5 * (design_.min_length + design_.max_length));
    assembly_modes_->solver = std::make_unique<AssemblyModeSolver>(
        design_.base_joints, platform_rel_, inverse_kinematics(home_pose_for(mid)));
  });
  const AssemblyModes modes = assembly_modes_->solver->solve(lengths);
  ForwardSolutions out;
  out.complex_count = modes.complex_count;
  out.at_infinity = modes.at_infinity;
  out.failed = modes.failed;
  out.paths = modes.paths;
  out.failures = modes.failures;
  out.architecture_singular = modes.architecture_singular;
  out.distance_length = enclosure_length();  // rho, as in the working-mode certificate
  std::unique_ptr<MachineData> data = make_data();
  for (const AssemblyMode& m : modes.real) {
    ForwardSolution s;
    s.pose = Pose{m.position, angles_from_rotation(m.rotation)};
    s.residual = (inverse_kinematics(s.pose) - lengths).cwiseAbs().maxCoeff();
    s.jacobian_determinant = inverse_jacobian(s.pose).determinant();
    s.reachable = reachable(*data, s.pose);
    s.to_reference = pose_distance(s.pose, reference, out.distance_length);
    out.real.push_back(s);
  }
  for (std::size_t i = 0; i < out.real.size(); ++i)
    for (std::size_t j = 0; j < out.real.size(); ++j)
      if (i != j)
        out.real[i].nearest_other =
            std::min(out.real[i].nearest_other,
                     pose_distance(out.real[i].pose, out.real[j].pose, out.distance_length));
  std::stable_sort(out.real.begin(), out.real.end(),
                   [](const ForwardSolution& a, const ForwardSolution& b) {
                     return a.to_reference < b.to_reference;
                   });
  return out;
}

}  // namespace pkmopt
