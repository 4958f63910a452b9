#include "models/leg_chain/lathe_conversion.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "models/core/require.hpp"

namespace pkmopt {
namespace {

// The lathe model's checks name the model.
void require_lathe(bool condition, const std::string& message) {
  require(condition, "lathe_16k20f3: " + message);
}

bool finite_positive(double v) { return std::isfinite(v) && v > 0.0; }

}  // namespace

LegChainDesign lathe_16k20f3_design(const Lathe16k20f3Design& d) {
  require_lathe(finite_positive(d.centre_height), "centre_height must be > 0");
  require_lathe(std::isfinite(d.tool_reach) && d.tool_reach >= 0.0, "tool_reach must be >= 0");
  require_lathe(finite_positive(d.strut_length), "strut_length must be > 0");
  require_lathe(finite_positive(d.strut_joint_spread), "strut_joint_spread must be > 0");
  require_lathe(d.carriage_min < d.carriage_max, "carriage_min must be < carriage_max");
  require_lathe(finite_positive(d.leg_min_length) && d.leg_min_length < d.leg_max_length,
                "leg lengths must satisfy 0 < leg_min_length < leg_max_length");
  require_lathe(finite_positive(d.leg_base_spacing), "leg_base_spacing must be > 0");
  require_lathe(finite_positive(d.leg_joint_spacing), "leg_joint_spacing must be > 0");
  require_lathe(finite_positive(d.strut_max_angle) && d.strut_max_angle < 0.5 * std::numbers::pi,
                "strut_max_angle must be in (0, 90) deg");
  require_lathe(finite_positive(d.leg_max_angle) && d.leg_max_angle < std::numbers::pi,
                "leg_max_angle must be in (0, 180) deg");
  require_lathe(finite_positive(d.strut_E) && finite_positive(d.strut_area) &&
                    finite_positive(d.leg_E) && finite_positive(d.leg_area),
                "E and areas must be > 0");
  require_lathe(d.carriage_stiffness >= 0.0 && d.leg_actuator_stiffness >= 0.0,
                "actuator stiffnesses must be >= 0");
  for (const double k : {d.strut_base_joint_stiffness, d.strut_platform_joint_stiffness,
                         d.leg_base_joint_stiffness, d.leg_platform_joint_stiffness})
    require_lathe(std::isfinite(k) && k >= 0.0, "joint stiffnesses must be >= 0 (0: rigid)");
  check_screw_drive(d.carriage_drive, "lathe_16k20f3: carriage_drive", false);
  check_screw_drive(d.leg_drive, "lathe_16k20f3: leg_drive", false);

  LegChainDesign design;
  design.model = "lathe_16k20f3";
  design.mobility = PlatformMobility::kSchoenflies;
  design.rotation_axis = Eigen::Vector3d::UnitX();
  design.tcp =
      -d.tool_reach * Eigen::Vector3d(0.0, std::cos(d.approach_angle), std::sin(d.approach_angle));
  design.actuator_error = d.actuator_error;
  // Home: the tool tip 100 mm in front of the spindle axis (FK start).
  design.home = Pose{{0.0, 0.1, 0.05}, Eigen::Vector3d::Zero()};

  for (int side = 0; side < 2; ++side) {
    const double sign = side == 0 ? -1.0 : 1.0;  // headstock side first
    LegChainLeg strut;
    strut.kind = LegKind::kPUS;
    strut.base_point = {0.0, d.guide_y, d.guide_z};
    strut.axis = Eigen::Vector3d::UnitX();
    strut.link_length = d.strut_length;
    strut.platform_point = {sign * d.strut_joint_spread, d.strut_joint_y, d.strut_joint_z};
    strut.q_min = d.carriage_min;
    strut.q_max = d.carriage_max;
    strut.branch = side == 0 ? 1 : -1;
    strut.E = d.strut_E;
    strut.area = d.strut_area;
    strut.rods = 2;
    strut.actuator_stiffness = d.carriage_stiffness;
    strut.drive = d.carriage_drive;
    strut.base_joint_stiffness = d.strut_base_joint_stiffness;
    strut.platform_joint_stiffness = d.strut_platform_joint_stiffness;
    strut.base_axis =
        side == 0 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d(-Eigen::Vector3d::UnitX());
    strut.base_max_angle = d.strut_max_angle;
    design.legs.push_back(strut);
  }
  for (int side = 0; side < 2; ++side) {
    const double sign = side == 0 ? -1.0 : 1.0;  // the rear (spindle-side) leg first
    LegChainLeg leg;
    leg.kind = LegKind::kUPS;
    leg.base_point = {d.leg_base_x, d.leg_base_y + sign * 0.5 * d.leg_base_spacing, d.leg_base_z};
    leg.platform_point = {0.0, sign * 0.5 * d.leg_joint_spacing, d.leg_joint_z};
    leg.q_min = d.leg_min_length;
    leg.q_max = d.leg_max_length;
    leg.E = d.leg_E;
    leg.area = d.leg_area;
    leg.rods = 1;
    leg.actuator_stiffness = d.leg_actuator_stiffness;
    leg.drive = d.leg_drive;
    leg.base_joint_stiffness = d.leg_base_joint_stiffness;
    leg.platform_joint_stiffness = d.leg_platform_joint_stiffness;
    leg.base_axis = -Eigen::Vector3d::UnitZ();
    leg.base_max_angle = d.leg_max_angle;
    design.legs.push_back(leg);
  }
  design.masses = d.masses;
  design.shapes = d.shapes;
  return design;
}

std::unique_ptr<Machine> make_lathe_16k20f3(const Lathe16k20f3Design& d) {
  return make_leg_chain_machine(lathe_16k20f3_design(d));
}

double seeds_strut_length(const SeedsStrutInputs& in) {
  const double dy = in.Y_D + 0.5 * in.D_max + in.Y_xx - in.Y_I;
  const double dz = in.Z_D + 0.5 * in.D_max + in.Z_xx - in.Z_I;
  return std::sqrt(in.X_K * in.X_K + dy * dy + dz * dz);
}

SeedsStrutInputs seeds_strut_inputs(const Lathe16k20f3Design& d, double D_max, double Y_xx,
                                    double Z_xx) {
  SeedsStrutInputs in;
  in.Y_D = -d.guide_y;
  in.Z_D = -d.guide_z;
  in.D_max = D_max;
  in.Y_xx = Y_xx;
  in.Z_xx = Z_xx;
  in.Y_I = -(d.tool_reach * std::cos(d.approach_angle) + d.strut_joint_y);
  in.Z_I = -(d.tool_reach * std::sin(d.approach_angle) + d.strut_joint_z);
  return in;
}

SeedsStrutLength seeds_strut_length_at_inclination(const SeedsStrutInputs& in, double max_angle) {
  SeedsStrutInputs across = in;
  across.X_K = 0.0;
  SeedsStrutLength out;
  out.length = seeds_strut_length(across) / std::sin(max_angle);
  out.X_K = out.length * std::cos(max_angle);
  return out;
}

std::vector<Pose> lathe_task_poses(const LatheTask& task) {
  for (int a = 0; a < 3; ++a) {
    if (task.counts(a) < 1) throw std::invalid_argument("lathe task: counts must be >= 1");
    if (!(task.lower(a) <= task.upper(a)))
      throw std::invalid_argument("lathe task: lower must be <= upper");
  }
  auto coordinate = [&](int axis, int i) {
    const int n = task.counts(axis);
    if (n == 1) return task.lower(axis);
    return task.lower(axis) + (task.upper(axis) - task.lower(axis)) * i / (n - 1);
  };
  std::vector<Pose> poses;
  for (int i = 0; i < task.counts(0); ++i)
    for (int j = 0; j < task.counts(1); ++j)
      for (int k = 0; k < task.counts(2); ++k)
        poses.push_back(
            Pose{{coordinate(0, i), coordinate(1, j), coordinate(2, k)}, Eigen::Vector3d::Zero()});
  return poses;
}

bool lathe_reaches(const Lathe16k20f3Design& d, const std::vector<Pose>& poses) {
  const auto machine = make_lathe_16k20f3(d);
  const auto data = machine->make_data();
  for (const Pose& pose : poses)
    if (!machine->reachable(*data, pose)) return false;
  return true;
}

std::optional<double> minimal_strut_length(Lathe16k20f3Design d, const std::vector<Pose>& poses,
                                           double lower, double upper, double tolerance) {
  if (!(lower > 0.0 && lower < upper && tolerance > 0.0))
    throw std::invalid_argument("minimal_strut_length: need 0 < lower < upper, tolerance > 0");
  d.strut_length = upper;
  if (!lathe_reaches(d, poses)) return std::nullopt;
  d.strut_length = lower;
  if (lathe_reaches(d, poses)) return lower;
  while (upper - lower > tolerance) {
    const double middle = 0.5 * (lower + upper);
    d.strut_length = middle;
    (lathe_reaches(d, poses) ? upper : lower) = middle;
  }
  return upper;
}

}  // namespace pkmopt
