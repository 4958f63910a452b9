// The report of a calibration (docs/calibration.md): report.json, its status, the split-half
// check and report.txt, from the setup read by io/calibration/calibration_files.hpp and the
// result of calibrate (problems/calibration/calibration.hpp).
//
// Example:
//   const nlohmann::json report = calibration_report_json(setup, result);
//   write_file_atomically("report.txt", calibration_report_text(report));
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "io/calibration/calibration_files.hpp"
#include "problems/calibration/calibration.hpp"

namespace pkmopt {

/// The report of a calibration as JSON (see docs/calibration.md for every field).
nlohmann::json calibration_report_json(const CalibrationSetup& setup,
                                       const CalibrationResult& result);
/// The report's `status`: {ok, warnings}; not ok (a result that is probably wrong) when the fit
/// did not converge, when more than `max_rejected_share` of the fitted poses were rejected, or
/// when forward kinematics of the calibrated machine fails on fitted or held-out poses.
nlohmann::json calibration_status(const nlohmann::json& report, const CalibrationResult& result,
                                  double max_rejected_share);
/// The split-half check of a calibration: its inlier poses fitted again in two alternate
/// halves (the sigmas of the full fit, no outlier rejection), and for the free parameters
/// z = (estimate_A - estimate_B) / sqrt(sigma_A^2 + sigma_B^2): {done, poses, parameters, z_rms,
/// z_max, z_max_parameter}; z_rms near 1 says the reported sigmas are believable. {done: false,
/// reason} when a half cannot identify the parameters.
nlohmann::json split_half_check(const CalibrationSetup& setup, const CalibrationResult& result);
/// The same report as readable text.
std::string calibration_report_text(const nlohmann::json& report);

}  // namespace pkmopt
