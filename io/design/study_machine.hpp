// The model's part of a design study: the `machine:` section of a study file, read by the model
// it names (io/machine/model_registry.hpp), and what the study engine then asks of that model.
//
//   machine:
//     model: linear_delta                   # a registered model with a design family
//     parameters: {rod: {min: 0.5, max: 1.0}, stroke: 0.6}   # number = fixed, {min, max} = free
//     rods: {E: 7.0e10, area: 3.0e-5}       # every other key of the model's machine file
//
// A model takes part in design studies in one of two ways (ModelEntry):
//   design_family   a DesignFamily built around a template machine section
//                   (problems/design/machine_design.hpp): `parameters:` takes the family's
//                   parameters,
//                   every other key of the model's machine file may follow except the keys the
//                   parameters set, and the problem is a MachineDesignProblem;
//   study_machine   a reader of its own section (the hexapod: its parameters, a smooth
//                   formulation for gradient solvers, actuator catalogs).
// Either gives a StudyMachine: the parameters in file units, the resolved section, the model's
// capabilities in studies, and the design problem for the study's goals.
//
// Example:
//   const YamlValue study = YamlValue::load_file("studies/library/tripod-z3.yaml");
//   std::unique_ptr<StudyMachine> machine = read_study_machine(study.required("machine"));
//   DesignGoals goals;  // task, objectives, constraints (studies/design_study.cpp reads them)
//   std::unique_ptr<DesignProblem> problem = machine->make_problem(std::move(goals));
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "io/format/yaml_reader.hpp"
#include "problems/design/design_problem.hpp"
#include "problems/design/machine_design.hpp"

namespace pkmopt {

struct ModelEntry;  // io/machine/model_registry.hpp

/// One design parameter of a study in file units (m; degrees for *_deg and unit "deg").
struct StudyParameter {
  std::string name;
  std::string unit;  ///< "m" or "deg"
  double min = 0.0;
  double max = 0.0;  ///< == min when the parameter is fixed
  bool free() const { return min < max; }
};

class StudyMachine {
 public:
  virtual ~StudyMachine() = default;

  /// The model's name (`model:`).
  std::string model;
  /// Every design parameter of the model, in problem order (the free ones are the variables).
  std::vector<StudyParameter> parameters;
  /// The section with every default filled in: "machine:\n  model: NAME\n  ...".
  std::string resolved_yaml;
  /// The platform keeps its orientation: the task must not tilt or turn.
  bool translational = false;

  /// True when the model's problem has a smooth formulation with gradients (Ipopt, NLopt
  /// gradient algorithms, the front builders); false: NSGA-II and derivative-free NLopt only.
  virtual bool smooth_formulation() const { return false; }
  /// Reads a constraint `{actuator: NAME | cheapest, catalog: FILE}` of the study at
  /// `study_path`: adds the rows it implies to `constraints` and returns its resolved YAML line.
  /// A model that chooses no actuators refuses it (InputError at the `actuator` key).
  virtual std::string read_actuator_constraint(const YamlValue& constraint,
                                               const std::string& study_path,
                                               const DesignTask& task,
                                               std::vector<DesignConstraint>& constraints);
  /// The catalog `{actuator: cheapest}` chose from; null when there is none.
  virtual const ActuatorCatalog* actuator_catalog() const { return nullptr; }
  /// True when the catalog prices every drive (each_drive: true).
  virtual bool prices_each_drive() const { return false; }
  /// The design problem for the study's goals. Throws std::invalid_argument naming a field.
  virtual std::unique_ptr<DesignProblem> make_problem(DesignGoals goals) const = 0;
  /// The machine file of a design (every parameter, internal units), for `pkmopt analyze`.
  virtual std::string machine_file(const std::vector<double>& parameters) const = 0;
  /// The design family behind it (design-family models, as a hybrid's module); null for a model
  /// with a reader of its own.
  virtual const DesignFamily* design_family() const { return nullptr; }
};

/// Reads a study's `machine:` section through the model it names. Throws InputError (a model
/// without a design family: "one of hexapod, delta, ... (the models with a design family)").
std::unique_ptr<StudyMachine> read_study_machine(const YamlValue& machine);

/// The docs table of a model's study section: its own (study_machine models, "machine hexapod")
/// or its family's parameters ("machine.parameters delta"). Throws std::invalid_argument for a
/// model without one.
std::string study_machine_fields_markdown(std::string_view model);

/// The StudyMachine of a design-family model (io/design/family_study_machine.cpp).
std::unique_ptr<StudyMachine> read_family_study_machine(const ModelEntry& entry,
                                                        const YamlValue& machine);
/// The StudyMachine of a design family with its parameters (file units) and resolved section
/// (a model whose study section holds another model's, as a hybrid's module).
std::unique_ptr<StudyMachine> make_family_study_machine(std::string model, DesignFamily family,
                                                        std::vector<StudyParameter> parameters,
                                                        std::string resolved_yaml);
/// The docs table of a design family's parameters.
std::string family_parameters_markdown(const DesignFamily& family);

}  // namespace pkmopt
