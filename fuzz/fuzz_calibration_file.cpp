// libFuzzer target: calibration files (pkmopt calibrate reads them) with the machine and
// measurement files they name: the nominal machine and measurements of the calibration demo
// are staged beside the input as nominal.yaml and measurements.csv.
#include <cstddef>
#include <cstdint>

#include "fuzz/fuzz_input.hpp"
#include "io/calibration/calibration_files.hpp"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  fuzz::stage("studies/library/calibration-demo/nominal.yaml", "nominal.yaml");
  fuzz::stage("studies/library/calibration-demo/measurements.csv", "measurements.csv");
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  fuzz::expect_input_errors([&] {
    (void)pkmopt::read_calibration_setup(fuzz::write_input(data, size, "calibration.yaml"));
  });
  return 0;
}
