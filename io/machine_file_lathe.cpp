#include "io/machine_file_lathe.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>
#include <utility>

#include "io/csv.hpp"

namespace pkmopt {
namespace {

void read_number(const YamlValue& root, const char* key, double& value) {
  if (auto v = root.optional(key)) value = v->as_double();
}

void read_positive(const YamlValue& root, const char* key, double& value) {
  if (auto v = root.optional(key)) value = v->as_positive();
}

void read_angle(const YamlValue& root, const char* key, double lo_deg, double hi_deg,
                double& value) {
  if (auto v = root.optional(key)) {
    const double deg = v->as_double();
    if (!(deg > lo_deg && deg < hi_deg))
      v->fail(fmt::format("an angle in degrees in ({}, {})", format_number(lo_deg),
                          format_number(hi_deg)),
              v->describe());
    value = deg_to_rad(deg);
  }
}

void read_pair(const YamlValue& root, const char* key, bool positive, double& low, double& high) {
  if (auto v = root.optional(key)) {
    const auto values = v->as_doubles(2);
    if (!(values[0] < values[1]) || (positive && !(values[0] > 0.0)))
      v->fail(positive ? "[low, high] with 0 < low < high (m)" : "[low, high] with low < high (m)",
              v->describe());
    low = values[0];
    high = values[1];
  }
}

}  // namespace

Lathe16k20f3Design read_lathe_16k20f3_design(const YamlValue& root) {
  root.check_keys({"model",
                   "name",
                   "description",
                   "centre_height",
                   "tool_reach",
                   "approach_angle_deg",
                   "strut_length",
                   "guide_y",
                   "guide_z",
                   "strut_joint_spread",
                   "strut_joint_y",
                   "strut_joint_z",
                   "carriage_travel",
                   "strut_max_angle_deg",
                   "strut_E",
                   "strut_area",
                   "carriage_stiffness",
                   "leg_base_x",
                   "leg_base_y",
                   "leg_base_z",
                   "leg_base_spacing",
                   "leg_joint_spacing",
                   "leg_joint_z",
                   "leg_length",
                   "leg_max_angle_deg",
                   "leg_E",
                   "leg_area",
                   "leg_actuator_stiffness",
                   "actuator_error"});
  Lathe16k20f3Design d;
  read_positive(root, "centre_height", d.centre_height);
  if (auto v = root.optional("tool_reach")) d.tool_reach = v->as_non_negative();
  read_angle(root, "approach_angle_deg", -90.0, 90.0, d.approach_angle);
  read_positive(root, "strut_length", d.strut_length);
  read_number(root, "guide_y", d.guide_y);
  read_number(root, "guide_z", d.guide_z);
  read_positive(root, "strut_joint_spread", d.strut_joint_spread);
  read_number(root, "strut_joint_y", d.strut_joint_y);
  read_number(root, "strut_joint_z", d.strut_joint_z);
  read_pair(root, "carriage_travel", false, d.carriage_min, d.carriage_max);
  read_angle(root, "strut_max_angle_deg", 0.0, 90.0, d.strut_max_angle);
  read_positive(root, "strut_E", d.strut_E);
  read_positive(root, "strut_area", d.strut_area);
  if (auto v = root.optional("carriage_stiffness")) d.carriage_stiffness = v->as_non_negative();
  read_number(root, "leg_base_x", d.leg_base_x);
  read_number(root, "leg_base_y", d.leg_base_y);
  read_number(root, "leg_base_z", d.leg_base_z);
  read_positive(root, "leg_base_spacing", d.leg_base_spacing);
  read_positive(root, "leg_joint_spacing", d.leg_joint_spacing);
  read_number(root, "leg_joint_z", d.leg_joint_z);
  read_pair(root, "leg_length", true, d.leg_min_length, d.leg_max_length);
  read_angle(root, "leg_max_angle_deg", 0.0, 180.0, d.leg_max_angle);
  read_positive(root, "leg_E", d.leg_E);
  read_positive(root, "leg_area", d.leg_area);
  if (auto v = root.optional("leg_actuator_stiffness"))
    d.leg_actuator_stiffness = v->as_non_negative();
  if (auto v = root.optional("actuator_error")) d.actuator_error = v->as_non_negative();
  try {
    (void)make_lathe_16k20f3(d);
  } catch (const std::invalid_argument& e) {
    root.fail(e.what());
  }
  return d;
}

std::unique_ptr<Machine> load_lathe_machine(const YamlValue& root, const std::string& model) {
  if (model != "lathe_16k20f3") return nullptr;
  return make_lathe_16k20f3(read_lathe_16k20f3_design(root));
}

}  // namespace pkmopt
