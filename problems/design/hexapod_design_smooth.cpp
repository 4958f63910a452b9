// The smooth formulation of the hexapod design problem (problems/design/hexapod_design.hpp): its
// rows (epigraph objectives, constraints, reach rows) for any scalar type, and their gradient by
// forward-mode automatic differentiation (ceres::Jet).
#include <ceres/jet.h>
#include <fmt/format.h>

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <type_traits>

#include "models/hexapod/swept_envelope.hpp"
#include "problems/design/hexapod_design.hpp"
#include "problems/design/hexapod_design_detail.hpp"

namespace pkmopt {

using hexapod_design_detail::semi_regular_joints;

namespace {

// Derivatives with respect to the 7 parameters, then the (at most 2) epigraph variables.
constexpr int kMaxEpigraph = 2;
using DesignJet = ceres::Jet<double, kNumDesignParameters + kMaxEpigraph>;

double metric_sign(Sense sense) { return sense == Sense::maximize ? -1.0 : 1.0; }

}  // namespace

// The rows of the smooth formulation (Ipopt, NLopt): epigraph variables of the objectives that
// have one, the rows of each constraint, the reach rows, and the bound of the stiffness epigraph
// variable. Goals without a smooth form are refused.
void HexapodDesignProblem::set_up_smooth_formulation(const std::string& where) {
  const std::size_t poses = spec_.task.poses.size();
  const HexapodJointLimits& limits = spec_.machine_template.joints;
  const std::size_t reach_per_pose = 12 + (std::isfinite(limits.base_max_angle) ? 6 : 0) +
                                     (std::isfinite(limits.platform_max_angle) ? 6 : 0);
  if ((spec_.machine_template.leg_shape.present() || spec_.task.installation_space.present() ||
       !spec_.task.obstacles.empty()) &&
      spec_.require_reachable)
    throw std::invalid_argument(fmt::format(
        "{}: the legs' interference (machine.legs.diameter, cylinder, rod) and the task's "
        "installation_space and obstacles have no smooth formulation; use an evolutionary "
        "optimizer (aggregate formulation)",
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

// In doubles, for fitness and the aggregate formulation's reach violation.
template double HexapodDesignProblem::reach_rows<double>(
    const std::array<double, kNumDesignParameters>& p, std::vector<double>* rows) const;
template void HexapodDesignProblem::smooth_rows<double>(
    const std::array<double, kNumDesignParameters>& p, const std::vector<double>& epigraph,
    std::vector<double>& rows) const;

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
