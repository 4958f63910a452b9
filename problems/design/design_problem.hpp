// What every design problem offers the study engine, whatever machine it designs.
//
// A design problem turns a vector of free design parameters into a machine, measures it over a
// task and presents [objectives | inequality constraints] to the optimizers through the problem
// interface (optimizer/problem.hpp). The study engine (result files, journal, reports) needs a
// little more, the same for every model:
//   task(), objectives(), constraints(), require_reachable()   the goals it was built from
//   aggregate()          true when fitness has one row per objective, constraint and the
//                        reachability row (the derivative-free formulation); false for a smooth
//                        formulation whose rows are per pose (its gradient is then a capability:
//                        Problem::has_gradient)
//   free_parameters()    the indices of the free parameters among all of the model's design
//                        parameters, in variable order
//   design_parameters(x) every design parameter (internal units: m, rad) of a variable vector
//   home_height(p)       the task's lift along base z (m) of a parameter vector
//   measure(x)           the metrics of a design, its aggregate rows and why it failed, if it did
//   actuator_catalog()   the catalog the legs' actuators are chosen from; null when the problem
//                        chooses none (a capability of hexapod problems)
//
// The models' problems implement it: HexapodDesignProblem (problems/design/hexapod_design.hpp, with
// its smooth formulation and SIMD batch evaluation) and MachineDesignProblem
// (problems/design/machine_design.hpp, any design family).
//
// Example:
//   const DesignProblem& problem = *study.problem;
//   const DesignRecord record = problem.measure(x);
//   if (record.ok()) std::cout << record.metrics[int(DesignMetric::stiffness_min)] << " N/m\n";
#pragma once

#include <string>
#include <vector>

#include "optimizer/problem.hpp"
#include "problems/design/actuator_catalog.hpp"
#include "problems/design/design_metrics.hpp"

namespace pkmopt {

enum class DesignFormulation { aggregate, smooth };

/// The goals a design problem is built from (the part of a study that is the same for every
/// model).
struct DesignGoals {
  std::string name = "design";
  DesignTask task;
  std::vector<DesignObjective> objectives;
  std::vector<DesignConstraint> constraints;
  bool require_reachable = true;
  DesignFormulation formulation = DesignFormulation::aggregate;
};

/// One measured design.
struct DesignRecord {
  std::vector<double> parameters;  ///< every design parameter, internal units
  double home_height = 0.0;        ///< m
  DesignMetrics metrics{};         ///< by DesignMetric; only the needed ones
  /// The aggregate rows [objectives | constraints | reachability] (kFailurePenalty when failed).
  std::vector<double> aggregate;
  std::string failure;  ///< empty when the evaluation succeeded
  /// With an actuator catalog: the chosen entry's index, -1 when none carries the legs.
  int actuator = -1;
  /// With a catalog pricing every drive: each group's entry in words (drive_choice_text).
  std::string drives;
  bool ok() const { return failure.empty(); }
};

class DesignProblem : public Problem {
 public:
  virtual const DesignTask& task() const = 0;
  virtual const std::vector<DesignObjective>& objectives() const = 0;
  virtual const std::vector<DesignConstraint>& constraints() const = 0;
  virtual bool require_reachable() const = 0;
  virtual bool aggregate() const = 0;
  virtual const std::vector<int>& free_parameters() const = 0;
  virtual std::vector<double> design_parameters(const std::vector<double>& x) const = 0;
  virtual double home_height(const std::vector<double>& parameters) const = 0;
  virtual DesignRecord measure(const std::vector<double>& x) const = 0;
  virtual const ActuatorCatalog* actuator_catalog() const { return nullptr; }
  /// True when the catalog prices every drive (drive_cost, drive_overload) instead of choosing
  /// one entry for the legs (actuator_cost, the per-design entry of the outputs).
  virtual bool prices_each_drive() const { return false; }
};

}  // namespace pkmopt
