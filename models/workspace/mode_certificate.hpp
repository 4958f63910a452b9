// The proof that a machine keeps one working mode over a region of poses: no parallel
// (type II) singularity inside it, so det J keeps one sign and the machine cannot pass into
// another assembly mode there. A grid of poses cannot give this: a singular surface can pass
// between its points. Here each box of poses is proved free of singular poses, or split.
//
// Method (interval analysis, as in Merlet, "A formal-numerical approach for robust in-workspace
// singularity detection", IEEE Trans. Robotics 23(3), 2007). For a box X of poses the machine
// gives an interval matrix [J] holding J_c(x) for every x in X (JacobianEnclosure,
// models/core/capabilities.hpp: the inverse Jacobian, angular columns divided by rho). With C an
// approximate inverse of [J]'s midpoint, the interval matrix E = I - C [J] is computed; when
//     beta = ||E||_inf < 1  (an upper bound, in outward-rounded arithmetic),
// every matrix M of [J] is regular (C M = I - E_M with ||E_M|| < 1; Rump's and Rohn's
// criterion), so det J_c(x) != 0 on X and, X being connected, keeps the sign of det at the
// midpoint. Moreover ||J_c(x)^-1||_inf <= ||C||_inf / (1 - beta), so
//     margin(x) = 1 / ||J_c(x)^-1||_inf >= (1 - beta) / ||C||_inf
// for every x in X: the certified margin (no unit; it is a lower bound of sqrt(6) times the
// smallest singular value of J_c, and 0 exactly at a singular pose). A box is certified when
// it is proved regular with a certified margin of at least min_margin; otherwise it is split in
// two along its widest side (positions in m, angles times rho) until its widest side is below
// min_size, and then reported. Boxes are split breadth first, so that when the evaluation
// budget runs out the proved part is spread over the region. The region is certified when every box
// is and all their determinants have one sign: the union of boxes that share faces is connected, so
// the working mode is one.
//
// Boxes are handled in parallel, each first box of the region by itself: the result is the
// same for any thread count.
//
// Example:
//   const auto enclosure = machine.jacobian_enclosure();
//   const ModeCertificate c = certify_working_mode(*enclosure.get(), boxes, {});
//   if (c.certified()) ...; else for (const auto& b : c.uncertified) report(b);
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "models/core/capabilities.hpp"
#include "models/workspace/workspace.hpp"

namespace pkmopt {

/// Boxes a design metric certifies at most (about 4 s on one core; the 300 x 300 x 200 mm box
/// of the milling studies, tilted up to 20 degrees, needs about 50,000 for the sample hexapod).
inline constexpr std::int64_t kDesignCertifyBudget = 100'000;

struct CertifyOptions {
  double min_size = 1e-3;   ///< m: a box whose widest side (angles times rho) is below is reported
  double min_margin = 0.0;  ///< the certified margin a box must reach (0: regular is enough)
  std::int64_t max_evaluations = 4'000'000;  ///< boxes evaluated in all (shared by first boxes)
  bool keep_parts = false;  ///< also list every uncertified part (ModeCertificate::parts)
};

/// A first box of the region with parts that could not be certified: how many boxes were left
/// (split down to min_size, or when the budget ran out), their share of the first box's measure,
/// and the smallest margin at their centres (margin(x) above, 0 when J is singular there) with
/// the sign of det J_c there.
struct UncertifiedBox {
  PoseBox box;
  std::int64_t parts = 0;
  double fraction = 0.0;
  double centre_margin = INFINITY;
  int centre_sign = 0;
  bool budget = false;  ///< parts were left when the evaluation budget ran out
};

struct ModeCertificate {
  std::int64_t positive_boxes = 0;  ///< certified boxes with det J_c > 0
  std::int64_t negative_boxes = 0;  ///< certified boxes with det J_c < 0
  double positive_fraction = 0.0;   ///< of the region's measure (its boxes' volumes, rho-scaled)
  double negative_fraction = 0.0;
  double uncertified_fraction = 0.0;
  std::vector<UncertifiedBox> uncertified;  ///< first boxes with uncertified parts, in order
  std::vector<UncertifiedBox> parts;        ///< with keep_parts: every uncertified part
  double min_margin = INFINITY;             ///< smallest certified margin over the certified boxes
  /// Smallest margin(x) at the centres of the certified boxes: a sampled value, not a bound.
  double min_centre_margin = INFINITY;
  std::int64_t evaluations = 0;
  /// Every box certified and all of one sign: one working mode everywhere.
  bool certified() const {
    return uncertified.empty() && (positive_boxes == 0 || negative_boxes == 0);
  }
};

/// Certifies the union of `region` (boxes of poses) for `enclosure`. Throws
/// std::invalid_argument for an empty region, a box with lo > hi or non-finite bounds, or
/// options out of range (min_size <= 0, min_margin < 0, max_evaluations < 1).
ModeCertificate certify_working_mode(const JacobianEnclosure& enclosure,
                                     const std::vector<PoseBox>& region,
                                     const CertifyOptions& options);

/// The share of `region` proved free of parallel singularities with one working mode, for a
/// design metric: the larger of the two signs' shares of the region's measure (1 exactly when
/// the region is certified), with boxes split down to 1/16 of the region's widest side and at
/// most `budget` boxes (boxes left count as not proved). Throws as certify_working_mode.
double singularity_free_share(const JacobianEnclosure& enclosure, const PoseBox& region,
                              std::int64_t budget = kDesignCertifyBudget);

/// The orientation set of a workspace as the orientation part of a box (position 0): R0 its
/// nominal rotation, theta in [0, tilt], phi in [0, 2 pi] (a single 0 without tilt), gamma in
/// [-yaw_range, yaw_range].
PoseBox orientation_box(const OrientationSet& set);

/// The cells of a workspace grid: for each inside node p, the box p +- h/2 with the
/// orientations of `orientations` (orientation_box).
std::vector<PoseBox> workspace_cells(const std::vector<WorkspacePoint>& points, double h,
                                     const PoseBox& orientations);

/// margin(x) = 1 / ||J_c(x)^-1||_inf at one pose (the box's lower corners) and the sign of
/// det J_c there (0 and 0 when J_c is singular or not defined).
std::pair<double, int> pose_margin(const JacobianEnclosure& enclosure, const PoseBox& point);

}  // namespace pkmopt
