#include "models/workspace/mode_certificate.hpp"

#include <fmt/format.h>

#include <Eigen/LU>
#include <algorithm>
#include <deque>
#include <numbers>
#include <stdexcept>

namespace pkmopt {
namespace {

using Matrix6 = Eigen::Matrix<double, 6, 6>;

// ||M||_inf, rounded up.
double inf_norm(const Matrix6& M) {
  double largest = 0.0;
  for (int r = 0; r < 6; ++r) {
    Interval sum = 0.0;
    for (int c = 0; c < 6; ++c) sum += Interval(std::abs(M(r, c)));
    largest = std::max(largest, sum.hi);
  }
  return largest;
}

Matrix6 midpoint(const IntervalJacobian& J) {
  Matrix6 M;
  for (int r = 0; r < 6; ++r)
    for (int c = 0; c < 6; ++c) M(r, c) = J[r][c].mid();
  return M;
}

// The outcome of one box.
struct Proof {
  bool regular = false;
  int sign = 0;
  double margin = 0.0;         // certified lower bound (when regular)
  double centre_margin = 0.0;  // 1 / ||J_c(x_mid)^-1||_inf (when regular)
};

// The centre of a box, as a box of one pose.
PoseBox centre_of(const PoseBox& b) {
  PoseBox c = b;
  c.position_lo = c.position_hi = 0.5 * (b.position_lo + b.position_hi);
  c.theta = b.theta.mid();
  c.phi = b.phi.mid();
  c.gamma = b.gamma.mid();
  return c;
}

// The box's coordinates minus the centre's, as intervals (p_x, p_y, p_z, theta, phi, gamma).
std::array<Interval, 6> offsets(const PoseBox& b, const PoseBox& c) {
  std::array<Interval, 6> d;
  for (int k = 0; k < 3; ++k)
    d[k] = Interval(b.position_lo(k), b.position_hi(k)) - Interval(c.position_lo(k));
  d[3] = b.theta - Interval(c.theta.lo);
  d[4] = b.phi - Interval(c.phi.lo);
  d[5] = b.gamma - Interval(c.gamma.lo);
  return d;
}

// Regularity of every J_c over `box`: E = I - C J_c(x) for all x in the box is enclosed twice,
// by the interval matrix of the box (C [J]) and by the mean-value form (C J_c(x_mid) + sum_k
// (C slopes_k) (X_k - x_mid,k)); both hold every E_x, so their intersection does.
Proof prove(const JacobianEnclosure& enclosure, const PoseBox& box) {
  Proof proof;
  IntervalJacobian J, Jc;
  IntervalJacobianSlopes slopes;
  const PoseBox centre = centre_of(box);
  if (!enclosure.enclose_jacobian(box, J, &slopes) || !enclosure.enclose_jacobian(centre, Jc))
    return proof;
  const Matrix6 mid = midpoint(Jc);
  if (!mid.allFinite()) return proof;
  const Eigen::FullPivLU<Matrix6> lu(mid);
  if (!lu.isInvertible()) return proof;
  const Matrix6 C = lu.inverse();
  if (!C.allFinite()) return proof;
  const std::array<Interval, 6> d = offsets(box, centre);
  double beta = 0.0;
  for (int r = 0; r < 6; ++r) {
    Interval row = 0.0;
    for (int c = 0; c < 6; ++c) {
      const Interval identity(r == c ? 1.0 : 0.0);
      Interval naive = identity, mean_value = identity;
      for (int j = 0; j < 6; ++j) {
        naive -= Interval(C(r, j)) * J[j][c];
        mean_value -= Interval(C(r, j)) * Jc[j][c];
      }
      for (int k = 0; k < 6; ++k) {
        if (d[k].lo == 0.0 && d[k].hi == 0.0) continue;
        Interval slope = 0.0;
        for (int j = 0; j < 6; ++j) slope += Interval(C(r, j)) * slopes[k][j][c];
        mean_value -= slope * d[k];
      }
      const Interval e{std::max(naive.lo, mean_value.lo), std::min(naive.hi, mean_value.hi)};
      row += Interval(e.magnitude());
    }
    beta = std::max(beta, row.hi);
  }
  if (!(beta < 1.0)) return proof;
  proof.regular = true;
  proof.sign = lu.determinant() > 0.0 ? 1 : -1;
  // (1 - beta) rounded down over ||C|| rounded up, rounded down.
  const Interval margin = (Interval(1.0) - Interval(beta)) / Interval(inf_norm(C));
  proof.margin = std::max(0.0, margin.lo);
  proof.centre_margin = 1.0 / inf_norm(C);
  return proof;
}

// The sides of a box in metres (angles times rho; phi times rho sin theta, how far it moves the
// tool axis).
std::array<double, 6> sides(const PoseBox& b, double rho) {
  const double reach = std::sin(std::min(b.theta.hi, std::numbers::pi / 2.0));
  return {b.position_hi(0) - b.position_lo(0), b.position_hi(1) - b.position_lo(1),
          b.position_hi(2) - b.position_lo(2), rho * b.theta.width(),
          rho * reach * b.phi.width(),         rho * b.gamma.width()};
}

// The measure of a box: the product of its non-zero sides (m^k), for the fractions.
double measure(const PoseBox& b, double rho, const std::array<bool, 6>& used) {
  const auto s = sides(b, rho);
  double m = 1.0;
  for (int k = 0; k < 6; ++k)
    if (used[k]) m *= std::max(s[k], 0.0);
  return m;
}

std::pair<PoseBox, PoseBox> split(const PoseBox& b, int side) {
  PoseBox lo = b, hi = b;
  if (side < 3) {
    const double m = 0.5 * (b.position_lo(side) + b.position_hi(side));
    lo.position_hi(side) = m;
    hi.position_lo(side) = m;
  } else {
    Interval PoseBox::*member = side == 3   ? &PoseBox::theta
                                : side == 4 ? &PoseBox::phi
                                            : &PoseBox::gamma;
    const double m = (b.*member).mid();
    (lo.*member).hi = m;
    (hi.*member).lo = m;
  }
  return {lo, hi};
}

// What one first box of the region gives.
struct Part {
  std::int64_t positive = 0, negative = 0, evaluations = 0;
  double positive_measure = 0.0, negative_measure = 0.0, uncertified_measure = 0.0;
  double min_margin = INFINITY, min_centre_margin = INFINITY;
  UncertifiedBox uncertified;  // of the first box
  std::vector<UncertifiedBox> parts;
};

Part certify_box(const JacobianEnclosure& enclosure, const PoseBox& first,
                 const CertifyOptions& options, std::int64_t budget,
                 const std::array<bool, 6>& used) {
  const double rho = enclosure.enclosure_length();
  Part part;
  part.uncertified.box = first;
  // Breadth first: when the budget runs out, what is proved is spread over the whole box.
  std::deque<PoseBox> queue{first};
  while (!queue.empty()) {
    const PoseBox box = queue.front();
    queue.pop_front();
    const auto s = sides(box, rho);
    const double widest = *std::max_element(s.begin(), s.end());
    const bool out_of_budget = part.evaluations >= budget;
    Proof proof;
    if (!out_of_budget) {
      ++part.evaluations;
      proof = prove(enclosure, box);
    }
    if (proof.regular && proof.margin >= options.min_margin) {
      (proof.sign > 0 ? part.positive : part.negative) += 1;
      (proof.sign > 0 ? part.positive_measure : part.negative_measure) += measure(box, rho, used);
      part.min_margin = std::min(part.min_margin, proof.margin);
      part.min_centre_margin = std::min(part.min_centre_margin, proof.centre_margin);
      continue;
    }
    if (out_of_budget || widest < options.min_size) {
      const auto [margin, sign] = pose_margin(enclosure, centre_of(box));
      UncertifiedBox& u = part.uncertified;
      u.parts += 1;
      u.budget = u.budget || out_of_budget;
      if (margin < u.centre_margin) {
        u.centre_margin = margin;
        u.centre_sign = sign;
      }
      if (options.keep_parts) part.parts.push_back({box, 1, 1.0, margin, sign, out_of_budget});
      part.uncertified_measure += measure(box, rho, used);
      continue;
    }
    const int side = static_cast<int>(std::max_element(s.begin(), s.end()) - s.begin());
    const auto [lo, hi] = split(box, side);
    queue.push_back(lo);
    queue.push_back(hi);
  }
  return part;
}

void check_region(const std::vector<PoseBox>& region, const CertifyOptions& options) {
  if (region.empty())
    throw std::invalid_argument("certify_working_mode: expected boxes, found none");
  if (!(std::isfinite(options.min_size) && options.min_size > 0.0))
    throw std::invalid_argument(
        fmt::format("certify_working_mode: expected min_size > 0, found {}", options.min_size));
  if (!(std::isfinite(options.min_margin) && options.min_margin >= 0.0))
    throw std::invalid_argument(fmt::format(
        "certify_working_mode: expected min_margin >= 0, found {}", options.min_margin));
  if (options.max_evaluations < 1)
    throw std::invalid_argument("certify_working_mode: expected max_evaluations >= 1");
  for (const PoseBox& b : region) {
    const bool finite =
        b.position_lo.allFinite() && b.position_hi.allFinite() && b.R0.allFinite() &&
        std::isfinite(b.theta.lo) && std::isfinite(b.theta.hi) && std::isfinite(b.phi.lo) &&
        std::isfinite(b.phi.hi) && std::isfinite(b.gamma.lo) && std::isfinite(b.gamma.hi);
    const bool ordered = (b.position_lo.array() <= b.position_hi.array()).all() &&
                         b.theta.lo <= b.theta.hi && b.phi.lo <= b.phi.hi &&
                         b.gamma.lo <= b.gamma.hi;
    if (!finite || !ordered)
      throw std::invalid_argument(
          "certify_working_mode: expected boxes with finite bounds, lower <= upper");
  }
}

}  // namespace

double singularity_free_share(const JacobianEnclosure& enclosure, const PoseBox& region,
                              std::int64_t budget) {
  const auto s = sides(region, enclosure.enclosure_length());
  CertifyOptions options;
  options.min_size = std::max(*std::max_element(s.begin(), s.end()) / 16.0, 1e-6);
  options.max_evaluations = budget;
  // Certified: one sign's share is positive / positive, exactly 1.
  const ModeCertificate c = certify_working_mode(enclosure, {region}, options);
  return std::max(c.positive_fraction, c.negative_fraction);
}

PoseBox orientation_box(const OrientationSet& set) {
  PoseBox box;
  box.R0 = rotation_zyx<double>(set.nominal_angles);
  box.theta = Interval(0.0, set.tilt);
  box.phi = set.tilt > 0.0 ? Interval(0.0, 2.0 * std::numbers::pi) : Interval(0.0);
  box.gamma = Interval(-set.yaw_range, set.yaw_range);
  return box;
}

std::vector<PoseBox> workspace_cells(const std::vector<WorkspacePoint>& points, double h,
                                     const PoseBox& orientations) {
  std::vector<PoseBox> cells;
  cells.reserve(points.size());
  const Eigen::Vector3d half = Eigen::Vector3d::Constant(0.5 * h);
  for (const WorkspacePoint& p : points) {
    PoseBox b = orientations;
    b.position_lo = p.position - half;
    b.position_hi = p.position + half;
    cells.push_back(b);
  }
  return cells;
}

std::pair<double, int> pose_margin(const JacobianEnclosure& enclosure, const PoseBox& point) {
  PoseBox x = point;
  x.position_hi = x.position_lo;
  x.theta.hi = x.theta.lo;
  x.phi.hi = x.phi.lo;
  x.gamma.hi = x.gamma.lo;
  IntervalJacobian J;
  if (!enclosure.enclose_jacobian(x, J)) return {0.0, 0};
  const Matrix6 M = midpoint(J);
  const Eigen::FullPivLU<Matrix6> lu(M);
  if (!M.allFinite() || !lu.isInvertible()) return {0.0, 0};
  const double norm = inf_norm(lu.inverse());
  return {std::isfinite(norm) && norm > 0.0 ? 1.0 / norm : 0.0, lu.determinant() > 0.0 ? 1 : -1};
}

ModeCertificate certify_working_mode(const JacobianEnclosure& enclosure,
                                     const std::vector<PoseBox>& region,
                                     const CertifyOptions& options) {
  check_region(region, options);
  // The sides the region spans: a fixed orientation or a flat box adds no factor to a measure.
  const double rho = enclosure.enclosure_length();
  std::array<bool, 6> used{};
  for (const PoseBox& b : region) {
    const auto s = sides(b, rho);
    for (int k = 0; k < 6; ++k) used[k] = used[k] || s[k] > 0.0;
  }
  const std::int64_t n = static_cast<std::int64_t>(region.size());
  const std::int64_t budget = std::max<std::int64_t>(1, options.max_evaluations / n);
  std::vector<Part> parts(region.size());
#pragma omp parallel for schedule(dynamic, 1)
  for (std::int64_t k = 0; k < n; ++k)
    parts[static_cast<std::size_t>(k)] =
        certify_box(enclosure, region[static_cast<std::size_t>(k)], options, budget, used);
  ModeCertificate c;
  double positive = 0.0, negative = 0.0, uncertified = 0.0;
  for (Part& p : parts) {
    c.positive_boxes += p.positive;
    c.negative_boxes += p.negative;
    c.evaluations += p.evaluations;
    positive += p.positive_measure;
    negative += p.negative_measure;
    uncertified += p.uncertified_measure;
    c.min_margin = std::min(c.min_margin, p.min_margin);
    c.min_centre_margin = std::min(c.min_centre_margin, p.min_centre_margin);
    if (p.uncertified.parts > 0) {
      const double whole = p.positive_measure + p.negative_measure + p.uncertified_measure;
      p.uncertified.fraction = whole > 0.0 ? p.uncertified_measure / whole : 1.0;
      c.uncertified.push_back(p.uncertified);
    }
    for (UncertifiedBox& b : p.parts) c.parts.push_back(std::move(b));
  }
  const double total = positive + negative + uncertified;
  if (total > 0.0) {
    c.positive_fraction = positive / total;
    c.negative_fraction = negative / total;
    c.uncertified_fraction = uncertified / total;
  }
  return c;
}

}  // namespace pkmopt
