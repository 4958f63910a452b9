// Tests of the hexapod-rapid study (studies/library/hexapod-rapid/) in its reduced form through
// the CLI: the static and the dynamic study resolve to themselves and run; every feasible design
// of the dynamic front meets the 60 Hz bound and its chosen drive carries its accelerated force;
// the reported actuator_force_dynamic_max of a front design equals the acceleration bound
// recomputed from its written machine file over the study's task poses.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "io/machine/machine_file.hpp"
#include "models/dynamics/acceleration_capability.hpp"
#include "studies/design_study.hpp"
#include "tests/cli_runner.hpp"
#include "tests/scratch_dir.hpp"

namespace pkmopt {
namespace {

namespace fs = std::filesystem;

std::string source_path(const std::string& relative) {
  return (fs::path(PKMOPT_SOURCE_DIR) / relative).string();
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

class RapidStudy : public scratch::ScratchDirTest {
 protected:
  // The study with 24 x 6 designs and the catalog by its absolute path, run into <dir_>/<name>.
  nlohmann::json run_reduced(const std::string& name) {
    const std::string source = source_path("studies/library/hexapod-rapid/" + name + ".yaml");
    const DesignStudy study = load_design_study(source);
    const std::string again = write(name + "-resolved/study.yaml", study.resolved_yaml);
    // Resolved again it is the same but for the comment on where the milling wrench came from.
    std::string expected;
    for (std::size_t at = 0; at < study.resolved_yaml.size();) {
      const std::size_t end = study.resolved_yaml.find('\n', at) + 1;
      const std::string line = study.resolved_yaml.substr(at, end - at);
      if (!line.starts_with("  #")) expected += line;
      at = end;
    }
    EXPECT_EQ(load_design_study(again).resolved_yaml, expected);
    const std::string text =
        replaced(replaced(cli_runner::read_text(source), "population: 80, generations: 50",
                          "population: 24, generations: 6"),
                 "../catalogs/sew-cms.yaml", source_path("studies/library/catalogs/sew-cms.yaml"));
    const std::string file = write(name + "/study.yaml", text);
    const cli_runner::CliRun run = run_cli("run " + file + " --out " + path(name + "/out"));
    EXPECT_EQ(run.status, 0) << run.out << run.err;
    return nlohmann::json::parse(cli_runner::read_text(dir_ / name / "out" / "pareto.json"));
  }
};

TEST_F(RapidStudy, DynamicFrontMeetsTheFrequencyBoundAndItsDrivesCarryTheRapids) {
  const nlohmann::json still = run_reduced("static");
  EXPECT_FALSE(still["designs"].empty());
  const nlohmann::json rapid = run_reduced("dynamic");
  ASSERT_FALSE(rapid["designs"].empty());
  int feasible = 0;
  for (const nlohmann::json& d : rapid["designs"]) {
    if (!d["feasible"].get<bool>()) continue;
    ++feasible;
    EXPECT_LE(d["constraints"]["g_natural_frequency_min_min"].get<double>(), 0.0) << d.dump();
    const nlohmann::json& a = d["actuator"];
    ASSERT_TRUE(a.is_object()) << d.dump();
    EXPECT_LE(a["actuator_force_dynamic_max"].get<double>(), a["peak_force"].get<double>());
    EXPECT_LE(a["leg_force_max"].get<double>(), a["max_force"].get<double>());
  }
  ASSERT_GT(feasible, 0);

  // The first feasible design, recomputed from its machine file: the worst accelerated force
  // over the study's task poses (lifted by the design's home height).
  const DesignStudy study =
      load_design_study(source_path("studies/library/hexapod-rapid/dynamic.yaml"));
  for (const nlohmann::json& d : rapid["designs"]) {
    if (!d["feasible"].get<bool>()) continue;
    const auto machine = load_machine_file(
        (dir_ / "dynamic" / "out" / d["machine_file"].get<std::string>()).string());
    const auto data = machine->make_data();
    double worst = 0.0;
    Eigen::VectorXd bound;
    for (Pose pose : study.task().poses) {
      pose.position.z() += d["home_height"].get<double>();
      ASSERT_TRUE(
          acceleration_force_bound(*machine, *data, pose, study.task().wrench, 9.81, bound));
      worst = std::max(worst, bound.maxCoeff());
    }
    const double reported = d["actuator"]["actuator_force_dynamic_max"].get<double>();
    EXPECT_NEAR(reported, worst, 1e-9 * worst);
    EXPECT_GT(reported, d["actuator"]["leg_force_max"].get<double>());  // 1 g adds to the cut
    break;
  }
}

}  // namespace
}  // namespace pkmopt
