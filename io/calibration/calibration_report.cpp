#include "io/calibration/calibration_report.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

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

namespace {

// The noise the fit used: given, estimated from the residuals, or not resolved by the data.
nlohmann::json noise_estimate_json(const CalibrationResult& result) {
  using nlohmann::json;
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
  return estimate;
}

// The gauge: the parameters held at nominal to define the frames, and why.
nlohmann::json gauge_json(const CalibrationSetup& setup) {
  std::vector<std::string> gauge_names;
  for (int index : setup.gauge_fixed) gauge_names.push_back(calibration_parameter_name(index));
  std::string reason =
      setup.frame == "base"
          ? "poses measured in the base frame: the instrument defines the base frame and the "
            "target the TCP frame, no gauge freedom exists"
          : "instrument and target transforms are free: any rigid motion of the base frame "
            "(6) and of the platform frame (6) leaves the data unchanged; the listed joint "
            "coordinates are held at nominal to define both frames";
  return {{"mode", setup.gauge}, {"fixed", gauge_names}, {"reason", reason}};
}

// The errors before (nominal machine, as measured) and after (calibrated machine, with each
// campaign's shifts) on the fitted inliers, the held-out rows and the held-out inliers.
nlohmann::json errors_report_json(const CalibrationSetup& setup, const CalibrationResult& result,
                                  const std::vector<CalibrationMeasurement>& shifted,
                                  const std::vector<int>& inliers,
                                  const std::vector<int>& held_out_inliers) {
  using nlohmann::json;
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
  return errors;
}

// The parameters of the model (the instrument's and target's in the instrument frame), in
// m, deg or 1: nominal, estimate, change and sigma.
nlohmann::json parameters_json(const CalibrationSetup& setup, const CalibrationResult& result) {
  using nlohmann::json;
  const CalibrationVector& nominal = setup.nominal;
  const CalibrationVector& estimate = result.estimate;
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
  return parameters;
}

// Measurement campaigns: each one's leg zero shifts against the reference (the first label).
nlohmann::json campaigns_json(const CalibrationSetup& setup, const CalibrationResult& result) {
  using nlohmann::json;
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
  return campaigns;
}

// How well the data identify the free parameters: rank, singular values, observability indices.
nlohmann::json identification_json(const Identification& id) {
  using nlohmann::json;
  const auto& s = id.singular_values;
  return {
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
}

// Held-out rows screened with the calibrated machine (`fitted`: the sigmas of the final fit):
// each row's own pose fitted with the machine held; chi^2 above the threshold flags a gross
// outlier. Returns the outliers {row, line, chi2}; the other rows go to `inliers`.
nlohmann::json screen_held_out(const CalibrationSetup& setup, const CalibrationResult& result,
                               const std::vector<CalibrationMeasurement>& shifted,
                               const CalibrationOptions& fitted, std::vector<int>& inliers) {
  const std::vector<double> held_out_chi2 = fixed_machine_chi2(
      setup.nominal_design.tcp, result.estimate, shifted, setup.held_out, fitted);
  nlohmann::json outliers = nlohmann::json::array();
  for (std::size_t r = 0; r < setup.held_out.size(); ++r) {
    const int k = setup.held_out[r];
    if (held_out_chi2[r] > setup.options.outlier_chi2) {
      outliers.push_back({{"row", k + 1},
                          {"line", setup.measurements[static_cast<std::size_t>(k)].line},
                          {"chi2", held_out_chi2[r]}});
    } else {
      inliers.push_back(k);
    }
  }
  return outliers;
}

}  // namespace

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
  report["noise_estimate"] = noise_estimate_json(result);

  std::vector<int> inliers;  // the fitted rows the fit kept
  for (std::size_t r = 0; r < setup.fit.size(); ++r) {
    if (std::find(result.outliers.begin(), result.outliers.end(), static_cast<int>(r)) ==
        result.outliers.end()) {
      inliers.push_back(setup.fit[r]);
    }
  }
  // The calibrated machine sees each campaign with its estimated leg zero shifts.
  const std::vector<CalibrationMeasurement> shifted =
      with_campaign_shifts(setup.measurements, result);
  std::vector<int> held_out_inliers;
  const json held_out_outliers = screen_held_out(setup, result, shifted, fitted, held_out_inliers);
  report["poses"] = {{"total", setup.measurements.size()},
                     {"fitted", inliers.size()},
                     {"held_out", setup.held_out.size()},
                     {"outliers", result.outliers.size()},
                     {"held_out_outliers", held_out_outliers.size()}};

  std::vector<std::string> fixed_names;
  for (int index : setup.fixed) fixed_names.push_back(calibration_parameter_name(index));
  report["gauge"] = gauge_json(setup);
  report["fixed_by_user"] = fixed_names;

  report["solver"] = {{"converged", result.converged},
                      {"iterations", result.iterations},
                      {"message", result.solver_message},
                      {"chi2_per_dof", result.chi2_per_dof}};

  report["errors"] = errors_report_json(setup, result, shifted, inliers, held_out_inliers);
  report["noise_floor"] = {
      {"tcp_position_rms", std::sqrt(3.0) * fitted.sigma_position},
      {"tcp_orientation_rms_deg", std::sqrt(3.0) * rad_to_deg(fitted.sigma_orientation)}};

  report["parameters"] = parameters_json(setup, result);
  report["campaigns"] = campaigns_json(setup, result);
  json pairs = json::array();
  for (const CorrelatedPair& p : result.correlated) {
    pairs.push_back({{"first", calibration_parameter_name(p.first)},
                     {"second", calibration_parameter_name(p.second)},
                     {"correlation", p.correlation}});
  }
  report["correlated_pairs"] = pairs;
  report["identification"] = identification_json(result.identification);
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

namespace {

// The files, the poses, a warning when the result is probably wrong, and the input warnings.
std::string report_header_text(const nlohmann::json& r) {
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
  return out;
}

// The noise the fit used (given, estimated or not resolved); empty without an estimate.
std::string noise_text(const nlohmann::json& r) {
  std::string out;
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
  return out;
}

// The errors before and after, on the fitted, held-out and held-out inlier rows, and the
// noise floor.
std::string errors_text(const nlohmann::json& r) {
  std::string out;
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
  return out;
}

// Each campaign's leg zero shifts against the reference; empty with one campaign.
std::string campaigns_text(const nlohmann::json& r) {
  std::string out;
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
  return out;
}

// The split-half check.
std::string split_half_text(const nlohmann::json& r) {
  std::string out;
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
  return out;
}

// How well the data identify the free parameters.
std::string identification_text(const nlohmann::json& r) {
  std::string out;
  const auto& id = r["identification"];
  out += fmt::format(
      "\nIdentification: rank {} of {} free\n"
      "  unscaled (parameters in m, 1, rad): O1 {}  O2 (cond) {}  O3 (sigma_min) {}  O4 {}\n"
      "  scaled (parameters in units of their a-priori sigma): O1 {}  O2 {}  O3 {}  O4 {}\n",
      id["rank"].get<int>(), id["free_parameters"].get<int>(), observability_text(id["O1"]),
      observability_text(id["O2"]), observability_text(id["O3"]), observability_text(id["O4"]),
      observability_text(id["scaled"]["O1"]), observability_text(id["scaled"]["O2"]),
      observability_text(id["scaled"]["O3"]), observability_text(id["scaled"]["O4"]));
  return out;
}

// The parameters and the strongly correlated pairs.
std::string parameters_text(const nlohmann::json& r) {
  std::string out;
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
  return out;
}

// The outliers of the fit and among the held-out rows.
std::string outliers_text(const nlohmann::json& r) {
  std::string out;
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

}  // namespace

std::string calibration_report_text(const nlohmann::json& r) {
  std::string out = report_header_text(r) + noise_text(r);
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
  out += errors_text(r) + campaigns_text(r) + split_half_text(r) + identification_text(r) +
         parameters_text(r) + outliers_text(r);
  return out;
}

}  // namespace pkmopt
