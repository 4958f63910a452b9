#include "problems/design/leg_chain_design.hpp"

#include <utility>

#include "models/core/pose.hpp"
#include "models/core/require.hpp"
#include "models/geometry/joint_layout.hpp"

namespace pkmopt {

namespace {

// build = make(design(p)), machine_file = writer(design(p)), machine_size = the envelope.
template <typename FromParameters, typename Make, typename Writer>
void wire_family(DesignFamily& family, FromParameters design, Make make, Writer writer) {
  family.build = [design, make](const std::vector<double>& p) { return make(design(p)); };
  if (writer)
    family.machine_file = [design, writer](const std::vector<double>& p) {
      return writer(design(p));
    };
  family.machine_size = envelope_machine_size;
}

}  // namespace

DesignFamily delta_family(const DeltaDesign& t, DesignWriter<DeltaDesign> writer) {
  DesignFamily family;
  family.model = "delta";
  family.translational = true;
  family.parameters = {
      {"base_radius", "m", "centre to each drive pivot", t.base_radius, false, false},
      {"platform_radius", "m", "TCP to each rod-pair centre", t.platform_radius, false, true},
      {"upper_arm", "m", "crank length", t.upper_arm, false, false},
      {"rod", "m", "parallelogram rod length", t.rod, false, false},
      {"drive_min_deg", "deg", "lower end of the drive range (below drive_max_deg)",
       rad_to_deg(t.theta_min), true, true, 180.0},
      {"drive_max_deg", "deg", "upper end of the drive range", rad_to_deg(t.theta_max), true, true,
       180.0},
      {"home_height", "m", "the task region is lifted by this along base z", 0.0, true, true}};
  family.parameter_keys = {"base_radius", "platform_radius", "upper_arm", "rod", "drive_range_deg"};
  auto design = [t](const std::vector<double>& p) {
    DeltaDesign d = t;
    d.base_radius = p.at(0);
    d.platform_radius = p.at(1);
    d.upper_arm = p.at(2);
    d.rod = p.at(3);
    d.theta_min = p.at(4);
    d.theta_max = p.at(5);
    require(d.theta_min < d.theta_max, "drive_min_deg must be below drive_max_deg");
    return d;
  };
  wire_family(family, design, make_delta, writer);
  return family;
}

DesignFamily linear_delta_family(const LinearDeltaDesign& t,
                                 DesignWriter<LinearDeltaDesign> writer) {
  DesignFamily family;
  family.model = "linear_delta";
  family.translational = true;
  family.parameters = {
      {"guide_radius", "m", "guide foot (z = 0) distance from the centre", t.guide_radius, false,
       false},
      {"platform_radius", "m", "TCP to each rod-pair centre", t.platform_radius, false, true},
      {"rod", "m", "parallelogram rod length", t.rod, false, false},
      {"stroke", "m", "carriage travel q ∈ [0, stroke] along each guide", t.q_max - t.q_min, false,
       false},
      {"inclination_deg", "deg", "guide tilt towards the centre", rad_to_deg(t.inclination), true,
       true, 89.0},
      {"home_height", "m", "the task region is lifted by this along base z", 0.0, true, true}};
  family.parameter_keys = {"guide_radius", "platform_radius", "rod", "stroke", "inclination_deg"};
  auto design = [t](const std::vector<double>& p) {
    LinearDeltaDesign d = t;
    d.guide_radius = p.at(0);
    d.platform_radius = p.at(1);
    d.rod = p.at(2);
    d.q_min = 0.0;
    d.q_max = p.at(3);
    d.inclination = p.at(4);
    return d;
  };
  wire_family(family, design, make_linear_delta, writer);
  return family;
}

DesignFamily hexaglide_family(const HexaglideDesign& t, DesignWriter<HexaglideDesign> writer) {
  // Template geometry read back as parameters: the platform radius and pair separation of the
  // semi-regular form (joint 0 of Rz(90) * semi_regular_platform_joints), the guide offset of
  // guide 0 from its joint.
  const Eigen::Vector3d b0 = t.platform_joints.col(0);
  const double radius = b0.head<2>().norm();
  // Joint 0 sits at azimuth 90 - 60 + sep/2 = 30 + sep/2 deg (docs/conventions.md, turned by 90).
  const double separation = 2.0 * (rad_to_deg(std::atan2(b0.y(), b0.x())) - 30.0);
  const double offset = std::abs(t.guide_y[0] - b0.y());
  DesignFamily family;
  family.model = "hexaglide";
  family.parameters = {
      {"platform_radius", "m", "semi-regular platform (turned 90° about z)", radius, false, false},
      {"pair_separation_deg", "deg", "angle between the joints of a pair", separation, false, true,
       119.0},
      {"guide_offset", "m", "guide i at y = b_i.y ± offset (outwards)", offset, false, true},
      {"strut", "m", "constant strut length", t.strut, false, false},
      {"stroke", "m", "carriages travel q ∈ [−stroke/2, stroke/2] along x", t.q_max - t.q_min,
       false, false},
      {"inclination_deg", "deg", "guide tilt about y", rad_to_deg(t.inclination), true, true, 89.0},
      {"home_height", "m",
       "lift of the task region along base z, added to the machine section's own home_height", 0.0,
       true, true}};
  family.parameter_keys = {"guides", "strut", "platform", "platform_joints", "stroke"};
  auto design = [t](const std::vector<double>& p) {
    HexaglideDesign d = t;
    require(p.at(1) < deg_to_rad(120.0), "pair_separation_deg must be below 120");
    d.platform_joints =
        Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix() *
        semi_regular_platform_joints(p.at(0), p.at(1));
    for (int i = 0; i < 6; ++i) {
      const double y = d.platform_joints(1, i);
      d.guide_y[static_cast<std::size_t>(i)] = y + (y >= 0.0 ? p.at(2) : -p.at(2));
    }
    d.strut = p.at(3);
    d.q_min = -0.5 * p.at(4);
    d.q_max = 0.5 * p.at(4);
    d.inclination = p.at(5);
    d.home_height = t.home_height + p.at(6);
    return d;
  };
  wire_family(family, design, make_hexaglide, writer);
  return family;
}

DesignFamily tripod_3prs_family(const Tripod3PrsDesign& t, DesignWriter<Tripod3PrsDesign> writer) {
  DesignFamily family;
  family.model = "tripod_3prs";
  family.parameters = {
      {"base_radius", "m", "head axis to each slide", t.base_radius, false, false},
      {"platform_radius", "m", "platform centre to each spherical joint", t.platform_radius, false,
       false},
      {"strut", "m", "constant strut length", t.strut, false, false},
      {"stroke", "m",
       "slide travel q ∈ [q_min, q_min + stroke] (q_min of the machine section's stroke, default "
       "0)",
       t.q_max - t.q_min, false, false},
      {"home_height", "m", "the task region is lifted by this along base z", 0.0, true, true}};
  family.parameter_keys = {"base_radius", "platform_radius", "strut", "stroke"};
  auto design = [t](const std::vector<double>& p) {
    Tripod3PrsDesign d = t;
    d.base_radius = p.at(0);
    d.platform_radius = p.at(1);
    d.strut = p.at(2);
    d.q_max = t.q_min + p.at(3);
    return d;
  };
  wire_family(family, design, make_tripod_3prs, writer);
  return family;
}

DesignFamily tripod_3rps_family(const Tripod3RpsDesign& t, DesignWriter<Tripod3RpsDesign> writer) {
  DesignFamily family;
  family.model = "tripod_3rps";
  family.parameters = {
      {"base_radius", "m", "head axis to each base revolute joint", t.base_radius, false, false},
      {"platform_radius", "m", "platform centre to each spherical joint", t.platform_radius, false,
       false},
      {"min_length", "m", "the shortest leg", t.q_min, false, false},
      {"stroke", "m", "leg length q ∈ [min_length, min_length + stroke]", t.q_max - t.q_min, false,
       false},
      {"home_height", "m", "the task region is lifted by this along base z", 0.0, true, true}};
  family.parameter_keys = {"base_radius", "platform_radius", "leg_length"};
  auto design = [t](const std::vector<double>& p) {
    Tripod3RpsDesign d = t;
    d.base_radius = p.at(0);
    d.platform_radius = p.at(1);
    d.q_min = p.at(2);
    d.q_max = p.at(2) + p.at(3);
    return d;
  };
  wire_family(family, design, make_tripod_3rps, writer);
  return family;
}

}  // namespace pkmopt
