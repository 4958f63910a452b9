// Tests of io/machine/machine_file_hybrid: the field list of the hybrid machine file gives the docs
// table of docs/hybrid-machines.md and the reader takes every key of it (the code, the axis names
// and the module file are read by hand next to it); the writer's files read back to the same
// design.
#include "io/machine/machine_file_hybrid.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "io/format/input_error.hpp"
#include "models/core/pose.hpp"

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
                "range, stiffness, error, mass");
  // A module with masses: the axes' masses and the world gravity are read; gravity without
  // masses is an error.
  const HybridDesign heavy = read_hybrid_design(
      yaml("model: hybrid\nserial: {code: \"1\", range: [[-1, 1]], mass: [80]}\n"
           "parallel: {file: hexapod_masses.yaml, home: [0, 0, 0.9]}\ngravity: [0, 0.5, -9.8]\n"));
  EXPECT_EQ(heavy.axes[0].mass, 80.0);
  EXPECT_EQ(heavy.gravity, Eigen::Vector3d(0, 0.5, -9.8));
  ASSERT_TRUE(heavy.module->dynamics());
  try {
    (void)read_hybrid_design(
        yaml("model: hybrid\nserial: {code: \"1\", range: [[-1, 1]]}\n"
             "parallel: {file: hexapod.yaml, home: [0, 0, 0.9]}\n"
             "gravity: [0, 0, -9.81]\n"));
    ADD_FAILURE() << "gravity without masses was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), file +
                                         "4:10: gravity: expected gravity only with a module "
                                         "that has masses, found gravity and a module without "
                                         "masses");
  }
}

// Every hybrid machine file shipped in the repo (a line `model: hybrid` in a .yaml file).
std::vector<std::string> shipped_hybrid_files() {
  std::vector<std::string> files;
  for (const char* dir : {"examples", "studies", "tests"}) {
    const std::filesystem::path root = std::filesystem::path(PKMOPT_SOURCE_DIR) / dir;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(root)) {
      if (!entry.is_regular_file() || entry.path().extension() != ".yaml") continue;
      std::ifstream in(entry.path());
      std::stringstream text;
      text << in.rdbuf();
      const std::string t = "\n" + text.str();
      if (t.find("\nmodel: hybrid\n") != std::string::npos) files.push_back(entry.path().string());
    }
  }
  return files;
}

// Every member equal (==); the module compared by what a machine tells about itself.
void expect_same_design(const HybridDesign& a, const HybridDesign& b) {
  ASSERT_EQ(a.chain.elements().size(), b.chain.elements().size());
  for (std::size_t i = 0; i < a.chain.elements().size(); ++i) {
    const ChainElement& x = a.chain.elements()[i];
    const ChainElement& y = b.chain.elements()[i];
    EXPECT_EQ(x.motion, y.motion) << "element " << i;
    EXPECT_EQ(x.variable, y.variable) << "element " << i;
    EXPECT_EQ(x.value, y.value) << "element " << i;
    EXPECT_EQ(x.name, y.name) << "element " << i;
  }
  EXPECT_EQ(a.chain.num_variables(), b.chain.num_variables());
  ASSERT_EQ(a.axes.size(), b.axes.size());
  for (std::size_t i = 0; i < a.axes.size(); ++i) {
    EXPECT_EQ(a.axes[i].min, b.axes[i].min) << "axis " << i;
    EXPECT_EQ(a.axes[i].max, b.axes[i].max) << "axis " << i;
    EXPECT_EQ(a.axes[i].stiffness, b.axes[i].stiffness) << "axis " << i;
    EXPECT_EQ(a.axes[i].error, b.axes[i].error) << "axis " << i;
    EXPECT_EQ(a.axes[i].mass, b.axes[i].mass) << "axis " << i;
  }
  EXPECT_EQ(a.home, b.home);
  ASSERT_NE(a.module, nullptr);
  ASSERT_NE(b.module, nullptr);
  EXPECT_EQ(a.module->model(), b.module->model());
  EXPECT_EQ(a.module->num_actuators(), b.module->num_actuators());
  EXPECT_EQ(a.module->revolute_actuators(), b.module->revolute_actuators());
  EXPECT_EQ(a.module->envelope_volume(), b.module->envelope_volume());
}

// Written, then read by the strict reader as the file `path`; the design must be the same and
// writing it again the same text.
void expect_round_trip(const HybridDesign& design, const std::string& module_file,
                       const std::string& path) {
  const std::string text = hybrid_design_to_yaml(design, module_file);
  SCOPED_TRACE(path + ":\n" + text);
  HybridDesign again;
  ASSERT_NO_THROW(again = read_hybrid_design(YamlValue::load_string(text, path)));
  expect_same_design(design, again);
  EXPECT_EQ(hybrid_design_to_yaml(again, module_file), text);
}

TEST(HybridMachineFileWriter, ShippedFilesRoundTripExactly) {
  const std::vector<std::string> files = shipped_hybrid_files();
  EXPECT_GE(files.size(), 2u);  // examples/hybrid_long_axis_hexapod.yaml, hybrid_gantry_3prs.yaml
  for (const std::string& path : files) {
    const YamlValue root = YamlValue::load_file(path);
    const HybridDesign design = read_hybrid_design(root);
    // Written next to the original: the module named as the original names it.
    expect_round_trip(design, root.required("parallel").required("file").as_string(), path);
  }
}

TEST(HybridMachineFileWriter, WritesEveryKey) {
  HybridDesign design =
      read_hybrid_design(yaml("model: hybrid\nserial: {code: \"1 2\", range: [[-1, 1], [-1, 1]]}\n"
                              "parallel: {file: hexapod.yaml, home: [0, 0, 0.9]}\n"));
  // Constants of every kind (a rotation whose degrees need more than 12 digits), names that
  // YAML must quote, values without a short decimal form.
  design.chain =
      SerialChain({{.motion = 3, .variable = false, .value = -0.25, .name = ""},
                   {.motion = 1, .variable = true, .value = 0.0, .name = "X"},
                   {.motion = 4, .variable = false, .value = deg_to_rad(30.0), .name = ""},
                   {.motion = 2, .variable = true, .value = 0.0, .name = "Y: \"second\" \\ axis"},
                   {.motion = 6, .variable = false, .value = deg_to_rad(1.0 / 3.0), .name = ""},
                   {.motion = 5, .variable = false, .value = deg_to_rad(-12.5), .name = ""},
                   {.motion = 1, .variable = false, .value = 0.1 + 0.2, .name = ""}});
  design.axes = {{.min = -1.5, .max = 1.0 / 3.0, .stiffness = 1.5e8, .error = 0.0},
                 {.min = 0.0, .max = 0.0, .stiffness = 0.0, .error = 2e-6 / 3.0}};
  design.home = Eigen::Vector3d(0.1, -0.2, 0.9 + 1e-12);
  const std::string text = hybrid_design_to_yaml(design, "hexapod.yaml");
  for (const char* key :
       {"model: hybrid\n", "\n  code: ", "\n  axes: ", "\n  range: ", "\n  stiffness: ",
        "\n  error: ", "\nparallel:\n  file: hexapod.yaml\n", "\n  home: "})
    EXPECT_NE(text.find(key), std::string::npos) << key << " missing in\n" << text;
  EXPECT_NE(text.find("code: \"3:-0.25 1 4:30 2 6:"), std::string::npos) << text;
  EXPECT_NE(text.find("axes: [X, \"Y: \\\"second\\\" \\\\ axis\"]"), std::string::npos) << text;
  expect_round_trip(design, "hexapod.yaml", kExamples + "hybrid_test.yaml");
}

// A module with masses: the axes' masses and the world gravity are written and read back.
TEST(HybridMachineFileWriter, WritesMassesAndGravity) {
  HybridDesign design =
      read_hybrid_design(yaml("model: hybrid\nserial: {code: \"1 2\", range: [[-1, 1], [-1, 1]]}\n"
                              "parallel: {file: hexapod_masses.yaml, home: [0, 0, 0.9]}\n"));
  design.axes[0].mass = 120.0 / 7.0;
  design.axes[1].mass = 0.0;
  design.gravity = {0.1, 0.0, -9.80665};
  const std::string text = hybrid_design_to_yaml(design, "hexapod_masses.yaml");
  EXPECT_NE(text.find("\n  mass: ["), std::string::npos) << text;
  EXPECT_NE(text.find("\ngravity: [0.1, 0, -9.80665]\n"), std::string::npos) << text;
  expect_round_trip(design, "hexapod_masses.yaml", kExamples + "hybrid_test.yaml");
  HybridDesign again =
      read_hybrid_design(YamlValue::load_string(text, kExamples + "hybrid_test.yaml"));
  EXPECT_EQ(again.gravity, design.gravity);
}

TEST(HybridMachineFileWriter, LeavesDefaultsOut) {
  const HybridDesign design =
      read_hybrid_design(yaml("model: hybrid\nserial: {code: \"1\", range: [[-1, 1]]}\n"
                              "parallel: {file: hexapod.yaml, home: [0, 0, 0.9]}\n"));
  // No axis names, all axes rigid and exact: axes, stiffness and error are left out.
  EXPECT_EQ(hybrid_design_to_yaml(design, "hexapod.yaml"),
            "model: hybrid\nserial:\n  code: \"1\"\n  range: [[-1, 1]]\n"
            "parallel:\n  file: hexapod.yaml\n  home: [0, 0, 0.9]\n");
  expect_round_trip(design, "hexapod.yaml", kExamples + "hybrid_test.yaml");
}

TEST(HybridMachineFileWriter, ModuleFileIsResolvedFromTheWrittenFile) {
  const std::string example = kExamples + "hybrid_gantry_3prs.yaml";
  const HybridDesign design = read_hybrid_design(YamlValue::load_file(example));
  // A file written to another directory names the module relative to that directory ...
  const std::filesystem::path elsewhere =
      std::filesystem::path(PKMOPT_SOURCE_DIR) / "tests" / "io" / "written.yaml";
  const std::string relative =
      std::filesystem::relative(kExamples + "tripod_3prs.yaml", elsewhere.parent_path()).string();
  EXPECT_EQ(relative, "../../examples/tripod_3prs.yaml");
  expect_round_trip(design, relative, elsewhere.string());
  // ... or absolutely; the original's relative name does not resolve from there.
  const std::string absolute = std::filesystem::absolute(kExamples + "tripod_3prs.yaml").string();
  expect_round_trip(design, absolute, "/nonexistent/written.yaml");
  EXPECT_THROW((void)read_hybrid_design(YamlValue::load_string(
                   hybrid_design_to_yaml(design, "tripod_3prs.yaml"), elsewhere.string())),
               InputError);
}

TEST(HybridMachineFileWriter, InlineModuleReadsAsItsFile) {
  // The module written inside the hybrid's file (parallel.machine) gives the same machine as the
  // module file it copies, at every pose; the writer's inline form reads back to the same design.
  const std::string example = kExamples + "hybrid_gantry_3prs.yaml";
  const HybridDesign from_file = read_hybrid_design(YamlValue::load_file(example));
  std::ifstream module_in(kExamples + "tripod_3prs.yaml");
  std::stringstream module_text;
  module_text << module_in.rdbuf();
  const std::string text = hybrid_design_to_yaml(from_file, "", module_text.str());
  EXPECT_NE(text.find("parallel:\n  machine:\n    model: tripod_3prs\n"), std::string::npos)
      << text;
  EXPECT_EQ(text.find("file:"), std::string::npos) << text;
  const HybridDesign inline_design =
      read_hybrid_design(YamlValue::load_string(text, "/nowhere/inline.yaml"));
  expect_same_design(from_file, inline_design);
  const HybridMachine a(from_file), b(inline_design);
  auto da = a.make_data(), db = b.make_data();
  int reached = 0;
  for (const Pose& pose : {Pose{{0.1, -0.2, 1.15}, {0.05, -0.08, 0}},
                           Pose{{-0.4, 0.3, 1.25}, {-0.1, 0.0, 0}}}) {
    PoseMetrics ma, mb;
    a.analyze(*da, pose, Wrench::Zero(), ma);
    b.analyze(*db, pose, Wrench::Zero(), mb);
    EXPECT_EQ(ma.reachable, mb.reachable);
    reached += ma.reachable ? 1 : 0;
    EXPECT_EQ(ma.q, mb.q);
    EXPECT_EQ(ma.stiffness_min, mb.stiffness_min);
  }
  EXPECT_EQ(reached, 2);
  // Exactly one of file and machine; an inline serial or hybrid module is refused.
  auto error = [](const std::string& t) {
    try {
      (void)read_hybrid_design(YamlValue::load_string(t, "h.yaml"));
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  const std::string head = "model: hybrid\nserial: {code: \"1\", range: [[-1, 1]]}\n";
  EXPECT_NE(error(head + "parallel: {home: [0, 0, 1]}\n")
                .find("parallel: expected exactly one of file (the module's machine file) and "
                      "machine (the module inline), found neither"),
            std::string::npos);
  EXPECT_NE(error(head + "parallel: {file: a.yaml, machine: {model: hexapod}, home: [0, 0, 1]}\n")
                .find("found both"),
            std::string::npos);
  EXPECT_NE(error(head + "parallel: {machine: {model: serial, code: \"1\"}, home: [0, 0, 1]}\n")
                .find("parallel.machine: expected a parallel machine file, found the inline module "
                      "(model: serial)"),
            std::string::npos)
      << error(head + "parallel: {machine: {model: serial, code: \"1\"}, home: [0, 0, 1]}\n");
}

}  // namespace
}  // namespace pkmopt
