// libFuzzer target: the CSV readers: pose files (analyze --poses), timed paths (trajectory
// --path) and calibration measurements, each from the same bytes.
#include <cstddef>
#include <cstdint>

#include "fuzz/fuzz_input.hpp"
#include "io/calibration/calibration_files.hpp"
#include "io/format/csv.hpp"
#include "io/format/pose_csv.hpp"
#include "io/results/trajectory_files.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = fuzz::write_input(data, size, "input.csv");
  fuzz::expect_input_errors([&] { (void)pkmopt::read_pose_csv(path); });
  fuzz::expect_input_errors([&] { (void)pkmopt::read_path_csv(path); });
  fuzz::expect_input_errors([&] { (void)pkmopt::read_measurement_csv(path, 1e-3); });
  return 0;
}
