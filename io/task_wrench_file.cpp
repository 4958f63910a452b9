#include "io/task_wrench_file.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "problems/cutting_load.hpp"

namespace pkmopt {
namespace {

double read_or(const YamlValue& map, std::string_view key, double fallback) {
  const auto value = map.optional(key);
  return value ? value->as_double() : fallback;
}

// Maps a model's complaint "name: expected ..., found ..." to the key of that name.
[[noreturn]] void fail_at_key(const YamlValue& map, const std::string& problem) {
  const std::string key = problem.substr(0, problem.find(':'));
  const auto value = map.optional(key);
  const std::string rest = problem.substr(problem.find(':') + 2);
  if (value) value->fail(rest);
  map.fail(problem);
}

TaskWrench read_turning(const YamlValue& root) {
  root.check_keys({"turning", "approach_angle_deg", "rotation_deg", "factor"});
  const YamlValue t = root.required("turning");
  t.check_keys({"diameter_mm", "depth_mm", "feed_mm_per_rev", "tool_life_min", "C_v", "x_v", "y_v",
                "m", "K_v", "C_p", "x_p", "y_p", "n_p", "K_p", "radial_ratio", "axial_ratio"});
  TurningConditions c;
  c.diameter_mm = t.required("diameter_mm").as_double();
  c.depth_mm = t.required("depth_mm").as_double();
  c.feed_mm_per_rev = t.required("feed_mm_per_rev").as_double();
  c.tool_life_min = t.required("tool_life_min").as_double();
  c.C_v = t.required("C_v").as_double();
  c.x_v = t.required("x_v").as_double();
  c.y_v = t.required("y_v").as_double();
  c.m = t.required("m").as_double();
  c.K_v = t.required("K_v").as_double();
  c.C_p = t.required("C_p").as_double();
  c.x_p = t.required("x_p").as_double();
  c.y_p = t.required("y_p").as_double();
  c.n_p = t.required("n_p").as_double();
  c.K_p = t.required("K_p").as_double();
  c.radial_ratio = read_or(t, "radial_ratio", c.radial_ratio);
  c.axial_ratio = read_or(t, "axial_ratio", c.axial_ratio);
  if (const std::string problem = check_turning_conditions(c); !problem.empty()) {
    fail_at_key(t, problem);
  }
  const TurningLoad load = turning_load(c);
  double approach = 0.0;
  if (const auto a = root.optional("approach_angle_deg")) {
    if (a->is_scalar() && a->as_string() == "optimal") {
      approach = optimal_approach_angle(load);
    } else {
      const double deg = a->as_double();
      if (!(std::abs(deg) <= 180.0))
        a->fail("an angle in degrees in [-180, 180] or 'optimal'", a->describe());
      approach = deg_to_rad(deg);
    }
  }
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  if (const auto r = root.optional("rotation_deg")) {
    const std::vector<double> deg = r->as_doubles(3);
    rotation = rotation_zyx<double>(
        Eigen::Vector3d(deg_to_rad(deg[0]), deg_to_rad(deg[1]), deg_to_rad(deg[2])));
  }
  TaskWrench result;
  result.wrench.head<3>() = rotation * turning_machine_force(load, approach);
  result.origin = fmt::format(
      "turning: V {:.2f} m/min, n {:.0f} rev/min, P_z {:.0f} N, P_y {:.0f} N, P_x {:.0f} N, "
      "approach {:.2f} deg",
      load.cutting_speed, load.spindle_speed, load.tangential, load.radial, load.axial,
      approach * 180.0 / std::numbers::pi);
  return result;
}

TaskWrench read_milling(const YamlValue& root) {
  root.check_keys({"milling", "feed_direction", "factor"});
  const YamlValue m = root.required("milling");
  m.check_keys({"cutter_diameter_mm", "teeth", "cutting_speed", "feed_per_tooth_mm", "width_mm",
                "depth_mm", "lead_angle_deg", "k_c1", "m_c", "radial_ratio", "axial_ratio"});
  MillingConditions c;
  c.cutter_diameter_mm = m.required("cutter_diameter_mm").as_double();
  const YamlValue teeth = m.required("teeth");
  const long long n = teeth.as_int();
  if (n < 1 || n > 1000) teeth.fail("an integer in [1, 1000]", teeth.describe());
  c.teeth = static_cast<int>(n);
  c.cutting_speed = m.required("cutting_speed").as_double();
  c.feed_per_tooth_mm = m.required("feed_per_tooth_mm").as_double();
  c.width_mm = m.required("width_mm").as_double();
  c.depth_mm = m.required("depth_mm").as_double();
  c.lead_angle_deg = read_or(m, "lead_angle_deg", c.lead_angle_deg);
  c.k_c1 = m.required("k_c1").as_double();
  c.m_c = read_or(m, "m_c", c.m_c);
  c.radial_ratio = read_or(m, "radial_ratio", c.radial_ratio);
  c.axial_ratio = read_or(m, "axial_ratio", c.axial_ratio);
  if (const std::string problem = check_milling_conditions(c); !problem.empty()) {
    fail_at_key(m, problem);
  }
  Eigen::Vector3d feed = Eigen::Vector3d::UnitX();
  if (const auto f = root.optional("feed_direction")) {
    const std::vector<double> v = f->as_doubles(3);
    feed = Eigen::Vector3d(v[0], v[1], v[2]);
    if (!(feed.norm() > 0.0) || v[2] != 0.0) {
      f->fail("a non-zero direction in the base x-y plane [x, y, 0]", f->describe());
    }
  }
  const MillingLoad load = milling_load(c);
  TaskWrench result;
  result.wrench = milling_wrench(load, feed);
  result.origin = fmt::format(
      "milling: n {:.0f} rev/min, v_f {:.0f} mm/min, h_m {:.4f} mm, k_c {:.0f} N/mm^2, "
      "P_c {:.2f} kW, F_t {:.0f} N, F_r {:.0f} N, F_a {:.0f} N",
      load.spindle_speed, load.table_feed, load.mean_chip_thickness, load.specific_force,
      load.power_kw, load.tangential, load.radial, load.axial);
  return result;
}

}  // namespace

TaskWrench read_task_wrench(const YamlValue& value) {
  if (value.is_sequence()) {
    const std::vector<double> w = value.as_doubles(6);
    TaskWrench result;
    for (int i = 0; i < 6; ++i) result.wrench(i) = w[static_cast<std::size_t>(i)];
    return result;
  }
  if (!value.is_map()) {
    value.fail("a list of 6 numbers or a map with 'turning' or 'milling'", value.describe());
  }
  if (value.has("turning") || value.has("milling")) {
    TaskWrench result = value.has("turning") ? read_turning(value) : read_milling(value);
    if (const auto f = value.optional("factor")) {
      const double factor = f->as_double();
      if (!(factor > 0.0 && factor <= 100.0)) f->fail("a number in (0, 100]", f->describe());
      result.wrench *= factor;
      result.origin += fmt::format(", times factor {:g}", factor);
    }
    return result;
  }
  value.fail("a list of 6 numbers or a map with 'turning' or 'milling'", value.describe());
}

}  // namespace pkmopt
