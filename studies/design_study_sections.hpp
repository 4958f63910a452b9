// The sections of a design study file, read one function each (studies/design_study.hpp has the
// schema and load_design_study, which calls these). Internal to the studies layer.
#pragma once

#include <array>
#include <optional>
#include <string>

#include "io/format/field_list.hpp"
#include "io/format/yaml_reader.hpp"
#include "problems/design/machine_design.hpp"
#include "studies/design_study.hpp"
#include "studies/optimizer_fields.hpp"

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

/// task.region with shape: box, in file units: a grid of points[a] positions along each axis
/// (one: the centre) spanning size[a] around the centre.
struct BoxRegionSection {
  std::array<double, 3> centre{};
  std::array<double, 3> size{};
  std::array<int, 3> points{1, 1, 1};
};

/// task.region with shape: cylinder, in file units: the centre, `rings` rings of `per_ring`
/// points each, on `layers` layers spanning `height` along z.
struct CylinderRegionSection {
  std::array<double, 3> centre{};
  double radius = 0.0;
  double height = 0.0;
  int rings = 1;
  int per_ring = 6;
  int layers = 1;
};

/// One entry of `objectives:` (exactly one of the two keys; -1: not given).
struct ObjectiveEntry {
  int minimize = -1;
  int maximize = -1;
};

/// One `{metric, max|min}` entry of `constraints:`.
struct ConstraintEntry {
  int metric = -1;
  std::optional<double> max;
  std::optional<double> min;
};

/// "one of stiffness_min, singularity_margin, ...": every metric name, for messages.
const std::string& metric_names_text();

/// The metric names as a FieldChoice over DesignMetric codes.
FieldChoice<int> metric_choice(int& member);

template <class Fields>
void describe_fields(Fields& f, BoxRegionSection& b) {
  f.note("shape", "box or cylinder", "", "required", "the region's shape");
  f.field("centre", b.centre,
          {.required = true, .unit = "m", .doc = "centre of the region in the base frame"});
  f.field("size", b.size,
          {.min = 0, .required = true, .unit = "m", .doc = "edge lengths along x, y and z"});
  f.field("points", b.points,
          {.min = 1, .max = 1000, .doc = "grid points along x, y and z (1: the centre's value)"});
}

template <class Fields>
void describe_fields(Fields& f, CylinderRegionSection& c) {
  f.note("shape", "box or cylinder", "", "required", "the region's shape");
  f.field("centre", c.centre,
          {.required = true, .unit = "m", .doc = "centre of the region in the base frame"});
  f.field("radius", c.radius,
          {.min = 0, .required = true, .unit = "m", .doc = "radius of the outermost ring"});
  f.field("height", c.height,
          {.min = 0, .required = true, .unit = "m", .doc = "extent of the layers along z"});
  f.field("rings", c.rings,
          {.min = 0, .max = 100, .doc = "rings of points around the centre point, evenly spaced"});
  f.field("per_ring", c.per_ring, {.min = 1, .max = 1000, .doc = "points on each ring"});
  f.field("layers", c.layers, {.min = 1, .max = 1000, .doc = "layers along z"});
}

template <class Fields>
void describe_fields(Fields& f, ObjectiveEntry& o) {
  const std::string& names = metric_names_text();
  FieldChoice<int> minimize = metric_choice(o.minimize);
  FieldChoice<int> maximize = metric_choice(o.maximize);
  f.field("minimize", minimize, {.expected = names, .doc = "a metric to minimise"});
  f.field("maximize", maximize, {.expected = names, .doc = "a metric to maximise"});
}

template <class Fields>
void describe_fields(Fields& f, ConstraintEntry& c) {
  FieldChoice<int> metric = metric_choice(c.metric);
  f.field("metric", metric,
          {.required = true, .expected = metric_names_text(), .doc = "the bounded metric"});
  f.field("max", c.max, {.doc = "upper bound g = metric − max ≤ 0 (give max or min)"});
  f.field("min", c.min, {.doc = "lower bound g = min − metric ≤ 0"});
}

/// output: which extra result files a run writes.
struct OutputSection {
  bool designs = true;
  int front_size = 0;  ///< 0: every non-dominated design
};

/// The field rule of a limit the workspace command and Python share (models/workspace).
inline FieldRule limit_rule(const ValueLimit& limit, std::string_view unit, std::string_view doc) {
  return FieldRule{.min = limit.min,
                   .max = limit.max,
                   .min_exclusive = limit.min_exclusive,
                   .max_exclusive = limit.max_exclusive,
                   .unit = unit,
                   .expected = limit.expected,
                   .doc = doc};
}

template <class Fields>
void describe_fields(Fields& f, TaskOrientationsSection& o) {
  using namespace workspace_limits;
  f.field("tilt_deg", o.tilt_deg,
          limit_rule(kTiltDeg, "deg", "half-angle of the tool's tilt cone at every task position"));
  f.field("yaw_deg", o.yaw_deg, limit_rule(kYawRangeDeg, "deg", "yaw range ± about the tool axis"));
  f.field("step_deg", o.step_deg,
          limit_rule(kOrientationStepDeg, "deg", "sampling step of tilt and yaw"));
}

template <class Fields>
void describe_fields(Fields& f, TaskWorkspaceSection& w) {
  using namespace workspace_limits;
  f.field("resolution", w.resolution,
          limit_rule(kResolution, "m", "grid spacing of the workspace_volume objective"));
  f.field("tilt_deg", w.tilt_deg,
          limit_rule(kTiltDeg, "deg",
                     "the workspace holds the positions reachable with every orientation of this "
                     "tilt cone"));
  f.field("yaw_deg", w.yaw_deg, limit_rule(kYawRangeDeg, "deg", "... and of this yaw range"));
  f.field("step_deg", w.step_deg,
          limit_rule(kOrientationStepDeg, "deg", "sampling step of the orientations"));
}

template <class Fields>
void describe_fields(Fields& f, OutputSection& o) {
  f.field("designs", o.designs,
          {.doc = "write designs/<id>.yaml, a machine file per Pareto design"});
  front_size_field(f, o.front_size);
}

/// The `task:` section; appends its resolved YAML to `yaml`. `placement` (m) is added to the
/// region's centre (an architecture synthesis places one task in each candidate's frame).
void read_task(const YamlValue& task, DesignTask& task_spec, DesignStudy& study, std::string& yaml,
               const std::array<double, 3>& placement = {});

}  // namespace pkmopt::design_study_detail
