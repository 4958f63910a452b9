#include "problems/design/hexapod_design.hpp"

#include <fmt/format.h>

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <span>
#include <stdexcept>
#include <type_traits>

#include "models/dynamics/acceleration_capability.hpp"
#include "models/geometry/sketch_envelope.hpp"
#include "models/hexapod/swept_envelope.hpp"
#include "models/sample_machines.hpp"
#include "models/workspace/mode_certificate.hpp"
#include "problems/design/hexapod_design_detail.hpp"

namespace pkmopt {

using hexapod_design_detail::semi_regular_joints;

namespace {

constexpr std::array<std::string_view, kNumDesignParameters> kParameterNames = {
    "base_radius",
    "platform_radius",
    "base_pair_separation_deg",
    "platform_pair_separation_deg",
    "min_length",
    "stroke",
    "home_height"};

}  // namespace

std::string_view design_parameter_name(int index) { return kParameterNames.at(index); }
bool design_parameter_in_degrees(int index) {
  return index == kBasePairSeparation || index == kPlatformPairSeparation;
}

HexapodDesignSpec::HexapodDesignSpec() {
  machine_template = sample_machines::conventions_hexapod_design();
  const std::array<double, kNumDesignParameters> values = {
      0.60, 0.25, deg_to_rad(20), deg_to_rad(20), 0.70, 0.45, 0.0};
  for (int i = 0; i < kNumDesignParameters; ++i) parameters[i] = {values[i], values[i]};
}

HexapodDesignProblem::HexapodDesignProblem(HexapodDesignSpec spec) : spec_(std::move(spec)) {
  const std::string where = fmt::format("hexapod design problem '{}'", spec_.name);
  for (int i = 0; i < kNumDesignParameters; ++i) {
    const ParameterRange& r = spec_.parameters[i];
    if (!std::isfinite(r.lower) || !std::isfinite(r.upper) || r.lower > r.upper)
      throw std::invalid_argument(
          fmt::format("{}: parameter {}: expected finite lower <= upper, "
                      "found [{}, {}]",
                      where, kParameterNames[i], r.lower, r.upper));
    if (!r.fixed()) free_.push_back(i);
  }
  needed_ = check_design_goals(where, spec_.objectives, spec_.constraints, spec_.task);
  check_machine_for_goals(where);
  set_up_actuator_catalog(where);
  if (spec_.formulation == DesignFormulation::aggregate) {
    num_inequality_ = spec_.constraints.size() + (spec_.require_reachable ? 1 : 0);
    return;
  }
  set_up_smooth_formulation(where);
}

// The machine has what the goals need: masses for a_max and the dynamic metrics, the legs' shape
// for their clearance.
void HexapodDesignProblem::check_machine_for_goals(const std::string& where) {
  if (spec_.task.acceleration_max > 0.0 && !spec_.machine_template.masses.present)
    throw std::invalid_argument(fmt::format(
        "{}: task a_max needs the machine's masses (machine.masses, docs/dynamics.md)", where));
  // With a_max the drives are sized for the accelerated task: the catalog choice uses it.
  if (spec_.task.acceleration_max > 0.0 && spec_.actuator_catalog)
    needed_[static_cast<int>(DesignMetric::actuator_force_dynamic_max)] = true;
  for (const DesignMetric metric : {DesignMetric::natural_frequency_min, DesignMetric::moving_mass,
                                    DesignMetric::actuator_force_dynamic_max})
    if (needed_[static_cast<int>(metric)] && !spec_.machine_template.masses.present)
      throw std::invalid_argument(
          fmt::format("{}: {} needs the machine's masses (machine.masses, docs/dynamics.md)", where,
                      design_metric_name(metric)));
  if (needed_[static_cast<int>(DesignMetric::leg_clearance_min)] &&
      !spec_.machine_template.leg_shape.present())
    throw std::invalid_argument(fmt::format(
        "{}: leg_clearance_min needs the legs' shape (machine.legs.diameter, or legs.cylinder "
        "and legs.rod; docs/interference.md)",
        where));
}

// The actuator catalog the design chooses its drives from: checked, its costs, the stroke within
// its longest entry; without one, no goal may need it.
void HexapodDesignProblem::set_up_actuator_catalog(const std::string& where) {
  if (spec_.actuator_catalog) {
    const ActuatorCatalog& catalog = *spec_.actuator_catalog;
    if (catalog.entries.empty())
      throw std::invalid_argument(
          fmt::format("{}: actuator catalog '{}': expected at least one linear "
                      "entry, found none",
                      where, catalog.name));
    std::string problem = check_actuator_catalog(catalog);
    if (problem.empty()) problem = actuator_metric_mismatch(needed_, spec_.each_drive);
    if (problem.empty() && spec_.each_drive) problem = check_drive_pricing(catalog);
    if (!problem.empty())
      throw std::invalid_argument(
          fmt::format("{}: actuator catalog '{}': {}", where, catalog.name, problem));
    try {
      if (!spec_.each_drive) pricing_ = catalog_pricing(catalog);
    } catch (const std::invalid_argument& error) {
      throw std::invalid_argument(fmt::format("{}: {}", where, error.what()));
    }
    double longest = 0.0;
    for (const ActuatorEntry& e : catalog.entries) longest = std::max(longest, e.stroke);
    if (spec_.parameters[kStroke].upper > longest)
      throw std::invalid_argument(fmt::format(
          "{}: parameter stroke: expected an upper bound <= {} m (the longest entry of actuator "
          "catalog '{}'), found {} m",
          where, longest, catalog.name, spec_.parameters[kStroke].upper));
    needed_[static_cast<int>(DesignMetric::leg_force_max)] = true;
  } else {
    for (int m = 0; m < kNumDesignMetrics; ++m)
      if (needed_[m] && is_actuator_metric(static_cast<DesignMetric>(m)))
        throw std::invalid_argument(
            fmt::format("{}: {} needs an actuator catalog to choose from, found none", where,
                        design_metric_name(static_cast<DesignMetric>(m))));
  }
}

Bounds HexapodDesignProblem::bounds() const {
  Bounds b;
  for (int i : free_) {
    b.lower.push_back(spec_.parameters[i].lower);
    b.upper.push_back(spec_.parameters[i].upper);
  }
  for (std::size_t objective : epigraph_objectives_) {
    b.lower.push_back(0.0);
    b.upper.push_back(spec_.objectives[objective].metric == DesignMetric::leg_force_max
                          ? kEpigraphForceUpper / kEpigraphForceUnit
                          : stiffness_upper_);
  }
  return b;
}

std::array<double, kNumDesignParameters> HexapodDesignProblem::parameters_of(
    const std::vector<double>& x) const {
  if (x.size() != free_.size() + epigraph_objectives_.size())
    throw std::invalid_argument(fmt::format("{}: expected {} variables, found {}", spec_.name,
                                            free_.size() + epigraph_objectives_.size(), x.size()));
  std::array<double, kNumDesignParameters> p;
  for (int i = 0; i < kNumDesignParameters; ++i) p[i] = spec_.parameters[i].lower;
  for (std::size_t j = 0; j < free_.size(); ++j) p[free_[j]] = x[j];
  return p;
}

std::vector<double> HexapodDesignProblem::design_parameters(const std::vector<double>& x) const {
  const std::array<double, kNumDesignParameters> p = parameters_of(x);
  return {p.begin(), p.end()};
}

double HexapodDesignProblem::home_height(const std::vector<double>& parameters) const {
  return parameters.at(kHomeHeight);
}

DesignRecord HexapodDesignProblem::measure(const std::vector<double>& x) const {
  DesignEvaluation ev = evaluate(x);
  DesignRecord record;
  record.parameters.assign(ev.parameters.begin(), ev.parameters.end());
  record.home_height = ev.parameters[kHomeHeight];
  record.metrics = ev.metrics;
  record.aggregate = aggregate_fitness(ev);
  record.actuator = ev.actuator;
  if (spec_.actuator_catalog && spec_.each_drive && ev.ok())
    record.drives = drive_choice_text(*spec_.actuator_catalog, ev.drive_needs, ev.drive_choice);
  record.failure = std::move(ev.failure);
  return record;
}

HexapodDesign HexapodDesignProblem::design_of(
    const std::array<double, kNumDesignParameters>& p) const {
  return hexapod_design_of(spec_.machine_template, p);
}

HexapodDesign hexapod_design_of(const HexapodDesign& machine_template,
                                const std::array<double, kNumDesignParameters>& p) {
  HexapodDesign d = machine_template;
  d.base_joints = semi_regular_joints<double>(p[kBaseRadius], p[kBasePairSeparation], false);
  d.platform_joints =
      semi_regular_joints<double>(p[kPlatformRadius], p[kPlatformPairSeparation], true);
  d.min_length = p[kMinLength];
  d.max_length = p[kMinLength] + p[kStroke];
  return d;
}

// Reachability terms (each <= 0 when satisfied) for every pose; returns their maximum.
DesignEvaluation HexapodDesignProblem::evaluate(const std::vector<double>& x) const {
  DesignEvaluation ev;
  ev.parameters = parameters_of(x);
  const auto& p = ev.parameters;
  ev.metrics.fill(0.0);
  ev.reach_violation = reach_rows<double>(p, nullptr);
  ev.reachable = ev.reach_violation <= 0.0;
  if (!std::isfinite(ev.reach_violation)) ev.failure = "non-finite leg lengths at a task pose";
  auto metric = [&](DesignMetric m) -> double& { return ev.metrics[static_cast<int>(m)]; };
  metric(DesignMetric::machine_size) =
      std::numbers::pi * p[kBaseRadius] * p[kBaseRadius] * (p[kMinLength] + p[kStroke]);

  std::optional<Hexapod> hexapod;
  try {
    hexapod.emplace(design_of(p));
  } catch (const std::invalid_argument& error) {
    ev.failure = fmt::format("invalid machine: {}", error.what());
    return ev;
  }
  const double h = p[kHomeHeight];
  if (!spec_.task.obstacles.empty()) keep_out_of_obstacles(*hexapod, h, ev);
  measure_task_poses(*hexapod, h, ev);
  if (needed_[static_cast<int>(DesignMetric::moving_mass)]) {
    ev.metrics[static_cast<int>(DesignMetric::moving_mass)] = moving_mass(
        spec_.machine_template.masses, std::vector<LegBodyKind>(6, LegBodyKind::kTelescopic));
  }
  if (spec_.actuator_catalog) price_legs(p[kStroke], ev);
  measure_task_region(*hexapod, h, ev);
  measure_workspace_metrics(*hexapod, spec_.task.workspace, needed_, ev.metrics, ev.failure);
  check_finite_metrics(needed_, ev.metrics, ev.failure);
  if (!ev.ok()) ev.actuator = -1;
  return ev;
}

void HexapodDesignProblem::keep_out_of_obstacles(const Hexapod& hexapod, double h,
                                                 DesignEvaluation& ev) const {
  // The drawn hexapod must keep out of the obstacles: how deep it goes in (m) joins the
  // reachability terms.
  const std::unique_ptr<MachineData> sketch_data = hexapod.make_data();
  for (Pose pose : spec_.task.poses) {
    pose.position.z() += h;
    const std::optional<double> in =
        sketch_intrusion(hexapod, *sketch_data, pose, spec_.task.obstacles);
    if (in) ev.reach_violation = std::max(ev.reach_violation, *in);
  }
  ev.reachable = ev.reach_violation <= 0.0;
}

void HexapodDesignProblem::measure_task_poses(const Hexapod& hexapod, double h,
                                              DesignEvaluation& ev) const {
  auto need = [&](DesignMetric m) { return needed_[static_cast<int>(m)]; };
  const bool compliance = need(DesignMetric::tcp_deflection_max) ||
                          need(DesignMetric::stiffness_min_loaded) ||
                          need(DesignMetric::natural_frequency_min);
  const bool dynamic_force = need(DesignMetric::actuator_force_dynamic_max);
  if (!need(DesignMetric::stiffness_min) && !need(DesignMetric::singularity_margin) &&
      !need(DesignMetric::leg_force_max) && !need(DesignMetric::tcp_error_max) && !compliance &&
      !dynamic_force && !need(DesignMetric::leg_clearance_min))
    return;
  HexapodData data(hexapod);
  data.compliance_metrics = compliance;
  PoseMetrics m;
  TaskWorstCase worst;
  Eigen::VectorXd bound;
  double& force = ev.metrics[static_cast<int>(DesignMetric::actuator_force_dynamic_max)];
  for (std::size_t k = 0; k < spec_.task.poses.size(); ++k) {
    Pose pose = spec_.task.poses[k];
    pose.position.z() += h;
    hexapod.compute_metrics(data, pose, spec_.task.wrench, m);
    if (m.singular && ev.failure.empty())
      ev.failure = fmt::format("singular at task pose {} (x {:.4g}, y {:.4g}, z {:.4g} m)", k,
                               pose.position.x(), pose.position.y(), pose.position.z());
    worst.add(m);
    if (dynamic_force) {
      if (acceleration_force_bound(hexapod, data, pose, spec_.task.wrench,
                                   spec_.task.acceleration_max, bound)) {
        force = std::max(force, bound.maxCoeff());
      } else {
        force = std::numeric_limits<double>::infinity();  // singular: check_finite_metrics
      }
    }
  }
  worst.store(ev.metrics);
}

void HexapodDesignProblem::price_legs(double stroke, DesignEvaluation& ev) const {
  auto metric = [&](DesignMetric m) -> double& { return ev.metrics[static_cast<int>(m)]; };
  const ActuatorCatalog& catalog = *spec_.actuator_catalog;
  // The cutting load against the continuous rating; with a_max, the accelerated task's force
  // against the peak rating too.
  const bool dynamic_force = needed_[static_cast<int>(DesignMetric::actuator_force_dynamic_max)];
  const ActuatorRequirement need{
      .force = metric(DesignMetric::leg_force_max),
      .stroke = stroke,
      .peak_force = dynamic_force ? metric(DesignMetric::actuator_force_dynamic_max) : 0.0};
  if (spec_.each_drive) {
    ev.drive_needs = {{.count = 6,
                       .force = need.force,
                       .peak_force = need.peak_force,
                       .stroke = need.stroke,
                       .drives = {0, 1, 2, 3, 4, 5}}};
    ev.drive_choice = choose_drives(catalog, ev.drive_needs);
    metric(DesignMetric::drive_cost) = ev.drive_choice.cost;
    metric(DesignMetric::drive_overload) = ev.drive_choice.overload;
    return;
  }
  const StudyActuatorChoice choice = study_actuator_choice(catalog, pricing_, need);
  ev.actuator = choice.entry;
  metric(DesignMetric::actuator_cost) = choice.cost;
  metric(DesignMetric::actuator_overload) = choice.overload;
}

void HexapodDesignProblem::measure_task_region(const Hexapod& hexapod, double h,
                                               DesignEvaluation& ev) const {
  auto need = [&](DesignMetric m) { return needed_[static_cast<int>(m)]; };
  auto metric = [&](DesignMetric m) -> double& { return ev.metrics[static_cast<int>(m)]; };
  if (need(DesignMetric::task_singularity_free)) {
    PoseBox region = *spec_.task.region;  // check_design_goals: present when needed
    region.position_lo.z() += h;
    region.position_hi.z() += h;
    metric(DesignMetric::task_singularity_free) = singularity_free_share(hexapod, region);
  }
  if (!need(DesignMetric::swept_volume) && !need(DesignMetric::footprint) &&
      !need(DesignMetric::task_margin))
    return;
  std::vector<Pose> poses = spec_.task.poses;
  for (Pose& pose : poses) pose.position.z() += h;
  if (need(DesignMetric::swept_volume) || need(DesignMetric::footprint)) {
    const SweptEnvelope envelope = swept_envelope(hexapod, poses);
    metric(DesignMetric::swept_volume) = envelope.volume;
    metric(DesignMetric::footprint) = envelope.footprint;
  }
  if (need(DesignMetric::task_margin))
    metric(DesignMetric::task_margin) =
        task_margin(hexapod, poses, task_margin_limit(spec_.task.poses));
}

std::vector<double> HexapodDesignProblem::aggregate_fitness(const DesignEvaluation& ev) const {
  return aggregate_design_rows(spec_.objectives, spec_.constraints, spec_.require_reachable,
                               ev.metrics, ev.reach_violation, !ev.ok());
}

std::vector<double> HexapodDesignProblem::fitness(const std::vector<double>& x) const {
  if (spec_.formulation == DesignFormulation::aggregate) return aggregate_fitness(evaluate(x));
  const std::array<double, kNumDesignParameters> p = parameters_of(x);
  const std::vector<double> epigraph(x.begin() + static_cast<std::ptrdiff_t>(free_.size()),
                                     x.end());
  std::vector<double> rows;
  smooth_rows<double>(p, epigraph, rows);
  for (double& v : rows)
    if (!std::isfinite(v)) v = kFailurePenalty;
  return rows;
}

}  // namespace pkmopt
