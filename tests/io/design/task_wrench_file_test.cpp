// Tests of io/design/task_wrench_file: hand-typed, turning and milling task wrenches, and errors.
#include "io/design/task_wrench_file.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include "io/format/input_error.hpp"

namespace pkmopt {
namespace {

TaskWrench read(const std::string& text) {
  const YamlValue root = YamlValue::load_string(text, "study.yaml");
  return read_task_wrench(root.required("wrench"));
}

std::string error_of(const std::string& text) {
  try {
    read(text);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

// The seeds' turning case (see tests/problems/design/cutting_load_test.cpp).
const std::string kSeedsTurning =
    "wrench:\n"
    "  turning: {diameter_mm: 120, depth_mm: 3, feed_mm_per_rev: 0.84, tool_life_min: 60,\n"
    "            C_v: 340, x_v: 0.15, y_v: 0.45, m: 0.2, K_v: 0.85,\n"
    "            C_p: 200, x_p: 1, y_p: 0.75, n_p: 0, K_p: 1.127}\n";

TEST(TaskWrenchFile, HandTypedList) {
  const TaskWrench w = read("wrench: [1, 2, -3, 0.5, 0, 0]\n");
  EXPECT_EQ(w.wrench, (Wrench() << 1, 2, -3, 0.5, 0, 0).finished());
  EXPECT_EQ(w.origin, "");
}

TEST(TaskWrenchFile, TurningAtTheOptimalAngleGivesTheSeeds6633N) {
  const TaskWrench w = read(kSeedsTurning + "  approach_angle_deg: optimal\n");
  EXPECT_NEAR(w.wrench(2), 6633.0, 0.5);
  EXPECT_NEAR(w.wrench(1), 0.0, 1e-9);
  EXPECT_NEAR(w.wrench(0), 0.2 * 5933.2, 0.5);
  EXPECT_EQ(w.wrench.tail<3>(), Eigen::Vector3d::Zero());
  EXPECT_EQ(w.origin,
            "turning: V 116.89 m/min, n 310 rev/min, P_z 5933 N, P_y 2967 N, P_x 1187 N, "
            "approach 26.57 deg");
  // Turning the lathe frame by 90 deg about x moves the force from z to -y.
  const TaskWrench turned =
      read(kSeedsTurning + "  approach_angle_deg: optimal\n  rotation_deg: [90, 0, 0]\n");
  EXPECT_NEAR(turned.wrench(1), -6633.0, 0.5);
  EXPECT_NEAR(turned.wrench(2), 0.0, 1e-9);
  // Without an approach angle the tool-frame force itself.
  const TaskWrench straight = read(kSeedsTurning);
  EXPECT_NEAR(straight.wrench(2), 5933.2, 0.5);
  EXPECT_NEAR(straight.wrench(1), 0.5 * straight.wrench(2), 1e-9);
}

TEST(TaskWrenchFile, Milling) {
  const TaskWrench w = read(
      "wrench:\n"
      "  milling: {cutter_diameter_mm: 63, teeth: 5, cutting_speed: 220, feed_per_tooth_mm: "
      "0.15,\n"
      "            width_mm: 63, depth_mm: 3, k_c1: 1700}\n"
      "  feed_direction: [0, 1, 0]\n");
  // Full slot: h_m = 2 f_z / pi, k_c = 1700 h_m^-0.25, F_t = a_p a_e f_z z n k_c / (1000 v_c)
  // (the power-based mean rim force written out).
  const double h_m = 2.0 * 0.15 / M_PI;
  const double k_c = 1700.0 * std::pow(h_m, -0.25);
  const double n = 1000.0 * 220.0 / (M_PI * 63.0);
  const double F_t = 3.0 * 63.0 * 0.15 * 5 * n * k_c / 1000.0 / 220.0;
  EXPECT_NEAR(w.wrench(1), -F_t, 1e-9 * F_t);        // against the feed (+y)
  EXPECT_NEAR(w.wrench(0), -0.3 * F_t, 1e-9 * F_t);  // e_z x e_y = -e_x
  EXPECT_NEAR(w.wrench(2), 0.2 * F_t, 1e-9 * F_t);
  EXPECT_NEAR(w.wrench(5), -F_t * 0.063 / 2.0, 1e-9 * F_t);  // cutting torque, N*m
  EXPECT_EQ(w.origin.rfind("milling: n 1112 rev/min", 0), 0u) << w.origin;
  const TaskWrench doubled = read(
      "wrench:\n"
      "  milling: {cutter_diameter_mm: 63, teeth: 5, cutting_speed: 220, feed_per_tooth_mm: "
      "0.15,\n"
      "            width_mm: 63, depth_mm: 3, k_c1: 1700}\n"
      "  feed_direction: [0, 1, 0]\n  factor: 2\n");
  EXPECT_TRUE(doubled.wrench.isApprox(2.0 * w.wrench, 1e-15));
  EXPECT_EQ(doubled.origin, w.origin + ", times factor 2");
  EXPECT_EQ(error_of(kSeedsTurning + "  factor: 0\n"),
            "study.yaml:5:11: wrench.factor: expected a number in (0, 100], found '0'");
}

TEST(TaskWrenchFile, BadInputGivesExactMessages) {
  EXPECT_EQ(error_of("wrench: [1, 2, 3]\n"),
            "study.yaml:1:9: wrench: expected a list of 6, found a list of 3");
  EXPECT_EQ(error_of("wrench: 5\n"),
            "study.yaml:1:9: wrench: expected a list of 6 numbers or a map with 'turning' or "
            "'milling', found '5'");
  EXPECT_EQ(error_of("wrench: {drilling: 1}\n"),
            "study.yaml:1:9: wrench: expected a list of 6 numbers or a map with 'turning' or "
            "'milling', found a map");
  std::string bad = kSeedsTurning;
  bad.replace(bad.find("depth_mm: 3"), 11, "depth_mm: 0");
  EXPECT_EQ(error_of(bad),
            "study.yaml:2:41: wrench.turning.depth_mm: expected a finite number > 0, found 0");
  EXPECT_EQ(error_of(kSeedsTurning + "  approach_angle_deg: steep\n"),
            "study.yaml:5:23: wrench.approach_angle_deg: expected a finite number, found 'steep'");
  EXPECT_EQ(error_of(kSeedsTurning + "  spin: 1\n"),
            "study.yaml:5:3: wrench.spin: unknown key 'spin'; allowed keys here: turning, "
            "approach_angle_deg, rotation_deg, factor");
  EXPECT_EQ(error_of("wrench:\n  milling: {cutter_diameter_mm: 63, teeth: 5, cutting_speed: "
                     "220, feed_per_tooth_mm: 0.1, width_mm: 80, depth_mm: 3, k_c1: 1700}\n"),
            "study.yaml:2:101: wrench.milling.width_mm: expected at most cutter_diameter_mm "
            "(63), found 80");
  EXPECT_EQ(error_of("wrench:\n  milling: {cutter_diameter_mm: 63, teeth: 5, cutting_speed: "
                     "220, feed_per_tooth_mm: 0.1, width_mm: 8, depth_mm: 3, k_c1: 1700}\n"
                     "  feed_direction: [0, 0, 1]\n"),
            "study.yaml:3:19: wrench.feed_direction: expected a non-zero direction in the base "
            "x-y plane [x, y, 0], found a list of 3");
}

}  // namespace
}  // namespace pkmopt

namespace pkmopt {
namespace {

// docs/design-studies.md carries the cutting models' key tables exactly as the reader's field
// lists generate them; the failure message shows the block to paste.
TEST(TaskWrenchFile, DocsTablesMatchTheFieldLists) {
  std::ifstream in(std::string(PKMOPT_SOURCE_DIR) + "/docs/design-studies.md");
  std::stringstream docs;
  docs << in.rdbuf();
  for (const char* model : {"turning", "milling"}) {
    const std::string block = std::string("<!-- fields: ") + model + " -->\n" +
                              cutting_model_fields_markdown(model) + "<!-- /fields -->\n";
    EXPECT_NE(docs.str().find(block), std::string::npos)
        << "docs/design-studies.md lacks the generated table of '" << model << "':\n"
        << block;
  }
}

}  // namespace
}  // namespace pkmopt
