// Tests of io/calibration/calibration_report: the report's status names each probably-wrong
// condition, and report.txt of the shipped calibration demo carries every section of report.json
// in order, its numbers as the JSON holds them.
#include "io/calibration/calibration_report.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

namespace {

// The status of a report: each probably-wrong condition gives its warning, none gives ok.
TEST(CalibrationStatus, EachProblemIsNamed) {
  nlohmann::json report;
  report["poses"] = {{"fitted", 90}, {"outliers", 10}};
  for (const char* set : {"fitted", "held_out"})
    report["errors"]["after"][set] = {{"count", 30}, {"fk_failures", 0}};
  pkmopt::CalibrationResult result;
  result.converged = true;
  EXPECT_TRUE(pkmopt::calibration_status(report, result, 0.2)["ok"].get<bool>());
  result.converged = false;
  result.solver_message = "Maximum number of iterations reached.";
  nlohmann::json status = pkmopt::calibration_status(report, result, 0.2);
  EXPECT_FALSE(status["ok"].get<bool>());
  ASSERT_EQ(status["warnings"].size(), 1u);
  EXPECT_EQ(status["warnings"][0],
            "the fit did not converge (Maximum number of iterations reached.)");
  result.converged = true;
  status = pkmopt::calibration_status(report, result, 0.05);  // 10 of 100 > 5 %
  ASSERT_EQ(status["warnings"].size(), 1u);
  EXPECT_EQ(status["warnings"][0].get<std::string>().rfind("10 of 100 poses of the fit (10 %)", 0),
            0u);
  report["errors"]["after"]["held_out"]["fk_failures"] = 3;
  status = pkmopt::calibration_status(report, result, 0.2);
  ASSERT_EQ(status["warnings"].size(), 1u);
  EXPECT_EQ(status["warnings"][0].get<std::string>().rfind(
                "forward kinematics of the calibrated machine failed on 3 of 30 held-out poses", 0),
            0u);
}

// report.txt of a real calibration (the shipped demo: simulated measurements of a known machine):
// the sections in order, and the numbers of report.json in them.
TEST(CalibrationReport, TextCarriesEverySectionOfTheJson) {
  const std::string file = (std::filesystem::path(PKMOPT_SOURCE_DIR) / "studies" / "library" /
                            "calibration-demo" / "calibration.yaml")
                               .string();
  const pkmopt::CalibrationSetup setup = pkmopt::read_calibration_setup(file);
  const pkmopt::CalibrationResult result = pkmopt::calibrate(
      setup.nominal_design, setup.nominal, pkmopt::fitted_measurements(setup), setup.options);
  const nlohmann::json report = pkmopt::calibration_report_json(setup, result);
  ASSERT_TRUE(report["status"]["ok"].get<bool>()) << report["status"].dump();
  const std::string text = pkmopt::calibration_report_text(report);
  std::size_t at = 0;
  for (const char* section :
       {"pkmopt calibration report (", "frame: ", "noise: position ", "solver: converged true",
        "gauge (", "\nErrors (um", "after / fitted", "noise floor (sqrt(3) sigma)",
        "\nIdentification: rank ", "\nParameters (m, deg", "\nStrongly correlated pairs",
        "\nOutliers (pose chi2 > ", "\nHeld-out outliers"}) {
    const std::size_t found = text.find(section, at);
    ASSERT_NE(found, std::string::npos) << section << " after offset " << at << "\n" << text;
    at = found;
  }
  EXPECT_NE(text.find(fmt::format("poses: {} total, {} fitted", report["poses"]["total"].get<int>(),
                                  report["poses"]["fitted"].get<int>())),
            std::string::npos);
  for (const auto& p : report["parameters"])
    EXPECT_NE(text.find(fmt::format("{:<15}", p["name"].get<std::string>())), std::string::npos)
        << p["name"];
}

}  // namespace
