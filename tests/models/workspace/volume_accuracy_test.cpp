// Tests of models/workspace/volume_accuracy: on a small (a fifth of the size, under a litre) and a
// full-size copy of the docs/conventions.md hexapod, the resolution chosen for a 0.5 % tolerance
// gives a volume within its reported error of a Monte Carlo estimate of the same rule (10^6
// uniform samples of Hexapod::reachable in the search box, 4 standard errors); the estimate of
// a fixed grid bounds its true error against the converged volume; a bad tolerance is refused.
#include "models/workspace/volume_accuracy.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <stdexcept>

#include "models/hexapod/hexapod.hpp"
#include "models/sample_machines.hpp"
#include "tests/models/workspace/monte_carlo_volume.hpp"

namespace pkmopt {
namespace {

// The docs/conventions.md hexapod with every length times `scale`.
Hexapod scaled_hexapod(double scale) {
  HexapodDesign d = sample_machines::conventions_hexapod_design();
  d.base_joints *= scale;
  d.platform_joints *= scale;
  d.min_length *= scale;
  d.max_length *= scale;
  d.tcp *= scale;
  return Hexapod(d);
}

TEST(VolumeAccuracy, SmallAndLargeMachinesMeetTheToleranceAgainstMonteCarlo) {
  for (const double scale : {0.2, 1.0}) {
    const Hexapod hexapod = scaled_hexapod(scale);
    WorkspaceOptions options;
    const VolumeAccuracy acc = choose_workspace_resolution(hexapod, options, 0.005);
    ASSERT_TRUE(acc.met) << scale;
    EXPECT_LE(acc.error, 0.005 * acc.volume);
    EXPECT_GE(acc.grids, 2);
    options.resolution = acc.resolution;
    const WorkspaceResult ws = compute_workspace(hexapod, options);
    EXPECT_DOUBLE_EQ(ws.volume, acc.volume);  // the volume-only path gives the same number
    const test_volume::MonteCarlo mc =
        test_volume::monte_carlo_volume(hexapod, ws.search_box, Eigen::Vector3d::Zero(), 20261202);
    EXPECT_LT(std::abs(acc.volume - mc.volume), acc.error + 4.0 * mc.standard_error)
        << "scale " << scale << ": " << acc.volume << " +- " << acc.error << " vs Monte Carlo "
        << mc.volume << " +- " << mc.standard_error << " (h " << acc.resolution << ")";
  }
  // The small machine's volume is 0.2^3 of the large one's (to the tolerances).
  const double small = choose_workspace_resolution(scaled_hexapod(0.2), {}, 0.005).volume;
  const double large = choose_workspace_resolution(scaled_hexapod(1.0), {}, 0.005).volume;
  EXPECT_NEAR(small / (0.008 * large), 1.0, 0.01);
}

// A fixed 40 mm grid on the full-size machine: its estimated error bounds the difference to the
// converged volume (a 0.02 % tolerance).
TEST(VolumeAccuracy, FixedGridEstimateBoundsItsError) {
  const Hexapod hexapod = scaled_hexapod(1.0);
  WorkspaceOptions options;
  options.resolution = 0.04;
  const VolumeAccuracy fixed = workspace_volume_accuracy(hexapod, options);
  EXPECT_FALSE(fixed.met);
  EXPECT_EQ(fixed.tolerance, 0.0);
  const VolumeAccuracy fine = choose_workspace_resolution(hexapod, options, 2e-4);
  ASSERT_TRUE(fine.met);
  EXPECT_LE(std::abs(fixed.volume - fine.volume), fixed.error + fine.error);
  EXPECT_GT(fixed.relative_error(), 1e-4);  // a coarse grid has a visible error
}

TEST(VolumeAccuracy, BadToleranceIsRefused) {
  const Hexapod hexapod = scaled_hexapod(1.0);
  EXPECT_THROW(choose_workspace_resolution(hexapod, {}, 0.0), std::invalid_argument);
  EXPECT_THROW(choose_workspace_resolution(hexapod, {}, 1.0), std::invalid_argument);
  EXPECT_THROW(choose_workspace_resolution(hexapod, {}, std::nan("")), std::invalid_argument);
}

}  // namespace
}  // namespace pkmopt
