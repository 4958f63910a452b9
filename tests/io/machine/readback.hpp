// Checks shared by the tests of the machine-file writers: a written file read back gives the same
// design, angles to the 12 significant digits the writers give degrees.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace pkmopt::readback_test {

/// An angle (rad) read back from a file that wrote it in degrees with 12 significant digits.
inline void expect_angle(double read, double written, const std::string& what) {
  if (std::isinf(written)) {
    EXPECT_EQ(read, written) << what;
  } else {
    EXPECT_NEAR(read, written, 1e-11 * std::max(1.0, std::abs(written))) << what;
  }
}

}  // namespace pkmopt::readback_test
