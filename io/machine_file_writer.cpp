#include "io/machine_file_writer.hpp"

#include <fmt/format.h>

#include <cmath>
#include <optional>

#include "io/csv.hpp"

namespace pkmopt {
namespace {

// Machine-file text helpers: numbers in their shortest round-trip form (format_number).
// Degrees of an angle in rad, to 12 significant digits (60, not 59.99999999999999).
std::string degrees(double rad) { return fmt::format("{:.12g}", rad_to_deg(rad)); }
std::string vector3(const Eigen::Vector3d& v) {
  return fmt::format("[{}, {}, {}]", format_number(v.x()), format_number(v.y()), format_number(v.z()));
}

std::string link_stiffness_yaml(const LinkStiffness& k) {
  return k.axial_stiffness > 0.0 ? fmt::format("{{axial_stiffness: {}}}", format_number(k.axial_stiffness))
                                 : fmt::format("{{E: {}, area: {}}}", format_number(k.E), format_number(k.area));
}

// joints: {<base_key>: deg, platform_max_angle_deg: deg} with the finite limits (or nothing).
std::string joints_yaml(const char* base_key, double base_limit, double platform_limit) {
  std::string items;
  if (std::isfinite(base_limit)) items += fmt::format("{}: {}", base_key, degrees(base_limit));
  if (std::isfinite(platform_limit))
    items += fmt::format("{}platform_max_angle_deg: {}", items.empty() ? "" : ", ",
                         degrees(platform_limit));
  return items.empty() ? "" : "joints: {" + items + "}\n";
}

// The keys every leg-chain machine file has after its geometry: link stiffness, actuator
// stiffness (when not rigid), joint limits, tool, characteristic length.
std::string links_and_joints_yaml(const char* links_key, const LinkStiffness& k,
                                  const char* actuator_key, const char* base_joint_key,
                                  double base_limit, double platform_limit,
                                  const Eigen::Vector3d& tcp, const std::optional<double>& length) {
  std::string text = fmt::format("{}: {}\n", links_key, link_stiffness_yaml(k));
  if (k.actuator_stiffness > 0.0)
    text += fmt::format("{}: {}\n", actuator_key, format_number(k.actuator_stiffness));
  text += joints_yaml(base_joint_key, base_limit, platform_limit);
  text += "tool: {tcp: " + vector3(tcp) + "}\n";
  if (length) text += "characteristic_length: " + format_number(*length) + "\n";
  return text;
}

}  // namespace

std::string delta_machine_file(const DeltaDesign& d) {
  std::string text = "model: delta\n";
  text += fmt::format("base_radius: {}\nplatform_radius: {}\nupper_arm: {}\nrod: {}\n",
                      format_number(d.base_radius), format_number(d.platform_radius), format_number(d.upper_arm),
                      format_number(d.rod));
  text += fmt::format("drive_range_deg: [{}, {}]\n", degrees(d.theta_min), degrees(d.theta_max));
  text += fmt::format("branch: {}\n", d.branch > 0 ? "elbow_out" : "elbow_in");
  text += links_and_joints_yaml("rods", d.stiffness, "drive_stiffness", "elbow_max_angle_deg",
                                d.elbow_max_angle, d.platform_max_angle, d.tcp,
                                d.characteristic_length);
  text += "actuator_error_deg: " + degrees(d.actuator_error) + "\n";
  return text;
}

std::string linear_delta_machine_file(const LinearDeltaDesign& d) {
  std::string text = "model: linear_delta\n";
  text += fmt::format("guide_radius: {}\nplatform_radius: {}\nrod: {}\ninclination_deg: {}\n",
                      format_number(d.guide_radius), format_number(d.platform_radius), format_number(d.rod),
                      degrees(d.inclination));
  text += fmt::format("stroke: [{}, {}]\n", format_number(d.q_min), format_number(d.q_max));
  text += links_and_joints_yaml("rods", d.stiffness, "carriage_stiffness", "carriage_max_angle_deg",
                                d.carriage_max_angle, d.platform_max_angle, d.tcp,
                                d.characteristic_length);
  text += "actuator_error: " + format_number(d.actuator_error) + "\n";
  return text;
}

std::string hexaglide_machine_file(const HexaglideDesign& d) {
  std::string text = "model: hexaglide\n";
  std::string ys, zs, joints;
  for (int i = 0; i < 6; ++i) {
    ys += (i ? ", " : "") + format_number(d.guide_y[static_cast<std::size_t>(i)]);
    zs += (i ? ", " : "") + format_number(d.guide_z[static_cast<std::size_t>(i)]);
    joints += (i ? ", " : "") + vector3(d.platform_joints.col(i));
  }
  text += fmt::format("guides: {{y: [{}], z: [{}], inclination_deg: {}}}\n", ys, zs,
                      degrees(d.inclination));
  text += "strut: " + format_number(d.strut) + "\n";
  text += "platform_joints: [" + joints + "]\n";
  text += fmt::format("stroke: [{}, {}]\n", format_number(d.q_min), format_number(d.q_max));
  text += links_and_joints_yaml("struts", d.stiffness, "carriage_stiffness",
                                "carriage_max_angle_deg", d.carriage_max_angle,
                                d.platform_max_angle, d.tcp, d.characteristic_length);
  text += "actuator_error: " + format_number(d.actuator_error) + "\n";
  text += "home_height: " + format_number(d.home_height) + "\n";
  return text;
}

std::string tripod_3prs_machine_file(const Tripod3PrsDesign& d) {
  std::string text = "model: tripod_3prs\n";
  text += fmt::format("base_radius: {}\nplatform_radius: {}\nstrut: {}\n", format_number(d.base_radius),
                      format_number(d.platform_radius), format_number(d.strut));
  text += fmt::format("stroke: [{}, {}]\n", format_number(d.q_min), format_number(d.q_max));
  text += "tool_length: " + format_number(d.tool_length) + "\n";
  text += fmt::format("struts: {}\n", link_stiffness_yaml(d.stiffness));
  if (d.stiffness.actuator_stiffness > 0.0)
    text += "slide_stiffness: " + format_number(d.stiffness.actuator_stiffness) + "\n";
  text += joints_yaml("revolute_max_angle_deg", d.revolute_max_angle, d.platform_max_angle);
  if (d.characteristic_length)
    text += "characteristic_length: " + format_number(*d.characteristic_length) + "\n";
  text += "actuator_error: " + format_number(d.actuator_error) + "\n";
  return text;
}

std::string lathe_16k20f3_machine_file(const Lathe16k20f3Design& d) {
  std::string text = "model: lathe_16k20f3\n";
  auto line = [&text](const char* key, double value) {
    text += fmt::format("{}: {}\n", key, format_number(value));
  };
  line("centre_height", d.centre_height);
  line("tool_reach", d.tool_reach);
  line("approach_angle_deg", rad_to_deg(d.approach_angle));
  line("strut_length", d.strut_length);
  line("guide_y", d.guide_y);
  line("guide_z", d.guide_z);
  line("strut_joint_spread", d.strut_joint_spread);
  line("strut_joint_y", d.strut_joint_y);
  line("strut_joint_z", d.strut_joint_z);
  text +=
      fmt::format("carriage_travel: [{}, {}]\n", format_number(d.carriage_min), format_number(d.carriage_max));
  line("strut_max_angle_deg", rad_to_deg(d.strut_max_angle));
  line("strut_E", d.strut_E);
  line("strut_area", d.strut_area);
  line("carriage_stiffness", d.carriage_stiffness);
  line("leg_base_x", d.leg_base_x);
  line("leg_base_y", d.leg_base_y);
  line("leg_base_z", d.leg_base_z);
  line("leg_base_spacing", d.leg_base_spacing);
  line("leg_joint_spacing", d.leg_joint_spacing);
  line("leg_joint_z", d.leg_joint_z);
  text += fmt::format("leg_length: [{}, {}]\n", format_number(d.leg_min_length), format_number(d.leg_max_length));
  line("leg_max_angle_deg", rad_to_deg(d.leg_max_angle));
  line("leg_E", d.leg_E);
  line("leg_area", d.leg_area);
  line("leg_actuator_stiffness", d.leg_actuator_stiffness);
  line("actuator_error", d.actuator_error);
  return text;
}

std::string family_machine_file(const FamilyDesign& design) {
  return std::visit(
      [](const auto& d) -> std::string {
        using T = std::decay_t<decltype(d)>;
        if constexpr (std::is_same_v<T, DeltaDesign>) return delta_machine_file(d);
        if constexpr (std::is_same_v<T, LinearDeltaDesign>) return linear_delta_machine_file(d);
        if constexpr (std::is_same_v<T, HexaglideDesign>) return hexaglide_machine_file(d);
        if constexpr (std::is_same_v<T, Tripod3PrsDesign>) return tripod_3prs_machine_file(d);
        if constexpr (std::is_same_v<T, Lathe16k20f3Design>) return lathe_16k20f3_machine_file(d);
      },
      design);
}

}  // namespace pkmopt
