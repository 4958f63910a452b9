// The named leg-chain models: delta, linear delta, hexaglide and 3-PRS tripod designs
// (`*_design`) and their machines (`make_*`).
#include <Eigen/Geometry>
#include <cmath>
#include <memory>

#include "models/core/require.hpp"
#include "models/geometry/joint_layout.hpp"
#include "models/leg_chain/leg_chain.hpp"
#include "models/leg_chain/leg_chain_detail.hpp"

namespace pkmopt {
namespace {

using detail::kPi;

// Azimuth unit vector (cos phi, sin phi, 0).
Eigen::Vector3d radial(double phi) { return {std::cos(phi), std::sin(phi), 0.0}; }

void apply_stiffness(LegChainLeg& leg, const LinkStiffness& k, int rods) {
  leg.axial_stiffness = k.axial_stiffness;
  leg.E = k.E;
  leg.area = k.area;
  leg.rods = rods;
  leg.actuator_stiffness = k.actuator_stiffness;
  leg.drive = k.drive;
  leg.base_joint_stiffness = k.base_joint_stiffness;
  leg.platform_joint_stiffness = k.platform_joint_stiffness;
  leg.link_section = k.section;
  leg.parallelogram_width = k.parallelogram_width;
}

}  // namespace

LegChainDesign delta_design(const DeltaDesign& p) {
  require(std::isfinite(p.base_radius) && p.base_radius >= 0.0,
          "base_radius must be a finite number >= 0");
  require(std::isfinite(p.platform_radius) && p.platform_radius >= 0.0,
          "platform_radius must be a finite number >= 0");
  LegChainDesign d;
  d.model = "delta";
  d.mobility = PlatformMobility::kTranslational;
  for (int i = 0; i < 3; ++i) {
    const double phi = deg_to_rad(-90.0 + 120.0 * i);
    const Eigen::Vector3d u = radial(phi);
    LegChainLeg leg;
    leg.kind = LegKind::kRUS;
    leg.base_point = p.base_radius * u;
    leg.crank_zero = u;
    // n0 = w x d0 must be -z (positive theta lowers the elbow): w = d0 x n0 = u x (-z).
    leg.axis = u.cross(-Eigen::Vector3d::UnitZ());
    leg.crank_length = p.upper_arm;
    leg.link_length = p.rod;
    leg.platform_point = p.platform_radius * u;
    leg.q_min = p.theta_min;
    leg.q_max = p.theta_max;
    leg.branch = p.branch;
    apply_stiffness(leg, p.stiffness, 2);
    leg.crank_section = p.crank_section;  // the pair's bars: the crank axis (the default)
    leg.base_max_angle = p.elbow_max_angle;
    leg.platform_max_angle = p.platform_max_angle;
    leg.base_axis = -Eigen::Vector3d::UnitZ();     // crank frame at theta = 0: down
    leg.platform_axis = Eigen::Vector3d::UnitZ();  // -s_i points up at the platform
    d.legs.push_back(leg);
  }
  d.tcp = p.tcp;
  d.characteristic_length = p.characteristic_length;
  d.actuator_error = p.actuator_error;
  // Home: the platform straight below with the cranks horizontal (if the rods reach).
  const double dr = p.base_radius + p.upper_arm - p.platform_radius;
  const double h2 = p.rod * p.rod - dr * dr;
  d.home.position = Eigen::Vector3d(0, 0, -(h2 > 0.0 ? std::sqrt(h2) : p.rod)) + p.tcp;
  d.masses = p.masses;
  d.shapes = p.shapes;
  return d;
}

std::unique_ptr<Machine> make_delta(const DeltaDesign& d) {
  return make_leg_chain_machine(delta_design(d));
}

LegChainDesign linear_delta_design(const LinearDeltaDesign& p) {
  require(std::isfinite(p.inclination) && std::abs(p.inclination) < kPi / 2,
          "the guide inclination must be within (-90, 90) degrees");
  LegChainDesign d;
  d.model = "linear_delta";
  d.mobility = PlatformMobility::kTranslational;
  for (int i = 0; i < 3; ++i) {
    const double phi = deg_to_rad(-90.0 + 120.0 * i);
    const Eigen::Vector3d u = radial(phi);
    LegChainLeg leg;
    leg.kind = LegKind::kPUS;
    leg.base_point = p.guide_radius * u;
    // Upwards along the guide, leaning towards the centre by the inclination.
    leg.axis = std::cos(p.inclination) * Eigen::Vector3d::UnitZ() - std::sin(p.inclination) * u;
    leg.link_length = p.rod;
    leg.platform_point = p.platform_radius * u;
    leg.q_min = p.q_min;
    leg.q_max = p.q_max;
    leg.branch = -1;  // carriage above the platform point: q > u.d, B_i < 0
    apply_stiffness(leg, p.stiffness, 2);
    if (leg.parallelogram_width > 0.0)  // the carriage bar: horizontal, tangential
      leg.parallelogram_axis = Eigen::Vector3d::UnitZ().cross(u);
    leg.base_max_angle = p.carriage_max_angle;
    leg.platform_max_angle = p.platform_max_angle;
    leg.base_axis = -Eigen::Vector3d::UnitZ();
    leg.platform_axis = Eigen::Vector3d::UnitZ();
    d.legs.push_back(leg);
  }
  d.tcp = p.tcp;
  d.characteristic_length = p.characteristic_length;
  d.actuator_error = p.actuator_error;
  // Home: the carriages at mid-stroke, platform straight below them.
  const double qm = 0.5 * (p.q_min + p.q_max);
  const Eigen::Vector3d carriage = d.legs[0].base_point + qm * d.legs[0].axis;
  const double dr = carriage.head<2>().norm() - p.platform_radius;
  const double h2 = p.rod * p.rod - dr * dr;
  d.home.position =
      Eigen::Vector3d(0, 0, carriage.z() - (h2 > 0.0 ? std::sqrt(h2) : p.rod)) + p.tcp;
  d.masses = p.masses;
  d.shapes = p.shapes;
  return d;
}

std::unique_ptr<Machine> make_linear_delta(const LinearDeltaDesign& d) {
  return make_leg_chain_machine(linear_delta_design(d));
}

HexaglideDesign::HexaglideDesign()
    : platform_joints(Eigen::AngleAxisd(kPi / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix() *
                      semi_regular_platform_joints(0.25, 20.0 * kDegToRad)) {
  for (int i = 0; i < 6; ++i) {
    const double y = platform_joints(1, i);
    guide_y[static_cast<std::size_t>(i)] = y + (y >= 0.0 ? 0.3 : -0.3);
  }
}

LegChainDesign hexaglide_design(const HexaglideDesign& p) {
  require(std::isfinite(p.inclination) && std::abs(p.inclination) < kPi / 2,
          "the guide inclination must be within (-90, 90) degrees");
  LegChainDesign d;
  d.model = "hexaglide";
  d.mobility = PlatformMobility::kSixDof;
  const Eigen::Vector3d u(std::cos(p.inclination), 0.0, std::sin(p.inclination));
  for (int i = 0; i < 6; ++i) {
    LegChainLeg leg;
    leg.kind = LegKind::kPUS;
    leg.base_point = Eigen::Vector3d(0.0, p.guide_y[static_cast<std::size_t>(i)],
                                     p.guide_z[static_cast<std::size_t>(i)]);
    leg.axis = u;
    leg.link_length = p.strut;
    leg.platform_point = p.platform_joints.col(i);
    leg.q_min = p.q_min;
    leg.q_max = p.q_max;
    // Carriage on the far side of its platform joint: x_c < x_P (q < u.d, B > 0) for b.x < 0.
    leg.branch = p.platform_joints(0, i) < 0.0 ? 1 : -1;
    apply_stiffness(leg, p.stiffness, 1);
    leg.base_max_angle = p.carriage_max_angle;
    leg.platform_max_angle = p.platform_max_angle;
    leg.base_axis = Eigen::Vector3d::UnitZ();
    leg.platform_axis = -Eigen::Vector3d::UnitZ();
    d.legs.push_back(leg);
  }
  d.tcp = p.tcp;
  d.characteristic_length = p.characteristic_length;
  d.actuator_error = p.actuator_error;
  d.home.position = Eigen::Vector3d(0, 0, p.home_height);
  d.masses = p.masses;
  d.shapes = p.shapes;
  return d;
}

std::unique_ptr<Machine> make_hexaglide(const HexaglideDesign& d) {
  return make_leg_chain_machine(hexaglide_design(d));
}

namespace {

// The tripod heads' shared frame: three legs at azimuths -90 + 120 (i - 1) deg, each in the
// vertical plane through the head axis (its revolute joint tangential), the platform points at
// platform_radius, the TCP tool_length beyond the platform centre; `leg` gives the kind and what
// only its kind has.
template <class Tripod>
LegChainDesign planar_tripod(const Tripod& p, const char* model, LegChainLeg leg) {
  require(std::isfinite(p.base_radius) && p.base_radius > 0.0,
          "base_radius must be a finite number > 0");
  require(std::isfinite(p.platform_radius) && p.platform_radius > 0.0,
          "platform_radius must be a finite number > 0");
  require(std::isfinite(p.tool_length), "tool_length must be a finite number");
  LegChainDesign d;
  d.model = model;
  d.mobility = PlatformMobility::kPlanarLegs;
  leg.q_min = p.q_min;
  leg.q_max = p.q_max;
  apply_stiffness(leg, p.stiffness, 1);
  leg.base_max_angle = p.revolute_max_angle;
  leg.platform_max_angle = p.platform_max_angle;
  leg.base_axis = Eigen::Vector3d::UnitZ();
  leg.platform_axis = -Eigen::Vector3d::UnitZ();
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector3d u = radial(deg_to_rad(-90.0 + 120.0 * i));
    leg.base_point = p.base_radius * u;
    leg.platform_point = p.platform_radius * u;
    leg.plane_normal = Eigen::Vector3d::UnitZ().cross(u);  // tangential
    d.legs.push_back(leg);
  }
  d.tcp = Eigen::Vector3d(0, 0, p.tool_length);
  d.characteristic_length = p.characteristic_length;
  d.actuator_error = p.actuator_error;
  d.masses = p.masses;
  d.shapes = p.shapes;
  return d;
}

}  // namespace

LegChainDesign tripod_3prs_design(const Tripod3PrsDesign& p) {
  LegChainLeg leg;
  leg.kind = LegKind::kPUS;
  leg.axis = Eigen::Vector3d::UnitZ();
  leg.link_length = p.strut;
  leg.branch = 1;  // platform point on the +z side of the carriage: B_i = s_i . z > 0
  LegChainDesign d = planar_tripod(p, "tripod_3prs", leg);
  // Home: level platform, carriages at mid-stroke.
  const double dr = p.base_radius - p.platform_radius;
  const double h2 = p.strut * p.strut - dr * dr;
  d.home.position =
      Eigen::Vector3d(0, 0, 0.5 * (p.q_min + p.q_max) + (h2 > 0.0 ? std::sqrt(h2) : p.strut)) +
      d.tcp;
  return d;
}

std::unique_ptr<Machine> make_tripod_3prs(const Tripod3PrsDesign& d) {
  return make_leg_chain_machine(tripod_3prs_design(d));
}

LegChainDesign tripod_3rps_design(const Tripod3RpsDesign& p) {
  LegChainLeg leg;
  leg.kind = LegKind::kUPS;
  LegChainDesign d = planar_tripod(p, "tripod_3rps", leg);
  // Home: level platform, legs at the middle of their range.
  const double dr = p.base_radius - p.platform_radius;
  const double length = 0.5 * (p.q_min + p.q_max);
  const double h2 = length * length - dr * dr;
  d.home.position = Eigen::Vector3d(0, 0, h2 > 0.0 ? std::sqrt(h2) : length) + d.tcp;
  return d;
}

std::unique_ptr<Machine> make_tripod_3rps(const Tripod3RpsDesign& d) {
  return make_leg_chain_machine(tripod_3rps_design(d));
}

}  // namespace pkmopt
