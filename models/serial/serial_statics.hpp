// The statics of serial feed axes, shared by serial machines (models/serial/serial_machine.hpp)
// and the serial axes of hybrid machines (models/hybrid/hybrid_machine.hpp).
//
// With J_f the tool's twist per axis rate (6 x n: [u; 0] for a linear axis, [u x (r_0 - o); u]
// for a rotary one) and W = [f; m] the wrench at the tool point:
//   drive loads   tau = J_f^T W (a linear axis carries the force along it, a rotary one the
//                 moment about it; the statics of a serial chain by virtual work);
//   compliance    C = sum_i J_f,i J_f,i^T / k_i over the elastic axes (k_i > 0): the drives in
//                 series, each yielding by its load over its stiffness;
//   error columns e_i J_f,t,i for the axes with a positioning error e_i > 0: the tool point's
//                 error is the sum of the columns times signs in [-1, 1], whose largest norm is
//                 at a vertex (max_norm_over_sign_vectors, models/core/linalg.hpp).
// Units follow each axis (models/serial/serial_axis.hpp).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "models/core/pose.hpp"
#include "models/serial/serial_axis.hpp"

namespace pkmopt {

/// J_f (6 x n) for the axes in `axes` (n entries).
using FeedJacobian = Eigen::Matrix<double, 6, Eigen::Dynamic>;

/// tau = J_f^T W.
Eigen::VectorXd serial_drive_loads(const FeedJacobian& Jf, const Wrench& wrench);

/// Adds sum_i J_f,i J_f,i^T / k_i (the elastic axes) to C, axis by axis in order.
void add_serial_compliance(const FeedJacobian& Jf, const std::vector<SerialAxis>& axes,
                           Matrix6d& C);

/// Appends e_i J_f,t,i for each axis with e_i > 0 to columns(:, used..) and advances `used`;
/// `columns` must have room for them.
template <class Columns>
void append_serial_error_columns(const FeedJacobian& Jf, const std::vector<SerialAxis>& axes,
                                 Columns& columns, int& used) {
  for (std::size_t i = 0; i < axes.size(); ++i) {
    const double e = axes[i].error;
    if (e > 0.0) columns.col(used++) = e * Jf.template block<3, 1>(0, static_cast<Eigen::Index>(i));
  }
}

}  // namespace pkmopt
