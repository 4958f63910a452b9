// Tests of io/model_registry: the built-in models, lookups and their messages, registering a
// model of one's own, and the docs tables every model's field list generates.
#include "io/model_registry.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "io/input_error.hpp"
#include "io/machine_description.hpp"
#include "io/machine_file.hpp"
#include "models/hexapod.hpp"

namespace pkmopt {
namespace {

std::vector<std::string> names() {
  std::vector<std::string> out;
  for (const ModelEntry* entry : registered_models()) out.push_back(entry->name);
  return out;
}

std::string message_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(ModelRegistry, HoldsTheBuiltInModelsInOrder) {
  EXPECT_EQ(names(), (std::vector<std::string>{"hexapod", "delta", "linear_delta", "hexaglide",
                                               "tripod_3prs", "leg_chain", "lathe_16k20f3",
                                               "hybrid", "serial"}));
  // Serial axes are described, not computed: they have no machine.
  EXPECT_EQ(machine_model_names(),
            "hexapod, delta, linear_delta, hexaglide, tripod_3prs, leg_chain, lathe_16k20f3, "
            "hybrid");
  EXPECT_EQ(find_model("serial")->load, nullptr);
  EXPECT_EQ(find_model("tetrapod"), nullptr);
}

TEST(ModelRegistry, AnUnknownOrUncomputableModelIsRefusedAtItsValue) {
  const std::string unknown =
      message_of([] { (void)load_machine(YamlValue::load_string("model: tetrapod\n", "m.yaml")); });
  EXPECT_EQ(unknown,
            "m.yaml:1:8: model: expected a known model (hexapod, delta, linear_delta, hexaglide, "
            "tripod_3prs, leg_chain, lathe_16k20f3, hybrid), found 'tetrapod'");
  const std::string serial = message_of([] {
    (void)load_machine(YamlValue::load_string("model: serial\ncode: \"123\"\n", "s.yaml"));
  });
  EXPECT_NE(serial.find("s.yaml:1:8: model: expected a known model ("), std::string::npos)
      << serial;
}

// A model registered by a program is found by every lookup for as long as its registration
// lives: loading, describing and the list in messages.
TEST(ModelRegistry, ARegisteredModelIsUsedByTheOrdinaryPathsWhileItLives) {
  const std::string text =
      "model: twin_hexapod\nbase: {radius: 0.6, pair_separation_deg: 20}\n"
      "platform: {radius: 0.25, pair_separation_deg: 20}\n"
      "legs: {min_length: 0.7, max_length: 1.15, axial_stiffness: 2.0e8}\n";
  {
    ModelEntry entry;
    entry.name = "twin_hexapod";
    entry.load = [](const YamlValue& root) -> std::unique_ptr<Machine> {
      // The hexapod's reader, with this model's name in place of its own.
      YAML::Node node = YAML::Clone(root.node());
      node["model"] = "hexapod";
      return std::make_unique<Hexapod>(read_hexapod_design(
          YamlValue(node, std::make_shared<const std::string>(root.file()), "")));
    };
    entry.platform_dofs = [](const YamlValue&) { return PlatformDofs{3, 3}; };
    const ModelRegistration registration(std::move(entry));
    EXPECT_EQ(names().back(), "twin_hexapod");
    EXPECT_NE(machine_model_names().find(", twin_hexapod"), std::string::npos);
    const auto machine = load_machine(YamlValue::load_string(text, "twin.yaml"));
    EXPECT_EQ(machine->num_actuators(), 6);
    const MachineDescription d = describe_machine(YamlValue::load_string(text, "twin.yaml"));
    EXPECT_EQ(d.model, "twin_hexapod");
    EXPECT_EQ(d.translations + d.rotations, 6);
    EXPECT_EQ(d.parallel_drives, 6);
    // One name, one model.
    ModelEntry again;
    again.name = "twin_hexapod";
    EXPECT_THROW(ModelRegistration{std::move(again)}, std::invalid_argument);
  }
  EXPECT_EQ(find_model("twin_hexapod"), nullptr);
  EXPECT_NE(message_of([&] { (void)load_machine(YamlValue::load_string(text, "twin.yaml")); }), "");
}

TEST(ModelRegistry, ARegistrationNeedsANameAndADescription) {
  EXPECT_THROW(ModelRegistration{ModelEntry{}}, std::invalid_argument);
  ModelEntry undescribed;
  undescribed.name = "undescribed";
  undescribed.load = [](const YamlValue&) -> std::unique_ptr<Machine> { return nullptr; };
  EXPECT_THROW(ModelRegistration{std::move(undescribed)}, std::invalid_argument);
}

// Every model's machine-file table is in the documentation exactly as its field list generates
// it (README.md or a page of docs/); the failure message shows the block to paste.
TEST(ModelRegistry, EveryModelsDocsTableMatchesItsFieldList) {
  std::string docs;
  const std::filesystem::path root(PKMOPT_SOURCE_DIR);
  std::vector<std::filesystem::path> files = {root / "README.md"};
  for (const auto& f : std::filesystem::directory_iterator(root / "docs"))
    if (f.path().extension() == ".md") files.push_back(f.path());
  for (const auto& f : files) {
    std::ifstream in(f);
    std::stringstream text;
    text << in.rdbuf();
    docs += text.str();
  }
  int tables = 0;
  for (const ModelEntry* entry : registered_models()) {
    if (!entry->fields_markdown) continue;
    const std::string block =
        "<!-- fields: " + entry->name + " -->\n" + entry->fields_markdown() + "<!-- /fields -->\n";
    EXPECT_NE(docs.find(block), std::string::npos)
        << "the docs lack the generated table of " << entry->name << ":\n"
        << block;
    ++tables;
  }
  EXPECT_EQ(tables, 8);
}

// Every example machine file names a registered model and loads to a machine of that model.
TEST(ModelRegistry, EveryExampleMachineFileLoadsThroughItsModel) {
  for (const auto& f :
       std::filesystem::directory_iterator(std::filesystem::path(PKMOPT_SOURCE_DIR) / "examples")) {
    if (f.path().extension() != ".yaml") continue;
    const YamlValue root = YamlValue::load_file(f.path().string());
    const std::string model = root.required("model").as_string();
    const ModelEntry* entry = find_model(model);
    ASSERT_NE(entry, nullptr) << f.path();
    if (!entry->load) continue;
    EXPECT_EQ(load_machine(root)->model(), model) << f.path();
  }
}

}  // namespace
}  // namespace pkmopt
