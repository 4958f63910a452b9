// Tests of the pkmopt binary for calibration: simulate-measurements -> calibrate -> analyze on
// the calibrated machine file, and bad calibration inputs giving exit status 2, one message
// and no output files.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "io/format/csv.hpp"
#include "tests/cli_runner.hpp"
#include "tests/scratch_dir.hpp"

namespace {

namespace fs = std::filesystem;

using cli_runner::CliRun;
using cli_runner::read_text;

class CalibrateCli : public scratch::ScratchDirTest {
 protected:
  void SetUp() override {
    machine_ = (fs::path(PKMOPT_SOURCE_DIR) / "examples/hexapod.yaml").string();
  }

  CliRun run(const std::string& args) { return run_cli(args); }

  // Simulated measurements (40 poses, 3 outliers) in dir_/sim; returns the CSV lines.
  std::vector<std::string> simulate() {
    const CliRun r =
        run("simulate-measurements " + machine_ + " --out " + path("sim") + " --poses 40 --seed 3");
    EXPECT_EQ(r.status, 0) << r.err;
    std::vector<std::string> lines;
    std::istringstream in(read_text(path("sim/measurements.csv")));
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    return lines;
  }

  // A calibration YAML next to the simulated data with `body` after the machine key.
  std::string calibration_file(const std::string& measurements, const std::string& body) {
    return write("calibration.yaml", "machine: " + path("sim/nominal.yaml") +
                                         "\nmeasurements: " + measurements + "\n" + body);
  }

  // Bad input: status 2, one line on stderr containing `fragment`, nothing in --out.
  void expect_calibrate_error(const std::string& calibration, const std::string& fragment) {
    const std::string out_dir = path("out");
    const CliRun r = run("calibrate " + calibration + " --out " + out_dir);
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_NE(r.err.find(fragment), std::string::npos) << "stderr: " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
    EXPECT_FALSE(fs::exists(out_dir));
  }

  std::string machine_;
};

const char* kGoodSettings =
    "frame: base\n"
    "actuators: {unit: mm, zero_length: 0.7}\n"
    "noise: {position: 2.0e-5, orientation_deg: 0.003, actuator: 0.001}\n"
    "model: 48\n";

TEST_F(CalibrateCli, SimulateCalibrateAnalyze) {
  const std::vector<std::string> lines = simulate();
  ASSERT_EQ(lines.size(), 41u);
  EXPECT_EQ(lines[0], "x,y,z,rx,ry,rz,q_1,q_2,q_3,q_4,q_5,q_6");
  for (const char* name : {"nominal.yaml", "truth.yaml", "truth.json", "calibration.yaml"}) {
    EXPECT_TRUE(fs::exists(path(std::string("sim/") + name))) << name;
  }
  // The same seed writes the same measurements.
  ASSERT_EQ(
      run("simulate-measurements " + machine_ + " --out " + path("sim2") + " --poses 40 --seed 3")
          .status,
      0);
  EXPECT_EQ(read_text(path("sim/measurements.csv")), read_text(path("sim2/measurements.csv")));

  const CliRun cal = run("calibrate " + path("sim/calibration.yaml") + " --out " + path("cal"));
  ASSERT_EQ(cal.status, 0) << cal.err;
  EXPECT_NE(cal.out.find("Held-out outliers"), std::string::npos);
  const nlohmann::json report = nlohmann::json::parse(read_text(path("cal/report.json")));
  EXPECT_EQ(read_text(path("cal/report.txt")), cal.out);
  EXPECT_EQ(report["poses"]["total"].get<int>(), 40);
  EXPECT_EQ(report["identification"]["rank"].get<int>(), 48);
  EXPECT_TRUE(report["solver"]["converged"].get<bool>());

  // Every simulated outlier is found, among the fitted or among the held-out rows, and no other.
  const nlohmann::json truth = nlohmann::json::parse(read_text(path("sim/truth.json")));
  std::set<int> expected, found;
  for (const auto& row : truth["outlier_rows"]) expected.insert(row.get<int>());
  for (const auto& o : report["outliers"]) found.insert(o["row"].get<int>());
  for (const auto& o : report["held_out_outliers"]) found.insert(o["row"].get<int>());
  EXPECT_EQ(found, expected);

  // Nominal misses by millimetres; calibrated, the clean held-out rows come within 3 times the
  // noise floor (sqrt(3) sigma), and the held-out RMS over all rows is the larger one when
  // gross outliers are held out.
  const double floor = report["noise_floor"]["tcp_position_rms"].get<double>();
  const auto& errors = report["errors"];
  EXPECT_GT(errors["before"]["held_out_inliers"]["tcp_position_rms"].get<double>(), 5e-4);
  EXPECT_LT(errors["after"]["held_out_inliers"]["tcp_position_rms"].get<double>(), 3.0 * floor);
  EXPECT_LT(errors["after"]["fitted"]["tcp_position_rms"].get<double>(), 3.0 * floor);
  EXPECT_GE(errors["after"]["held_out"]["tcp_position_rms"].get<double>(),
            errors["after"]["held_out_inliers"]["tcp_position_rms"].get<double>());
  EXPECT_EQ(errors["after"]["held_out"]["count"].get<int>(),
            errors["after"]["held_out_inliers"]["count"].get<int>() +
                static_cast<int>(report["held_out_outliers"].size()));

  // The calibrated machine file works with analyze and differs from the nominal one.
  const std::string poses =
      write("poses.csv", "x,y,z,rx,ry,rz\n0,0,0.85,0,0,0\n0.05,0,0.8,3,0,5\n");
  const CliRun calibrated = run("analyze " + path("cal/calibrated.yaml") + " --poses " + poses +
                                " --out " + path("calibrated.csv"));
  ASSERT_EQ(calibrated.status, 0) << calibrated.err;
  const CliRun nominal = run("analyze " + path("sim/nominal.yaml") + " --poses " + poses +
                             " --out " + path("nominal.csv"));
  ASSERT_EQ(nominal.status, 0) << nominal.err;
  const pkmopt::CsvTable a = pkmopt::read_csv_file(path("calibrated.csv"));
  const pkmopt::CsvTable b = pkmopt::read_csv_file(path("nominal.csv"));
  ASSERT_EQ(a.rows.size(), 2u);
  ASSERT_EQ(b.rows.size(), 2u);
  double largest_change = 0.0;
  for (int i = 1; i <= 6; ++i) {
    const int column = a.require_column("q_" + std::to_string(i));
    for (std::size_t r = 0; r < 2; ++r) {
      largest_change = std::max(
          largest_change, std::abs(a.number(a.rows[r], column) - b.number(b.rows[r], column)));
    }
  }
  EXPECT_GT(largest_change, 1e-4);  // joints moved by about a millimetre
  EXPECT_LT(largest_change, 1e-2);
}

TEST_F(CalibrateCli, WrongColumnCountIsAnError) {
  std::vector<std::string> lines = simulate();
  lines[5] = lines[5].substr(0, lines[5].rfind(','));  // row 5 loses q_6
  std::string text;
  for (const auto& line : lines) text += line + "\n";
  const std::string csv = write("measurements.csv", text);
  expect_calibrate_error(calibration_file(csv, kGoodSettings), "expected 12 fields");
}

TEST_F(CalibrateCli, MissingReadingColumnIsAnError) {
  std::vector<std::string> lines = simulate();
  std::string text;
  for (const auto& line : lines) text += line.substr(0, line.rfind(',')) + "\n";  // no q_6
  const std::string csv = write("measurements.csv", text);
  expect_calibrate_error(calibration_file(csv, kGoodSettings), "q_6");
}

TEST_F(CalibrateCli, MissingUnitIsAnError) {
  simulate();
  expect_calibrate_error(
      calibration_file(path("sim/measurements.csv"),
                       "actuators: {zero_length: 0.7}\n"
                       "noise: {position: 2.0e-5, orientation_deg: 0.003, actuator: 0.001}\n"),
      "unit");
}

TEST_F(CalibrateCli, NaNIsAnError) {
  std::vector<std::string> lines = simulate();
  lines[7].replace(0, lines[7].find(','), "nan");
  std::string text;
  for (const auto& line : lines) text += line + "\n";
  const std::string csv = write("measurements.csv", text);
  expect_calibrate_error(calibration_file(csv, kGoodSettings), "expected a finite number");
}

TEST_F(CalibrateCli, TooFewPosesIsAnError) {
  std::vector<std::string> lines = simulate();
  std::string text;
  for (std::size_t i = 0; i <= 8; ++i) text += lines[i] + "\n";  // 8 poses for 48 parameters
  const std::string csv = write("measurements.csv", text);
  expect_calibrate_error(calibration_file(csv, kGoodSettings), "too few poses");
}

// Without rotations a_i and b_i cannot be told apart: the message names them.
TEST_F(CalibrateCli, NonIdentifiableParameterIsAnError) {
  std::vector<std::string> lines = simulate();
  std::string text = lines[0] + "\n";
  for (std::size_t i = 1; i < lines.size(); ++i) {
    std::vector<std::string> cells;
    std::istringstream in(lines[i]);
    for (std::string cell; std::getline(in, cell, ',');) cells.push_back(cell);
    cells[3] = cells[4] = cells[5] = "0";
    std::string row;
    for (const auto& cell : cells) row += (row.empty() ? "" : ",") + cell;
    text += row + "\n";
  }
  const std::string csv = write("measurements.csv", text);
  expect_calibrate_error(calibration_file(csv, kGoodSettings), "cannot identify");
  const CliRun r = run("calibrate " + path("calibration.yaml") + " --out " + path("out"));
  EXPECT_NE(r.err.find("b1.x"), std::string::npos) << r.err;
}

// Instrument and target transforms free with `gauge: none`: the 12 frame freedoms are named.
TEST_F(CalibrateCli, GaugeLeftFreeIsAnError) {
  simulate();
  expect_calibrate_error(calibration_file(path("sim/measurements.csv"),
                                          "frame: instrument\n"
                                          "instrument: {position: [0, 0, 0]}\n"
                                          "actuators: {unit: mm, zero_length: 0.7}\n"
                                          "noise: {position: 2.0e-5, orientation_deg: 0.003, "
                                          "actuator: 0.001}\n"
                                          "gauge: none\n"),
                         "instrument.x");
}

}  // namespace

namespace {

// A result that is probably wrong is written and said: more rejected poses than
// max_rejected_share allows (the 3 simulated gross errors of 40 poses against 1 %) exits with
// status 3, one warning line naming the reason, and the report (text and JSON) saying it first.
TEST_F(CalibrateCli, TooManyRejectedPosesAreWrittenAndExitThree) {
  simulate();
  const std::string calibration =
      calibration_file(path("sim/measurements.csv"),
                       "actuators: {unit: mm, zero_length: 0.7}\n"
                       "noise: {position: 2.0e-5, orientation_deg: 0.003, actuator: 0.001}\n"
                       "max_rejected_share: 0.01\n");
  const CliRun r = run("calibrate " + calibration + " --out " + path("out"));
  EXPECT_EQ(r.status, 3) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_EQ(r.err.rfind("pkmopt: warning: ", 0), 0u) << r.err;
  EXPECT_NE(r.err.find("probably wrong: 3 of 40 poses of the fit (8 %) were rejected"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.out.find("WARNING: this result is probably wrong:"), std::string::npos);
  const nlohmann::json report = nlohmann::json::parse(read_text(path("out/report.json")));
  EXPECT_FALSE(report["status"]["ok"].get<bool>());
  EXPECT_EQ(report["status"]["warnings"].size(), 1u);
  EXPECT_TRUE(fs::exists(path("out/calibrated.yaml")));
}

// The given sigmas are only the start: the report gives them beside the estimated ones.
TEST_F(CalibrateCli, ReportGivesEstimatedAndGivenNoise) {
  simulate();
  const std::string calibration =
      calibration_file(path("sim/measurements.csv"),
                       "actuators: {unit: mm, zero_length: 0.7}\n"
                       "noise: {position: 2.0e-6, orientation_deg: 0.03, actuator: 0.001}\n");
  const CliRun r = run("calibrate " + calibration + " --out " + path("out"));
  EXPECT_EQ(r.status, 0) << r.err;
  const nlohmann::json report = nlohmann::json::parse(read_text(path("out/report.json")));
  const auto& noise = report["noise_estimate"];
  EXPECT_TRUE(noise["estimated"].get<bool>());
  EXPECT_EQ(noise["position"]["given"].get<double>(), 2.0e-6);
  EXPECT_TRUE(noise["position"]["resolved"].get<bool>());
  // simulate-measurements: 15 um plus 6 um per metre from the instrument.
  EXPECT_GT(noise["position"]["used"].get<double>(), 10e-6);
  EXPECT_LT(noise["position"]["used"].get<double>(), 30e-6);
  EXPECT_NE(r.out.find("(estimated +-"), std::string::npos) << r.out;
  EXPECT_TRUE(report["status"]["ok"].get<bool>());
  // The split-half check: the two halves' estimates differ by about their sigmas (z rms of 48
  // parameters near 1; 0.6..1.6 holds its sampling spread with room).
  const auto& split = report["split_half"];
  ASSERT_TRUE(split["done"].get<bool>()) << split.dump();
  EXPECT_EQ(split["parameters"].get<int>(), 48);
  EXPECT_GT(split["z_rms"].get<double>(), 0.6);
  EXPECT_LT(split["z_rms"].get<double>(), 1.6);
  EXPECT_NE(r.out.find("Split-half check"), std::string::npos);
}

}  // namespace

namespace {

// Measurement files as they come, each read to the same data: positions in mm (`pose_unit`),
// scalar-last quaternions under the names qw..qz (`quaternion_order: xyzw`; without it the mix-up
// is warned about and the fit is refused or flagged), the file's own column names (`columns:`),
// readings in screw revolutions with a different lead per leg, and a nominal machine file without
// any leg stiffness. Every variant gives the base calibration's estimate.
class CalibrateInputs : public CalibrateCli {
 protected:
  struct Row {
    std::vector<double> v;  // x, y, z (m), rx, ry, rz (deg), q_1..q_6 (mm)
  };
  std::vector<Row> rows() {
    std::vector<Row> out;
    const std::vector<std::string> lines = simulate();
    for (std::size_t k = 1; k < lines.size(); ++k) {
      Row r;
      std::stringstream in(lines[k]);
      for (std::string cell; std::getline(in, cell, ',');) r.v.push_back(std::stod(cell));
      out.push_back(r);
    }
    return out;
  }
  // report.json's parameter estimates of a calibration run (status 0 expected).
  std::vector<double> estimates(const std::string& measurements, const std::string& settings,
                                const std::string& out) {
    const std::string calibration =
        write(out + ".yaml", "machine: " + path("sim/nominal.yaml") +
                                 "\nmeasurements: " + measurements + "\n" + settings);
    const CliRun r = run("calibrate " + calibration + " --out " + path(out));
    EXPECT_EQ(r.status, 0) << out << ": " << r.err;
    std::vector<double> values;
    if (r.status != 0) return values;
    const nlohmann::json report = nlohmann::json::parse(read_text(path(out + "/report.json")));
    for (const auto& p : report["parameters"]) values.push_back(p["estimate"].get<double>());
    return values;
  }
  static std::string num(double v) {
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%.17g", v);
    return buffer;
  }
};

TEST_F(CalibrateInputs, EveryFormGivesTheSameCalibration) {
  const std::vector<Row> data = rows();
  const std::string noise = "noise: {position: 2.0e-5, orientation_deg: 0.003, actuator: 0.001}\n";
  const std::vector<double> base = estimates(
      path("sim/measurements.csv"), "actuators: {unit: mm, zero_length: 0.7}\n" + noise, "base");
  ASSERT_EQ(base.size(), 48u);
  auto expect_same = [&](const std::vector<double>& other, const char* what) {
    ASSERT_EQ(other.size(), base.size()) << what;
    for (std::size_t i = 0; i < base.size(); ++i)
      EXPECT_NEAR(other[i], base[i], 1e-9 + 1e-9 * std::abs(base[i])) << what << " " << i;
  };
  // Positions in mm, readings in revolutions of screws with leads 5, 5, 4, 5, 6, 5 mm, and the
  // file's own column names.
  const double lead[6] = {5e-3, 5e-3, 4e-3, 5e-3, 6e-3, 5e-3};
  std::string mm = "pos_x,pos_y,pos_z,rot_x,rot_y,rot_z,l1,l2,l3,l4,l5,l6\n";
  for (const Row& r : data) {
    for (int c = 0; c < 3; ++c) mm += num(r.v[c] * 1000.0) + ",";
    for (int c = 3; c < 6; ++c) mm += num(r.v[c]) + ",";
    for (int i = 0; i < 6; ++i) mm += num(r.v[6 + i] * 1e-3 / lead[i]) + (i < 5 ? "," : "\n");
  }
  write("mm.csv", mm);
  expect_same(estimates(path("mm.csv"),
                        "pose_unit: mm\n"
                        "columns: {x: pos_x, y: pos_y, z: pos_z, rx: rot_x, ry: rot_y, rz: rot_z, "
                        "q_1: l1, q_2: l2, q_3: l3, q_4: l4, q_5: l5, q_6: l6}\n"
                        "actuators: {unit: rev, lead: [0.005, 0.005, 0.004, 0.005, 0.006, "
                        "0.005], zero_length: 0.7}\n"
                        // 1 um in revolutions of the mean lead (5 mm), as the base's 0.001 mm
                        "noise: {position: 2.0e-5, orientation_deg: 0.003, actuator: 0.0002}\n",
                        "mm"),
              "mm, columns, leads");
  // The same millimetres read as metres: warned about, and the calibration refused or flagged.
  const std::string as_metres =
      write("as_metres.yaml",
            "machine: " + path("sim/nominal.yaml") + "\nmeasurements: " + path("mm.csv") +
                "\ncolumns: {x: pos_x, y: pos_y, z: pos_z, rx: rot_x, ry: rot_y, "
                "rz: rot_z, q_1: l1, q_2: l2, q_3: l3, q_4: l4, q_5: l5, q_6: l6}\n"
                "actuators: {unit: rev, lead: [0.005, 0.005, 0.004, 0.005, "
                "0.006, 0.005], zero_length: 0.7}\n" +
                noise);
  const CliRun metres = run("calibrate " + as_metres + " --out " + path("as_metres"));
  EXPECT_NE(metres.status, 0);
  EXPECT_NE(metres.err.find("are they in mm? `pose_unit: mm` reads them so"), std::string::npos)
      << metres.err;
  // Scalar-last quaternions under the names qw, qx, qy, qz.
  std::string quaternion = "x,y,z,qw,qx,qy,qz,q_1,q_2,q_3,q_4,q_5,q_6\n";
  for (const Row& r : data) {
    const double d = M_PI / 180.0;
    const Eigen::Quaterniond q = Eigen::AngleAxisd(r.v[5] * d, Eigen::Vector3d::UnitZ()) *
                                 Eigen::AngleAxisd(r.v[4] * d, Eigen::Vector3d::UnitY()) *
                                 Eigen::AngleAxisd(r.v[3] * d, Eigen::Vector3d::UnitX());
    for (int c = 0; c < 3; ++c) quaternion += num(r.v[c]) + ",";
    quaternion += num(q.x()) + "," + num(q.y()) + "," + num(q.z()) + "," + num(q.w());
    for (int i = 0; i < 6; ++i) quaternion += "," + num(r.v[6 + i]);
    quaternion += "\n";
  }
  write("quaternion.csv", quaternion);
  expect_same(estimates(path("quaternion.csv"),
                        "quaternion_order: xyzw\nactuators: {unit: mm, zero_length: 0.7}\n" + noise,
                        "quaternion"),
              "xyzw quaternions");
  const std::string mixed =
      write("mixed.yaml", "machine: " + path("sim/nominal.yaml") +
                              "\nmeasurements: " + path("quaternion.csv") +
                              "\nactuators: {unit: mm, zero_length: 0.7}\n" + noise);
  const CliRun r = run("calibrate " + mixed + " --out " + path("mixed"));
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.err.find("is the quaternion's scalar part in another column?"), std::string::npos)
      << r.err;
  // A nominal machine file without leg stiffness.
  std::string nominal = read_text(path("sim/nominal.yaml"));
  for (const char* key : {"  E: ", "  area: ", "  actuator_stiffness: "}) {
    const std::size_t at = nominal.find(key);
    ASSERT_NE(at, std::string::npos) << key;
    nominal.erase(at, nominal.find('\n', at) + 1 - at);
  }
  write("sim/nominal_no_stiffness.yaml", nominal);
  const std::string no_stiffness =
      write("no_stiffness.yaml", "machine: " + path("sim/nominal_no_stiffness.yaml") +
                                     "\nmeasurements: " + path("sim/measurements.csv") +
                                     "\nactuators: {unit: mm, zero_length: 0.7}\n" + noise);
  const CliRun s = run("calibrate " + no_stiffness + " --out " + path("stiffless"));
  EXPECT_EQ(s.status, 0) << s.err;
  EXPECT_NE(read_text(path("stiffless/calibrated.yaml")).find("placeholder of 1 N/m"),
            std::string::npos);
}

}  // namespace

namespace {

// A `campaign` column gives the second campaign its own leg zeros: the report lists both, the
// first as the reference, and the second's shifts (none simulated here) within four sigmas of 0.
TEST_F(CalibrateInputs, CampaignColumnGivesEachCampaignItsZeros) {
  const std::vector<std::string> lines = simulate();
  std::string csv = lines[0] + ",campaign\n";
  for (std::size_t k = 1; k < lines.size(); ++k)
    csv += lines[k] + (k <= lines.size() / 2 ? ",day 1\n" : ",day 2\n");
  write("campaigns.csv", csv);
  const std::string calibration =
      write("campaigns.yaml",
            "machine: " + path("sim/nominal.yaml") + "\nmeasurements: " + path("campaigns.csv") +
                "\nactuators: {unit: mm, zero_length: 0.7}\n"
                "noise: {position: 2.0e-5, orientation_deg: 0.003, actuator: 0.001}\n");
  const CliRun r = run("calibrate " + calibration + " --out " + path("campaigns"));
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("Campaigns (leg zero shifts"), std::string::npos) << r.out;
  const nlohmann::json report = nlohmann::json::parse(read_text(path("campaigns/report.json")));
  ASSERT_EQ(report["campaigns"].size(), 2u);
  EXPECT_EQ(report["campaigns"][0]["label"], "day 1");
  EXPECT_TRUE(report["campaigns"][0]["reference"].get<bool>());
  const auto& second = report["campaigns"][1];
  EXPECT_EQ(second["label"], "day 2");
  for (int i = 0; i < 6; ++i)
    EXPECT_LT(std::abs(second["shifts"][i].get<double>()),
              4.0 * second["shift_sigma"][i].get<double>())
        << i;
}

}  // namespace

namespace {

// A zero length that is not a finite number is refused with one message (it used to crash
// calibration-poses and to write `zero_length: nan` into the simulated calibration file).
TEST_F(CalibrateCli, NonFiniteZeroLengthIsRefused) {
  for (const char* value : {"nan", "inf", "1e308", "-1"}) {
    const CliRun poses = run("calibration-poses " + machine_ + " --count 10 --grid --steps 2 " +
                             "--zero-length " + value);
    EXPECT_EQ(poses.status, 2) << value << ": " << poses.err;
    // nan, inf and 1e308 are refused by the number policy of every option, -1 by the command.
    EXPECT_NE(poses.err.find("--zero-length: expected a "), std::string::npos) << poses.err;
    EXPECT_NE(poses.err.find(std::string("found ") + value), std::string::npos) << poses.err;
    EXPECT_EQ(std::count(poses.err.begin(), poses.err.end(), '\n'), 1) << poses.err;
    const CliRun sim = run("simulate-measurements " + machine_ + " --out " + path("z") +
                           " --zero-length " + value);
    EXPECT_EQ(sim.status, 2) << value << ": " << sim.err;
    EXPECT_FALSE(fs::exists(path("z/calibration.yaml")));
  }
}

}  // namespace
