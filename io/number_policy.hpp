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

#include <cmath>
#include <string_view>

#include "models/pose.hpp"

namespace pkmopt {

inline constexpr double kMaxInputMagnitude = 1e15;
inline constexpr double kMinInputMagnitude = 1e-30;
inline constexpr double kMaxInputLength = 1e3;  ///< m: no machine is a kilometre long
/// N and N*m: 100,000 tonnes-force; the models' own limit on a wrench (models/pose.hpp).
inline constexpr double kMaxInputForce = kMaxWrenchComponent;

/// "a finite number within +-1e15 (0 or at least 1e-30 in magnitude)", for messages.
inline constexpr std::string_view kSaneNumberText =
    "a finite number within +-1e15 (0 or at least 1e-30 in magnitude)";

/// True for a number the policy accepts (see the header comment).
inline bool sane_input_number(double x) {
  const double a = std::abs(x);
  return std::isfinite(x) && a <= kMaxInputMagnitude && (a == 0.0 || a >= kMinInputMagnitude);
}

}  // namespace pkmopt
