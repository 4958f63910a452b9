// libFuzzer target: pareto.json (pkmopt export and compare read it), then both of its writers.
#include <cstddef>
#include <cstdint>

#include "fuzz/fuzz_input.hpp"
#include "io/results/pareto_json.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  fuzz::expect_input_errors([&] {
    const pkmopt::ParetoFront front =
        pkmopt::read_pareto_json(fuzz::write_input(data, size, "pareto.json"));
    (void)pkmopt::pareto_csv(front);
    (void)pkmopt::pareto_json(front);
  });
  return 0;
}
