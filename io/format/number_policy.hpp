// What a number read from a user's input may be: the finiteness and range policy that keeps
// every computation free of overflow, underflow to subnormals and NaN.
//
// Every number in a machine, study, pose, path, calibration or pareto.json file and every
// numeric command-line option is
//   - finite, and 0 or of magnitude within [kMinInputMagnitude, kMaxInputMagnitude];
//   - for a length or position in metres, within +-kMaxInputLength;
//   - for a force (N) or moment (N*m) component of a wrench, within +-kMaxInputForce.
// Products of two such numbers stay far from the limits of a double, so a value the user gave
// can make a result infinite only where the conventions say so (a singular pose), never NaN.
//
//   if (!sane_input_number(x)) fail(kSaneNumberText, ...);
#pragma once

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <string_view>

#include "models/core/pose.hpp"

namespace pkmopt {

inline constexpr double kMaxInputMagnitude = 1e15;
inline constexpr double kMinInputMagnitude = 1e-30;
inline constexpr double kMaxInputLength = 1e3;  ///< m: no machine is a kilometre long
/// N and N*m: 100,000 tonnes-force; the models' own limit on a wrench (models/core/pose.hpp).
inline constexpr double kMaxInputForce = kMaxWrenchComponent;

/// "a finite number within +-1e15 (0 or at least 1e-30 in magnitude)", for messages.
inline constexpr std::string_view kSaneNumberText =
    "a finite number within +-1e15 (0 or at least 1e-30 in magnitude)";

/// "a length within +-1000 m", for messages.
inline constexpr std::string_view kLengthText = "a length within +-1000 m";

/// std::strtod with one rule for numbers too small for a double: text such as 1e-400, which
/// strtod reads as 0, reads as the smallest subnormal of its sign, so the policy refuses it as it
/// refuses 1e-31 (a number written non-zero is never read as 0).
inline double read_input_number(const char* text, char** end) {
  errno = 0;
  const double v = std::strtod(text, end);
  if (errno == ERANGE && std::abs(v) < std::numeric_limits<double>::min())
    return std::copysign(std::numeric_limits<double>::denorm_min(), v);
  return v;
}

/// True for a length or position in metres the policy accepts.
inline bool sane_input_length(double x) {
  return std::isfinite(x) && std::abs(x) <= kMaxInputLength;
}

/// True for a number the policy accepts (see the header comment).
inline bool sane_input_number(double x) {
  const double a = std::abs(x);
  return std::isfinite(x) && a <= kMaxInputMagnitude && (a == 0.0 || a >= kMinInputMagnitude);
}

}  // namespace pkmopt
