// The model registry: the one list of machine models.
//
// Every machine model registers once, with what the rest of pkmopt needs to know about it:
//   name            the `model:` value of its machine files ("hexapod", "delta", ...)
//   load            its machine file (a parsed YAML map) -> a Machine; strict, throws InputError
//                   naming file, line, column and key. Empty for a model that is described but
//                   not computed
//   fields_markdown the docs table of its machine file's keys (docs/machines.md), from the same
//                   field list its reader and writer use (io/format/field_list.hpp)
//   platform_dofs   the platform's degrees of freedom {translations, rotations} of a file, for
//                   `pkmopt describe`
//   describe        a description of its own (serial axes, hybrids); empty: the default one,
//                   platform_dofs and the actuators of the loaded machine
//   design_family or study_machine   how it takes part in design studies
//   (io/design/study_machine.hpp)
//   synthesis       the candidate structures it offers an architecture synthesis, with design
//                   spaces scaled from the task (studies/synthesis_study.hpp)
// Commands, the study engine, the Python package and the docs tables find models here; a
// model's own files (its machine, its field list, its design family) hold everything else
// about it, and no other file names it.
//
// The registry lives in io/ because an entry carries its file reader and docs table; the layers
// below (models/, problems/) know machines and design families, not their names in files.
//
// The built-in models are registered by io/machine/model_registry.cpp. A program (or a test) may
// add its own for as long as a ModelRegistration lives:
//
//   ModelEntry entry;
//   entry.name = "planar_3rpr";
//   entry.load = [](const YamlValue& root) { return std::make_unique<Planar3Rpr>(read(root)); };
//   entry.platform_dofs = [](const YamlValue&) { return PlatformDofs{2, 1}; };
//   const ModelRegistration registration(std::move(entry));
//   std::unique_ptr<Machine> m = load_machine(YamlValue::load_file("rpr.yaml"));
#pragma once

#include <array>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "io/format/yaml_reader.hpp"
#include "models/core/machine.hpp"
#include "problems/design/machine_design.hpp"

namespace pkmopt {

struct MachineDescription;  // io/machine/machine_description.hpp
class StudyMachine;         // io/design/study_machine.hpp

/// The degrees of freedom of a machine's platform (or tool) relative to its base.
struct PlatformDofs {
  int translations = 0;
  int rotations = 0;
};

/// The size of a task an architecture synthesis dimensions machines for
/// (studies/synthesis_study.hpp).
struct SynthesisScale {
  double size = 0.3;      ///< the task region's largest edge (box) or diameter (cylinder), m
  double height = 0.2;    ///< its extent along z, m
  double tilt_deg = 0.0;  ///< the tool's tilt cone
  double yaw_deg = 0.0;   ///< the yaw range (+-)
  /// The study measures a metric that needs masses (natural_frequency_min, moving_mass): the
  /// templates of models that take a mass model give one (synthesis_masses_yaml).
  bool masses = false;
};

/// A leg body of a synthesis template's mass model: its `masses.legs` key, its mass and length
/// (a link: its centre of mass halfway, a thin rod's inertia m l^2 / 12; length 0: a carriage,
/// mass only).
struct SynthesisBody {
  std::string key;      ///< cylinder, rod, carriage, link, crank
  double mass = 0.0;    ///< kg
  double length = 0.0;  ///< m (0 for a carriage)
};

/// A steel link (7850 kg/m^3) of cross-section `area` (m^2) and `length` (m).
SynthesisBody steel_link(std::string key, double area, double length);

/// The `masses:` section every synthesis template of a model with a mass model shares (empty
/// unless scale.masses): a 40 kg platform with its spindle (inertia 0.8, 0.8, 0.5 kg*m^2 about
/// its centre, which is the platform's origin) whatever the structure, and the legs' bodies.
std::string synthesis_masses_yaml(const SynthesisScale& scale,
                                  const std::vector<SynthesisBody>& legs);

/// A candidate structure a model offers an architecture synthesis: the study's machine section
/// with a design space scaled from the task, and where the task sits in the model's frame.
struct SynthesisTemplate {
  std::string name;                     ///< the candidate's name ("hexapod", "linear_delta")
  std::string structure;                ///< in words: "Gough–Stewart hexapod (6-UPS)"
  std::string machine_yaml;             ///< the `machine:` section's map, as YAML text
  std::array<double, 3> task_centre{};  ///< m, the task region's centre before home_height
};

/// One model of the registry (see the header comment).
struct ModelEntry {
  std::string name;
  std::function<std::unique_ptr<Machine>(const YamlValue& root)> load;
  std::function<std::string()> fields_markdown;
  std::function<PlatformDofs(const YamlValue& root)> platform_dofs;
  std::function<void(const YamlValue& root, MachineDescription& description)> describe;

  // Design studies (io/design/study_machine.hpp), one of:
  /// the model's design family around a template machine section (null: the defaults); the
  /// family's machine_file writes its designs;
  std::function<DesignFamily(const YamlValue* machine)> design_family;
  /// a reader of its own for a study's `machine:` section, with its docs table.
  std::function<std::unique_ptr<StudyMachine>(const YamlValue& machine)> study_machine;
  std::function<std::string()> study_fields_markdown;

  /// The candidates it offers an architecture synthesis for a task of this size; empty (or
  /// unset) for a model that takes no part in it.
  std::function<std::vector<SynthesisTemplate>(const SynthesisScale&)> synthesis;
};

/// The model named `name`; nullptr when none is registered.
const ModelEntry* find_model(std::string_view name);

/// The model of a machine file's `model:` value that `load` can build; throws InputError at the
/// value otherwise ("a known model (hexapod, delta, ...)").
const ModelEntry& machine_model(const YamlValue& model_value);

/// Every registered model, built-in ones first, in registration order.
std::vector<const ModelEntry*> registered_models();

/// The names of the models with a machine `load`, comma-separated ("hexapod, delta, ...").
std::string machine_model_names();

/// Adds a model for the lifetime of this object (a test's model, a plug-in); throws
/// std::invalid_argument when the name is empty or taken.
class ModelRegistration {
 public:
  explicit ModelRegistration(ModelEntry entry);
  ~ModelRegistration();
  ModelRegistration(const ModelRegistration&) = delete;
  ModelRegistration& operator=(const ModelRegistration&) = delete;

 private:
  std::string name_;
};

// The built-in entries, each defined next to its model's machine-file reader.
ModelEntry hexapod_model_entry();                   // io/machine/machine_file.cpp
std::vector<ModelEntry> leg_chain_model_entries();  // io/machine/machine_file_leg_chain.cpp
ModelEntry lathe_model_entry();                     // io/machine/machine_file_lathe.cpp
ModelEntry hybrid_model_entry();                    // io/machine/machine_file_hybrid.cpp
ModelEntry serial_model_entry();                    // io/machine/machine_file_serial.cpp

}  // namespace pkmopt
