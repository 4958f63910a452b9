#include "io/design/task_wrench_file.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "io/format/field_list.hpp"
#include "io/format/number_policy.hpp"
#include "problems/design/cutting_load.hpp"

namespace pkmopt {

// The keys of the cutting models, described once (io/format/field_list.hpp): the reader and the
// tables of docs/design-studies.md come from these lists. The models check their own value ranges
// (check_turning_conditions, check_milling_conditions).
template <class Fields>
void describe_fields(Fields& f, TurningConditions& c) {
  const FieldRule req{.required = true};
  auto rule = [&](std::string_view unit, std::string_view doc) {
    FieldRule r = req;
    r.unit = unit;
    r.doc = doc;
    return r;
  };
  f.field("diameter_mm", c.diameter_mm, rule("mm", "D, workpiece diameter"));
  f.field("depth_mm", c.depth_mm, rule("mm", "t, depth of cut"));
  f.field("feed_mm_per_rev", c.feed_mm_per_rev, rule("mm/rev", "s, feed"));
  f.field("tool_life_min", c.tool_life_min, rule("min", "T, tool life"));
  f.field("C_v", c.C_v, rule("", "speed coefficient of V = C_v/(T^m t^x_v s^y_v)·K_v"));
  f.field("x_v", c.x_v, rule("", "exponent of t in V"));
  f.field("y_v", c.y_v, rule("", "exponent of s in V"));
  f.field("m", c.m, rule("", "exponent of T in V"));
  f.field("K_v", c.K_v, rule("", "speed correction factor"));
  f.field("C_p", c.C_p, rule("", "force coefficient of P_z = 10·C_p·t^x_p·s^y_p·V^n_p·K_p"));
  f.field("x_p", c.x_p, rule("", "exponent of t in P_z"));
  f.field("y_p", c.y_p, rule("", "exponent of s in P_z"));
  f.field("n_p", c.n_p, rule("", "exponent of V in P_z"));
  f.field("K_p", c.K_p, rule("", "force correction factor (product of the handbook factors)"));
  f.field("radial_ratio", c.radial_ratio, {.doc = "P_y / P_z"});
  f.field("axial_ratio", c.axial_ratio, {.doc = "P_x / P_z"});
}

template <class Fields>
void describe_fields(Fields& f, MillingConditions& c) {
  f.field("cutter_diameter_mm", c.cutter_diameter_mm,
          {.required = true, .unit = "mm", .doc = "D_c, cutter diameter"});
  f.field("teeth", c.teeth, {.min = 1, .max = 1000, .required = true, .doc = "z_n, teeth"});
  f.field("cutting_speed", c.cutting_speed,
          {.required = true, .unit = "m/min", .doc = "v_c, cutting speed"});
  f.field("feed_per_tooth_mm", c.feed_per_tooth_mm,
          {.required = true, .unit = "mm", .doc = "f_z, feed per tooth"});
  f.field("width_mm", c.width_mm,
          {.required = true, .unit = "mm", .doc = "a_e, radial engagement (at most D_c)"});
  f.field("depth_mm", c.depth_mm, {.required = true, .unit = "mm", .doc = "a_p, axial depth"});
  f.field("lead_angle_deg", c.lead_angle_deg,
          {.unit = "deg", .doc = "κ_r, lead angle (90 for a square shoulder cutter)"});
  f.field("k_c1", c.k_c1,
          {.required = true, .unit = "N/mm²", .doc = "specific cutting force at h = 1 mm"});
  f.field("m_c", c.m_c, {.doc = "rise of the specific cutting force, k_c = k_c1·h_m^(−m_c)"});
  f.field("radial_ratio", c.radial_ratio, {.doc = "F_r / F_t"});
  f.field("axial_ratio", c.axial_ratio, {.doc = "F_a / F_t"});
}

namespace {

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
  TurningConditions c;
  read_fields(t, c);
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
  MillingConditions c;
  read_fields(m, c);
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
    const std::vector<YamlValue> items = value.elements(6);
    TaskWrench result;
    for (int i = 0; i < 6; ++i) {
      result.wrench(i) = items[static_cast<std::size_t>(i)].as_double();
      if (std::abs(result.wrench(i)) > kMaxWrenchComponent)
        items[static_cast<std::size_t>(i)].fail("a force or moment within +-1e9 N or N*m",
                                                items[static_cast<std::size_t>(i)].describe());
    }
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
      if (!wrench_within_limits(result.wrench))
        f->fail("a factor that keeps every wrench component within +-1e9 N or N*m", f->describe());
      result.origin += fmt::format(", times factor {:g}", factor);
    }
    return result;
  }
  value.fail("a list of 6 numbers or a map with 'turning' or 'milling'", value.describe());
}

std::string cutting_model_fields_markdown(std::string_view model) {
  if (model == "turning") return fields_markdown(TurningConditions{});
  if (model == "milling") return fields_markdown(MillingConditions{});
  throw std::invalid_argument("cutting_model_fields_markdown: unknown model '" +
                              std::string(model) + "'");
}

}  // namespace pkmopt
