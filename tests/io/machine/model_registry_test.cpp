// Tests of io/machine/model_registry: the built-in models, lookups and their messages, registering
// a model of one's own, and the docs tables every model's field list generates.
#include "io/machine/model_registry.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "io/format/input_error.hpp"
#include "io/machine/machine_description.hpp"
#include "io/machine/machine_file.hpp"
#include "models/hexapod/hexapod.hpp"

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
                                               "tripod_3prs", "tripod_3rps", "leg_chain",
                                               "lathe_16k20f3", "hybrid", "serial"}));
  EXPECT_EQ(machine_model_names(),
            "hexapod, delta, linear_delta, hexaglide, tripod_3prs, tripod_3rps, leg_chain, "
            "lathe_16k20f3, hybrid, serial");
  EXPECT_NE(find_model("serial")->load, nullptr);
  EXPECT_EQ(find_model("tetrapod"), nullptr);
}

TEST(ModelRegistry, AnUnknownOrUncomputableModelIsRefusedAtItsValue) {
  const std::string unknown =
      message_of([] { (void)load_machine(YamlValue::load_string("model: tetrapod\n", "m.yaml")); });
  EXPECT_EQ(unknown,
            "m.yaml:1:8: model: expected a known model (hexapod, delta, linear_delta, hexaglide, "
            "tripod_3prs, tripod_3rps, leg_chain, lathe_16k20f3, hybrid, serial), found "
            "'tetrapod'");
  // Serial chains other than 5-axis ones are described, not computed: refused at their code.
  const std::string serial = message_of([] {
    (void)load_machine(YamlValue::load_string("model: serial\ncode: \"123\"\n", "s.yaml"));
  });
  EXPECT_EQ(serial,
            "s.yaml:2:7: code: expected a 5-axis chain: two rotary and three linear feed axes "
            "besides the spindle (other chains are for `pkmopt describe` only), found '123' with "
            "0 rotary and 3 linear feed axes");
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
  EXPECT_EQ(tables, 9);
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

// Every design family of the registry writes its designs with its model's writer: the default
// design's file starts with the model's name and reads back to a machine of that model.
TEST(ModelRegistry, EveryRegisteredFamilyWritesItsModelsMachineFile) {
  int families = 0;
  for (const ModelEntry* entry : registered_models()) {
    if (!entry->design_family) continue;
    const DesignFamily family = entry->design_family(nullptr);
    ASSERT_TRUE(family.machine_file) << entry->name;
    const std::string text = family.machine_file(family.default_parameters());
    EXPECT_EQ(text.substr(0, text.find('\n')), "model: " + entry->name);
    EXPECT_EQ(load_machine(YamlValue::load_string(text, entry->name + ".yaml"))->model(),
              entry->name);
    ++families;
  }
  EXPECT_EQ(families, 7);  // delta, linear_delta, hexaglide, tripod_3prs, tripod_3rps, lathe,
                           // serial
}

// The registry is the one list of models: outside a model's own files (whose paths name its folder
// or family) and the registry, no source names a model. A file names a model when its code (not
// its comments) holds the model's name as a string literal. A new model is added to `own` below.
TEST(ModelRegistry, NoSourceOutsideAModelsOwnFilesNamesAModel) {
  // The path fragments of each built-in model's own files: its folder under models/, and the
  // files of io/ and problems/ named after it.
  const std::map<std::string, std::vector<std::string>> own = {
      {"hexapod", {"hexapod"}},
      {"delta", {"leg_chain"}},
      {"linear_delta", {"leg_chain"}},
      {"hexaglide", {"leg_chain"}},
      {"tripod_3prs", {"leg_chain"}},
      {"tripod_3rps", {"leg_chain"}},
      {"leg_chain", {"leg_chain"}},
      {"lathe_16k20f3", {"lathe"}},
      {"hybrid", {"hybrid"}},
      // A hybrid machine's file has a `serial` section: the axes that carry its module.
      {"serial", {"serial", "hybrid"}}};
  std::vector<std::string> listed;
  for (const auto& [name, fragments] : own) listed.push_back(name);
  std::vector<std::string> registered = names();
  std::sort(registered.begin(), registered.end());
  ASSERT_EQ(listed, registered) << "every registered model needs its own files listed here";
  // "hybrid" is also the name of a front builder (optimizer/hybrid.hpp), not of a machine there.
  const std::vector<std::pair<std::string, std::string>> other_meaning = {
      {"hybrid", "optimizer/"}, {"hybrid", "studies/optimizer_"}};

  namespace fs = std::filesystem;
  const fs::path root(PKMOPT_SOURCE_DIR);
  int files = 0;
  std::vector<std::string> found;
  for (const char* layer : {"models", "optimizer", "problems", "io", "report", "studies", "app",
                            "python/src", "fuzz"}) {
    for (const auto& item : fs::recursive_directory_iterator(root / layer)) {
      const std::string ext = item.path().extension().string();
      if (ext != ".cpp" && ext != ".hpp" && ext != ".inc") continue;
      const std::string path = fs::relative(item.path(), root).generic_string();
      if (path.starts_with("io/machine/model_registry.")) continue;
      std::ifstream in(item.path());
      std::stringstream text;
      text << in.rdbuf();
      // The code without its comments (a "//" inside a string literal ends nothing here: none
      // of the sources has one before a model name).
      std::string code;
      std::istringstream lines(text.str());
      for (std::string line; std::getline(lines, line);)
        code += line.substr(0, line.find("//")) + "\n";
      ++files;
      for (const auto& [name, fragments] : own) {
        if (code.find("\"" + name + "\"") == std::string::npos) continue;
        bool allowed = false;
        for (const std::string& fragment : fragments)
          allowed = allowed || path.find(fragment) != std::string::npos;
        for (const auto& [other, prefix] : other_meaning)
          allowed = allowed || (other == name && path.starts_with(prefix));
        if (!allowed) found.push_back(path + " names \"" + name + "\"");
      }
    }
  }
  EXPECT_GT(files, 200);
  EXPECT_TRUE(found.empty()) << ::testing::PrintToString(found);
}

}  // namespace
}  // namespace pkmopt
