#include "problems/design/machine_design.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "models/core/capabilities.hpp"
#include "models/core/require.hpp"
#include "models/geometry/sketch_envelope.hpp"

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

// The machine that stands for the family's designs where the problem checks what every design
// shares (its shape, its masses, its kind of drives): the middle of the ranges, else the family's
// defaults; nullptr when neither is a valid machine (the evaluations will say why).
std::unique_ptr<Machine> template_machine(const MachineDesignSpec& spec) {
  std::vector<double> middle;
  for (const ParameterRange& r : spec.parameters) middle.push_back(0.5 * (r.lower + r.upper));
  for (const std::vector<double>& p : {middle, spec.family.default_parameters()}) {
    try {
      return spec.family.build(p);
    } catch (const std::invalid_argument&) {
    }
  }
  return nullptr;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// The problem.

std::vector<DriveGroupNeed> drive_group_needs(const Machine& machine,
                                              const Eigen::VectorXd& drive_force) {
  std::vector<DriveGroupNeed> needs;
  std::vector<int> group_of;  // group number -> index in needs
  for (int i = 0; i < machine.num_actuators(); ++i) {
    const int g = machine.drive_group(i);
    auto at = std::find(group_of.begin(), group_of.end(), g);
    if (at == group_of.end()) {
      group_of.push_back(g);
      needs.push_back({.revolute = machine.revolute_actuator(i), .count = 0, .drives = {}});
      at = group_of.end() - 1;
    }
    DriveGroupNeed& need = needs[static_cast<std::size_t>(at - group_of.begin())];
    ++need.count;
    need.force = std::max(need.force, std::abs(drive_force(i)));
    need.drives.push_back(i);
    if (!need.revolute)
      need.stroke = std::max(need.stroke, machine.actuator_stroke(i).value_or(0.0));
  }
  return needs;
}

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
    if (needed_[m] && is_actuator_metric(static_cast<DesignMetric>(m)) && !spec_.actuator_catalog)
      throw std::invalid_argument(fmt::format(
          "{}: {} needs an actuator catalog to choose from (a constraint {{actuator: cheapest, "
          "catalog: FILE}}), found none",
          where, design_metric_name(static_cast<DesignMetric>(m))));
  if (spec_.actuator_catalog) set_up_actuator_catalog(where);
  if (spec_.task.acceleration_max > 0.0)
    throw std::invalid_argument(
        fmt::format("{}: task a_max is checked only in hexapod design problems", where));
  if (needed_[static_cast<int>(DesignMetric::actuator_force_dynamic_max)])
    throw std::invalid_argument(fmt::format(
        "{}: actuator_force_dynamic_max is computed only in hexapod design problems", where));
  if (needed_[static_cast<int>(DesignMetric::task_singularity_free)])
    throw std::invalid_argument(fmt::format(
        "{}: task_singularity_free is computed only in hexapod design problems (an interval "
        "enclosure of the hexapod's Jacobian over the task region)",
        where));
  check_template_machine(where);
}

void MachineDesignProblem::check_template_machine(const std::string& where) const {
  auto need = [&](DesignMetric m) { return needed_[static_cast<int>(m)]; };
  if (!need(DesignMetric::natural_frequency_min) && !need(DesignMetric::moving_mass) &&
      !need(DesignMetric::leg_clearance_min))
    return;
  // The template's masses and shape are every design's (the family's parameters are
  // dimensions); without a valid template every evaluation fails with the machine's reason.
  const std::unique_ptr<Machine> machine = template_machine(spec_);
  if (machine == nullptr) return;
  for (const DesignMetric metric : {DesignMetric::natural_frequency_min, DesignMetric::moving_mass})
    if (need(metric))
      if (const Capability<Dynamics> dynamics = machine->dynamics(); !dynamics)
        throw std::invalid_argument(fmt::format("{}: {} needs a mass model: {} (docs/dynamics.md)",
                                                where, design_metric_name(metric),
                                                dynamics.reason()));
  if (need(DesignMetric::leg_clearance_min) && !machine->checks_leg_interference())
    throw std::invalid_argument(fmt::format(
        "{}: leg_clearance_min needs the links' shape (machine.link_diameter or crank_diameter, "
        "docs/interference.md)",
        where));
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

void MachineDesignProblem::set_up_actuator_catalog(const std::string& where) {
  const ActuatorCatalog& catalog = *spec_.actuator_catalog;
  if (catalog.entries.empty() && catalog.rotary_entries.empty())
    throw std::invalid_argument(fmt::format(
        "{}: actuator catalog '{}': expected at least one entry, found none", where, catalog.name));
  if (const std::string problem = check_actuator_catalog(catalog); !problem.empty())
    throw std::invalid_argument(
        fmt::format("{}: actuator catalog '{}': {}", where, catalog.name, problem));
  if (const std::string problem = actuator_metric_mismatch(needed_, spec_.each_drive);
      !problem.empty())
    throw std::invalid_argument(fmt::format("{}: {}", where, problem));
  std::unique_ptr<Machine> machine = template_machine(spec_);
  if (machine == nullptr) machine = spec_.family.build(spec_.family.default_parameters());
  if (spec_.each_drive) {
    if (const std::string problem = check_drive_pricing(catalog); !problem.empty())
      throw std::invalid_argument(
          fmt::format("{}: actuator catalog '{}': {}", where, catalog.name, problem));
    for (int i = 0; i < machine->num_actuators(); ++i) {
      const bool revolute = machine->revolute_actuator(i);
      if (revolute ? catalog.rotary_entries.empty() : catalog.entries.empty())
        throw std::invalid_argument(fmt::format(
            "{}: actuator catalog '{}' has no {} entries for the {} family's drive {}", where,
            catalog.name, revolute ? "rotary" : "linear", spec_.family.model, i + 1));
      if (!revolute && !machine->actuator_stroke(i))
        throw std::invalid_argument(
            fmt::format("{}: the {} family gives no actuator stroke to choose a catalog entry by",
                        where, spec_.family.model));
    }
    return;
  }
  if (catalog.entries.empty())
    throw std::invalid_argument(
        fmt::format("{}: actuator catalog '{}': expected at least one linear entry, found none",
                    where, catalog.name));
  pricing_ = catalog_pricing(catalog);  // throws when only some entries have a cost
  // The catalog holds linear drives: a family with revolute drives (a delta's cranks) has none
  // to choose.
  if (machine->any_revolute_actuator())
    throw std::invalid_argument(fmt::format(
        "{}: actuator catalog '{}' holds linear drives; the {} family's drives are revolute", where,
        catalog.name, spec_.family.model));
  for (const int i : spec_.actuator_drives)
    if (i < 0 || i >= machine->num_actuators())
      throw std::invalid_argument(
          fmt::format("{}: actuator_drives: expected drives 0..{}, found {}", where,
                      machine->num_actuators() - 1, i));
  for (int i = 0; i < machine->num_actuators(); ++i)
    if (!machine->actuator_stroke(i))
      throw std::invalid_argument(
          fmt::format("{}: the {} family gives no actuator stroke to choose a catalog entry by",
                      where, spec_.family.model));
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
  ev.metrics[static_cast<int>(DesignMetric::machine_size)] =
      spec_.family.machine_size(*machine, ev.parameters);
  const double h = home_height_of(ev.parameters);
  const Eigen::VectorXd drive_force = measure_task_poses(*machine, h, ev);
  measure_envelope(*machine, h, ev);
  if (ev.analysed_poses == 0 && ev.failure.empty())
    ev.failure = "no task pose can be analysed (every pose is unreachable and singular)";
  if (needed_[static_cast<int>(DesignMetric::moving_mass)]) {
    const Capability<Dynamics> dynamics = machine->dynamics();
    ev.metrics[static_cast<int>(DesignMetric::moving_mass)] =
        dynamics ? dynamics->moving_mass() : std::numeric_limits<double>::quiet_NaN();
  }
  if (spec_.actuator_catalog) price_drives(*machine, drive_force, ev);
  measure_workspace_metrics(*machine, spec_.task.workspace, needed_, ev.metrics, ev.failure);
  check_finite_metrics(needed_, ev.metrics, ev.failure);
  return ev;
}

Eigen::VectorXd MachineDesignProblem::measure_task_poses(const Machine& machine, double h,
                                                         MachineDesignEvaluation& ev) const {
  // Every pose is analysed (reachability and the per-pose metrics come from one call).
  const std::unique_ptr<MachineData> data = machine.make_data();
  data->compliance_metrics = needed_[static_cast<int>(DesignMetric::tcp_deflection_max)] ||
                             needed_[static_cast<int>(DesignMetric::stiffness_min_loaded)] ||
                             needed_[static_cast<int>(DesignMetric::natural_frequency_min)];
  PoseMetrics m;
  TaskWorstCase worst;
  Eigen::VectorXd drive_force = Eigen::VectorXd::Zero(machine.num_actuators());  // max |tau_i|
  double reach_sum = 0.0;
  const InstallationSpace& space = spec_.task.installation_space;
  const std::vector<ObstacleBox>& obstacles = spec_.task.obstacles;
  const std::unique_ptr<MachineData> sketch_data =
      space.present() || !obstacles.empty() ? machine.make_data() : nullptr;
  MachineSketch sketch;
  for (std::size_t k = 0; k < spec_.task.poses.size(); ++k) {
    Pose pose = spec_.task.poses[k];
    pose.position.z() += h;
    machine.analyze(*data, pose, spec_.task.wrench, m);
    if (!m.reachable) reach_sum += pose_reach_violation(machine, pose);
    if (sketch_data != nullptr && machine.sketch(*sketch_data, pose, sketch)) {
      // The machine drawn at the pose must fit the installation space and keep out of the
      // obstacles: how far it sticks out and how deep it goes in (m, each at most 1 per pose)
      // are terms of the reach row, as an unreachable pose's excess.
      if (space.present()) reach_sum += std::min(1.0, std::max(0.0, sketch_excess(sketch, space)));
      if (!obstacles.empty())
        reach_sum += std::min(1.0, std::max(0.0, sketch_intrusion(sketch, obstacles)));
    }
    if (m.singular && !m.reachable) continue;  // no metrics (e.g. a leg that cannot close)
    // A singular pose fails the design when its statics blow up (a parallel machine: forces
    // and compliance without bound); a serial machine's free rotary axis (the tool along it)
    // loses a motion, not the statics, and is measured (singularity_margin 0 there).
    const bool statics_finite =
        std::isfinite(m.stiffness_min) && m.stiffness_min > 0.0 && m.tau.allFinite();
    if (m.singular && !statics_finite && ev.failure.empty())
      ev.failure = fmt::format("singular at task pose {} (x {:.4g}, y {:.4g}, z {:.4g} m)", k,
                               pose.position.x(), pose.position.y(), pose.position.z());
    worst.add(m);
    drive_force = drive_force.cwiseMax(m.tau.cwiseAbs());
    ++ev.analysed_poses;
  }
  ev.reach_violation = reach_sum / static_cast<double>(spec_.task.poses.size());
  ev.reachable = reach_sum == 0.0;
  worst.store(ev.metrics);
  return drive_force;
}

void MachineDesignProblem::measure_envelope(const Machine& machine, double h,
                                            MachineDesignEvaluation& ev) const {
  auto metric = [&](DesignMetric m) -> double& { return ev.metrics[static_cast<int>(m)]; };
  const bool margin = needed_[static_cast<int>(DesignMetric::task_margin)];
  const bool envelope_needed = needed_[static_cast<int>(DesignMetric::swept_volume)] ||
                               needed_[static_cast<int>(DesignMetric::footprint)];
  if (!margin && !envelope_needed) return;
  std::vector<Pose> lifted = spec_.task.poses;  // the task poses after the home_height lift
  for (Pose& pose : lifted) pose.position.z() += h;
  if (margin)
    metric(DesignMetric::task_margin) =
        task_margin(machine, lifted, task_margin_limit(spec_.task.poses));
  if (envelope_needed) {
    const SketchEnvelope envelope = sketch_envelope(machine, lifted);
    const bool drawn = envelope.drawn > 0;
    metric(DesignMetric::swept_volume) =
        drawn ? envelope.volume : std::numeric_limits<double>::quiet_NaN();
    metric(DesignMetric::footprint) =
        drawn ? envelope.footprint : std::numeric_limits<double>::quiet_NaN();
    if (!drawn && ev.failure.empty())
      ev.failure = "the machine cannot be drawn at any task pose (swept_volume, footprint)";
  }
}

void MachineDesignProblem::price_drives(const Machine& machine, const Eigen::VectorXd& drive_force,
                                        MachineDesignEvaluation& ev) const {
  auto metric = [&](DesignMetric m) -> double& { return ev.metrics[static_cast<int>(m)]; };
  const ActuatorCatalog& catalog = *spec_.actuator_catalog;
  if (spec_.each_drive) {
    ev.drive_needs = drive_group_needs(machine, drive_force);
    ev.drive_choice = choose_drives(catalog, ev.drive_needs);
    metric(DesignMetric::drive_cost) = ev.drive_choice.cost;
    metric(DesignMetric::drive_overload) = ev.drive_choice.overload;
    return;
  }
  // Every chosen drive gets the entry: the largest force over the task, the longest stroke.
  double stroke = 0.0, force = 0.0;
  for (int i = 0; i < machine.num_actuators(); ++i) {
    if (!spec_.actuator_drives.empty() &&
        std::find(spec_.actuator_drives.begin(), spec_.actuator_drives.end(), i) ==
            spec_.actuator_drives.end())
      continue;
    stroke = std::max(stroke, machine.actuator_stroke(i).value_or(0.0));
    force = std::max(force, drive_force(i));
  }
  const ActuatorRequirement need{.force = force, .stroke = stroke};
  const StudyActuatorChoice choice = study_actuator_choice(catalog, pricing_, need);
  ev.actuator = choice.entry;
  metric(DesignMetric::actuator_cost) = choice.cost;
  metric(DesignMetric::actuator_overload) = choice.overload;
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
  record.actuator = ev.actuator;
  if (spec_.actuator_catalog && spec_.each_drive)
    record.drives = drive_choice_text(*spec_.actuator_catalog, ev.drive_needs, ev.drive_choice);
  return record;
}

std::vector<double> MachineDesignProblem::fitness(const std::vector<double>& x) const {
  return aggregate_fitness(evaluate(x));
}

}  // namespace pkmopt
