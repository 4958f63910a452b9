// Serial machine axes by coordinate code: a chain of elementary motions, each a 4x4
// homogeneous matrix, from the workpiece (or the bed) to the tool.
//
// Elementary motions (the coordinate-code method of machine-tool accuracy analysis, after
// Reshetov & Portman, "Accuracy of Machine Tools", ASME Press 1988):
//   1, 2, 3  translation by a along x, y, z:  A^1(a) = [I  (a,0,0)^T; 0 1], ...
//   4, 5, 6  rotation by phi about x, y, z:   A^4(phi) = [Rx(phi) 0; 0 1], ...
// A code such as "641236" lists the motions in chain order; with every motion an axis, the
// form-shaping function of a 5-axis milling machine with a rotating spindle is
//   r_0 = A^6(psi) A^4(theta) A^1(x) A^2(y) A^3(z) A^6(phi) r_tool
// (table rotations C and A, then X, Y, Z, then the spindle). An element may also be constant
// (a fixed offset or angle between two axes), written "3:0.25" in a code string.
//
// Units: m and rad inside; the machine-file reader takes degrees for rotations.
//
//   SerialChain chain = SerialChain::from_code("641236");
//   Eigen::Matrix4d T = chain.transform(q);          // q: one value per variable element
//   Eigen::Vector3d r0 = chain.tool_point(q, r_tool);
//
// Structure class by drive coupling (16K20F3 conversion study): "P<n>З<m>" with n the feed
// drives in open (serial) chains and m the drives in closed (parallel) chains: P5З0 a
// traditional 5-axis machine, P0З6 a hexapod, P2З3 a gantry X/Y carrying a 3-PRS head,
// P1З6 a long axis carrying a hexapod. (З is the Cyrillic letter Ze, as in that study.)
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

namespace pkmopt {

/// One elementary motion of a chain.
struct ChainElement {
  int motion = 1;        ///< 1..6 (see above)
  bool variable = true;  ///< an axis (its value comes from q) or a constant
  double value = 0.0;    ///< the constant (m or rad) when !variable
  std::string name;      ///< axis name ("X", "C", "S"...), may be empty
};

/// A^k(value) for k = 1..6 (throws std::invalid_argument for another k).
template <typename T>
Eigen::Matrix<T, 4, 4> elementary_motion(int motion, const T& value);

/// dA^k(value)/dvalue.
Eigen::Matrix4d elementary_motion_derivative(int motion, double value);

class SerialChain {
 public:
  SerialChain() = default;
  explicit SerialChain(std::vector<ChainElement> elements);

  /// Parses a coordinate code: digits 1..6, each a variable axis; "k:v" a constant element
  /// (e.g. "6 4 1 2 3:0.3 6" or "641236"; spaces and commas separate). Throws
  /// std::invalid_argument naming the offending character.
  static SerialChain from_code(const std::string& code);

  const std::vector<ChainElement>& elements() const { return elements_; }
  /// The code of the chain's motions ("641236"; constants included as their digit).
  std::string code() const;
  int num_variables() const { return num_variables_; }
  int num_translations() const;  ///< variable translational axes
  int num_rotations() const;     ///< variable rotary axes

  /// The product of the elements' matrices at axis values q (size num_variables()).
  Eigen::Matrix4d transform(const Eigen::VectorXd& q) const;
  /// The tool point r_0 = transform(q) [r_tool; 1].
  Eigen::Vector3d tool_point(const Eigen::VectorXd& q, const Eigen::Vector3d& r_tool) const;
  /// d r_0 / d q (3 x num_variables()).
  Eigen::Matrix<double, 3, Eigen::Dynamic> tool_point_jacobian(const Eigen::VectorXd& q,
                                                               const Eigen::Vector3d& r_tool) const;
  /// The tool's twist per unit axis velocity (6 x num_variables()): column j is [v; omega] of the
  /// tool frame at the tool point r_0 (base axes) when axis j moves at unit speed, the others
  /// still: a linear axis gives [R_j e_a; 0], a rotary one omega = R_j e_a and
  /// v = omega x (r_0 - o_j), with (R_j, o_j) the frame the element moves in (the product of the
  /// elements before it). Rows 0..2 are tool_point_jacobian.
  Eigen::Matrix<double, 6, Eigen::Dynamic> twist_jacobian(const Eigen::VectorXd& q,
                                                          const Eigen::Vector3d& r_tool) const;

 private:
  void check_q(const Eigen::VectorXd& q) const;

  std::vector<ChainElement> elements_;
  int num_variables_ = 0;
};

/// "P<serial>З<parallel>" (UTF-8; З is U+0417).
std::string structure_class(int serial_drives, int parallel_drives);

}  // namespace pkmopt
