#include "io/machine/machine_file_hybrid.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>

#include "io/design/hybrid_study_machine.hpp"
#include "io/format/csv.hpp"
#include "io/format/field_list.hpp"
#include "io/machine/machine_description.hpp"
#include "io/machine/machine_file.hpp"
#include "io/machine/machine_file_serial.hpp"
#include "io/machine/model_registry.hpp"

namespace pkmopt {
namespace {

// The serial section's keys; range, stiffness and error have one entry per element of
// design.axes (sized from the code, which is read by hand with the axis names).
template <class Fields>
void describe_serial(Fields& g, HybridDesign& d) {
  g.note("code", "a coordinate code", "m, deg", "required",
         "the serial chain: variable elements 1, 2, 3 (translations) only; constants \"k:v\" "
         "(m for 1..3, degrees for 4..6)");
  g.note("axes", "distinct names, one per variable axis", "", "none", "names of the variable axes");
  std::vector<FieldRange> ranges;
  FieldColumn stiffness;
  FieldColumn error;
  FieldColumn mass;
  for (HybridAxis& a : d.axes) {
    ranges.push_back({.low = a.min, .high = a.max, .closed = true, .found_values = true});
    stiffness.members.push_back(&a.stiffness);
    error.members.push_back(&a.error);
    mass.members.push_back(&a.mass);
  }
  g.field("range", ranges,
          {.required = true,
           .unit = "m",
           .expected = "[min, max] with min <= max (m)",
           .doc = "travel of each variable axis ([0, 0]: a fixed axis)"});
  // The writer leaves a list out when every axis has the default 0.
  auto all_zero = [&d](double HybridAxis::*member) {
    return [&d, member] {
      return std::all_of(d.axes.begin(), d.axes.end(),
                         [member](const HybridAxis& a) { return a.*member == 0.0; });
    };
  };
  g.field("stiffness", stiffness,
          {.min = 0,
           .unit = "N/m",
           .default_text = "all 0 (rigid)",
           .doc = "axial stiffness of each axis drive, one per axis (0: rigid)",
           .omit_when = all_zero(&HybridAxis::stiffness)});
  g.field("error", error,
          {.min = 0,
           .unit = "m",
           .default_text = "all 0 (exact)",
           .doc = "positioning error half-width of each axis, one per axis",
           .omit_when = all_zero(&HybridAxis::error)});
  g.field("mass", mass,
          {.min = 0,
           .unit = "kg",
           .default_text = "all 0 (massless)",
           .doc = "the mass each axis moves on its own (its carriage; the axes it carries and "
                  "the module count separately), one per axis; used when the module has masses "
                  "(docs/dynamics.md)",
           .omit_when = all_zero(&HybridAxis::mass)});
}

template <class Fields>
void describe_parallel(Fields& g, HybridDesign& d) {
  g.note("file", "a machine file", "", "required (or machine)",
         "the module's machine file, relative to this file (not serial or hybrid, prismatic "
         "drives)");
  g.note("machine", "a map", "", "none",
         "the module's machine file written inline (its keys as in its own file), instead of "
         "file");
  g.field(
      "home", d.home,
      {.required = true, .unit = "m", .doc = "module-local reference point h of the follow rule"});
}

template <class Fields>
void describe_fields(Fields& f, HybridDesign& d) {
  f.note("model", "hybrid", "", "required", "the machine model");
  f.note("name", "a text", "", "none", "free text");
  f.note("description", "a text", "", "none", "free text");
  f.section("serial", {.required = true, .doc = "the serial axes carrying the module"},
            [&](auto& g) { describe_serial(g, d); });
  f.section("parallel", {.required = true, .doc = "the parallel module"},
            [&](auto& g) { describe_parallel(g, d); });
  f.field("gravity", d.gravity,
          {.unit = "m/s²",
           .default_text = "[0, 0, -9.81]",
           .doc = "world frame, for the dynamics when the module has masses (the module file's "
                  "own gravity is not used)",
           .omit_when = [&d] { return d.gravity == Eigen::Vector3d(0, 0, -9.81); }});
}

template <class Describe>
void check_keys_of(const YamlValue& map, Describe&& describe) {
  FieldKeys keys;
  describe(keys);
  map.check_keys(keys.keys);
}

}  // namespace

// A module's machine file (its root map): refused when it is not a parallel machine. A hybrid or
// serial module (this file itself, say) is refused before anything reads it further, so a file
// naming itself cannot recurse.
YamlValue checked_module(YamlValue module_root, const YamlValue& where, const std::string& what) {
  module_root.expect_map();
  const std::string module_model = module_root.required("model").as_string();
  // Parallel machines are the models with a platform (ModelEntry::platform_dofs).
  const ModelEntry* entry = find_model(module_model);
  if (entry != nullptr && !entry->platform_dofs)
    where.fail("a parallel machine file", what + " (model: " + module_model + ")");
  return module_root;
}

YamlValue read_hybrid_module_file(const YamlValue& file, const std::string& hybrid_file) {
  const std::filesystem::path module =
      std::filesystem::path(hybrid_file).parent_path() / file.as_string();
  std::error_code error;
  if (!std::filesystem::is_regular_file(module, error)) {
    file.fail("an existing machine file",
              "'" + module.string() + "' (" +
                  (error && error != std::errc::no_such_file_or_directory ? error.message()
                                                                          : "no such file") +
                  ")");
  }
  return checked_module(YamlValue::load_file(module.string()), file, "'" + module.string() + "'");
}

YamlValue read_hybrid_module(const YamlValue& parallel, const std::string& hybrid_file) {
  const bool file = parallel.has("file"), inline_machine = parallel.has("machine");
  if (file == inline_machine)
    parallel.fail("exactly one of file (the module's machine file) and machine (the module inline)",
                  file ? "both" : "neither");
  if (file) return read_hybrid_module_file(parallel.required("file"), hybrid_file);
  const YamlValue machine = parallel.required("machine");
  return checked_module(machine, machine, "the inline module");
}

HybridDesign read_hybrid_design(const YamlValue& root) {
  HybridDesign design;
  check_keys_of(root, [&](auto& keys) { describe_fields(keys, design); });

  const YamlValue serial = root.required("serial");
  check_keys_of(serial, [&](auto& keys) { describe_serial(keys, design); });
  const YamlValue code = serial.required("code");
  design.chain = chain_of_code(code);
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
  {
    FieldReader reader(serial);  // range, stiffness, error: one entry per axis
    describe_serial(reader, design);
  }

  const YamlValue parallel = root.required("parallel");
  check_keys_of(parallel, [&](auto& keys) { describe_parallel(keys, design); });
  const YamlValue module_root = read_hybrid_module(parallel, root.file());
  design.module = load_machine(module_root);
  if (design.module->revolute_actuators()) {
    parallel.required(parallel.has("file") ? "file" : "machine")
        .fail(
            "a parallel machine with prismatic actuators (revolute drives would mix degrees "
            "with the axes' metres in q)",
            "'" + module_root.file() + "' (model: " + module_root.required("model").as_string() +
                ", revolute drives)");
  }
  {
    FieldReader reader(parallel);  // home
    describe_parallel(reader, design);
  }
  if (const auto gravity = root.optional("gravity")) {  // by hand: the one top-level number list
    if (!design.module->dynamics()) {
      gravity->fail("gravity only with a module that has masses",
                    "gravity and a module without masses");
    }
    const std::vector<YamlValue> g = gravity->elements(3);
    for (int k = 0; k < 3; ++k) design.gravity(k) = g[static_cast<std::size_t>(k)].as_double();
  }

  try {
    HybridMachine check(design);  // the constructor's own checks (dependent axes, ...)
  } catch (const std::invalid_argument& e) {
    code.fail(e.what());
  }
  return design;
}

void check_hybrid_numbers(const YamlValue& root, int num_variables) {
  HybridDesign design;
  design.axes.resize(static_cast<std::size_t>(std::max(num_variables, 0)));
  {
    FieldReader reader(root.required("serial"));
    describe_serial(reader, design);
  }
  {
    FieldReader reader(root.required("parallel"));
    describe_parallel(reader, design);
  }
  if (const auto gravity = root.optional("gravity"))
    for (const YamlValue& g : gravity->elements(3)) (void)g.as_double();
}

std::unique_ptr<Machine> load_hybrid_machine(const YamlValue& root) {
  return std::make_unique<HybridMachine>(read_hybrid_design(root));
}

std::string hybrid_design_to_yaml(const HybridDesign& design, const std::string& module_file,
                                  const std::string& module_yaml) {
  HybridDesign copy = design;
  std::string out = "model: hybrid\nserial:\n";
  // By hand, as the reader takes them: the code (with the constants), the axis names.
  out += "  code: \"" + serial_code_text(copy.chain) + "\"\n";
  std::string names;
  bool named = false;
  for (const ChainElement& e : copy.chain.elements()) {
    if (!e.variable) continue;
    names += (names.empty() ? "" : ", ") + yaml_scalar(e.name);
    named = named || !e.name.empty();
  }
  if (named) out += "  axes: [" + names + "]\n";
  FieldWriter serial;  // range, stiffness, error
  describe_serial(serial, copy);
  out += serial.block(2);
  if (module_yaml.empty()) {
    out += "parallel:\n  file: " + yaml_scalar(module_file) + "\n";  // by hand
  } else {
    out += "parallel:\n  machine:\n";  // the module's file, inline
    std::istringstream lines(module_yaml);
    for (std::string line; std::getline(lines, line);)
      if (!line.empty() && line[0] != '#') out += "    " + line + "\n";
  }
  FieldWriter parallel;  // home
  describe_parallel(parallel, copy);
  out += parallel.block(2);
  if (copy.gravity != Eigen::Vector3d(0, 0, -9.81)) {
    out += "gravity: [" + format_number(copy.gravity(0)) + ", " + format_number(copy.gravity(1)) +
           ", " + format_number(copy.gravity(2)) + "]\n";
  }
  return out;
}

std::string hybrid_machine_fields_markdown() {
  FieldDocs docs;
  HybridDesign design;
  describe_fields(docs, design);
  return docs.markdown();
}

namespace {

// `pkmopt describe`: the serial axes, then the parallel module's degrees of freedom and drives.
void describe_hybrid(const YamlValue& root, MachineDescription& d) {
  root.check_keys({"model", "name", "description", "serial", "parallel", "gravity"});
  const YamlValue serial = root.required("serial");
  serial.check_keys({"code", "axes", "range", "stiffness", "error", "mass"});
  const int axes = describe_serial_axes(serial, false, d);
  // The numbers by the rules `analyze` reads them with: one reader, one verdict.
  check_hybrid_numbers(root, axes);
  const YamlValue parallel = root.required("parallel");
  parallel.check_keys({"file", "machine", "home"});
  const YamlValue module_root = read_hybrid_module(parallel, root.file());
  const MachineDescription inner = describe_machine(module_root);
  d.translations += inner.translations;
  d.rotations += inner.rotations;
  d.parallel_drives = inner.parallel_drives;
  d.details.push_back(fmt::format("parallel: {} ({})", inner.model,
                                  parallel.has("file") ? module_root.file() : "inline"));
}

// Architecture synthesis: serial axes carrying each parallel structure with prismatic drives,
// ball-screw axes of 1.5e8 N/m and 5 um travelling +- the task's size, the module working about
// its own task place (the follow rule's home):
//   xy_NAME  an X/Y gantry carrying a structure that cannot move its tool along x and y (a 3-PRS
//            head: the Sprint Z3 on a gantry);
//   x_NAME   a long X axis carrying a structure that can (a hexapod on a long axis, P1З6): the
//            module then covers less of the task along x.
// No masses: the carriages' are not assumed, and a head with parasitic motion takes none on
// moving axes.
std::vector<SynthesisTemplate> hybrid_synthesis(const SynthesisScale& scale) {
  std::vector<SynthesisTemplate> out;
  SynthesisScale module_scale = scale;
  module_scale.masses = false;
  const double travel = std::max(scale.size, 0.1);
  for (const ModelEntry* module : registered_models()) {
    if (module->name == "hybrid" || !module->synthesis || !module->platform_dofs ||
        !module->design_family)
      continue;
    // A module's drives must be prismatic (the hybrid model's rule): its family's default design
    // says so for every design of the family.
    const DesignFamily family = module->design_family(nullptr);
    if (family.build(family.default_parameters())->any_revolute_actuator()) continue;
    for (const SynthesisTemplate& head : module->synthesis(module_scale)) {
      const YamlValue section = YamlValue::load_string(head.machine_yaml, head.name);
      const bool gantry = module->platform_dofs(section).translations < 2;
      SynthesisTemplate t;
      t.name = (gantry ? "xy_" : "x_") + head.name;
      t.structure =
          (gantry ? "X/Y gantry carrying a " : "long X axis carrying a ") + head.structure;
      t.task_centre = head.task_centre;
      t.machine_yaml =
          gantry ? fmt::format(
                       "model: hybrid\n"
                       "serial: {{code: \"12\", axes: [X, Y], range: [[{0:.4g}, {1:.4g}], "
                       "[{0:.4g}, {1:.4g}]], stiffness: [1.5e8, 1.5e8], error: [5.0e-6, "
                       "5.0e-6]}}\n",
                       -travel, travel)
                 : fmt::format(
                       "model: hybrid\n"
                       "serial: {{code: \"1\", axes: [X], range: [[{:.4g}, {:.4g}]], "
                       "stiffness: [1.5e8], error: [5.0e-6]}}\n",
                       -travel, travel);
      t.machine_yaml += fmt::format(
          "parallel:\n"
          "  home: [{:.4g}, {:.4g}, {:.4g}]\n"
          "  machine:\n",
          head.task_centre[0], head.task_centre[1], head.task_centre[2]);
      std::istringstream lines(head.machine_yaml);
      for (std::string line; std::getline(lines, line);) t.machine_yaml += "    " + line + "\n";
      out.push_back(std::move(t));
    }
  }
  return out;
}

}  // namespace

ModelEntry hybrid_model_entry() {
  ModelEntry entry;
  entry.name = "hybrid";
  entry.load = load_hybrid_machine;
  entry.fields_markdown = hybrid_machine_fields_markdown;
  entry.describe = describe_hybrid;
  entry.study_machine = read_hybrid_study_machine;
  entry.study_fields_markdown = hybrid_study_machine_markdown;
  entry.synthesis = hybrid_synthesis;
  return entry;
}

}  // namespace pkmopt
