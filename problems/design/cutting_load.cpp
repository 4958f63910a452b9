#include "problems/design/cutting_load.hpp"

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace pkmopt {
namespace {

// "" when value is finite and > 0 (or >= 0 with allow_zero), else the complaint.
std::string check_value(const char* name, double value, bool allow_zero = false) {
  if (std::isfinite(value) && (value > 0.0 || (allow_zero && value == 0.0))) return {};
  return fmt::format("{}: expected a finite number {}, found {}", name, allow_zero ? ">= 0" : "> 0",
                     value);
}

std::string check_exponent(const char* name, double value) {
  if (std::isfinite(value)) return {};
  return fmt::format("{}: expected a finite number, found {}", name, value);
}

template <typename... Checks>
std::string first_failure(const Checks&... checks) {
  std::string result;
  ((result.empty() && !checks.empty() ? (result = checks, 0) : 0), ...);
  return result;
}

}  // namespace

std::string check_turning_conditions(const TurningConditions& c) {
  return first_failure(
      check_value("diameter_mm", c.diameter_mm), check_value("depth_mm", c.depth_mm),
      check_value("feed_mm_per_rev", c.feed_mm_per_rev),
      check_value("tool_life_min", c.tool_life_min), check_value("C_v", c.C_v),
      check_exponent("x_v", c.x_v), check_exponent("y_v", c.y_v), check_exponent("m", c.m),
      check_value("K_v", c.K_v), check_value("C_p", c.C_p), check_exponent("x_p", c.x_p),
      check_exponent("y_p", c.y_p), check_exponent("n_p", c.n_p), check_value("K_p", c.K_p),
      check_value("radial_ratio", c.radial_ratio, true),
      check_value("axial_ratio", c.axial_ratio, true));
}

TurningLoad turning_load(const TurningConditions& c) {
  if (const std::string problem = check_turning_conditions(c); !problem.empty()) {
    throw std::invalid_argument("turning conditions: " + problem);
  }
  TurningLoad load;
  load.cutting_speed = c.C_v /
                       (std::pow(c.tool_life_min, c.m) * std::pow(c.depth_mm, c.x_v) *
                        std::pow(c.feed_mm_per_rev, c.y_v)) *
                       c.K_v;
  load.spindle_speed = 1000.0 * load.cutting_speed / (std::numbers::pi * c.diameter_mm);
  load.tangential = 10.0 * c.C_p * std::pow(c.depth_mm, c.x_p) *
                    std::pow(c.feed_mm_per_rev, c.y_p) * std::pow(load.cutting_speed, c.n_p) *
                    c.K_p;
  load.radial = c.radial_ratio * load.tangential;
  load.axial = c.axial_ratio * load.tangential;
  return load;
}

Eigen::Vector3d turning_machine_force(const TurningLoad& load, double approach_angle) {
  const double c = std::cos(approach_angle);
  const double s = std::sin(approach_angle);
  return {load.axial, load.radial * c - load.tangential * s, load.radial * s + load.tangential * c};
}

double optimal_approach_angle(const TurningLoad& load) {
  return std::atan2(load.radial, load.tangential);
}

std::string check_milling_conditions(const MillingConditions& c) {
  std::string problem = first_failure(
      check_value("cutter_diameter_mm", c.cutter_diameter_mm),
      check_value("cutting_speed", c.cutting_speed),
      check_value("feed_per_tooth_mm", c.feed_per_tooth_mm), check_value("width_mm", c.width_mm),
      check_value("depth_mm", c.depth_mm), check_value("k_c1", c.k_c1),
      check_value("m_c", c.m_c, true), check_value("radial_ratio", c.radial_ratio, true),
      check_value("axial_ratio", c.axial_ratio, true));
  if (!problem.empty()) return problem;
  if (c.teeth < 1) return fmt::format("teeth: expected an integer >= 1, found {}", c.teeth);
  if (c.width_mm > c.cutter_diameter_mm) {
    return fmt::format("width_mm: expected at most cutter_diameter_mm ({}), found {}",
                       c.cutter_diameter_mm, c.width_mm);
  }
  if (!(std::isfinite(c.lead_angle_deg) && c.lead_angle_deg > 0.0 && c.lead_angle_deg <= 90.0)) {
    return fmt::format("lead_angle_deg: expected an angle in (0, 90], found {}", c.lead_angle_deg);
  }
  if (!(c.m_c < 1.0)) return fmt::format("m_c: expected a number < 1, found {}", c.m_c);
  return {};
}

MillingLoad milling_load(const MillingConditions& c) {
  if (const std::string problem = check_milling_conditions(c); !problem.empty()) {
    throw std::invalid_argument("milling conditions: " + problem);
  }
  MillingLoad load;
  load.spindle_speed = 1000.0 * c.cutting_speed / (std::numbers::pi * c.cutter_diameter_mm);
  load.table_feed = c.feed_per_tooth_mm * c.teeth * load.spindle_speed;
  const double ratio = 2.0 * c.width_mm / c.cutter_diameter_mm;  // 1 - cos(phi_e)
  const double engagement = std::acos(1.0 - ratio);
  const double kappa = c.lead_angle_deg * std::numbers::pi / 180.0;
  load.mean_chip_thickness = c.feed_per_tooth_mm * std::sin(kappa) * ratio / engagement;
  load.specific_force = c.k_c1 * std::pow(load.mean_chip_thickness, -c.m_c);
  load.power_kw = c.depth_mm * c.width_mm * load.table_feed * load.specific_force / 60.0e6;
  load.tangential = 60000.0 * load.power_kw / c.cutting_speed;
  load.radial = c.radial_ratio * load.tangential;
  load.axial = c.axial_ratio * load.tangential;
  load.spindle_torque = load.tangential * c.cutter_diameter_mm / 2000.0;
  return load;
}

Wrench milling_wrench(const MillingLoad& load, const Eigen::Vector3d& feed_direction) {
  const double norm = feed_direction.norm();
  if (!(std::isfinite(norm) && norm > 0.0) || std::abs(feed_direction.z()) > 1e-12 * norm) {
    throw std::invalid_argument(fmt::format(
        "milling feed direction: expected a non-zero vector in the base x-y plane, found "
        "[{}, {}, {}]",
        feed_direction.x(), feed_direction.y(), feed_direction.z()));
  }
  const Eigen::Vector3d f = feed_direction / norm;
  const Eigen::Vector3d across = Eigen::Vector3d::UnitZ().cross(f);
  Wrench w = Wrench::Zero();
  w.head<3>() = -load.tangential * f + load.radial * across + load.axial * Eigen::Vector3d::UnitZ();
  w(5) = -load.spindle_torque;
  return w;
}

}  // namespace pkmopt
