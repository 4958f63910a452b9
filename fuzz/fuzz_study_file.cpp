// libFuzzer target: study files (design studies with a machine, benchmark studies) as
// `pkmopt validate` reads them: the whole study resolved, nothing run.
#include <cstddef>
#include <cstdint>

#include "fuzz/fuzz_input.hpp"
#include "io/format/yaml_reader.hpp"
#include "studies/benchmark_study.hpp"
#include "studies/design_study.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  fuzz::expect_input_errors([&] {
    const pkmopt::YamlValue root =
        pkmopt::YamlValue::load_file(fuzz::write_input(data, size, "study.yaml"));
    if (root.is_map() && root.has("machine")) {
      (void)pkmopt::load_design_study(root);
    } else {
      (void)pkmopt::load_benchmark_study(root);
    }
  });
  return 0;
}
