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
#include "pkmopt/version.hpp"

namespace pkmopt {
namespace {

// An observability index for report.txt: {:.4g}, or "n/a" where report.json has null (an
// infinite condition number, a rank-deficient fit).
std::string observability_text(const nlohmann::json& value) {
  if (!value.is_number()) return "n/a";
  const double v = value.get<double>();
  return std::isfinite(v) ? fmt::format("{:.4g}", v) : "n/a";
}

std::string resolve_path(const std::string& base_file, const std::string& path) {
  const std::filesystem::path p(path);
  if (p.is_absolute()) return path;
  return (std::filesystem::path(base_file).parent_path() / p).lexically_normal().string();
}

nlohmann::json errors_json(const CalibrationErrors& e) {
  nlohmann::json j;
  j["count"] = e.count;
  j["leg_rms"] = std::vector<double>(e.leg_rms.data(), e.leg_rms.data() + 6);
  j["leg_max"] = std::vector<double>(e.leg_max.data(), e.leg_max.data() + 6);
  j["leg_rms_all"] = std::sqrt(e.leg_rms.squaredNorm() / 6.0);
  j["tcp_position_rms"] = e.tcp_position_rms;
  j["tcp_position_max"] = e.tcp_position_max;
  j["tcp_orientation_rms_deg"] = rad_to_deg(e.tcp_orientation_rms);
  j["tcp_orientation_max_deg"] = rad_to_deg(e.tcp_orientation_max);
  j["fk_failures"] = e.fk_failures;
  return j;
}

bool is_angle(int index) {
  return index >= kCalibrationInstrumentIndex && (index - kCalibrationInstrumentIndex) % 6 >= 3;
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

CalibrationSetup read_calibration_setup(const std::string& path) {
  CalibrationSetup setup;
  setup.file = path;
  const YamlValue root = YamlValue::load_file(path);
  const CalibrationFile file = read_calibration_file(root);

  // Nominal machine.
  setup.machine_file = resolve_path(path, file.machine);
  setup.nominal_design = read_calibration_machine(setup.machine_file, &setup.stiffness_placeholder);

  // Frames.
  setup.frame = file.frame;
  const Pose instrument{file.instrument_position, deg_to_rad(file.instrument_angles_deg)};
  const Pose target{file.target_position, deg_to_rad(file.target_angles_deg)};

  // Actuators.
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
  Vec6<double> zero_length = Vec6<double>::Zero();
  if (file.zero_length.size() == 6) {
    for (int i = 0; i < 6; ++i) zero_length(i) = file.zero_length[static_cast<std::size_t>(i)];
  } else if (file.zero_length.size() == 1) {
    zero_length.setConstant(file.zero_length.front());
  }
  setup.nominal = nominal_calibration_vector(setup.nominal_design, zero_length, instrument, target);

  // Noise.
  setup.options.sigma_position = file.noise_position;
  setup.options.sigma_orientation = deg_to_rad(file.noise_orientation_deg);
  setup.options.sigma_actuator = file.noise_actuator * setup.unit_scale;

  // Free parameters.
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

  // Solver.
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

  // Measurements.
  setup.measurement_file = resolve_path(path, file.measurements);
  MeasurementFormat format;
  format.reading_scale = setup.leg_scale;
  format.position_scale = file.pose_unit == "mm" ? 1e-3 : 1.0;
  format.quaternion_order = file.quaternion_order;
  format.columns = file.columns;
  setup.measurements =
      read_measurement_csv(setup.measurement_file, format, &setup.warnings, &setup.campaigns);
  const int num_rows = static_cast<int>(setup.measurements.size());

  // Validation rows (`rows` checked against the number of data rows here).
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

  // Every campaign needs fitted rows (the reference's fix the leg offsets; a further campaign's
  // six shifts need at least 3).
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
  std::vector<CalibrationMeasurement> fitted;
  for (int k : setup.fit) fitted.push_back(setup.measurements[static_cast<std::size_t>(k)]);
  int num_free = 0;
  for (bool f : setup.options.free) num_free += f ? 1 : 0;
  if (6 * static_cast<int>(fitted.size()) < num_free + 1) {
    throw InputError(fmt::format(
        "{}: too few poses: {} fitted rows ({} held out) give {} equations, the {} free "
        "parameters (model {}{}) need more; measure at least {} poses (3 times as many is a "
        "good rule), hold out fewer, or fix parameters",
        setup.measurement_file, fitted.size(), setup.held_out.size(), 6 * fitted.size(), num_free,
        setup.model, setup.frame == "instrument" ? " + instrument + target" : "",
        num_free / 6 + 1));
  }
  if (setup.gauge == "auto") {
    setup.gauge_fixed =
        choose_gauge_fixing(setup.nominal, setup.nominal_design.tcp, fitted, setup.options);
    for (int index : setup.gauge_fixed) setup.options.free[static_cast<std::size_t>(index)] = false;
  }
  return setup;
}

nlohmann::json calibration_report_json(const CalibrationSetup& setup,
                                       const CalibrationResult& result) {
  using nlohmann::json;
  json report;
  report["pkmopt_version"] = kVersion;
  report["calibration_file"] = setup.file;
  report["machine_file"] = setup.machine_file;
  report["measurement_file"] = setup.measurement_file;
  report["frame"] = setup.frame;
  report["model"] = setup.model;
  report["actuator_unit"] = setup.unit;
  report["actuator_unit_scale"] = setup.unit_scale;
  report["actuator_leg_scale"] =
      std::vector<double>(setup.leg_scale.data(), setup.leg_scale.data() + 6);
  report["input_warnings"] = setup.warnings;
  report["noise"] = {{"position", setup.options.sigma_position},
                     {"orientation_deg", rad_to_deg(setup.options.sigma_orientation)},
                     {"actuator", setup.options.sigma_actuator}};
  // The sigmas of the final fit: estimated from the residuals
  // (problems/calibration/calibration_noise.cpp) unless the file turns that off; everything below
  // (screening, noise floor) uses them.
  CalibrationOptions fitted = setup.options;
  if (result.noise_estimated) {
    fitted.sigma_position = result.estimated_sigma(0);
    fitted.sigma_orientation = result.estimated_sigma(1);
    fitted.sigma_actuator = result.estimated_sigma(2);
  }
  {
    const char* names[3] = {"position", "orientation_deg", "actuator"};
    json estimate = {{"estimated", result.noise_estimated},
                     {"iterations", result.noise_iterations},
                     {"covariance_scale", result.covariance_scale}};
    for (int g = 0; g < 3; ++g) {
      const double unit = g == 1 ? kRadToDeg : 1.0;
      const bool resolved = result.noise_resolved[static_cast<std::size_t>(g)];
      estimate[names[g]] = {
          {"given", result.given_sigma(g) * unit},
          {"used", result.estimated_sigma(g) * unit},
          {"resolved", resolved},
          {"relative_sd", resolved ? json(result.noise_relative_sd(g)) : json(nullptr)},
          {"redundancy", result.group_redundancy(g)}};
    }
    report["noise_estimate"] = estimate;
  }

  std::vector<int> inliers;
  for (std::size_t r = 0; r < setup.fit.size(); ++r) {
    if (std::find(result.outliers.begin(), result.outliers.end(), static_cast<int>(r)) ==
        result.outliers.end()) {
      inliers.push_back(setup.fit[r]);
    }
  }
  // Held-out rows screened with the calibrated machine: each row's own pose fitted with the
  // machine held; chi^2 above the threshold flags a gross outlier.
  // The calibrated machine sees each campaign with its estimated leg zero shifts.
  const std::vector<CalibrationMeasurement> shifted =
      with_campaign_shifts(setup.measurements, result);
  const std::vector<double> held_out_chi2 = fixed_machine_chi2(
      setup.nominal_design.tcp, result.estimate, shifted, setup.held_out, fitted);
  std::vector<int> held_out_inliers;
  json held_out_outliers = json::array();
  for (std::size_t r = 0; r < setup.held_out.size(); ++r) {
    const int k = setup.held_out[r];
    if (held_out_chi2[r] > setup.options.outlier_chi2) {
      held_out_outliers.push_back({{"row", k + 1},
                                   {"line", setup.measurements[static_cast<std::size_t>(k)].line},
                                   {"chi2", held_out_chi2[r]}});
    } else {
      held_out_inliers.push_back(k);
    }
  }
  report["poses"] = {{"total", setup.measurements.size()},
                     {"fitted", inliers.size()},
                     {"held_out", setup.held_out.size()},
                     {"outliers", result.outliers.size()},
                     {"held_out_outliers", held_out_outliers.size()}};

  std::vector<std::string> gauge_names, fixed_names;
  for (int index : setup.gauge_fixed) gauge_names.push_back(calibration_parameter_name(index));
  for (int index : setup.fixed) fixed_names.push_back(calibration_parameter_name(index));
  std::string reason =
      setup.frame == "base"
          ? "poses measured in the base frame: the instrument defines the base frame and the "
            "target the TCP frame, no gauge freedom exists"
          : "instrument and target transforms are free: any rigid motion of the base frame "
            "(6) and of the platform frame (6) leaves the data unchanged; the listed joint "
            "coordinates are held at nominal to define both frames";
  report["gauge"] = {{"mode", setup.gauge}, {"fixed", gauge_names}, {"reason", reason}};
  report["fixed_by_user"] = fixed_names;

  report["solver"] = {{"converged", result.converged},
                      {"iterations", result.iterations},
                      {"message", result.solver_message},
                      {"chi2_per_dof", result.chi2_per_dof}};

  const CalibrationVector& nominal = setup.nominal;
  const CalibrationVector& estimate = result.estimate;
  json errors;
  errors["before"]["fitted"] =
      errors_json(calibration_errors(setup.nominal_design, nominal, setup.measurements, inliers));
  errors["after"]["fitted"] =
      errors_json(calibration_errors(setup.nominal_design, estimate, shifted, inliers));
  errors["before"]["held_out"] = errors_json(
      calibration_errors(setup.nominal_design, nominal, setup.measurements, setup.held_out));
  errors["after"]["held_out"] =
      errors_json(calibration_errors(setup.nominal_design, estimate, shifted, setup.held_out));
  errors["before"]["held_out_inliers"] = errors_json(
      calibration_errors(setup.nominal_design, nominal, setup.measurements, held_out_inliers));
  errors["after"]["held_out_inliers"] =
      errors_json(calibration_errors(setup.nominal_design, estimate, shifted, held_out_inliers));
  report["errors"] = errors;
  report["noise_floor"] = {
      {"tcp_position_rms", std::sqrt(3.0) * fitted.sigma_position},
      {"tcp_orientation_rms_deg", std::sqrt(3.0) * rad_to_deg(fitted.sigma_orientation)}};

  json parameters = json::array();
  for (int i = 0; i < kCalibrationParameters; ++i) {
    const bool in_model = i < kCalibrationMachineParameters || setup.frame == "instrument";
    if (!in_model) continue;
    const double scale = is_angle(i) ? kRadToDeg : 1.0;
    parameters.push_back({{"name", calibration_parameter_name(i)},
                          {"unit", is_angle(i) ? "deg" : calibration_parameter_unit(i)},
                          {"free", setup.options.free[static_cast<std::size_t>(i)]},
                          {"nominal", nominal(i) * scale},
                          {"estimate", estimate(i) * scale},
                          {"change", (estimate(i) - nominal(i)) * scale},
                          {"sigma", result.sigma(i) * scale}});
  }
  report["parameters"] = parameters;
  // Measurement campaigns: each one's leg zero shifts against the reference (the first label).
  json campaigns = json::array();
  for (std::size_t c = 0; c < setup.campaigns.size(); ++c) {
    int fitted_rows = 0, held_rows = 0;
    for (int k : setup.fit)
      fitted_rows +=
          setup.measurements[static_cast<std::size_t>(k)].campaign == static_cast<int>(c);
    for (int k : setup.held_out)
      held_rows += setup.measurements[static_cast<std::size_t>(k)].campaign == static_cast<int>(c);
    json entry = {{"label", setup.campaigns[c]},
                  {"reference", c == 0},
                  {"fitted_rows", fitted_rows},
                  {"held_out_rows", held_rows}};
    if (c > 0 && c <= result.campaign_shifts.size()) {
      const Vec6<double>& shift = result.campaign_shifts[c - 1];
      const Vec6<double> sigma = c <= result.campaign_shift_sigma.size()
                                     ? result.campaign_shift_sigma[c - 1]
                                     : Vec6<double>::Zero();
      entry["shifts"] = std::vector<double>(shift.data(), shift.data() + 6);
      entry["shift_sigma"] = std::vector<double>(sigma.data(), sigma.data() + 6);
      entry["estimated"] =
          c <= result.campaign_estimated.size() && result.campaign_estimated[c - 1];
    }
    campaigns.push_back(entry);
  }
  report["campaigns"] = campaigns;
  json pairs = json::array();
  for (const CorrelatedPair& p : result.correlated) {
    pairs.push_back({{"first", calibration_parameter_name(p.first)},
                     {"second", calibration_parameter_name(p.second)},
                     {"correlation", p.correlation}});
  }
  report["correlated_pairs"] = pairs;
  const Identification& id = result.identification;
  const auto& s = id.singular_values;
  report["identification"] = {
      {"free_parameters", id.free_indices.size()},
      {"rank", id.rank},
      {"singular_values", std::vector<double>(s.data(), s.data() + s.size())},
      {"O1", id.O1},
      {"O2", id.O2},
      {"O3", id.O3},
      {"O4", id.O4},
      {"scaled",
       {{"parameter_scale", std::vector<double>(id.column_scale.data(),
                                                id.column_scale.data() + id.column_scale.size())},
        {"singular_values",
         std::vector<double>(id.scaled.singular_values.data(),
                             id.scaled.singular_values.data() + id.scaled.singular_values.size())},
        {"O1", id.scaled.O1},
        {"O2", id.scaled.O2},
        {"O3", id.scaled.O3},
        {"O4", id.scaled.O4}}}};
  json outliers = json::array();
  for (int r : result.outliers) {
    const int k = setup.fit[static_cast<std::size_t>(r)];
    outliers.push_back({{"row", k + 1},
                        {"line", setup.measurements[static_cast<std::size_t>(k)].line},
                        {"chi2", result.chi2[static_cast<std::size_t>(r)]}});
  }
  report["outliers"] = outliers;
  report["held_out_outliers"] = held_out_outliers;
  report["outlier_chi2"] = setup.options.outlier_chi2;
  report["split_half"] = split_half_check(setup, result);
  report["status"] = calibration_status(report, result, setup.options.max_rejected_share);
  return report;
}

nlohmann::json split_half_check(const CalibrationSetup& setup, const CalibrationResult& result) {
  // The inliers of the fit, alternately into two halves (so both span the workspace alike).
  std::array<std::vector<CalibrationMeasurement>, 2> halves;
  std::size_t n = 0;
  for (std::size_t r = 0; r < setup.fit.size(); ++r) {
    if (std::find(result.outliers.begin(), result.outliers.end(), static_cast<int>(r)) !=
        result.outliers.end())
      continue;
    halves[n++ % 2].push_back(setup.measurements[static_cast<std::size_t>(setup.fit[r])]);
  }
  CalibrationOptions options = setup.options;
  options.reject_outliers = false;  // the inliers only; their sigmas as the full fit found them
  options.estimate_noise = false;
  options.sigma_position = result.estimated_sigma(0);
  options.sigma_orientation = result.estimated_sigma(1);
  options.sigma_actuator = result.estimated_sigma(2);
  std::array<CalibrationResult, 2> fits;
  try {
    for (int h = 0; h < 2; ++h)
      fits[static_cast<std::size_t>(h)] = calibrate(setup.nominal_design, setup.nominal,
                                                    halves[static_cast<std::size_t>(h)], options);
  } catch (const CalibrationError& e) {
    return {{"done", false}, {"reason", e.what()}};
  }
  // z = (theta_A - theta_B) / sqrt(sigma_A^2 + sigma_B^2) over the free parameters: about
  // standard normal when the reported sigmas are believable.
  double sum = 0.0, worst = 0.0;
  int count = 0;
  std::string worst_name;
  for (int i = 0; i < kCalibrationParameters; ++i) {
    if (!options.free[static_cast<std::size_t>(i)]) continue;
    const double s = std::hypot(fits[0].sigma(i), fits[1].sigma(i));
    if (!(s > 0.0)) continue;
    const double z = (fits[0].estimate(i) - fits[1].estimate(i)) / s;
    sum += z * z;
    ++count;
    if (std::abs(z) > worst) {
      worst = std::abs(z);
      worst_name = calibration_parameter_name(i);
    }
  }
  return {{"done", count > 0},   {"poses", {halves[0].size(), halves[1].size()}},
          {"parameters", count}, {"z_rms", count > 0 ? std::sqrt(sum / count) : 0.0},
          {"z_max", worst},      {"z_max_parameter", worst_name}};
}

nlohmann::json calibration_status(const nlohmann::json& report, const CalibrationResult& result,
                                  double max_rejected_share) {
  nlohmann::json warnings = nlohmann::json::array();
  if (!result.converged)
    warnings.push_back(fmt::format("the fit did not converge ({})", result.solver_message));
  const int fitted = report["poses"]["fitted"].get<int>();
  const int rejected = report["poses"]["outliers"].get<int>();
  const int attempted = fitted + rejected;
  if (attempted > 0 && rejected > max_rejected_share * attempted)
    warnings.push_back(fmt::format(
        "{} of {} poses of the fit ({:.0f} %) were rejected as outliers, more than {:.0f} %: "
        "check the units of the readings and the poses, the quaternion order and the fixed "
        "parameters",
        rejected, attempted, 100.0 * rejected / attempted, 100.0 * max_rejected_share));
  for (const char* set : {"fitted", "held_out"}) {
    const auto& e = report["errors"]["after"][set];
    const int failures = e["fk_failures"].get<int>();
    if (failures > 0)
      warnings.push_back(fmt::format(
          "forward kinematics of the calibrated machine failed on {} of {} {} poses: their TCP "
          "errors are not in the table",
          failures, e["count"].get<int>(), std::string(set) == "fitted" ? "fitted" : "held-out"));
  }
  return {{"ok", warnings.empty()}, {"warnings", warnings}};
}

std::string calibration_report_text(const nlohmann::json& r) {
  std::string out;
  out += fmt::format("pkmopt calibration report ({})\n", r["calibration_file"].get<std::string>());
  out += fmt::format("machine: {}\nmeasurements: {}\n", r["machine_file"].get<std::string>(),
                     r["measurement_file"].get<std::string>());
  out += fmt::format(
      "frame: {}, model: {}, poses: {} total, {} fitted, {} held out, {} outliers in the fit, "
      "{} among the held-out rows\n",
      r["frame"].get<std::string>(), r["model"].get<std::string>(), r["poses"]["total"].get<int>(),
      r["poses"]["fitted"].get<int>(), r["poses"]["held_out"].get<int>(),
      r["poses"]["outliers"].get<int>(), r["poses"]["held_out_outliers"].get<int>());
  if (r.contains("status") && !r["status"]["ok"].get<bool>()) {
    out += "\nWARNING: this result is probably wrong:\n";
    for (const auto& w : r["status"]["warnings"]) out += "  - " + w.get<std::string>() + "\n";
    out += "\n";
  }
  if (r.contains("input_warnings"))
    for (const auto& w : r["input_warnings"])
      out += "input warning: " + w.get<std::string>() + "\n";
  if (r.contains("noise_estimate")) {
    const auto& n = r["noise_estimate"];
    auto sigma = [&](const char* key, double unit, const char* unit_name, const char* format) {
      const auto& g = n[key];
      std::string text = fmt::format(fmt::runtime(format), g["used"].get<double>() * unit);
      text += unit_name;
      if (!n["estimated"].get<bool>()) return text + " (given)";
      if (!g["resolved"].get<bool>())
        return text + fmt::format(fmt::runtime(std::string(" (not resolved by the data; given ") +
                                               format + "{})"),
                                  g["given"].get<double>() * unit, unit_name);
      return text +
             fmt::format(
                 fmt::runtime(std::string(" (estimated +-{:.0f} %, given ") + format + "{})"),
                 50.0 * g["relative_sd"].get<double>(), g["given"].get<double>() * unit, unit_name);
    };
    out += fmt::format("noise: position {}, orientation {}, readings {}\n",
                       sigma("position", 1e6, " um", "{:.3g}"),
                       sigma("orientation_deg", 1.0, " deg", "{:.3g}"),
                       sigma("actuator", 1e6, " um", "{:.3g}"));
  }
  out += fmt::format("solver: converged {}, {} iterations, chi2/dof {:.3f}\n",
                     r["solver"]["converged"].get<bool>(), r["solver"]["iterations"].get<int>(),
                     r["solver"]["chi2_per_dof"].get<double>());
  out += fmt::format("gauge ({}): {}\n", r["gauge"]["mode"].get<std::string>(),
                     r["gauge"]["reason"].get<std::string>());
  if (!r["gauge"]["fixed"].empty()) {
    std::string names;
    for (const auto& n : r["gauge"]["fixed"]) {
      names.push_back(' ');
      names.append(n.get<std::string>());
    }
    out += fmt::format("  held at nominal:{}\n", names);
  }
  out += "\nErrors (um for legs and TCP position, deg for TCP orientation)\n";
  out += fmt::format("{:<30}{:>8}{:>12}{:>12}{:>14}{:>14}{:>12}{:>12}\n", "", "poses", "leg rms",
                     "leg max", "TCP pos rms", "TCP pos max", "TCP rot rms", "TCP rot max");
  for (const char* when : {"before", "after"}) {
    for (const char* set : {"fitted", "held_out", "held_out_inliers"}) {
      const auto& e = r["errors"][when][set];
      double leg_max = 0.0;
      for (const auto& v : e["leg_max"]) leg_max = std::max(leg_max, v.get<double>());
      const int count = e["count"].get<int>();
      const int solved = count - e["fk_failures"].get<int>();
      // No poses (or no forward-kinematics solution): "n/a", never a 0.00 that reads as exact.
      auto cell = [](bool have, double value, int width, int digits) {
        return have ? fmt::format("{:>{}.{}f}", value, width, digits)
                    : fmt::format("{:>{}}", "n/a", width);
      };
      out += fmt::format("{:<30}{:>8}", fmt::format("{} / {}", when, set), count);
      out += cell(count > 0, 1e6 * e["leg_rms_all"].get<double>(), 12, 2);
      out += cell(count > 0, 1e6 * leg_max, 12, 2);
      out += cell(solved > 0, 1e6 * e["tcp_position_rms"].get<double>(), 14, 2);
      out += cell(solved > 0, 1e6 * e["tcp_position_max"].get<double>(), 14, 2);
      out += cell(solved > 0, e["tcp_orientation_rms_deg"].get<double>(), 12, 5);
      out += cell(solved > 0, e["tcp_orientation_max_deg"].get<double>(), 12, 5);
      out += solved < count
                 ? fmt::format("  ({} without a forward-kinematics solution)\n", count - solved)
                 : "\n";
    }
  }
  out +=
      fmt::format("noise floor (sqrt(3) sigma): TCP position {:.2f} um, orientation {:.5f} deg\n",
                  1e6 * r["noise_floor"]["tcp_position_rms"].get<double>(),
                  r["noise_floor"]["tcp_orientation_rms_deg"].get<double>());
  if (r.contains("campaigns") && !r["campaigns"].empty()) {
    out +=
        "\nCampaigns (leg zero shifts against the reference, um; held-out rows use their "
        "campaign's fitted shifts)\n";
    for (const auto& c : r["campaigns"]) {
      out += fmt::format("  {:<16} {:>4} fitted, {:>4} held out", c["label"].get<std::string>(),
                         c["fitted_rows"].get<int>(), c["held_out_rows"].get<int>());
      if (c["reference"].get<bool>()) {
        out += "  (reference)\n";
      } else if (!c.value("estimated", false)) {
        out += "  no fitted rows: no shifts estimated (taken as 0)\n";
      } else {
        for (int i = 0; i < 6; ++i)
          out += fmt::format("  {:+.1f} +-{:.1f}", 1e6 * c["shifts"][i].get<double>(),
                             1e6 * c["shift_sigma"][i].get<double>());
        out += "\n";
      }
    }
  }
  if (r.contains("split_half")) {
    const auto& s = r["split_half"];
    if (s["done"].get<bool>())
      out += fmt::format(
          "\nSplit-half check (the inliers fitted in two alternate halves of {} and {} poses): "
          "parameter differences over their sigmas, rms {:.2f} (about 1 when the sigmas are "
          "believable), largest {:.2f} ({})\n",
          s["poses"][0].get<int>(), s["poses"][1].get<int>(), s["z_rms"].get<double>(),
          s["z_max"].get<double>(), s["z_max_parameter"].get<std::string>());
    else
      out += "\nSplit-half check: not possible (" +
             s.value("reason", std::string("no free parameter")) + ")\n";
  }
  const auto& id = r["identification"];
  out += fmt::format(
      "\nIdentification: rank {} of {} free\n"
      "  unscaled (parameters in m, 1, rad): O1 {}  O2 (cond) {}  O3 (sigma_min) {}  O4 {}\n"
      "  scaled (parameters in units of their a-priori sigma): O1 {}  O2 {}  O3 {}  O4 {}\n",
      id["rank"].get<int>(), id["free_parameters"].get<int>(), observability_text(id["O1"]),
      observability_text(id["O2"]), observability_text(id["O3"]), observability_text(id["O4"]),
      observability_text(id["scaled"]["O1"]), observability_text(id["scaled"]["O2"]),
      observability_text(id["scaled"]["O3"]), observability_text(id["scaled"]["O4"]));
  out += "\nParameters (m, deg, or 1 for gains; change = estimate - nominal)\n";
  out += fmt::format("{:<15}{:>5}{:>16}{:>16}{:>14}{:>14}\n", "name", "free", "nominal", "estimate",
                     "change", "sigma");
  for (const auto& p : r["parameters"]) {
    out += fmt::format("{:<15}{:>5}{:>16.9f}{:>16.9f}{:>14.3e}{:>14.3e}\n",
                       p["name"].get<std::string>(), p["free"].get<bool>() ? "yes" : "no",
                       p["nominal"].get<double>(), p["estimate"].get<double>(),
                       p["change"].get<double>(), p["sigma"].get<double>());
  }
  out += "\nStrongly correlated pairs\n";
  if (r["correlated_pairs"].empty()) out += "  none\n";
  for (const auto& p : r["correlated_pairs"]) {
    out += fmt::format("  {} ~ {}: {:.4f}\n", p["first"].get<std::string>(),
                       p["second"].get<std::string>(), p["correlation"].get<double>());
  }
  out += fmt::format("\nOutliers (pose chi2 > {})\n", r["outlier_chi2"].get<double>());
  if (r["outliers"].empty()) out += "  none\n";
  for (const auto& o : r["outliers"]) {
    out += fmt::format("  data row {} (line {}): chi2 {:.1f}\n", o["row"].get<int>(),
                       o["line"].get<int>(), o["chi2"].get<double>());
  }
  out += fmt::format(
      "\nHeld-out outliers (pose chi2 > {} with the calibrated machine; excluded from "
      "held_out_inliers)\n",
      r["outlier_chi2"].get<double>());
  if (r["held_out_outliers"].empty()) out += "  none\n";
  for (const auto& o : r["held_out_outliers"]) {
    out += fmt::format("  data row {} (line {}): chi2 {:.1f}\n", o["row"].get<int>(),
                       o["line"].get<int>(), o["chi2"].get<double>());
  }
  return out;
}

}  // namespace pkmopt
