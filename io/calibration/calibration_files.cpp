#include "io/calibration/calibration_files.hpp"

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <set>

#include "io/format/csv.hpp"
#include "io/format/input_error.hpp"
#include "io/format/pose_csv.hpp"
#include "io/format/yaml_reader.hpp"
#include "io/machine/machine_file.hpp"

namespace pkmopt {
namespace {

std::string resolve_path(const std::string& base_file, const std::string& path) {
  const std::filesystem::path p(path);
  if (p.is_absolute()) return path;
  return (std::filesystem::path(base_file).parent_path() / p).lexically_normal().string();
}

}  // namespace

std::vector<CalibrationMeasurement> read_measurement_csv(const std::string& path,
                                                         const MeasurementFormat& format,
                                                         std::vector<std::string>* warnings,
                                                         std::vector<std::string>* campaigns) {
  CsvTable table = read_csv_file(path);
  // `columns:` renames the file's columns to pkmopt's before anything else, all at once (by the
  // file's own names); two columns may not end up with one name.
  {
    std::vector<std::string> renamed = table.header;
    for (const auto& [ours, theirs] : format.columns) {
      const auto it = std::find(table.header.begin(), table.header.end(), theirs);
      if (it == table.header.end()) {
        std::string names;
        for (const auto& name : table.header) names += (names.empty() ? "" : ",") + name;
        throw InputError(
            fmt::format("{}columns.{}: expected a column '{}' in the file, found the columns {}",
                        location_prefix(path, table.header_line), ours, theirs, names));
      }
      renamed[static_cast<std::size_t>(it - table.header.begin())] = ours;
    }
    for (std::size_t c = 0; c < renamed.size(); ++c)
      for (std::size_t d = c + 1; d < renamed.size(); ++d)
        if (renamed[c] == renamed[d])
          throw InputError(fmt::format(
              "{}columns: expected one column named '{}', found two after the renaming: the "
              "file's '{}' (column {}) and '{}' (column {})",
              location_prefix(path, table.header_line), renamed[c], table.header[c], c + 1,
              table.header[d], d + 1));
    table.header = renamed;
  }
  const bool quaternion = table.column("qw") >= 0;
  std::vector<std::string> expected = {"x", "y", "z"};
  if (quaternion) {
    expected.insert(expected.end(), {"qw", "qx", "qy", "qz"});
  } else {
    expected.insert(expected.end(), {"rx", "ry", "rz"});
  }
  for (int i = 1; i <= 6; ++i) expected.push_back(fmt::format("q_{}", i));
  const int campaign_column = table.column("campaign");
  if (campaign_column >= 0) expected.push_back("campaign");
  auto expected_text = [&] {
    std::string text;
    for (const auto& name : expected) {
      if (!text.empty()) text.push_back(',');
      text.append(name);
    }
    return text;
  };
  for (std::size_t c = 0; c < table.header.size(); ++c) {
    if (std::find(expected.begin(), expected.end(), table.header[c]) == expected.end()) {
      throw InputError(fmt::format(
          "{}column {} '{}': expected only the columns {} ({}), found an unknown column",
          location_prefix(path, table.header_line), c + 1, table.header[c], expected_text(),
          quaternion ? "or rx,ry,rz instead of qw,qx,qy,qz"
                     : "or qw,qx,qy,qz instead of rx,ry,rz"));
    }
  }
  if (!format.quaternion_order.empty() && !quaternion)
    throw InputError(
        fmt::format("{}quaternion_order: expected the columns qw, qx, qy, qz, "
                    "found rx, ry, rz (angles need no order)",
                    location_prefix(path, table.header_line)));
  if (!format.quaternion_order.empty() && quaternion) {
    // By column order: the four quaternion columns as they stand in the file are w, x, y, z
    // (wxyz) or x, y, z, w (xyzw), whatever their names.
    std::vector<int> at;
    for (std::size_t c = 0; c < table.header.size(); ++c)
      if (table.header[c].size() == 2 && table.header[c][0] == 'q' &&
          std::string("wxyz").find(table.header[c][1]) != std::string::npos)
        at.push_back(static_cast<int>(c));
    const std::string order = format.quaternion_order;
    for (std::size_t k = 0; k < at.size() && k < 4; ++k)
      table.header[static_cast<std::size_t>(at[k])] = std::string("q") + order[k];
  }
  const PoseColumns pose_columns = find_pose_columns(table, PoseOrientation::euler_or_quaternion);
  std::vector<int> reading_columns;
  for (int i = 1; i <= 6; ++i)
    reading_columns.push_back(table.require_column(fmt::format("q_{}", i)));
  if (table.rows.empty()) {
    throw InputError(
        fmt::format("{}expected at least one measured pose, found none", location_prefix(path)));
  }
  std::vector<CalibrationMeasurement> measurements;
  std::vector<std::string> labels;
  int scalar_elsewhere = 0;  // rows whose largest quaternion component is not the scalar one
  for (const CsvRow& row : table.rows) {
    CalibrationMeasurement m;
    m.line = row.line;
    m.pose = pose_of_row(table, row, pose_columns, format.position_scale);
    for (int i = 0; i < 6; ++i)
      m.stroke(i) =
          table.number(row, reading_columns[static_cast<std::size_t>(i)]) * format.reading_scale(i);
    if (campaign_column >= 0) {
      const std::string& label = row.cells[static_cast<std::size_t>(campaign_column)];
      if (label.empty())
        throw InputError(
            fmt::format("{}column 'campaign': expected a campaign label, found an "
                        "empty cell",
                        location_prefix(path, row.line)));
      auto it = std::find(labels.begin(), labels.end(), label);
      if (it == labels.end()) it = labels.insert(labels.end(), label);
      m.campaign = static_cast<int>(it - labels.begin());
    }
    if (quaternion) {
      const double w = std::abs(table.number(row, pose_columns.qw));
      const double v = std::max({std::abs(table.number(row, pose_columns.qx)),
                                 std::abs(table.number(row, pose_columns.qy)),
                                 std::abs(table.number(row, pose_columns.qz))});
      if (v > 0.9 && w < 0.3) ++scalar_elsewhere;
    }
    measurements.push_back(m);
  }
  // A machine tool's platform turns by tens of degrees at most, so |qw| is near 1; most rows
  // with a vector component near +-1 instead mean the scalar part is in another column.
  if (warnings && quaternion && 2 * scalar_elsewhere > static_cast<int>(table.rows.size()))
    warnings->push_back(fmt::format(
        "{}: {} of {} rows have |qw| < 0.3 and a vector part near 1 (turns near 180 deg): is "
        "the quaternion's scalar part in another column? `quaternion_order: xyzw` reads the "
        "four columns in file order as x, y, z, w",
        path, scalar_elsewhere, table.rows.size()));
  // No machine tool measures its TCP tens of metres from the instrument: positions that large
  // are millimetres read as metres.
  std::vector<double> distances;
  for (const CalibrationMeasurement& m : measurements) distances.push_back(m.pose.position.norm());
  std::nth_element(distances.begin(),
                   distances.begin() + static_cast<std::ptrdiff_t>(distances.size() / 2),
                   distances.end());
  const double median_distance = distances[distances.size() / 2];
  if (warnings && median_distance > 20.0)
    warnings->push_back(fmt::format(
        "{}: the measured positions are {:.4g} m from the origin (median): are they in mm? "
        "`pose_unit: mm` reads them so",
        path, median_distance));
  if (campaigns) *campaigns = labels.size() > 1 ? labels : std::vector<std::string>{};
  return measurements;
}

std::vector<CalibrationMeasurement> read_measurement_csv(const std::string& path,
                                                         double unit_scale) {
  MeasurementFormat format;
  format.reading_scale.setConstant(unit_scale);
  return read_measurement_csv(path, format, nullptr);
}

HexapodDesign read_calibration_machine(const std::string& path, bool* stiffness_placeholder) {
  const YamlValue machine = YamlValue::load_file(path);
  const YamlValue model = machine.required("model");
  if (model.as_string() != kHexapodModel)
    model.fail(fmt::format("'{}' (calibration)", kHexapodModel), model.describe());
  // Calibration never uses the legs' stiffness: a file without one gets a placeholder (the
  // node is shared, so the other keys keep their lines for messages).
  bool placeholder = false;
  if (const auto legs = machine.optional("legs");
      legs && legs->is_map() && !legs->has("E") && !legs->has("area") &&
      !legs->has("axial_stiffness") && !legs->has("actuator_stiffness")) {
    YAML::Node node = legs->node();
    node["axial_stiffness"] = "1.0";
    placeholder = true;
  }
  if (stiffness_placeholder) *stiffness_placeholder = placeholder;
  return read_hexapod_design(machine);
}

std::vector<CalibrationMeasurement> fitted_measurements(const CalibrationSetup& setup) {
  std::vector<CalibrationMeasurement> fitted;
  fitted.reserve(setup.fit.size());
  for (int k : setup.fit) fitted.push_back(setup.measurements[static_cast<std::size_t>(k)]);
  return fitted;
}

namespace {

// The actuator unit: the scale of readings to metres, per leg (a lead per leg for rev).
void read_actuator_unit(const CalibrationFile& file, CalibrationSetup& setup) {
  setup.unit = file.unit;
  if (setup.unit == "m") {
    setup.unit_scale = 1.0;
  } else if (setup.unit == "mm") {
    setup.unit_scale = 1e-3;
  } else if (setup.unit == "rev") {
    setup.unit_scale = 0.0;
    for (int i = 0; i < 6; ++i) {
      setup.leg_scale(i) =
          file.lead.size() == 6 ? file.lead[static_cast<std::size_t>(i)] : file.lead.front();
      setup.unit_scale += setup.leg_scale(i) / 6.0;
    }
  } else {
    setup.unit_scale = 1.0 / file.counts_per_metre;
  }
  if (setup.unit != "rev") setup.leg_scale.setConstant(setup.unit_scale);
}

// The legs' zero lengths (m): none, one for every leg, or six.
Vec6<double> zero_lengths(const CalibrationFile& file) {
  Vec6<double> zero_length = Vec6<double>::Zero();
  if (file.zero_length.size() == 6) {
    for (int i = 0; i < 6; ++i) zero_length(i) = file.zero_length[static_cast<std::size_t>(i)];
  } else if (file.zero_length.size() == 1) {
    zero_length.setConstant(file.zero_length.front());
  }
  return zero_length;
}

// The free parameters: the model's, the instrument's and target's in the instrument frame, less
// the fixed ones.
void read_free_parameters(const CalibrationFile& file, CalibrationSetup& setup) {
  setup.model = file.model;
  setup.options.free =
      model_free_mask(setup.model == "42" ? CalibrationModelKind::k42 : CalibrationModelKind::k48);
  if (setup.frame == "instrument") {
    for (int i = kCalibrationInstrumentIndex; i < kCalibrationParameters; ++i) {
      setup.options.free[static_cast<std::size_t>(i)] = true;
    }
  }
  for (const std::string& name : file.fixed) {
    const int index = calibration_parameter_index(name);  // a known name (read_calibration_file)
    setup.options.free[static_cast<std::size_t>(index)] = false;
    setup.fixed.push_back(index);
  }
  setup.gauge = file.gauge;
}

// The solver's options (loss, outliers, iterations, noise estimation, scaling).
void read_solver_options(const CalibrationFile& file, CalibrationSetup& setup) {
  setup.options.loss = file.loss;
  setup.options.loss_scale = file.loss_scale;
  setup.options.outlier_chi2 = file.outlier_chi2;
  setup.options.max_iterations = file.max_iterations;
  setup.options.estimate_noise = file.noise_estimate;
  setup.options.max_rejected_share = file.max_rejected_share;
  setup.options.correlation_threshold = file.correlation_threshold;
  setup.options.parameter_scale = calibration_parameter_scale(
      file.length_scale, file.gain_scale, file.frame_position_scale,
      file.frame_angle_scale_deg ? deg_to_rad(*file.frame_angle_scale_deg) : 1e-3);
}

// The fitted and held-out rows (`validation`; `rows` checked against the number of data rows).
void split_validation_rows(const YamlValue& root, const CalibrationFile& file,
                           CalibrationSetup& setup) {
  const int num_rows = static_cast<int>(setup.measurements.size());
  std::set<int> held_out;
  if (file.every > 0) {
    for (int k = 0; k < num_rows; ++k) {
      if ((k + 1) % file.every == 0) held_out.insert(k);
    }
  }
  if (!file.rows.empty()) {
    const std::vector<YamlValue> items = root.required("validation").required("rows").elements();
    for (std::size_t i = 0; i < file.rows.size(); ++i) {
      const long long row = file.rows[i];
      if (row < 1 || row > num_rows) {
        items[i].fail(fmt::format("a data row number in 1..{}", num_rows), items[i].describe());
      }
      held_out.insert(static_cast<int>(row - 1));
    }
  }
  for (int k = 0; k < num_rows; ++k) {
    (held_out.count(k) ? setup.held_out : setup.fit).push_back(k);
  }
}

// Enough fitted rows: every campaign has its own (the reference's fix the leg offsets; a further
// campaign's six shifts need at least 3), and the fitted poses give more equations than there
// are free parameters.
void check_fitted_rows(const CalibrationSetup& setup) {
  for (std::size_t c = 0; c < setup.campaigns.size(); ++c) {
    int count = 0;
    for (int k : setup.fit)
      count += setup.measurements[static_cast<std::size_t>(k)].campaign == static_cast<int>(c);
    if (c == 0 ? count == 0 : count < 3)
      throw InputError(fmt::format(
          "{}: campaign '{}': expected {}, found {} fitted row(s){}", setup.measurement_file,
          setup.campaigns[c],
          c == 0 ? "fitted rows of the reference campaign (the first label in the file)"
                 : "at least 3 fitted rows for its six leg zero shifts",
          count,
          c == 0 ? ": without them its leg offsets cannot be told from the other campaigns' "
                   "shifts; hold out fewer of its rows or put another campaign first"
                 : ""));
  }
  const std::size_t fitted = setup.fit.size();
  int num_free = 0;
  for (bool f : setup.options.free) num_free += f ? 1 : 0;
  if (6 * static_cast<int>(fitted) < num_free + 1) {
    throw InputError(fmt::format(
        "{}: too few poses: {} fitted rows ({} held out) give {} equations, the {} free "
        "parameters (model {}{}) need more; measure at least {} poses (3 times as many is a "
        "good rule), hold out fewer, or fix parameters",
        setup.measurement_file, fitted, setup.held_out.size(), 6 * fitted, num_free, setup.model,
        setup.frame == "instrument" ? " + instrument + target" : "", num_free / 6 + 1));
  }
}

}  // namespace

CalibrationSetup read_calibration_setup(const std::string& path) {
  CalibrationSetup setup;
  setup.file = path;
  const YamlValue root = YamlValue::load_file(path);
  const CalibrationFile file = read_calibration_file(root);

  // Nominal machine.
  setup.machine_file = resolve_path(path, file.machine);
  setup.nominal_design = read_calibration_machine(setup.machine_file, &setup.stiffness_placeholder);

  // Frames and actuators.
  setup.frame = file.frame;
  const Pose instrument{file.instrument_position, deg_to_rad(file.instrument_angles_deg)};
  const Pose target{file.target_position, deg_to_rad(file.target_angles_deg)};
  read_actuator_unit(file, setup);
  setup.nominal =
      nominal_calibration_vector(setup.nominal_design, zero_lengths(file), instrument, target);

  // Noise.
  setup.options.sigma_position = file.noise_position;
  setup.options.sigma_orientation = deg_to_rad(file.noise_orientation_deg);
  setup.options.sigma_actuator = file.noise_actuator * setup.unit_scale;

  read_free_parameters(file, setup);
  read_solver_options(file, setup);

  // Measurements.
  setup.measurement_file = resolve_path(path, file.measurements);
  MeasurementFormat format;
  format.reading_scale = setup.leg_scale;
  format.position_scale = file.pose_unit == "mm" ? 1e-3 : 1.0;
  format.quaternion_order = file.quaternion_order;
  format.columns = file.columns;
  setup.measurements =
      read_measurement_csv(setup.measurement_file, format, &setup.warnings, &setup.campaigns);
  split_validation_rows(root, file, setup);
  check_fitted_rows(setup);

  if (setup.gauge == "auto") {
    setup.gauge_fixed = choose_gauge_fixing(setup.nominal, setup.nominal_design.tcp,
                                            fitted_measurements(setup), setup.options);
    for (int index : setup.gauge_fixed) setup.options.free[static_cast<std::size_t>(index)] = false;
  }
  return setup;
}

}  // namespace pkmopt
