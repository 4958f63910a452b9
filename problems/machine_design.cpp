#include "problems/machine_design.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "models/hexapod.hpp"
#include "models/require.hpp"

namespace pkmopt {

// ---------------------------------------------------------------------------------------------
// Families.

double FamilyParameter::to_internal(double file_value) const {
  return in_degrees() ? deg_to_rad(file_value) : file_value;
}
double FamilyParameter::to_file(double internal_value) const {
  return in_degrees() ? rad_to_deg(internal_value) : internal_value;
}

int DesignFamily::index_of(std::string_view name) const {
  for (std::size_t i = 0; i < parameters.size(); ++i)
    if (parameters[i].name == name) return static_cast<int>(i);
  return -1;
}

std::vector<double> DesignFamily::default_parameters() const {
  std::vector<double> p;
  for (const FamilyParameter& parameter : parameters)
    p.push_back(parameter.to_internal(parameter.default_value));
  return p;
}

double envelope_machine_size(const Machine& machine, const std::vector<double>& /*parameters*/) {
  return machine_envelope_volume(machine).value_or(std::numeric_limits<double>::quiet_NaN());
}

std::vector<ParameterRange> default_ranges(const DesignFamily& family) {
  std::vector<ParameterRange> ranges;
  for (double value : family.default_parameters()) ranges.push_back({value, value});
  return ranges;
}

namespace {

double lift(const std::vector<double>& p, std::size_t home_index) { return p.at(home_index); }

}  // namespace

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

// ---------------------------------------------------------------------------------------------
// The problem.

double pose_reach_violation(const Machine& machine, const Pose& pose) {
  const std::optional<double> excess = machine.reach_excess(pose);
  // Unreachable for a reason the terms do not see (a rotation of a translational platform...).
  if (!excess || !(*excess > 0.0)) return 1.0;
  return std::min(1.0, *excess);
}

MachineDesignProblem::MachineDesignProblem(MachineDesignSpec spec) : spec_(std::move(spec)) {
  const std::string where = fmt::format("{} design problem '{}'", spec_.family.model, spec_.name);
  const DesignFamily& family = spec_.family;
  if (!family.build || !family.machine_size)
    throw std::invalid_argument(where + ": the design family lacks a builder or machine_size");
  if (spec_.parameters.size() != family.parameters.size())
    throw std::invalid_argument(fmt::format("{}: expected {} parameter ranges, found {}", where,
                                            family.parameters.size(), spec_.parameters.size()));
  for (std::size_t i = 0; i < spec_.parameters.size(); ++i) {
    const ParameterRange& r = spec_.parameters[i];
    if (!std::isfinite(r.lower) || !std::isfinite(r.upper) || r.lower > r.upper)
      throw std::invalid_argument(
          fmt::format("{}: parameter {}: expected finite lower <= upper, found [{}, {}]", where,
                      family.parameters[i].name, r.lower, r.upper));
    if (!r.fixed()) free_.push_back(static_cast<int>(i));
  }
  home_height_ = family.index_of("home_height");
  needed_ = check_design_goals(where, spec_.objectives, spec_.constraints, spec_.task);
  for (int m = 0; m < kNumDesignMetrics; ++m)
    if (needed_[m] && is_actuator_metric(static_cast<DesignMetric>(m)))
      throw std::invalid_argument(fmt::format(
          "{}: {} needs an actuator catalog to choose from, which only hexapod design problems "
          "have; bound leg_force_max instead",
          where, design_metric_name(static_cast<DesignMetric>(m))));
  if (spec_.task.acceleration_max > 0.0)
    throw std::invalid_argument(
        fmt::format("{}: task a_max needs a mass model, which only hexapod design problems have "
                    "(machine.masses)",
                    where));
  for (const DesignMetric metric : {DesignMetric::natural_frequency_min, DesignMetric::moving_mass,
                                    DesignMetric::actuator_force_dynamic_max})
    if (needed_[static_cast<int>(metric)])
      throw std::invalid_argument(fmt::format(
          "{}: {} needs a mass model, which only hexapod design problems have (machine.masses)",
          where, design_metric_name(metric)));
  if (spec_.task.installation_space.present())
    throw std::invalid_argument(fmt::format(
        "{}: task installation_space is checked only in hexapod design problems", where));
  for (const DesignMetric m : {DesignMetric::swept_volume, DesignMetric::footprint})
    if (needed_[static_cast<int>(m)])
      throw std::invalid_argument(fmt::format(
          "{}: {} is computed only in hexapod design problems (the convex hull of the joints "
          "over the task); this family has machine_size",
          where, design_metric_name(m)));
  if (needed_[static_cast<int>(DesignMetric::leg_clearance_min)]) {
    // The template's shape is every design's (the family's parameters are dimensions).
    const std::vector<double> middle = [&] {
      std::vector<double> p;
      for (const ParameterRange& r : spec_.parameters) p.push_back(0.5 * (r.lower + r.upper));
      return p;
    }();
    bool shaped = false;
    try {
      shaped = family.build(middle)->checks_leg_interference();
    } catch (const std::invalid_argument&) {
      shaped = true;  // an invalid middle design says nothing about the shape; evaluations will
    }
    if (!shaped)
      throw std::invalid_argument(fmt::format(
          "{}: leg_clearance_min needs the links' shape (machine.link_diameter or crank_diameter, "
          "docs/interference.md)",
          where));
  }
}

Bounds MachineDesignProblem::bounds() const {
  Bounds b;
  for (int i : free_) {
    b.lower.push_back(spec_.parameters[static_cast<std::size_t>(i)].lower);
    b.upper.push_back(spec_.parameters[static_cast<std::size_t>(i)].upper);
  }
  return b;
}

std::vector<double> MachineDesignProblem::parameters_of(const std::vector<double>& x) const {
  if (x.size() != free_.size())
    throw std::invalid_argument(
        fmt::format("{}: expected {} variables, found {}", spec_.name, free_.size(), x.size()));
  std::vector<double> p;
  for (const ParameterRange& r : spec_.parameters) p.push_back(r.lower);
  for (std::size_t j = 0; j < free_.size(); ++j) p[static_cast<std::size_t>(free_[j])] = x[j];
  return p;
}

double MachineDesignProblem::home_height_of(const std::vector<double>& parameters) const {
  return home_height_ < 0 ? 0.0 : lift(parameters, static_cast<std::size_t>(home_height_));
}

MachineDesignEvaluation MachineDesignProblem::evaluate(const std::vector<double>& x) const {
  MachineDesignEvaluation ev;
  ev.parameters = parameters_of(x);
  ev.metrics.fill(0.0);
  ev.reach_violation = 1.0;
  std::unique_ptr<Machine> machine;
  try {
    machine = spec_.family.build(ev.parameters);
  } catch (const std::invalid_argument& error) {
    ev.failure = fmt::format("invalid machine: {}", error.what());
    return ev;
  }
  auto metric = [&](DesignMetric m) -> double& { return ev.metrics[static_cast<int>(m)]; };
  metric(DesignMetric::machine_size) = spec_.family.machine_size(*machine, ev.parameters);

  // Every pose is analysed (reachability and the per-pose metrics come from one call).
  const double h = home_height_of(ev.parameters);
  const std::unique_ptr<MachineData> data = machine->make_data();
  data->compliance_metrics = needed_[static_cast<int>(DesignMetric::tcp_deflection_max)] ||
                             needed_[static_cast<int>(DesignMetric::stiffness_min_loaded)];
  PoseMetrics m;
  TaskWorstCase worst;
  double reach_sum = 0.0;
  for (std::size_t k = 0; k < spec_.task.poses.size(); ++k) {
    Pose pose = spec_.task.poses[k];
    pose.position.z() += h;
    machine->analyze(*data, pose, spec_.task.wrench, m);
    if (!m.reachable) reach_sum += pose_reach_violation(*machine, pose);
    if (m.singular && !m.reachable) continue;  // no metrics (e.g. a leg that cannot close)
    if (m.singular && ev.failure.empty())
      ev.failure = fmt::format("singular at task pose {} (x {:.4g}, y {:.4g}, z {:.4g} m)", k,
                               pose.position.x(), pose.position.y(), pose.position.z());
    worst.add(m);
    ++ev.analysed_poses;
  }
  ev.reach_violation = reach_sum / static_cast<double>(spec_.task.poses.size());
  ev.reachable = reach_sum == 0.0;
  if (ev.analysed_poses == 0 && ev.failure.empty())
    ev.failure = "no task pose can be analysed (every pose is unreachable and singular)";
  worst.store(ev.metrics);
  measure_workspace_metrics(*machine, spec_.task.workspace, needed_, ev.metrics, ev.failure);
  check_finite_metrics(needed_, ev.metrics, ev.failure);
  return ev;
}

std::vector<double> MachineDesignProblem::aggregate_fitness(
    const MachineDesignEvaluation& ev) const {
  return aggregate_design_rows(spec_.objectives, spec_.constraints, spec_.require_reachable,
                               ev.metrics, ev.reach_violation, !ev.ok());
}

DesignRecord MachineDesignProblem::measure(const std::vector<double>& x) const {
  MachineDesignEvaluation ev = evaluate(x);
  DesignRecord record;
  record.home_height = home_height_of(ev.parameters);
  record.metrics = ev.metrics;
  record.aggregate = aggregate_fitness(ev);
  record.failure = std::move(ev.failure);
  record.parameters = std::move(ev.parameters);
  return record;
}

std::vector<double> MachineDesignProblem::fitness(const std::vector<double>& x) const {
  return aggregate_fitness(evaluate(x));
}

}  // namespace pkmopt
