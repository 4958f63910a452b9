// Tests of `pkmopt choose` on a short run of studies/library/hexapod-quick.yaml (stiffness_min
// maximised, machine_size minimised): each rule against pareto.json and against an independent
// computation here, the machine file written, and bad input refused with one line, exit 2 and
// nothing written.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "io/results/pareto_json.hpp"
#include "tests/cli_runner.hpp"
#include "tests/scratch_dir.hpp"

namespace pkmopt {
namespace {

namespace fs = std::filesystem;
using cli_runner::CliRun;
using cli_runner::read_text;

class ChooseCli : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    scratch_ = new scratch::ScratchDir("ChooseCli");
    std::string study =
        read_text(fs::path(PKMOPT_SOURCE_DIR) / "studies/library/hexapod-quick.yaml");
    const std::string full = "population: 60, generations: 80";
    study.replace(study.find(full), full.size(), "population: 40, generations: 30");
    const std::string file = scratch_->write("study.yaml", study);
    const CliRun r = cli_runner::run_cli(scratch_->path(),
                                         "run " + file + " --out " + results() + " --no-progress");
    ASSERT_EQ(r.status, 0) << r.err;
    front_ = new ParetoFront(read_pareto_json(results() + "/pareto.json"));
  }
  static void TearDownTestSuite() {
    delete front_;
    delete scratch_;
  }
  static std::string results() { return (scratch_->path() / "res").string(); }
  static CliRun run(const std::string& args) { return cli_runner::run_cli(scratch_->path(), args); }
  // The id on the first line "choose: ID, one of ...".
  static std::string chosen(const CliRun& r) {
    const std::size_t at = r.out.find("choose: ");
    if (at == std::string::npos) return "";
    return r.out.substr(at + 8, r.out.find(',', at) - at - 8);
  }
  // Feasible designs' objectives in minimisation sign, each scaled to [0, 1] over them.
  static std::vector<std::vector<double>> normalised(std::vector<std::string>& ids) {
    std::vector<std::vector<double>> f;
    for (const ParetoDesign& d : front_->designs) {
      if (!d.feasible) continue;
      ids.push_back(d.id);
      f.push_back({-d.objectives[0], d.objectives[1]});  // stiffness_min is maximised
    }
    for (int i = 0; i < 2; ++i) {
      double lo = 1e300, hi = -1e300;
      for (const auto& p : f) lo = std::min(lo, p[i]), hi = std::max(hi, p[i]);
      for (auto& p : f) p[i] = (p[i] - lo) / (hi - lo);
    }
    return f;
  }

  static scratch::ScratchDir* scratch_;
  static ParetoFront* front_;
};
scratch::ScratchDir* ChooseCli::scratch_ = nullptr;
ParetoFront* ChooseCli::front_ = nullptr;

TEST_F(ChooseCli, KneeAndCompromiseAreThoseOfParetoJson) {
  ASSERT_GE(front_->designs.size(), 5u);
  ASSERT_TRUE(front_->knee && front_->compromise);
  const CliRun knee = run("choose " + results() + " --knee");
  ASSERT_EQ(knee.status, 0) << knee.err;
  EXPECT_EQ(chosen(knee), *front_->knee) << knee.out;
  const CliRun compromise =
      run("choose " + results() + " --compromise --out " + (scratch_->path() / "c.yaml").string());
  ASSERT_EQ(compromise.status, 0) << compromise.err;
  EXPECT_EQ(chosen(compromise), *front_->compromise) << compromise.out;
  // Independently: the compromise is nearest (0, 0) in normalised units.
  std::vector<std::string> ids;
  const auto f = normalised(ids);
  std::size_t best = 0;
  for (std::size_t k = 0; k < f.size(); ++k)
    if (std::hypot(f[k][0], f[k][1]) < std::hypot(f[best][0], f[best][1])) best = k;
  EXPECT_EQ(ids[best], *front_->compromise);
  // The machine file: comment lines naming the choice, then the design's file unchanged.
  const std::string written = read_text(scratch_->path() / "c.yaml");
  const std::string original =
      read_text(fs::path(results()) / "designs" / (*front_->compromise + ".yaml"));
  ASSERT_EQ(written.rfind('#', 0), 0u);
  EXPECT_EQ(written.substr(written.find('\n') + 1), original);
  EXPECT_NE(written.find("compromise"), std::string::npos);
  // It is a machine file pkmopt reads.
  EXPECT_EQ(run("describe " + (scratch_->path() / "c.yaml").string()).status, 0);
  // Without --out: DIR/chosen.yaml.
  EXPECT_TRUE(fs::exists(fs::path(results()) / "chosen.yaml"));
}

TEST_F(ChooseCli, WeightsChooseTheNearestPseudoWeights) {
  std::vector<std::string> ids;
  const auto f = normalised(ids);
  for (const double w0 : {0.1, 0.5, 0.9}) {
    const CliRun r = run(fmt::format("choose {} --weights stiffness_min={},machine_size={}",
                                     results(), 10 * w0, 10 * (1 - w0)));
    ASSERT_EQ(r.status, 0) << r.err;
    // Deb's pseudo-weights: w_i = (1 - f^_i) / sum_j (1 - f^_j), nearest (w0, 1 - w0).
    std::size_t best = 0;
    double best_d = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < f.size(); ++k) {
      const double a = 1 - f[k][0], b = 1 - f[k][1];
      const double d = std::hypot(a / (a + b) - w0, b / (a + b) - (1 - w0));
      if (d < best_d) best_d = d, best = k;
    }
    EXPECT_EQ(chosen(r), ids[best]) << r.out;
  }
  // All weight on the stiffness: the stiffest design.
  const CliRun stiff = run("choose " + results() + " --weights stiffness_min=1");
  std::size_t stiffest = 0;
  for (std::size_t k = 0; k < f.size(); ++k)
    if (f[k][0] < f[stiffest][0]) stiffest = k;
  EXPECT_EQ(chosen(stiff), ids[stiffest]) << stiff.out;
}

TEST_F(ChooseCli, AReferencePointOnTheFrontChoosesItsDesign) {
  for (const ParetoDesign& d : front_->designs) {
    if (!d.feasible) continue;
    const CliRun r =
        run(fmt::format("choose {} --reference stiffness_min={:.17g},machine_size={:.17g}",
                        results(), d.objectives[0], d.objectives[1]));
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(chosen(r), d.id) << r.out;
  }
  // Beyond every design (stiffer and smaller than all): the ray from it along (1, 1) in
  // normalised units; by hand: the smallest max_i (f^_i - z^_i).
  std::vector<std::string> ids;
  const auto f = normalised(ids);
  double s_max = 0, size_min = 1e300, s_lo = 1e300, size_hi = 0;
  for (const ParetoDesign& d : front_->designs) {
    if (!d.feasible) continue;
    s_max = std::max(s_max, d.objectives[0]);
    s_lo = std::min(s_lo, d.objectives[0]);
    size_min = std::min(size_min, d.objectives[1]);
    size_hi = std::max(size_hi, d.objectives[1]);
  }
  const double z_stiffness = s_max + 0.3 * (s_max - s_lo), z_size = size_min;
  const double z0 = (-z_stiffness + s_max) / (s_max - s_lo), z1 = 0.0;
  std::size_t best = 0;
  for (std::size_t k = 0; k < f.size(); ++k)
    if (std::max(f[k][0] - z0, f[k][1] - z1) < std::max(f[best][0] - z0, f[best][1] - z1)) best = k;
  const CliRun r =
      run(fmt::format("choose {} --reference stiffness_min={:.17g},machine_size={:.17g}", results(),
                      z_stiffness, z_size));
  EXPECT_EQ(chosen(r), ids[best]) << r.out;
}

TEST_F(ChooseCli, BadInputIsOneLineAndWritesNothing) {
  const std::string keep = scratch_->write("keep.yaml", "mine\n");
  for (const std::string& args :
       {std::string(" --knee --compromise"), std::string(""), std::string(" --weights x=1"),
        std::string(" --weights stiffness_min=-1"), std::string(" --weights stiffness_min=0"),
        std::string(" --reference stiffness_min=1e8"),
        std::string(" --reference stiffness_min=1e8,machine_size=inf"),
        std::string(" --weights machine_size=1,machine_size=2")}) {
    const CliRun r = run("choose " + results() + args + " --out " + keep);
    EXPECT_EQ(r.status, 2) << args << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_EQ(r.err.rfind("pkmopt: error: ", 0), 0u) << r.err;
    EXPECT_EQ(read_text(keep), "mine\n");
  }
  const CliRun folder = run("choose " + results() + " --knee --out " + scratch_->path().string());
  EXPECT_EQ(folder.status, 2) << folder.err;
  const CliRun missing = run("choose " + (scratch_->path() / "nothing").string() + " --knee");
  EXPECT_EQ(missing.status, 2) << missing.err;
  EXPECT_NE(missing.err.find("expected a results folder"), std::string::npos) << missing.err;
}

}  // namespace
}  // namespace pkmopt
