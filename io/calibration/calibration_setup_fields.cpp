// The keys of the calibration YAML, described once (io/format/field_list.hpp):
// read_calibration_file, calibration_file_yaml and the table of docs/calibration.md come from this
// list.
#include <fmt/format.h>

#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "io/calibration/calibration_files.hpp"
#include "io/format/csv.hpp"
#include "io/format/field_list.hpp"

namespace pkmopt {
namespace {

// A key whose value the field list cannot read by itself (one number or six, a list of names,
// a list of row numbers): `read` reads its YAML value, `text` gives the written value ("" leaves
// the key out), the docs row says `allowed` and `default_text`.
template <class Fields, class Read, class Text>
void custom_field(Fields& f, std::string_view key, std::string_view allowed, std::string_view unit,
                  std::string_view default_text, std::string_view doc, [[maybe_unused]] Read&& read,
                  [[maybe_unused]] Text&& text) {
  if constexpr (std::is_same_v<Fields, FieldReader>) {
    f.note(key, allowed, unit, default_text, doc);
    if (const auto v = f.section().optional(key)) read(*v);
  } else if constexpr (std::is_same_v<Fields, FieldWriter>) {
    const std::string value = text();
    if (!value.empty()) f.raw(key, value);
  } else {
    f.note(key, allowed, unit, default_text, doc);
  }
}

// "[a, b, c]" of a list of texts or integers; "" for an empty list.
template <class T>
std::string list_text(const std::vector<T>& items) {
  if (items.empty()) return "";
  std::string text;
  for (const T& item : items) {
    if (!text.empty()) text += ", ";
    if constexpr (std::is_same_v<T, std::string>) {
      text += item;
    } else {
      text += std::to_string(item);
    }
  }
  return "[" + text + "]";
}

// The written value of a key that takes one number or six: "" (left out), "0.7" or "[a, ...]".
std::string one_or_six_text(const std::vector<double>& values) {
  if (values.empty()) return "";
  if (values.size() == 1) return format_number(values.front());
  std::string text;
  for (double v : values) text += (text.empty() ? "" : ", ") + format_number(v);
  return "[" + text + "]";
}

constexpr std::string_view kParameterNames =
    "a1.x .. b6.z, offset1..6, gain1..6, instrument.x..rz, target.x..rz";

// position and angles_deg of a frame (instrument or target); both left out when zero.
template <class Fields>
void describe_frame(Fields& g, Eigen::Vector3d& position, Eigen::Vector3d& angles_deg,
                    std::string_view what) {
  g.field("position", position,
          {.unit = "m", .doc = what, .omit_when = [&position] { return position.isZero(0.0); }});
  g.field("angles_deg", angles_deg,
          {.unit = "deg",
           .expected = "[rx, ry, rz]",
           .doc = "its orientation, R = Rz·Ry·Rx",
           .omit_when = [&angles_deg] { return angles_deg.isZero(0.0); }});
}

FieldRule positive(std::string_view unit, std::string_view doc, bool required = false) {
  return {.min = 0, .min_exclusive = true, .required = required, .unit = unit, .doc = doc};
}

}  // namespace

template <class Fields>
void describe_fields(Fields& f, CalibrationFile& c) {
  const CalibrationFile defaults;
  f.field(
      "machine", c.machine,
      {.required = true, .doc = "nominal hexapod machine file, relative to the calibration file"});
  f.field("measurements", c.measurements,
          {.required = true, .doc = "measurement CSV, relative to the calibration file"});
  FieldChoice<std::string> frame{c.frame, {{"base", "base"}, {"instrument", "instrument"}}};
  f.field("frame", frame,
          {.doc = "`base`: poses are TCP poses measured in the base frame; `instrument`: target "
                  "poses in the instrument's own frame, the instrument-to-base and target-to-TCP "
                  "transforms are estimated too"});
  f.section("instrument",
            {.doc = "start value of the instrument frame's pose in the base frame; only with "
                    "`frame: instrument`",
             .omit_when = [&c] { return c.frame != "instrument"; }},
            [&](auto& g) {
              describe_frame(g, c.instrument_position, c.instrument_angles_deg,
                             "the instrument frame's origin in the base frame");
            });
  f.section("target",
            {.doc = "pose of the measured target in the TCP frame (held for `frame: base`, a "
                    "start value for `frame: instrument`)"},
            [&](auto& g) {
              describe_frame(g, c.target_position, c.target_angles_deg,
                             "the target's position in the TCP frame");
            });
  f.section("actuators", {.required = true, .doc = "the actuator readings q_1..q_6"}, [&](auto& g) {
    FieldChoice<std::string> unit{c.unit,
                                  {{"m", "m"}, {"mm", "mm"}, {"rev", "rev"}, {"counts", "counts"}}};
    g.field("unit", unit,
            {.required = true,
             .doc = "unit of the readings: metres, millimetres, screw revolutions (with `lead`) or "
                    "encoder counts (with `counts_per_metre`)"});
    custom_field(
        g, "lead", "a number > 0 or a list of 6 numbers > 0", "m/rev", "none",
        "screw lead, one for every leg or one per leg; required with `unit: rev`, not allowed "
        "otherwise",
        [&](const YamlValue& v) {
          c.lead = v.is_sequence() ? v.as_lengths(6) : std::vector<double>{v.as_length()};
          for (double lead : c.lead)
            if (!(lead > 0.0)) v.fail("screw leads > 0 (m/rev)", v.describe());
        },
        [&] { return one_or_six_text(c.lead); });
    FieldRule counts = positive("1/m",
                                "encoder counts per metre; required with `unit: counts`, "
                                "not allowed otherwise");
    counts.zero_is_unset = true;
    g.field("counts_per_metre", c.counts_per_metre, counts);
    custom_field(
        g, "zero_length", "a number or a list of 6 numbers", "m", "0",
        "leg length at reading 0, one for every leg or one per leg; 0: the readings are leg "
        "lengths",
        [&](const YamlValue& v) {
          c.zero_length = v.is_sequence() ? v.as_lengths(6) : std::vector<double>{v.as_length()};
        },
        [&] { return one_or_six_text(c.zero_length); });
  });
  f.section("noise", {.required = true, .doc = "the measurement noise (one sigma)"}, [&](auto& g) {
    g.field("position", c.noise_position, positive("m", "instrument position sigma", true));
    g.field("orientation_deg", c.noise_orientation_deg,
            positive("deg", "instrument orientation sigma", true));
    g.field("actuator", c.noise_actuator,
            positive("actuator unit", "reading sigma, in the unit of `actuators.unit`", true));
    g.field("estimate", c.noise_estimate,
            {.doc = "`true`: the sigmas are estimated from the residuals (variance components, "
                    "docs/calibration.md) and the given ones are only the start; `false`: the "
                    "given sigmas are taken as true",
             .omit_when = [&c] { return c.noise_estimate; }});
  });
  FieldChoice<std::string> pose_unit{c.pose_unit, {{"m", "m"}, {"mm", "mm"}}};
  f.field("pose_unit", pose_unit,
          {.doc = "unit of the measured positions x, y, z (and of `instrument` and `target` "
                  "positions: always m)",
           .omit_when = [&c] { return c.pose_unit == "m"; }});
  FieldChoice<std::string> quaternion_order{c.quaternion_order,
                                            {{"wxyz", "wxyz"}, {"xyzw", "xyzw"}}};
  f.field("quaternion_order", quaternion_order,
          {.default_text = "by column name",
           .doc = "read the four quaternion columns in their file order as w, x, y, z (`wxyz`) "
                  "or as x, y, z, w (`xyzw`, scalar last) whatever their names",
           .omit_when = [&c] { return c.quaternion_order.empty(); }});
  custom_field(
      f, "columns", "a map of pkmopt column names to the file's column names", "", "none",
      "renames the measurement file's columns, e.g. `{q_1: leg_length_1, x: pos_x}`; keys: x, y, "
      "z, rx, ry, rz, qw, qx, qy, qz, q_1..q_6, campaign",
      [&](const YamlValue& v) {
        v.expect_map();
        c.columns.clear();
        static const std::set<std::string> kNames = {"x",   "y",   "z",   "rx",  "ry",      "rz",
                                                     "qw",  "qx",  "qy",  "qz",  "q_1",     "q_2",
                                                     "q_3", "q_4", "q_5", "q_6", "campaign"};
        for (const std::string& key : v.keys()) {
          const YamlValue item = v.required(key);
          if (!kNames.count(key))
            item.fail(
                "a pkmopt column name (x, y, z, rx, ry, rz, qw, qx, qy, qz, q_1..q_6, campaign)",
                quote_found(key));
          c.columns.emplace_back(key, item.as_string());
        }
      },
      [&]() -> std::string {
        if (c.columns.empty()) return "";
        std::string text;
        for (const auto& [ours, theirs] : c.columns)
          text += (text.empty() ? "" : ", ") + ours + ": " + nlohmann::json(theirs).dump();
        return "{" + text + "}";
      });
  FieldChoice<std::string> model{c.model, {{"42", "42"}, {"48", "48"}}};
  f.field("model", model,
          {.doc = "`42`: joint coordinates and leg offsets; `48`: also the gains of the readings"});
  custom_field(
      f, "fixed", fmt::format("a list of parameter names ({})", kParameterNames), "", "none",
      "parameters held at nominal, e.g. `[a1.z, gain3]`",
      [&](const YamlValue& v) {
        c.fixed.clear();
        for (const YamlValue& item : v.elements()) {
          const std::string name = item.as_string();
          if (calibration_parameter_index(name) < 0)
            item.fail(fmt::format("a parameter name ({})", kParameterNames), item.describe());
          c.fixed.push_back(name);
        }
      },
      [&] { return list_text(c.fixed); });
  FieldChoice<std::string> gauge{c.gauge, {{"auto", "auto"}, {"none", "none"}}};
  f.field("gauge", gauge,
          {.doc = "`auto`: hold the joint coordinates that fix the frame freedoms; `none`: hold "
                  "nothing (a free gauge is then an error)"});
  f.section("loss", {.doc = "the robust loss of the first fit"}, [&](auto& g) {
    FieldChoice<CalibrationLoss> type{c.loss,
                                      {{"huber", CalibrationLoss::kHuber},
                                       {"cauchy", CalibrationLoss::kCauchy},
                                       {"none", CalibrationLoss::kNone}}};
    g.field("type", type,
            {.required = true,
             .default_text = "huber (required in a `loss` map)",
             .doc = "the loss function"});
    g.field(
        "scale", c.loss_scale,
        positive("", "where the loss turns robust, in sigma units (the sqrt of a pose's chi²)"));
  });
  f.field("outlier_chi2", c.outlier_chi2,
          {.min = 0,
           .min_exclusive = true,
           .doc = "a pose is an outlier when its chi² exceeds this (the default is the 0.9999 "
                  "quantile of chi² with 6 degrees of freedom)",
           .omit_when = [&c, d = defaults.outlier_chi2] { return c.outlier_chi2 == d; }});
  f.field(
      "max_rejected_share", c.max_rejected_share,
      {.min = 0,
       .max = 1,
       .min_exclusive = true,
       .doc = "a calibration that rejects more than this share of the fitted poses is "
              "reported as probably wrong (exit status 3)",
       .omit_when = [&c, d = defaults.max_rejected_share] { return c.max_rejected_share == d; }});
  f.field("max_iterations", c.max_iterations,
          {.min = 1,
           .max = 100000,
           .doc = "solver iteration limit",
           .omit_when = [&c, d = defaults.max_iterations] { return c.max_iterations == d; }});
  f.field("correlation_threshold", c.correlation_threshold,
          {.min = 0,
           .max = 1,
           .min_exclusive = true,
           .doc = "pairs of parameters whose correlation is at least this in magnitude are "
                  "reported",
           .omit_when = [&c, d = defaults.correlation_threshold] {
             return c.correlation_threshold == d;
           }});
  f.section(
      "parameter_scale",
      {.doc = "the a-priori sigma of each parameter kind, for the scaled observability indices"},
      [&](auto& g) {
        FieldRule length = positive("m", "joint coordinates and leg offsets");
        length.omit_when = [&c, d = defaults.length_scale] { return c.length_scale == d; };
        g.field("length", c.length_scale, length);
        FieldRule gain = positive("", "gains");
        gain.omit_when = [&c, d = defaults.gain_scale] { return c.gain_scale == d; };
        g.field("gain", c.gain_scale, gain);
        FieldRule frame_position = positive("m", "instrument and target positions");
        frame_position.omit_when = [&c, d = defaults.frame_position_scale] {
          return c.frame_position_scale == d;
        };
        g.field("frame_position", c.frame_position_scale, frame_position);
        FieldRule frame_angle = positive("deg", "instrument and target angles");
        frame_angle.default_text = "0.0573 (1e-3 rad)";
        g.field("frame_angle_deg", c.frame_angle_scale_deg, frame_angle);
      });
  f.section(
      "validation", {.doc = "data rows held out of the fit (`every` and `rows` may be combined)"},
      [&](auto& g) {
        g.field("every", c.every, {.min = 2, .zero_is_unset = true, .doc = "every n-th data row"});
        custom_field(
            g, "rows", "a list of data row numbers, each in 1..(number of data rows)", "", "none",
            "1-based data rows, e.g. `[3, 7, 11]`",
            [&](const YamlValue& v) {
              c.rows.clear();
              for (const YamlValue& item : v.elements()) c.rows.push_back(item.as_int());
            },
            [&] { return list_text(c.rows); });
      });
}

CalibrationFile read_calibration_file(const YamlValue& root) {
  CalibrationFile c;
  read_fields(root, c);
  // Checks across keys, after the list read.
  if (c.frame == "base") {
    if (const auto instrument = root.optional("instrument"))
      instrument->fail(
          "no instrument with frame: base (poses measured in the base frame); set frame: "
          "instrument");
  }
  const YamlValue actuators = root.required("actuators");
  if (c.unit == "rev") (void)actuators.required("lead");
  if (c.unit == "counts") (void)actuators.required("counts_per_metre");
  if (c.unit != "rev" && actuators.has("lead"))
    actuators.required("lead").fail("no lead unless unit: rev");
  if (c.unit != "counts" && actuators.has("counts_per_metre"))
    actuators.required("counts_per_metre").fail("no counts_per_metre unless unit: counts");
  return c;
}

std::string calibration_file_yaml(const CalibrationFile& file) {
  FieldWriter writer;
  CalibrationFile copy = file;
  describe_fields(writer, copy);
  return writer.flow_lines();
}

std::string calibration_fields_markdown() { return fields_markdown(CalibrationFile{}); }

}  // namespace pkmopt
