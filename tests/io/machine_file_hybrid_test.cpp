// Tests of io/machine_file_hybrid: the field list of the hybrid machine file gives the docs table
// of docs/hybrid-machines.md and the reader takes every key of it (the code, the axis names and the
// module file are read by hand next to it).
#include "io/machine_file_hybrid.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "io/input_error.hpp"

namespace pkmopt {
namespace {

const std::string kExamples = std::string(PKMOPT_SOURCE_DIR) + "/examples/";

// A file next to the examples, so that `parallel.file` names an example.
YamlValue yaml(const std::string& text) {
  return YamlValue::load_string(text, kExamples + "hybrid_test.yaml");
}

TEST(HybridMachineFileFields, DocsCarryTheGeneratedTable) {
  std::ifstream in(std::string(PKMOPT_SOURCE_DIR) + "/docs/hybrid-machines.md");
  std::stringstream docs;
  docs << in.rdbuf();
  const std::string block =
      "<!-- fields: hybrid -->\n" + hybrid_machine_fields_markdown() + "<!-- /fields -->\n";
  EXPECT_NE(docs.str().find(block), std::string::npos)
      << "docs/hybrid-machines.md lacks the generated hybrid table:\n"
      << block;
}

TEST(HybridMachineFileFields, ReadsEveryKey) {
  const HybridDesign d = read_hybrid_design(
      yaml("model: hybrid\nname: gantry\ndescription: two axes\n"
           "serial: {code: \"1 2 3:0.5\", axes: [X, Y], range: [[-1.5, 1.5], [0, 0]],\n"
           "         stiffness: [1.5e8, 0], error: [5e-6, 2e-6]}\n"
           "parallel: {file: tripod_3prs.yaml, home: [0, 0, 1.2]}\n"));
  ASSERT_EQ(d.axes.size(), 2u);
  EXPECT_EQ(d.axes[0].min, -1.5);
  EXPECT_EQ(d.axes[0].max, 1.5);
  EXPECT_EQ(d.axes[1].min, 0.0);  // [0, 0]: a fixed axis
  EXPECT_EQ(d.axes[1].max, 0.0);
  EXPECT_EQ(d.axes[0].stiffness, 1.5e8);
  EXPECT_EQ(d.axes[1].stiffness, 0.0);
  EXPECT_EQ(d.axes[0].error, 5e-6);
  EXPECT_EQ(d.axes[1].error, 2e-6);
  EXPECT_EQ(d.home, Eigen::Vector3d(0, 0, 1.2));
  ASSERT_NE(d.module, nullptr);
  EXPECT_EQ(std::string(d.module->model()), "tripod_3prs");
  EXPECT_EQ(d.chain.num_variables(), 2);
  // Absent lists: rigid, exact axes.
  const HybridDesign plain =
      read_hybrid_design(yaml("model: hybrid\nserial: {code: \"1\", range: [[-1, 1]]}\n"
                              "parallel: {file: hexapod.yaml, home: [0, 0, 0.9]}\n"));
  EXPECT_EQ(plain.axes[0].stiffness, 0.0);
  EXPECT_EQ(plain.axes[0].error, 0.0);
}

TEST(HybridMachineFileFields, ListsHaveOneEntryPerAxis) {
  auto error_of = [](const std::string& serial) {
    try {
      (void)read_hybrid_design(yaml("model: hybrid\nserial: " + serial +
                                    "\nparallel: {file: hexapod.yaml, home: [0, 0, 0.9]}\n"));
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string file = kExamples + "hybrid_test.yaml:";
  EXPECT_EQ(error_of("{code: \"12\", range: [[-1, 1], [0, 1]], error: [1e-6]}"),
            file + "2:55: serial.error: expected a list of 2, found a list of 1");
  EXPECT_EQ(error_of("{code: \"1\", range: [[-1, 1]], error: [-1e-6]}"),
            file + "2:47: serial.error[0]: expected a number >= 0, found '-1e-6'");
  EXPECT_EQ(error_of("{code: \"1\", range: [[-1]]}"),
            file + "2:29: serial.range[0]: expected a list of 2, found a list of 1");
  EXPECT_EQ(error_of("{code: \"1\", range: [[-1, 1]], colour: red}"),
            file +
                "2:39: serial.colour: unknown key 'colour'; allowed keys here: code, axes, "
                "range, stiffness, error");
}

}  // namespace
}  // namespace pkmopt
