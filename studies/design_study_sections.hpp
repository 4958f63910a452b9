// The sections of a design study file, read one function each (studies/design_study.hpp has the
// schema and load_design_study, which calls these). Internal to the studies layer.
#pragma once

#include <optional>
#include <string>

#include "io/field_list.hpp"
#include "io/yaml_reader.hpp"
#include "problems/hexapod_design.hpp"
#include "problems/machine_design.hpp"
#include "studies/design_study.hpp"

namespace pkmopt::design_study_detail {

/// task.orientations, in file units: the task poses' tilt cone and yaw range around each
/// position (degrees), sampled every step_deg.
struct TaskOrientationsSection {
  double tilt_deg = 0.0;
  double yaw_deg = 0.0;
  double step_deg = 10.0;
};

/// task.workspace, in file units: how workspace_volume is computed.
struct TaskWorkspaceSection {
  double resolution = 0.05;
  double tilt_deg = 0.0;
  double yaw_deg = 0.0;
  double step_deg = 5.0;
};

/// output: which extra result files a run writes.
struct OutputSection {
  bool designs = true;
};

template <class Fields>
void describe_fields(Fields& f, TaskOrientationsSection& o) {
  f.field("tilt_deg", o.tilt_deg,
          {.min = 0,
           .max = 89,
           .unit = "deg",
           .expected = "an angle in [0, 89] degrees",
           .doc = "half-angle of the tool's tilt cone at every task position"});
  f.field("yaw_deg", o.yaw_deg,
          {.min = 0,
           .max = 179,
           .unit = "deg",
           .expected = "an angle in [0, 179] degrees",
           .doc = "yaw range ± about the tool axis"});
  f.field("step_deg", o.step_deg,
          {.min = 0.5,
           .max = 90,
           .unit = "deg",
           .expected = "an angle in [0.5, 90] degrees",
           .doc = "sampling step of tilt and yaw"});
}

template <class Fields>
void describe_fields(Fields& f, TaskWorkspaceSection& w) {
  f.field("resolution", w.resolution,
          {.min = 0,
           .min_exclusive = true,
           .unit = "m",
           .doc = "grid spacing of the workspace_volume objective"});
  f.field(
      "tilt_deg", w.tilt_deg,
      {.min = 0,
       .max = 89,
       .unit = "deg",
       .expected = "an angle in [0, 89] degrees",
       .doc =
           "the workspace holds the positions reachable with every orientation of this tilt cone"});
  f.field("yaw_deg", w.yaw_deg,
          {.min = 0,
           .max = 179,
           .unit = "deg",
           .expected = "an angle in [0, 179] degrees",
           .doc = "... and of this yaw range"});
  f.field("step_deg", w.step_deg,
          {.min = 0.5,
           .max = 90,
           .unit = "deg",
           .expected = "an angle in [0.5, 90] degrees",
           .doc = "sampling step of the orientations"});
}

template <class Fields>
void describe_fields(Fields& f, OutputSection& o) {
  f.field("designs", o.designs,
          {.doc = "write designs/<id>.yaml, a machine file per Pareto design"});
}

/// {actuator: cheapest, catalog: FILE}: the optimiser chooses the entry.
inline constexpr const char* kCheapestActuator = "cheapest";

/// An integer >= 1.
int positive_int(const YamlValue& v);
/// An angle in degrees within [lo, hi], returned in radians.
double angle_deg(const YamlValue& v, double lo, double hi);
/// An angle in degrees within [lo, hi] (radians returned); `file_value` keeps the degrees.
double angle_deg_kept(const YamlValue& v, double lo, double hi, double& file_value);
/// "[a, b, c]" of the first n values, numbers in their shortest round-trip form.
std::string triple(const double* v, int n = 3);

/// The hexapod `machine:` section (parameters, legs, joints, tool, actuator_error); appends its
/// resolved YAML to `yaml`.
void read_machine(const YamlValue& machine, HexapodDesignSpec& spec, DesignStudy& study,
                  std::string& yaml);
/// The design family of a leg-chain model, its template read from `machine` (or the defaults).
std::optional<DesignFamily> leg_chain_family(const std::string& model, const YamlValue* machine);
/// The `machine:` section of a leg-chain model; appends its resolved YAML to `yaml`.
void read_leg_chain_machine(const YamlValue& machine, const std::string& model,
                            MachineDesignSpec& spec, DesignStudy& study, std::string& yaml);

/// The `task:` section; appends its resolved YAML to `yaml`.
void read_task(const YamlValue& task, DesignTask& task_spec, DesignStudy& study, std::string& yaml);
/// A metric name of an objective or constraint.
DesignMetric read_metric(const YamlValue& v);
/// {actuator: NAME | cheapest, catalog: FILE}; returns the resolved YAML line.
std::string read_actuator_constraint(const YamlValue& c, const std::string& study_path,
                                     HexapodDesignSpec& spec, DesignStudy& study);

}  // namespace pkmopt::design_study_detail
