#include "models/serial/serial_chain.hpp"

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

namespace pkmopt {

template <typename T>
Eigen::Matrix<T, 4, 4> elementary_motion(int motion, const T& value) {
  using std::cos;
  using std::sin;
  Eigen::Matrix<T, 4, 4> A = Eigen::Matrix<T, 4, 4>::Identity();
  if (motion >= 1 && motion <= 3) {
    A(motion - 1, 3) = value;
    return A;
  }
  if (motion < 4 || motion > 6) {
    throw std::invalid_argument(fmt::format("elementary motion: expected 1..6, found {}", motion));
  }
  // Rotation about axis a; the other two axes (b, c) in cyclic order.
  const int a = motion - 4;
  const int b = (a + 1) % 3;
  const int c = (a + 2) % 3;
  const T cs = cos(value);
  const T sn = sin(value);
  A(b, b) = cs;
  A(b, c) = -sn;
  A(c, b) = sn;
  A(c, c) = cs;
  return A;
}

template Eigen::Matrix<double, 4, 4> elementary_motion<double>(int, const double&);

Eigen::Matrix4d elementary_motion_derivative(int motion, double value) {
  Eigen::Matrix4d D = Eigen::Matrix4d::Zero();
  if (motion >= 1 && motion <= 3) {
    D(motion - 1, 3) = 1.0;
    return D;
  }
  if (motion < 4 || motion > 6) {
    throw std::invalid_argument(fmt::format("elementary motion: expected 1..6, found {}", motion));
  }
  const int a = motion - 4;
  const int b = (a + 1) % 3;
  const int c = (a + 2) % 3;
  D(b, b) = -std::sin(value);
  D(b, c) = -std::cos(value);
  D(c, b) = std::cos(value);
  D(c, c) = -std::sin(value);
  return D;
}

SerialChain::SerialChain(std::vector<ChainElement> elements) : elements_(std::move(elements)) {
  for (const ChainElement& e : elements_) {
    if (e.motion < 1 || e.motion > 6) {
      throw std::invalid_argument(
          fmt::format("chain element: motion expected 1..6, found {}", e.motion));
    }
    if (!e.variable && !std::isfinite(e.value)) {
      throw std::invalid_argument(
          fmt::format("chain element: constant expected finite, found {}", e.value));
    }
    if (e.variable) ++num_variables_;
  }
}

SerialChain SerialChain::from_code(const std::string& code) {
  std::vector<ChainElement> elements;
  std::size_t i = 0;
  while (i < code.size()) {
    const char ch = code[i];
    if (ch == ' ' || ch == ',') {
      ++i;
      continue;
    }
    if (ch < '1' || ch > '6') {
      throw std::invalid_argument(fmt::format(
          "coordinate code '{}': expected a motion digit 1..6 at position {}, found '{}'", code,
          i + 1, ch));
    }
    ChainElement element;
    element.motion = ch - '0';
    ++i;
    if (i < code.size() && code[i] == ':') {
      const std::size_t start = ++i;
      while (i < code.size() && code[i] != ' ' && code[i] != ',') ++i;
      const std::string text = code.substr(start, i - start);
      char* end = nullptr;
      errno = 0;
      const double value = std::strtod(text.c_str(), &end);
      // ERANGE: too large or too small for a double (1e-400 is not read as 0).
      if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(value) ||
          errno == ERANGE) {
        throw std::invalid_argument(fmt::format(
            "coordinate code '{}': expected a finite number after ':' at position {}, found "
            "'{}'",
            code, start + 1, text));
      }
      element.variable = false;
      element.value = value;
    } else if (i < code.size() && code[i] != ' ' && code[i] != ',' &&
               (code[i] < '1' || code[i] > '6')) {
      throw std::invalid_argument(fmt::format(
          "coordinate code '{}': expected a motion digit 1..6 at position {}, found '{}'", code,
          i + 1, code[i]));
    }
    elements.push_back(element);
  }
  if (elements.empty()) {
    throw std::invalid_argument(
        fmt::format("coordinate code '{}': expected at least one motion digit 1..6", code));
  }
  return SerialChain(std::move(elements));
}

std::string SerialChain::code() const {
  std::string out;
  for (const ChainElement& e : elements_) out += static_cast<char>('0' + e.motion);
  return out;
}

int SerialChain::num_translations() const {
  int n = 0;
  for (const ChainElement& e : elements_) n += (e.variable && e.motion <= 3) ? 1 : 0;
  return n;
}

int SerialChain::num_rotations() const { return num_variables_ - num_translations(); }

void SerialChain::check_q(const Eigen::VectorXd& q) const {
  if (q.size() != num_variables_) {
    throw std::invalid_argument(fmt::format("serial chain {}: expected {} axis values, found {}",
                                            code(), num_variables_, q.size()));
  }
}

Eigen::Matrix4d SerialChain::transform(const Eigen::VectorXd& q) const {
  check_q(q);
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  int k = 0;
  for (const ChainElement& e : elements_) {
    T = T * elementary_motion<double>(e.motion, e.variable ? q(k++) : e.value);
  }
  return T;
}

Eigen::Vector3d SerialChain::tool_point(const Eigen::VectorXd& q,
                                        const Eigen::Vector3d& r_tool) const {
  return (transform(q) * r_tool.homogeneous()).head<3>();
}

Eigen::Matrix<double, 3, Eigen::Dynamic> SerialChain::tool_point_jacobian(
    const Eigen::VectorXd& q, const Eigen::Vector3d& r_tool) const {
  check_q(q);
  const std::size_t n = elements_.size();
  // Prefix products P_j = A_0 ... A_{j-1}; suffix vectors s_j = A_{j+1} ... A_{n-1} r.
  std::vector<Eigen::Matrix4d> matrices(n);
  std::vector<double> values(n);
  int k = 0;
  for (std::size_t j = 0; j < n; ++j) {
    values[j] = elements_[j].variable ? q(k++) : elements_[j].value;
    matrices[j] = elementary_motion<double>(elements_[j].motion, values[j]);
  }
  std::vector<Eigen::Vector4d> suffix(n + 1);
  suffix[n] = r_tool.homogeneous();
  for (std::size_t j = n; j-- > 0;) suffix[j] = matrices[j] * suffix[j + 1];
  Eigen::Matrix<double, 3, Eigen::Dynamic> J(3, num_variables_);
  Eigen::Matrix4d prefix = Eigen::Matrix4d::Identity();
  k = 0;
  for (std::size_t j = 0; j < n; ++j) {
    if (elements_[j].variable) {
      J.col(k++) =
          (prefix * elementary_motion_derivative(elements_[j].motion, values[j]) * suffix[j + 1])
              .head<3>();
    }
    prefix = prefix * matrices[j];
  }
  return J;
}

Eigen::Matrix<double, 6, Eigen::Dynamic> SerialChain::twist_jacobian(
    const Eigen::VectorXd& q, const Eigen::Vector3d& r_tool) const {
  const Eigen::Vector3d r0 = tool_point(q, r_tool);
  Eigen::Matrix<double, 6, Eigen::Dynamic> J(6, num_variables_);
  Eigen::Matrix4d prefix = Eigen::Matrix4d::Identity();
  int k = 0;
  for (const ChainElement& e : elements_) {
    const double value = e.variable ? q(k) : e.value;
    if (e.variable) {
      Eigen::Vector3d axis = Eigen::Vector3d::Zero();
      axis((e.motion - 1) % 3) = 1.0;
      const Eigen::Vector3d direction = prefix.topLeftCorner<3, 3>() * axis;
      if (e.motion <= 3) {
        J.col(k) << direction, Eigen::Vector3d::Zero();
      } else {
        J.col(k) << direction.cross(r0 - prefix.topRightCorner<3, 1>()), direction;
      }
      ++k;
    }
    prefix = prefix * elementary_motion<double>(e.motion, value);
  }
  return J;
}

std::string structure_class(int serial_drives, int parallel_drives) {
  return fmt::format("P{}\u0417{}", serial_drives, parallel_drives);
}

}  // namespace pkmopt
