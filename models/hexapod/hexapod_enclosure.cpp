// Hexapod::enclose_jacobian: the inverse Jacobian over a box of poses in interval arithmetic
// (models/core/interval.hpp), and its derivatives for the mean-value form, for the proof that a
// region holds no parallel singularity (models/workspace/mode_certificate.hpp).
#include "models/hexapod/hexapod.hpp"

namespace pkmopt {
namespace {

// The rows [s_i^T, (r_i x s_i)^T / rho] at position p and rotation R, for a scalar T of
// models/core/interval.hpp. False when a leg's length may be 0.
template <class T>
bool jacobian_rows(const Eigen::Matrix<double, 3, 6>& base,
                   const Eigen::Matrix<double, 3, 6>& platform, double rho, const T (&p)[3],
                   const std::array<std::array<T, 3>, 3>& R, T (&J)[6][6]) {
  for (int i = 0; i < 6; ++i) {
    T r[3], pa[3], l[3];
    for (int k = 0; k < 3; ++k) {
      r[k] =
          R[k][0] * T(platform(0, i)) + R[k][1] * T(platform(1, i)) + R[k][2] * T(platform(2, i));
      pa[k] = p[k] - T(base(k, i));
      l[k] = pa[k] + r[k];
    }
    const T length2 = square(l[0]) + square(l[1]) + square(l[2]);
    Interval value;
    if constexpr (std::is_same_v<T, Interval>)
      value = length2;
    else
      value = length2.v;
    if (!(value.lo > 0.0)) return false;
    const T inverse = T(1.0) / sqrt(length2);
    // The moment r x l = r x (p - a): r x r = 0, and the interval form is tighter without it.
    const T m[3] = {r[1] * pa[2] - r[2] * pa[1], r[2] * pa[0] - r[0] * pa[2],
                    r[0] * pa[1] - r[1] * pa[0]};
    const T scale = inverse / T(rho);
    for (int k = 0; k < 3; ++k) {
      J[i][k] = l[k] * inverse;
      J[i][3 + k] = m[k] * scale;
    }
  }
  return true;
}

}  // namespace

double Hexapod::enclosure_length() const { return platform_rel_.colwise().norm().mean(); }

bool Hexapod::enclose_jacobian(const PoseBox& box, IntervalJacobian& J,
                               IntervalJacobianSlopes* slopes) const {
  const double rho = enclosure_length();
  if (!slopes) {
    const Interval p[3] = {{box.position_lo(0), box.position_hi(0)},
                           {box.position_lo(1), box.position_hi(1)},
                           {box.position_lo(2), box.position_hi(2)}};
    Interval rows[6][6];
    if (!jacobian_rows(design_.base_joints, platform_rel_, rho, p, enclose_rotation(box), rows))
      return false;
    for (int i = 0; i < 6; ++i)
      for (int k = 0; k < 6; ++k) J[i][k] = rows[i][k];
    return true;
  }
  using G = IntervalGradient<6>;
  const G p[3] = {G::coordinate({box.position_lo(0), box.position_hi(0)}, 0),
                  G::coordinate({box.position_lo(1), box.position_hi(1)}, 1),
                  G::coordinate({box.position_lo(2), box.position_hi(2)}, 2)};
  const auto R = box_rotation_of<G>(box.R0, G::coordinate(box.theta, 3), G::coordinate(box.phi, 4),
                                    G::coordinate(box.gamma, 5));
  G rows[6][6];
  if (!jacobian_rows(design_.base_joints, platform_rel_, rho, p, R, rows)) return false;
  for (int i = 0; i < 6; ++i)
    for (int k = 0; k < 6; ++k) {
      J[i][k] = rows[i][k].v;
      for (int c = 0; c < 6; ++c) (*slopes)[c][i][k] = rows[i][k].d[c];
    }
  return true;
}

}  // namespace pkmopt
