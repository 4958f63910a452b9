// libFuzzer target: machine files (every model) as `pkmopt describe` and `pkmopt analyze` read
// them: the description, then the machine analysed at the centre of its workspace search box
// under a cutting-size wrench. Besides the contract of fuzz_input.hpp, a NaN in the metrics is a
// finding (outputs never hold NaN; +inf marks a singular pose).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <vector>

#include "fuzz/fuzz_input.hpp"
#include "io/machine/machine_description.hpp"
#include "io/machine/machine_file.hpp"
#include "models/core/pose_analysis.hpp"

namespace {

void check_no_nan(const pkmopt::PoseMetrics& m) {
  const double scalars[] = {m.stiffness_min, m.singularity_margin, m.det_j,
                            m.tcp_error_max, m.tcp_deflection,     m.leg_clearance};
  bool nan = m.q.hasNaN() || m.tau.hasNaN() || m.natural_frequencies.hasNaN();
  for (double v : scalars) nan = nan || std::isnan(v);
  if (nan) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  fuzz::expect_input_errors([&] {
    const std::string path = fuzz::write_input(data, size, "machine.yaml");
    const pkmopt::MachineDescription description = pkmopt::describe_machine_file(path);
    (void)pkmopt::format_description(description);
    if (description.parallel_drives == 0) return;  // serial axes only: nothing to analyse
    const auto machine = pkmopt::load_machine_file(path);
    const auto box = machine->workspace_search_box({Eigen::Matrix3d::Identity()});
    if (!box) return;
    pkmopt::Pose pose;
    pose.position = box->center();
    pkmopt::Wrench wrench;
    wrench << 300.0, -200.0, 500.0, 10.0, 5.0, -2.0;
    const std::vector<pkmopt::Pose> poses = {pose};
    for (const pkmopt::PoseMetrics& m : pkmopt::analyze_poses(*machine, poses, wrench))
      check_no_nan(m);
  });
  return 0;
}
