// Checks of the values a model is built from.
//
// require(condition, message) throws std::invalid_argument(message) when the condition is false:
// models and problems use it for impossible geometry or options ("base radius must be > 0");
// the io layer turns these into located InputErrors for the user.
//
// Example:
//   pkmopt::require(design.rod > 0.0, "rod must be > 0");
#pragma once

#include <stdexcept>
#include <string>

namespace pkmopt {

/// Throws std::invalid_argument(message) unless `condition` holds.
inline void require(bool condition, const std::string& message) {
  if (!condition) throw std::invalid_argument(message);
}

}  // namespace pkmopt
