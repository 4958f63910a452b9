#include "problems/design/hexapod_design.hpp"

#include <ceres/jet.h>
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
#include "models/hexapod/swept_envelope.hpp"
#include "models/sample_machines.hpp"
#include "models/workspace/mode_certificate.hpp"

namespace pkmopt {
namespace {

constexpr std::array<std::string_view, kNumDesignParameters> kParameterNames = {
    "base_radius",
    "platform_radius",
    "base_pair_separation_deg",
    "platform_pair_separation_deg",
    "min_length",
    "stroke",
    "home_height"};

// Derivatives with respect to the 7 parameters, then the (at most 2) epigraph variables.
constexpr int kMaxEpigraph = 2;
using DesignJet = ceres::Jet<double, kNumDesignParameters + kMaxEpigraph>;

// Semi-regular joints (docs/conventions.md) for any scalar type.
template <typename T>
Eigen::Matrix<T, 3, 6> semi_regular_joints(const T& radius, const T& separation, bool platform) {
  using std::cos;
  using std::sin;
  Eigen::Matrix<T, 3, 6> joints;
  for (int i = 0; i < 6; ++i) {
    const double k120 = 120.0 * kDegToRad * (i / 2);
    const bool even = i % 2 == 0;
    T angle;
    if (!platform) {
      angle = even ? T(k120) - separation / 2.0 : T(k120) + separation / 2.0;
    } else {
      angle = even ? T(k120 - 60.0 * kDegToRad) + separation / 2.0
                   : T(k120 + 60.0 * kDegToRad) - separation / 2.0;
    }
    joints(0, i) = radius * cos(angle);
    joints(1, i) = radius * sin(angle);
    joints(2, i) = T(0.0);
  }
  return joints;
}

double metric_sign(Sense sense) { return sense == Sense::maximize ? -1.0 : 1.0; }

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
          fmt::format("{}: actuator catalog '{}': expected at least one "
                      "entry, found none",
                      where, catalog.name));
    const std::string problem = check_actuator_catalog(catalog);
    if (!problem.empty())
      throw std::invalid_argument(
          fmt::format("{}: actuator catalog '{}': {}", where, catalog.name, problem));
    try {
      pricing_ = catalog_pricing(catalog);
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

// The rows of the smooth formulation (Ipopt, NLopt): epigraph variables of the objectives that
// have one, the rows of each constraint, the reach rows, and the bound of the stiffness epigraph
// variable. Goals without a smooth form are refused.
void HexapodDesignProblem::set_up_smooth_formulation(const std::string& where) {
  const std::size_t poses = spec_.task.poses.size();
  const HexapodJointLimits& limits = spec_.machine_template.joints;
  const std::size_t reach_per_pose = 12 + (std::isfinite(limits.base_max_angle) ? 6 : 0) +
                                     (std::isfinite(limits.platform_max_angle) ? 6 : 0);
  if ((spec_.machine_template.leg_shape.present() || spec_.task.installation_space.present()) &&
      spec_.require_reachable)
    throw std::invalid_argument(fmt::format(
        "{}: the legs' interference (machine.legs.diameter, cylinder, rod) and the task's "
        "installation_space have no smooth formulation; use an evolutionary optimizer "
        "(aggregate formulation)",
        where));
  if (spec_.task.acceleration_max > 0.0)
    throw std::invalid_argument(fmt::format(
        "{}: task a_max has no smooth formulation (the inertia forces are not in the smooth "
        "rows); use an evolutionary optimizer (aggregate formulation)",
        where));
  for (std::size_t k = 0; k < spec_.objectives.size(); ++k) {
    const DesignObjective& o = spec_.objectives[k];
    if (o.metric == DesignMetric::leg_force_max && o.sense == Sense::minimize) {
      epigraph_objectives_.push_back(k);
      num_inequality_ += 12 * poses;
    } else if (o.metric == DesignMetric::stiffness_min && o.sense == Sense::maximize) {
      epigraph_objectives_.push_back(k);
      num_inequality_ += kStiffnessRowsPerPose * poses;
    } else if (o.metric != DesignMetric::machine_size) {
      throw std::invalid_argument(fmt::format(
          "{}: objective {} {} has no smooth formulation (smooth: minimize leg_force_max, "
          "maximize stiffness_min, machine_size); use an evolutionary optimizer (aggregate "
          "formulation)",
          where, o.sense == Sense::minimize ? "minimize" : "maximize",
          design_metric_name(o.metric)));
    }
  }
  for (std::size_t a = 0; a < epigraph_objectives_.size(); ++a)
    for (std::size_t b = 0; b < a; ++b)
      if (spec_.objectives[epigraph_objectives_[a]].metric ==
          spec_.objectives[epigraph_objectives_[b]].metric)
        throw std::invalid_argument(
            fmt::format("{}: objective {} is listed twice", where,
                        design_metric_name(spec_.objectives[epigraph_objectives_[a]].metric)));
  num_inequality_ += smooth_constraint_rows(where, poses);
  // Upper bound of the stiffness epigraph variable: stiffness_min <= lambda_max(K_tt) <=
  // sum k_i <= 6 k(q) at the shortest leg a reachable design can have.
  const LegStiffness& k = spec_.machine_template.stiffness;
  const double q_short = std::max(spec_.parameters[kMinLength].lower, 1e-3);
  double compliance = k.axial_stiffness > 0.0 ? 1.0 / k.axial_stiffness : q_short / (k.E * k.area);
  if (k.actuator_stiffness > 0.0) compliance += 1.0 / k.actuator_stiffness;
  stiffness_upper_ = 6.0 / compliance / kEpigraphStiffnessUnit;
  if (!std::isfinite(stiffness_upper_) || stiffness_upper_ <= 0.0) stiffness_upper_ = 1e6;
  if (spec_.require_reachable) num_inequality_ += reach_per_pose * poses;
}

// The rows of the constraints in the smooth formulation; a constraint without a smooth form is
// refused.
std::size_t HexapodDesignProblem::smooth_constraint_rows(const std::string& where,
                                                         std::size_t poses) const {
  std::size_t rows = 0;
  for (const DesignConstraint& c : spec_.constraints) {
    if (c.metric == DesignMetric::leg_force_max && c.relation == Relation::less_equal) {
      rows += 12 * poses;
    } else if (c.metric == DesignMetric::stiffness_min && c.relation == Relation::greater_equal) {
      rows += kStiffnessRowsPerPose * poses;
    } else if (c.metric == DesignMetric::machine_size) {
      rows += 1;
    } else if (c.metric == DesignMetric::actuator_overload && c.relation == Relation::less_equal) {
      if (!spec_.parameters[kStroke].fixed())
        throw std::invalid_argument(fmt::format(
            "{}: constraint actuator_overload <= has a smooth formulation only with a fixed "
            "stroke (the catalog's force capacity jumps where the stroke passes an entry's); "
            "fix the stroke or use an evolutionary optimizer (aggregate formulation)",
            where));
      rows += 12 * poses;
    } else {
      throw std::invalid_argument(fmt::format(
          "{}: constraint {} {} has no smooth formulation (smooth: leg_force_max <=, "
          "stiffness_min >=, machine_size <= or >=); use an evolutionary optimizer (aggregate "
          "formulation)",
          where, design_metric_name(c.metric), c.relation == Relation::less_equal ? "<=" : ">="));
    }
  }
  return rows;
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
template <typename T>
T HexapodDesignProblem::reach_rows(const std::array<T, kNumDesignParameters>& p,
                                   std::vector<T>* rows) const {
  const HexapodDesign& tmpl = spec_.machine_template;
  const Eigen::Matrix<T, 3, 6> base =
      semi_regular_joints<T>(p[kBaseRadius], p[kBasePairSeparation], false);
  Eigen::Matrix<T, 3, 6> platform_rel =
      semi_regular_joints<T>(p[kPlatformRadius], p[kPlatformPairSeparation], true);
  for (int i = 0; i < 6; ++i)
    for (int a = 0; a < 3; ++a) platform_rel(a, i) -= tmpl.tcp(a);
  const T max_length = p[kMinLength] + p[kStroke];
  const bool base_limit = std::isfinite(tmpl.joints.base_max_angle);
  const bool platform_limit = std::isfinite(tmpl.joints.platform_max_angle);
  const double cos_base = std::cos(tmpl.joints.base_max_angle);
  const double cos_platform = std::cos(tmpl.joints.platform_max_angle);
  T worst = T(-std::numeric_limits<double>::infinity());
  auto add = [&](const T& value) {
    if (rows) rows->push_back(value);
    if (value > worst) worst = value;
  };
  for (const Pose& pose : spec_.task.poses) {
    Vec3<T> position = pose.position.cast<T>();
    position(2) += p[kHomeHeight];
    const Vec3<T> angles = pose.angles.cast<T>();
    Vec6<T> q;
    Eigen::Matrix<T, 3, 6> s;
    hexapod_legs<T>(base, platform_rel, position, angles, &q, nullptr, &s);
    for (int i = 0; i < 6; ++i) add(p[kMinLength] - q(i));
    for (int i = 0; i < 6; ++i) add(q(i) - max_length);
    if (base_limit)
      for (int i = 0; i < 6; ++i) add(T(cos_base) - s.col(i).dot(tmpl.joints.base_axis.cast<T>()));
    if (platform_limit) {
      const Vec3<double> n = rotation_zyx<double>(pose.angles) * tmpl.joints.platform_axis;
      for (int i = 0; i < 6; ++i) add(T(cos_platform) + s.col(i).dot(n.cast<T>()));
    }
    // The legs' interference: min_clearance - clearance (m) over the pose's leg pairs; the
    // installation space: how far the legs (with their shape), the base or the platform joints
    // stick out (m). Only in the aggregate formulation (the smooth one refuses both).
    if constexpr (std::is_same_v<T, double>) {
      const InstallationSpace& space = spec_.task.installation_space;
      if (tmpl.leg_shape.present() || space.present()) {
        const Eigen::Matrix3d R = rotation_zyx<double>(pose.angles);
        const Eigen::Vector3d origin = position - R * tmpl.tcp;  // the platform frame's
        Capsule bodies[12];
        int n = 0;
        for (int i = 0; i < 6; ++i) {
          const Eigen::Vector3d a = base.col(i), p_i = a + q(i) * s.col(i);
          const int added = leg_bodies(tmpl.leg_shape, a, p_i, i, bodies + n);
          if (added == 0)
            bodies[n++] = {a, p_i, 0.0, i, true, true};  // a line leg
          else
            n += added;
        }
        const std::span<const Capsule> legs(bodies, static_cast<std::size_t>(n));
        if (tmpl.leg_shape.present()) {
          Clearance c = leg_clearance(legs);
          if (tmpl.bodies.present()) {
            body_clearance(legs, tmpl.bodies, R, origin, c);
          }
          add(tmpl.min_clearance - c.value);
        }
        if (space.present()) {
          double excess = -std::numeric_limits<double>::infinity();
          for (const Capsule& body : legs) excess = std::max(excess, space.excess(body));
          // The solids' outlines (the plates and the tool hold their circumscribed 32-gons).
          if (tmpl.bodies.present()) {
            std::vector<Eigen::Vector3d> outline;
            solid_outline_points(tmpl.bodies, R, origin, outline);
            for (const Eigen::Vector3d& x : outline)
              excess = std::max(excess, space.excess(x, 0.0));
          }
          add(excess);  // the legs' ends include every base and platform joint
        }
      }
    }
  }
  return worst;
}

template <typename T>
void HexapodDesignProblem::smooth_rows(const std::array<T, kNumDesignParameters>& p,
                                       const std::vector<T>& epigraph, std::vector<T>& rows) const {
  rows.clear();
  const T machine_size =
      T(std::numbers::pi) * p[kBaseRadius] * p[kBaseRadius] * (p[kMinLength] + p[kStroke]);
  std::size_t e = 0;
  for (const DesignObjective& o : spec_.objectives) {
    if (o.metric == DesignMetric::machine_size)
      rows.push_back(metric_sign(o.sense) * machine_size);
    else if (o.metric == DesignMetric::leg_force_max)
      rows.push_back(epigraph[e++] * kEpigraphForceUnit);  // N
    else
      rows.push_back(-epigraph[e++] * kEpigraphStiffnessUnit);  // -stiffness bound, N/m
  }
  // Statics at every pose from one LU of J^T: tau = J^-T w and P^T = J^-T [e_1 e_2 e_3], the
  // translational rows of J^-1, so C_tt = P diag(1/k) P^T (as Hexapod::compute_metrics).
  bool need_tau = false, need_compliance = false;
  for (std::size_t objective : epigraph_objectives_) {
    need_tau = need_tau || spec_.objectives[objective].metric == DesignMetric::leg_force_max;
    need_compliance =
        need_compliance || spec_.objectives[objective].metric == DesignMetric::stiffness_min;
  }
  for (const DesignConstraint& c : spec_.constraints) {
    need_tau = need_tau || c.metric == DesignMetric::leg_force_max ||
               c.metric == DesignMetric::actuator_overload;
    need_compliance = need_compliance || c.metric == DesignMetric::stiffness_min;
  }
  std::vector<Vec6<T>> tau;
  std::vector<Mat3<T>> compliance_tt;
  if (need_tau || need_compliance) {
    const Eigen::Matrix<T, 3, 6> base =
        semi_regular_joints<T>(p[kBaseRadius], p[kBasePairSeparation], false);
    Eigen::Matrix<T, 3, 6> platform_rel =
        semi_regular_joints<T>(p[kPlatformRadius], p[kPlatformPairSeparation], true);
    for (int i = 0; i < 6; ++i)
      for (int a = 0; a < 3; ++a) platform_rel(a, i) -= spec_.machine_template.tcp(a);
    Eigen::Matrix<T, 6, 4> rhs = Eigen::Matrix<T, 6, 4>::Zero();
    rhs(0, 0) = rhs(1, 1) = rhs(2, 2) = T(1.0);
    rhs.col(3) = spec_.task.wrench.cast<T>();
    const LegStiffness& k = spec_.machine_template.stiffness;
    for (const Pose& pose : spec_.task.poses) {
      Vec3<T> position = pose.position.cast<T>();
      position(2) += p[kHomeHeight];
      Vec6<T> q;
      Mat6<T> J;
      hexapod_legs<T>(base, platform_rel, position, pose.angles.cast<T>(), &q, &J);
      const Eigen::Matrix<T, 6, 4> solution =
          Eigen::PartialPivLU<Mat6<T>>(J.transpose()).solve(rhs);
      if (need_tau) tau.push_back(solution.col(3));
      if (need_compliance) {
        Mat3<T> ctt;
        for (int a = 0; a < 3; ++a)
          for (int b = 0; b <= a; ++b) {
            T sum(0.0);
            for (int i = 0; i < 6; ++i) {
              T leg = k.axial_stiffness > 0.0 ? T(1.0 / k.axial_stiffness) : q(i) / (k.E * k.area);
              if (k.actuator_stiffness > 0.0) leg += 1.0 / k.actuator_stiffness;
              sum += solution(i, a) * leg * solution(i, b);
            }
            ctt(a, b) = ctt(b, a) = sum;
          }
        compliance_tt.push_back(ctt);
      }
    }
  }
  // Force rows in kN: (+-tau_i - limit) / kEpigraphForceUnit.
  auto add_force_rows = [&](const T& limit) {
    for (const Vec6<T>& t : tau)
      for (int i = 0; i < 6; ++i) {
        rows.push_back((t(i) - limit) / kEpigraphForceUnit);
        rows.push_back((-t(i) - limit) / kEpigraphForceUnit);
      }
  };
  // stiffness_min >= s  <=>  lambda_max(C_tt) <= 1/s  <=>  M = I - s C_tt is positive
  // semidefinite  <=>  its 7 principal minors are >= 0: rows -minor <= 0 (dimensionless).
  auto add_stiffness_rows = [&](const T& stiffness) {
    for (const Mat3<T>& c : compliance_tt) {
      const Mat3<T> m = Mat3<T>::Identity() - stiffness * c;
      rows.push_back(-m(0, 0));
      rows.push_back(-m(1, 1));
      rows.push_back(-m(2, 2));
      rows.push_back(-(m(0, 0) * m(1, 1) - m(0, 1) * m(1, 0)));
      rows.push_back(-(m(0, 0) * m(2, 2) - m(0, 2) * m(2, 0)));
      rows.push_back(-(m(1, 1) * m(2, 2) - m(1, 2) * m(2, 1)));
      rows.push_back(-(m(0, 0) * (m(1, 1) * m(2, 2) - m(1, 2) * m(2, 1)) -
                       m(0, 1) * (m(1, 0) * m(2, 2) - m(1, 2) * m(2, 0)) +
                       m(0, 2) * (m(1, 0) * m(2, 1) - m(1, 1) * m(2, 0))));
    }
  };
  for (std::size_t k = 0; k < epigraph_objectives_.size(); ++k) {
    if (spec_.objectives[epigraph_objectives_[k]].metric == DesignMetric::leg_force_max)
      add_force_rows(epigraph[k] * kEpigraphForceUnit);
    else
      add_stiffness_rows(epigraph[k] * kEpigraphStiffnessUnit);
  }
  for (const DesignConstraint& c : spec_.constraints) {
    if (c.metric == DesignMetric::leg_force_max) {
      add_force_rows(T(c.bound));
    } else if (c.metric == DesignMetric::stiffness_min) {
      add_stiffness_rows(T(c.bound));
    } else if (c.metric == DesignMetric::actuator_overload) {  // fixed stroke: a constant capacity
      add_force_rows(T(c.bound + actuator_force_capacity(*spec_.actuator_catalog,
                                                         spec_.parameters[kStroke].lower)));
    } else {  // machine_size
      rows.push_back(c.relation == Relation::less_equal ? machine_size - c.bound
                                                        : T(c.bound) - machine_size);
    }
  }
  if (spec_.require_reachable) reach_rows<T>(p, &rows);
  // Tighten every inequality row by kSmoothRowMargin (rows are O(1)), so that a point a solver
  // accepts within its constraint tolerance passes the strict aggregate check g <= 0.
  for (std::size_t r = spec_.objectives.size(); r < rows.size(); ++r) rows[r] += kSmoothRowMargin;
}

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
  auto need = [&](DesignMetric m) { return needed_[static_cast<int>(m)]; };
  const bool compliance = need(DesignMetric::tcp_deflection_max) ||
                          need(DesignMetric::stiffness_min_loaded) ||
                          need(DesignMetric::natural_frequency_min);
  const bool dynamic_force = need(DesignMetric::actuator_force_dynamic_max);
  if (need(DesignMetric::stiffness_min) || need(DesignMetric::singularity_margin) ||
      need(DesignMetric::leg_force_max) || need(DesignMetric::tcp_error_max) || compliance ||
      dynamic_force || need(DesignMetric::leg_clearance_min)) {
    HexapodData data(*hexapod);
    data.compliance_metrics = compliance;
    PoseMetrics m;
    TaskWorstCase worst;
    Eigen::VectorXd bound;
    for (std::size_t k = 0; k < spec_.task.poses.size(); ++k) {
      Pose pose = spec_.task.poses[k];
      pose.position.z() += p[kHomeHeight];
      hexapod->compute_metrics(data, pose, spec_.task.wrench, m);
      if (m.singular && ev.failure.empty())
        ev.failure = fmt::format("singular at task pose {} (x {:.4g}, y {:.4g}, z {:.4g} m)", k,
                                 pose.position.x(), pose.position.y(), pose.position.z());
      worst.add(m);
      if (dynamic_force) {
        double& force = metric(DesignMetric::actuator_force_dynamic_max);
        if (acceleration_force_bound(*hexapod, data, pose, spec_.task.wrench,
                                     spec_.task.acceleration_max, bound)) {
          force = std::max(force, bound.maxCoeff());
        } else {
          force = std::numeric_limits<double>::infinity();  // singular: check_finite_metrics
        }
      }
    }
    worst.store(ev.metrics);
  }
  if (need(DesignMetric::moving_mass)) {
    ev.metrics[static_cast<int>(DesignMetric::moving_mass)] = moving_mass(
        spec_.machine_template.masses, std::vector<LegBodyKind>(6, LegBodyKind::kTelescopic));
  }
  if (spec_.actuator_catalog) {
    const ActuatorCatalog& catalog = *spec_.actuator_catalog;
    // The cutting load against the continuous rating; with a_max, the accelerated task's force
    // against the peak rating too.
    const ActuatorRequirement need{
        .force = metric(DesignMetric::leg_force_max),
        .stroke = p[kStroke],
        .peak_force = dynamic_force ? metric(DesignMetric::actuator_force_dynamic_max) : 0.0};
    const StudyActuatorChoice choice = study_actuator_choice(catalog, pricing_, need);
    ev.actuator = choice.entry;
    metric(DesignMetric::actuator_cost) = choice.cost;
    metric(DesignMetric::actuator_overload) = choice.overload;
  }
  if (need(DesignMetric::task_singularity_free)) {
    PoseBox region = *spec_.task.region;  // check_design_goals: present when needed
    region.position_lo.z() += p[kHomeHeight];
    region.position_hi.z() += p[kHomeHeight];
    metric(DesignMetric::task_singularity_free) = singularity_free_share(*hexapod, region);
  }
  if (need(DesignMetric::swept_volume) || need(DesignMetric::footprint) ||
      need(DesignMetric::task_margin)) {
    std::vector<Pose> poses = spec_.task.poses;
    for (Pose& pose : poses) pose.position.z() += p[kHomeHeight];
    if (need(DesignMetric::swept_volume) || need(DesignMetric::footprint)) {
      const SweptEnvelope envelope = swept_envelope(*hexapod, poses);
      metric(DesignMetric::swept_volume) = envelope.volume;
      metric(DesignMetric::footprint) = envelope.footprint;
    }
    if (need(DesignMetric::task_margin))
      metric(DesignMetric::task_margin) =
          task_margin(*hexapod, poses, task_margin_limit(spec_.task.poses));
  }
  measure_workspace_metrics(*hexapod, spec_.task.workspace, needed_, ev.metrics, ev.failure);
  check_finite_metrics(needed_, ev.metrics, ev.failure);
  if (!ev.ok()) ev.actuator = -1;
  return ev;
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

std::vector<double> HexapodDesignProblem::gradient(const std::vector<double>& x) const {
  if (spec_.formulation != DesignFormulation::smooth)
    throw std::logic_error(spec_.name + ": the aggregate formulation has no gradient");
  const std::array<double, kNumDesignParameters> p = parameters_of(x);
  std::array<DesignJet, kNumDesignParameters> pj;
  for (int i = 0; i < kNumDesignParameters; ++i) pj[i] = DesignJet(p[i], i);
  const std::size_t n_free = free_.size();
  const std::size_t n = n_free + epigraph_objectives_.size();
  std::vector<DesignJet> epigraph;
  for (std::size_t e = 0; e < epigraph_objectives_.size(); ++e)
    epigraph.emplace_back(x[n_free + e], kNumDesignParameters + static_cast<int>(e));
  std::vector<DesignJet> rows;
  smooth_rows<DesignJet>(pj, epigraph, rows);
  std::vector<double> jacobian(rows.size() * n, 0.0);
  for (std::size_t r = 0; r < rows.size(); ++r) {
    for (std::size_t j = 0; j < n_free; ++j) {
      const double v = rows[r].v(free_[j]);
      jacobian[r * n + j] = std::isfinite(v) ? v : 0.0;
    }
    for (std::size_t e = 0; e < epigraph_objectives_.size(); ++e) {
      const double v = rows[r].v(kNumDesignParameters + static_cast<int>(e));
      jacobian[r * n + n_free + e] = std::isfinite(v) ? v : 0.0;
    }
  }
  return jacobian;
}

}  // namespace pkmopt
