#include "io/machine_file.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

#include "io/csv.hpp"
#include "io/machine_file_hybrid.hpp"
#include "io/machine_file_lathe.hpp"
#include "io/machine_file_leg_chain.hpp"

namespace pkmopt {
namespace {

Eigen::Matrix<double, 3, 6> read_joint_list(const YamlValue& value) {
  Eigen::Matrix<double, 3, 6> joints;
  const auto rows = value.elements(6);
  for (int i = 0; i < 6; ++i) {
    const auto xyz = rows[static_cast<std::size_t>(i)].as_doubles(3);
    joints.col(i) << xyz[0], xyz[1], xyz[2];
  }
  return joints;
}

Eigen::Vector3d read_vector3(const YamlValue& value) {
  const auto v = value.as_doubles(3);
  return {v[0], v[1], v[2]};
}

double angle_limit(const YamlValue& value) {
  const double v = value.as_double();
  if (!(v > 0.0 && v <= 180.0)) value.fail("an angle in degrees in (0, 180]", value.describe());
  return deg_to_rad(v);
}

// Semi-regular hexagon {radius, pair_separation_deg}; `platform` selects the platform form.
Eigen::Matrix<double, 3, 6> read_hexagon(const YamlValue& value, bool platform) {
  value.check_keys({"radius", "pair_separation_deg"});
  const double radius = value.required("radius").as_positive();
  const YamlValue sep_value = value.required("pair_separation_deg");
  const double sep = sep_value.as_double();
  if (!(sep >= 0.0 && sep <= 120.0)) {
    sep_value.fail("an angle in degrees in [0, 120]", sep_value.describe());
  }
  return platform ? semi_regular_platform_joints(radius, deg_to_rad(sep))
                  : semi_regular_base_joints(radius, deg_to_rad(sep));
}

Eigen::Matrix<double, 3, 6> read_joints(const YamlValue& root, const char* form_key,
                                        const char* list_key, bool platform) {
  const bool has_form = root.has(form_key);
  const bool has_list = root.has(list_key);
  if (has_form && has_list) {
    root.required(list_key).fail(fmt::format("either '{}' or '{}', not both", form_key, list_key));
  }
  if (!has_form && !has_list) {
    root.fail(fmt::format("missing required key '{}' (or '{}')", form_key, list_key));
  }
  return has_form ? read_hexagon(root.required(form_key), platform)
                  : read_joint_list(root.required(list_key));
}

}  // namespace

HexapodDesign read_hexapod_design(const YamlValue& root) {
  root.check_keys({"model", "name", "description", "base", "base_joints", "platform",
                   "platform_joints", "legs", "joints", "tool", "characteristic_length",
                   "actuator_error"});
  HexapodDesign design;
  design.base_joints = read_joints(root, "base", "base_joints", false);
  design.platform_joints = read_joints(root, "platform", "platform_joints", true);

  const YamlValue legs = root.required("legs");
  legs.check_keys(
      {"min_length", "max_length", "axial_stiffness", "E", "area", "actuator_stiffness"});
  design.min_length = legs.required("min_length").as_positive();
  const YamlValue max_value = legs.required("max_length");
  design.max_length = max_value.as_positive();
  if (!(design.max_length > design.min_length)) {
    max_value.fail(fmt::format("a number > legs.min_length ({})", format_number(design.min_length)),
                   max_value.describe());
  }
  const bool has_axial = legs.has("axial_stiffness");
  const bool has_e = legs.has("E");
  const bool has_area = legs.has("area");
  if (has_axial && (has_e || has_area)) {
    legs.required("axial_stiffness").fail("either axial_stiffness or E and area, not both");
  }
  if (has_axial) {
    design.stiffness.axial_stiffness = legs.required("axial_stiffness").as_positive();
  } else if (has_e || has_area) {
    design.stiffness.E = legs.required("E").as_positive();
    design.stiffness.area = legs.required("area").as_positive();
  } else {
    legs.fail("missing the leg stiffness: give axial_stiffness (N/m), or E (Pa) and area (m^2)");
  }
  if (auto v = legs.optional("actuator_stiffness")) {
    design.stiffness.actuator_stiffness = v->as_positive();
  }

  if (auto joints = root.optional("joints")) {
    joints->check_keys(
        {"base_max_angle_deg", "platform_max_angle_deg", "base_axis", "platform_axis"});
    if (auto v = joints->optional("base_max_angle_deg")) {
      design.joints.base_max_angle = angle_limit(*v);
    }
    if (auto v = joints->optional("platform_max_angle_deg")) {
      design.joints.platform_max_angle = angle_limit(*v);
    }
    for (const char* key : {"base_axis", "platform_axis"}) {
      if (auto v = joints->optional(key)) {
        const Eigen::Vector3d axis = read_vector3(*v);
        if (!(axis.norm() > 1e-12)) v->fail("a non-zero vector", v->describe());
        (std::string(key) == "base_axis" ? design.joints.base_axis : design.joints.platform_axis) =
            axis.normalized();
      }
    }
  }
  if (auto tool = root.optional("tool")) {
    tool->check_keys({"tcp"});
    if (auto v = tool->optional("tcp")) design.tcp = read_vector3(*v);
  }
  if (auto v = root.optional("characteristic_length"))
    design.characteristic_length = v->as_positive();
  if (auto v = root.optional("actuator_error")) design.actuator_error = v->as_non_negative();

  try {
    Hexapod check(design);  // the constructor's own validation (degenerate platform, ...)
  } catch (const std::invalid_argument& e) {
    root.fail(e.what());
  }
  return design;
}

std::unique_ptr<Machine> load_machine(const YamlValue& root) {
  root.expect_map();
  const YamlValue model_value = root.required("model");
  const std::string model = model_value.as_string();
  if (model == "hexapod") return std::make_unique<Hexapod>(read_hexapod_design(root));
  if (auto machine = load_leg_chain_machine(root, model)) return machine;
  if (auto machine = load_lathe_machine(root, model)) return machine;
  if (model == "hybrid") return load_hybrid_machine(root);
  model_value.fail(
      fmt::format("a known model (hexapod, {}, lathe_16k20f3, hybrid)", leg_chain_model_names()),
      quote_found(model));
}

std::unique_ptr<Machine> load_machine_file(const std::string& path) {
  return load_machine(YamlValue::load_file(path));
}

std::string hexapod_design_to_yaml(const HexapodDesign& design) {
  auto vec = [](const Eigen::Vector3d& v) {
    return fmt::format("[{}, {}, {}]", format_number(v(0)), format_number(v(1)),
                       format_number(v(2)));
  };
  std::string out = "model: hexapod\n";
  out += "base_joints:\n";
  for (int i = 0; i < 6; ++i) out += "  - " + vec(design.base_joints.col(i)) + "\n";
  out += "platform_joints:\n";
  for (int i = 0; i < 6; ++i) out += "  - " + vec(design.platform_joints.col(i)) + "\n";
  out += fmt::format("legs:\n  min_length: {}\n  max_length: {}\n",
                     format_number(design.min_length), format_number(design.max_length));
  const LegStiffness& k = design.stiffness;
  if (k.axial_stiffness > 0.0) {
    out += fmt::format("  axial_stiffness: {}\n", format_number(k.axial_stiffness));
  } else {
    out += fmt::format("  E: {}\n  area: {}\n", format_number(k.E), format_number(k.area));
  }
  if (k.actuator_stiffness > 0.0) {
    out += fmt::format("  actuator_stiffness: {}\n", format_number(k.actuator_stiffness));
  }
  const HexapodJointLimits& j = design.joints;
  const bool base_limited = std::isfinite(j.base_max_angle);
  const bool platform_limited = std::isfinite(j.platform_max_angle);
  const bool default_axes = j.base_axis.isApprox(Eigen::Vector3d(0, 0, 1), 0.0) &&
                            j.platform_axis.isApprox(Eigen::Vector3d(0, 0, -1), 0.0);
  if (base_limited || platform_limited || !default_axes) {
    out += "joints:\n";
    if (base_limited) {
      out += fmt::format("  base_max_angle_deg: {}\n", format_number(rad_to_deg(j.base_max_angle)));
    }
    if (platform_limited) {
      out += fmt::format("  platform_max_angle_deg: {}\n",
                         format_number(rad_to_deg(j.platform_max_angle)));
    }
    if (!default_axes) {
      out += "  base_axis: " + vec(j.base_axis) + "\n";
      out += "  platform_axis: " + vec(j.platform_axis) + "\n";
    }
  }
  out += "tool:\n  tcp: " + vec(design.tcp) + "\n";
  if (design.characteristic_length) {
    out += fmt::format("characteristic_length: {}\n", format_number(*design.characteristic_length));
  }
  out += fmt::format("actuator_error: {}\n", format_number(design.actuator_error));
  return out;
}

}  // namespace pkmopt
