#include "io/machine_file_hybrid.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <set>
#include <stdexcept>
#include <string>

#include "io/csv.hpp"
#include "io/machine_file.hpp"

namespace pkmopt {

HybridDesign read_hybrid_design(const YamlValue& root) {
  root.check_keys({"model", "name", "description", "serial", "parallel"});
  HybridDesign design;

  const YamlValue serial = root.required("serial");
  serial.check_keys({"code", "axes", "range", "stiffness", "error"});
  const YamlValue code = serial.required("code");
  try {
    design.chain = SerialChain::from_code(code.as_string());
  } catch (const std::invalid_argument& e) {
    code.fail(e.what());
  }
  if (design.chain.num_rotations() > 0) {
    code.fail(
        "variable axes that are translations (motions 1, 2, 3; variable rotary axes are not "
        "computable in a hybrid, only `pkmopt describe` accepts them)",
        quote_found(design.chain.code()));
  }
  // Constant rotations are written in degrees.
  std::vector<ChainElement> elements = design.chain.elements();
  for (ChainElement& e : elements) {
    if (!e.variable && e.motion >= 4) e.value = deg_to_rad(e.value);
  }
  const int n = design.chain.num_variables();
  if (n == 0) code.fail("at least one variable axis", quote_found(design.chain.code()));
  if (const auto axes = serial.optional("axes")) {
    const auto names = axes->elements(n);
    std::set<std::string> unique;
    for (const YamlValue& name : names) unique.insert(name.as_string());
    if (static_cast<int>(unique.size()) != n) axes->fail("distinct axis names", axes->describe());
    int k = 0;
    for (ChainElement& e : elements) {
      if (e.variable) e.name = names[static_cast<std::size_t>(k++)].as_string();
    }
  }
  design.chain = SerialChain(std::move(elements));

  design.axes.resize(static_cast<std::size_t>(n));
  const auto ranges = serial.required("range").elements(n);
  for (int i = 0; i < n; ++i) {
    const YamlValue& r = ranges[static_cast<std::size_t>(i)];
    const auto v = r.as_doubles(2);
    if (!(v[0] <= v[1])) {
      r.fail("[min, max] with min <= max (m)",
             fmt::format("[{}, {}]", format_number(v[0]), format_number(v[1])));
    }
    design.axes[static_cast<std::size_t>(i)].min = v[0];
    design.axes[static_cast<std::size_t>(i)].max = v[1];
  }
  if (const auto stiffness = serial.optional("stiffness")) {
    const auto values = stiffness->elements(n);
    for (int i = 0; i < n; ++i) {
      design.axes[static_cast<std::size_t>(i)].stiffness =
          values[static_cast<std::size_t>(i)].as_non_negative();
    }
  }
  if (const auto error = serial.optional("error")) {
    const auto values = error->elements(n);
    for (int i = 0; i < n; ++i) {
      design.axes[static_cast<std::size_t>(i)].error =
          values[static_cast<std::size_t>(i)].as_non_negative();
    }
  }

  const YamlValue parallel = root.required("parallel");
  parallel.check_keys({"file", "home"});
  const YamlValue file = parallel.required("file");
  const std::filesystem::path module =
      std::filesystem::path(root.file()).parent_path() / file.as_string();
  if (!std::filesystem::is_regular_file(module)) {
    file.fail("an existing machine file", "'" + module.string() + "' (no such file)");
  }
  const YamlValue module_root = YamlValue::load_file(module.string());
  module_root.expect_map();
  const std::string module_model = module_root.required("model").as_string();
  if (module_model == "hybrid" || module_model == "serial") {
    file.fail("a parallel machine file", "'" + module.string() + "' (model: " + module_model + ")");
  }
  design.module = load_machine(module_root);
  if (design.module->revolute_actuators()) {
    file.fail(
        "a parallel machine with prismatic actuators (revolute drives would mix degrees "
        "with the axes' metres in q)",
        "'" + module.string() + "' (model: " + module_model + ", revolute drives)");
  }
  const auto home = parallel.required("home").as_doubles(3);
  design.home = Eigen::Vector3d(home[0], home[1], home[2]);

  try {
    HybridMachine check(design);  // the constructor's own checks (dependent axes, ...)
  } catch (const std::invalid_argument& e) {
    code.fail(e.what());
  }
  return design;
}

std::unique_ptr<Machine> load_hybrid_machine(const YamlValue& root) {
  return std::make_unique<HybridMachine>(read_hybrid_design(root));
}

}  // namespace pkmopt
