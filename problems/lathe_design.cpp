#include "problems/lathe_design.hpp"

#include <fmt/format.h>

#include <cmath>

namespace pkmopt {
namespace {

// Shortest text that round-trips.
std::string number(double v) { return fmt::format("{}", v); }

}  // namespace

std::string lathe_16k20f3_machine_file(const Lathe16k20f3Design& d) {
  std::string text = "model: lathe_16k20f3\n";
  auto line = [&text](const char* key, double value) {
    text += fmt::format("{}: {}\n", key, number(value));
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
      fmt::format("carriage_travel: [{}, {}]\n", number(d.carriage_min), number(d.carriage_max));
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
  text += fmt::format("leg_length: [{}, {}]\n", number(d.leg_min_length), number(d.leg_max_length));
  line("leg_max_angle_deg", rad_to_deg(d.leg_max_angle));
  line("leg_E", d.leg_E);
  line("leg_area", d.leg_area);
  line("leg_actuator_stiffness", d.leg_actuator_stiffness);
  line("actuator_error", d.actuator_error);
  return text;
}

DesignFamily lathe_16k20f3_family(const Lathe16k20f3Design& t) {
  DesignFamily family;
  family.model = "lathe_16k20f3";
  family.parameters = {{"strut_length", "m", t.strut_length, false, false},
                       {"guide_y", "m", t.guide_y, true, true},
                       {"leg_base_y", "m", t.leg_base_y, true, true},
                       {"home_height", "m", 0.0, true, true}};
  family.parameter_keys = {"strut_length", "guide_y", "leg_base_y"};
  auto design = [t](const std::vector<double>& p) {
    Lathe16k20f3Design d = t;
    d.strut_length = p.at(0);
    d.guide_y = p.at(1);
    d.leg_base_y = p.at(2);
    return d;
  };
  family.build = [design](const std::vector<double>& p) { return make_lathe_16k20f3(design(p)); };
  family.machine_file = [design](const std::vector<double>& p) {
    return lathe_16k20f3_machine_file(design(p));
  };
  family.machine_size = [](const Machine&, const std::vector<double>& p) {
    return p.at(0) * p.at(0) * p.at(0);
  };
  return family;
}

}  // namespace pkmopt
