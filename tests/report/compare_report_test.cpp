// Tests of report/compare_report (comparing the Pareto fronts of several runs), `pkmopt compare`.
// The results folders are written by the tests (pareto.json by hand, in the pkmopt-pareto-1
// format); hypervolumes are checked against inclusion-exclusion over the points (exact for the
// few points used here and independent of optimizer/indicators).
#include "report/compare_report.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <regex>
#include <string>
#include <vector>

#include "io/format/input_error.hpp"
#include "tests/cli_runner.hpp"
#include "tests/scratch_dir.hpp"

namespace fs = std::filesystem;
using cli_runner::read_text;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

struct ObjectiveSpec {
  std::string name, sense, unit;
};
struct DesignSpec {
  std::vector<double> objectives;  // user sign, NaN written as null
  bool feasible = true;
};

const ObjectiveSpec kStiffness{"stiffness_min", "maximize", "N/m"};
const ObjectiveSpec kSize{"machine_size", "minimize", "m^3"};
const ObjectiveSpec kForce{"leg_force_max", "minimize", "N"};

// pareto.json text of a run with one free parameter (base_radius = 0.5 + 0.01 * design number).
std::string pareto_json_text(const std::string& study, const std::string& model,
                             const std::vector<ObjectiveSpec>& objectives,
                             const std::vector<DesignSpec>& designs, int knee) {
  nlohmann::json root;
  root["format"] = "pkmopt-pareto-1";
  root["pkmopt_version"] = "0.1.0";
  root["study"] = study;
  root["description"] = "";
  root["model"] = model;
  root["parameters"] = {{{"name", "base_radius"}, {"unit", "m"}, {"min", 0.4}, {"max", 0.8}}};
  root["fixed_parameters"] = {{"stroke", 0.45}};
  root["objectives"] = nlohmann::json::array();
  for (const auto& o : objectives) {
    root["objectives"].push_back({{"name", o.name}, {"sense", o.sense}, {"unit", o.unit}});
  }
  root["constraints"] = nlohmann::json::array();
  root["task"] = {{"centre", {0, 0, 0.9}},
                  {"wrench", {300, 300, -3000, 0, 0, 0}},
                  {"tilt_deg", 20},
                  {"yaw_deg", 0}};
  root["designs"] = nlohmann::json::array();
  for (std::size_t d = 0; d < designs.size(); ++d) {
    nlohmann::json design;
    design["id"] = "d" + std::to_string(10000 + d).substr(1);
    design["parameters"] = {{"base_radius", 0.5 + 0.01 * static_cast<double>(d)}};
    design["home_height"] = 0.0;
    design["objectives"] = nlohmann::json::object();
    for (std::size_t k = 0; k < objectives.size(); ++k) {
      const double v = designs[d].objectives[k];
      design["objectives"][objectives[k].name] =
          std::isfinite(v) ? nlohmann::json(v) : nlohmann::json();
    }
    design["constraints"] = nlohmann::json::object();
    design["feasible"] = designs[d].feasible;
    root["designs"].push_back(design);
  }
  root["knee"] =
      knee >= 0 ? nlohmann::json("d" + std::to_string(10000 + knee).substr(1)) : nlohmann::json();
  return root.dump(2) + "\n";
}

// Exact hypervolume by inclusion-exclusion (minimisation): sum over non-empty subsets S of
// (-1)^(|S|+1) prod_i max(0, r_i - max_{a in S} a_i).
double inclusion_exclusion_hypervolume(const std::vector<std::vector<double>>& points,
                                       const std::vector<double>& reference) {
  const std::size_t n = points.size(), m = reference.size();
  double total = 0.0;
  for (unsigned mask = 1; mask < (1u << n); ++mask) {
    double volume = 1.0;
    int size = 0;
    for (std::size_t i = 0; i < m; ++i) {
      double worst = -std::numeric_limits<double>::infinity();
      for (std::size_t p = 0; p < n; ++p) {
        if (mask & (1u << p)) worst = std::max(worst, points[p][i]);
      }
      volume *= std::max(0.0, reference[i] - worst);
    }
    for (std::size_t p = 0; p < n; ++p) size += (mask >> p) & 1u;
    total += (size % 2 == 1 ? 1.0 : -1.0) * volume;
  }
  return total;
}

// Hypervolumes of several runs (points in minimisation form) against the reference of the
// documented rule: the union's worst value of each objective plus 10 % of the union's range.
std::vector<double> common_reference_hypervolumes(
    const std::vector<std::vector<std::vector<double>>>& runs) {
  std::vector<double> best, worst;
  for (const auto& points : runs) {
    for (const auto& p : points) {
      if (best.empty()) best = worst = p;
      for (std::size_t i = 0; i < p.size(); ++i) {
        best[i] = std::min(best[i], p[i]);
        worst[i] = std::max(worst[i], p[i]);
      }
    }
  }
  std::vector<double> reference(worst.size());
  for (std::size_t i = 0; i < worst.size(); ++i) {
    reference[i] = worst[i] + 0.1 * (worst[i] > best[i] ? worst[i] - best[i] : 1.0);
  }
  std::vector<double> out;
  for (const auto& points : runs) out.push_back(inclusion_exclusion_hypervolume(points, reference));
  return out;
}

std::vector<double> html_hypervolumes(const std::string& html) {
  const std::regex hv_pattern("data-hv=\"([^\"]+)\"");
  std::vector<double> found;
  for (auto it = std::sregex_iterator(html.begin(), html.end(), hv_pattern);
       it != std::sregex_iterator(); ++it) {
    found.push_back(std::stod((*it)[1].str()));
  }
  return found;
}

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

// The three runs used throughout: (stiffness_min N/m max, machine_size m^3 min[, leg_force N]).
// Run A: 3 feasible designs + 1 infeasible; run B: 3 feasible (one with a null size) and a third
// objective; run C: 2 feasible.
const std::vector<DesignSpec> kRunA{
    {{2.0e7, 0.40}, true}, {{3.0e7, 0.60}, true}, {{4.0e7, 0.90}, true}, {{5.0e7, 0.50}, false}};
const std::vector<DesignSpec> kRunB{{{0.35, 900, 2.5e7}, true},  // (size, force, stiffness)
                                    {{0.70, 800, 3.5e7}, true},
                                    {{kNaN, 700, 4.5e7}, true}};
const std::vector<DesignSpec> kRunC{{{1.0e7, 0.30}, true}, {{2.2e7, 0.45}, true}};

class CompareTest : public scratch::ScratchDirTest {
 protected:
  // Three results folders a, b and c in the test's scratch folder.
  void SetUp() override {
    write("a/pareto.json",
          pareto_json_text("hexapod-box", "hexapod", {kStiffness, kSize}, kRunA, 1));
    write("a/summary.json", R"({"algorithm": "nsga2", "evaluations": 4800})");
    write("b/pareto.json",
          pareto_json_text("hexaglide-box", "hexaglide", {kSize, kForce, kStiffness}, kRunB, 0));
    write("c/pareto.json",
          pareto_json_text("linear-delta-box", "linear_delta", {kStiffness, kSize}, kRunC, -1));
  }
  std::string dirs() const {
    return (dir_ / "a").string() + " " + (dir_ / "b").string() + " " + (dir_ / "c").string();
  }
  // The expected hypervolume of each run over (stiffness_min, machine_size): feasible designs
  // with finite values in minimisation form, reference = worst of the union + 10 % of its range.
  std::vector<double> expected_hypervolumes(std::vector<double>* reference_out = nullptr) const {
    std::vector<std::vector<std::vector<double>>> runs(3);
    auto add = [&](std::size_t run, double stiffness, double size) {
      runs[run].push_back({-stiffness, size});
    };
    for (const auto& d : kRunA) {
      if (d.feasible) add(0, d.objectives[0], d.objectives[1]);
    }
    add(1, 2.5e7, 0.35);  // run B stores (size, force, stiffness); its third design has no size
    add(1, 3.5e7, 0.70);
    for (const auto& d : kRunC) add(2, d.objectives[0], d.objectives[1]);
    // Union: stiffness 1.0e7 .. 4.5e7 is not reached (4.5e7 has a null size): 1.0e7 .. 4.0e7;
    // size 0.30 .. 0.90.
    const double stiffness_worst = -1.0e7, stiffness_best = -4.0e7;
    const double size_worst = 0.90, size_best = 0.30;
    const std::vector<double> reference{stiffness_worst + 0.1 * (stiffness_worst - stiffness_best),
                                        size_worst + 0.1 * (size_worst - size_best)};
    if (reference_out) *reference_out = reference;
    std::vector<double> out;
    for (const auto& points : runs)
      out.push_back(inclusion_exclusion_hypervolume(points, reference));
    return out;
  }
};

// ---- Library ------------------------------------------------------------------------------

TEST(InclusionExclusion, KnownStaircase) {
  // Two points of a unit square front: 0.25 + 0.25 - 0 = 0.5 minus overlap... checked by hand:
  // {(0, 0.5), (0.5, 0)} up to (1, 1): 0.5 + 0.5 - 0.25 = 0.75.
  EXPECT_DOUBLE_EQ(inclusion_exclusion_hypervolume({{0.0, 0.5}, {0.5, 0.0}}, {1.0, 1.0}), 0.75);
  EXPECT_DOUBLE_EQ(inclusion_exclusion_hypervolume({{0.5, 0.5, 0.5}}, {1.0, 1.0, 1.0}), 0.125);
}

TEST_F(CompareTest, SharedObjectivesAndHypervolumesInACommonReference) {
  const pkmopt::RunComparison c = pkmopt::load_run_comparison(
      {(dir_ / "a").string(), (dir_ / "b").string(), (dir_ / "c").string()}, "", "");
  ASSERT_EQ(c.runs.size(), 3u);
  ASSERT_EQ(c.shared_objectives.size(), 2u);
  EXPECT_EQ(c.shared_objectives[0].name, "stiffness_min");  // the first run's order
  EXPECT_EQ(c.shared_objectives[1].name, "machine_size");
  EXPECT_EQ(c.x_objective, 0u);
  EXPECT_EQ(c.y_objective, 1u);
  EXPECT_EQ(c.runs[1].objective_index, (std::vector<std::size_t>{2, 0}));
  EXPECT_EQ(c.value(1, 0, 0), 2.5e7);
  EXPECT_EQ(c.value(1, 0, 1), 0.35);
  EXPECT_EQ(c.runs[0].feasible, 3u);
  EXPECT_EQ(c.runs[0].shown, 4u);
  EXPECT_EQ(c.runs[0].counted, 3u);
  EXPECT_EQ(c.runs[1].shown, 2u);  // one size is null
  EXPECT_EQ(c.runs[1].counted, 2u);
  EXPECT_EQ(c.runs[0].algorithm.value_or(""), "nsga2");
  EXPECT_EQ(c.runs[0].evaluations.value_or(0), 4800);
  EXPECT_FALSE(c.runs[1].algorithm);

  std::vector<double> reference;
  const std::vector<double> expected = expected_hypervolumes(&reference);
  ASSERT_EQ(c.reference_point.size(), 2u);
  EXPECT_NEAR(c.reference_point[0], -reference[0], 1e-9);  // user sign: a stiffness, positive
  EXPECT_NEAR(c.reference_point[1], reference[1], 1e-15);
  EXPECT_NEAR(c.ideal_point[0], 4.0e7, 1e-9);
  EXPECT_NEAR(c.ideal_point[1], 0.30, 1e-15);
  const double box = (reference[0] - -4.0e7) * (reference[1] - 0.30);
  for (std::size_t r = 0; r < 3; ++r) {
    EXPECT_NEAR(c.runs[r].hypervolume, expected[r], 1e-9 * expected[r]) << "run " << r;
    EXPECT_NEAR(c.runs[r].hypervolume_fraction, expected[r] / box, 1e-12) << "run " << r;
    EXPECT_GT(c.runs[r].hypervolume, 0.0);
  }
  // The union's best run covers more: run A reaches stiffer designs than run C.
  EXPECT_GT(c.runs[0].hypervolume, c.runs[2].hypervolume);
  // Run B optimised leg_force_max too: said in a note.
  bool noted = false;
  for (const auto& note : c.notes) noted = noted || note.find("leg_force_max") != std::string::npos;
  EXPECT_TRUE(noted);
}

TEST_F(CompareTest, ThreeSharedObjectivesGiveAThreeDimensionalHypervolume) {
  const std::vector<DesignSpec> d1{{{1, 1, 3}, true}, {{2, 2, 1}, true}, {{3, 0.5, 2}, true}};
  const std::vector<DesignSpec> d2{{{2, 1.5, 2.5}, true}, {{0.5, 0.5, 0.5}, false}};
  const std::vector<ObjectiveSpec> objectives{
      {"f1", "maximize", ""}, {"f2", "minimize", "m"}, {"f3", "minimize", "N"}};
  write("p/pareto.json", pareto_json_text("p", "hexapod", objectives, d1, 0));
  write("q/pareto.json", pareto_json_text("q", "delta", objectives, d2, 0));
  const auto c =
      pkmopt::load_run_comparison({(dir_ / "p").string(), (dir_ / "q").string()}, "f3", "");
  EXPECT_EQ(c.x_objective, 2u);
  EXPECT_EQ(c.y_objective, 0u);
  // Union (minimisation form): f1 -3..-1, f2 0.5..2, f3 1..3 -> reference (-0.8, 2.15, 3.2).
  const std::vector<double> reference{-1 + 0.2, 2 + 0.15, 3 + 0.2};
  const double p_hv =
      inclusion_exclusion_hypervolume({{-1, 1, 3}, {-2, 2, 1}, {-3, 0.5, 2}}, reference);
  const double q_hv = inclusion_exclusion_hypervolume({{-2, 1.5, 2.5}}, reference);
  EXPECT_NEAR(c.runs[0].hypervolume, p_hv, 1e-12);
  EXPECT_NEAR(c.runs[1].hypervolume, q_hv, 1e-12);
  EXPECT_NEAR(c.runs[0].hypervolume_fraction, p_hv / (2.2 * 1.65 * 2.2), 1e-12);
}

TEST_F(CompareTest, RunsWithoutFeasibleDesignsHaveNoHypervolume) {
  const std::vector<DesignSpec> infeasible{{{1e7, 0.5}, false}};
  for (const std::string name : {"x", "y"}) {
    write(name + "/pareto.json",
          pareto_json_text(name, "hexapod", {kStiffness, kSize}, infeasible, 0));
  }
  const auto only_infeasible =
      pkmopt::load_run_comparison({(dir_ / "x").string(), (dir_ / "y").string()}, "", "");
  EXPECT_TRUE(std::isnan(only_infeasible.runs[0].hypervolume));
  EXPECT_TRUE(only_infeasible.reference_point.empty());
  EXPECT_NE(pkmopt::comparison_html(only_infeasible).find("no hypervolume"), std::string::npos);
  const auto mixed =
      pkmopt::load_run_comparison({(dir_ / "x").string(), (dir_ / "c").string()}, "", "");
  EXPECT_EQ(mixed.runs[0].hypervolume, 0.0);
  EXPECT_GT(mixed.runs[1].hypervolume, 0.0);
}

TEST_F(CompareTest, RunsOfTheSameStudyAreLabelledWithTheirFolders) {
  fs::copy(dir_ / "a", dir_ / "a2", fs::copy_options::recursive);
  const std::string a = (dir_ / "a").string(), a2 = (dir_ / "a2").string();
  const auto c = pkmopt::load_run_comparison({a, a2, (dir_ / "c").string()}, "", "");
  EXPECT_EQ(c.runs[0].label, "hexapod-box (hexapod, " + a + ")");
  EXPECT_EQ(c.runs[1].label, "hexapod-box (hexapod, " + a2 + ")");
  EXPECT_EQ(c.runs[2].label, "linear-delta-box (linear_delta)");
  // Identical fronts, identical hypervolumes.
  EXPECT_EQ(c.runs[0].hypervolume, c.runs[1].hypervolume);
}

TEST_F(CompareTest, IncompatibleRunsAreInputErrors) {
  auto expect_error = [&](const std::vector<std::string>& dirs, const std::string& x,
                          const std::string& y, const std::string& part) {
    try {
      pkmopt::load_run_comparison(dirs, x, y);
      ADD_FAILURE() << "no error for " << part;
    } catch (const pkmopt::InputError& e) {
      EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
    }
  };
  const std::string a = (dir_ / "a").string(), c = (dir_ / "c").string();
  expect_error({a}, "", "", "expected at least two results folders, found 1");
  expect_error({a, c}, "workspace_volume", "", "--x: expected an objective of every run");
  expect_error({a, c}, "", "leg_force_max", "--y: expected an objective of every run");
  expect_error({a, c}, "machine_size", "machine_size", "--y: expected an objective other");
  write(
      dir_ / "u/pareto.json",
      pareto_json_text("u", "hexapod", {kStiffness, {"machine_size", "minimize", "m"}}, kRunC, 0));
  expect_error({a, (dir_ / "u").string()}, "", "",
               (dir_ / "u/pareto.json").string() + ": objectives[1].unit: expected 'm^3'");
  write("s/pareto.json",
        pareto_json_text("s", "hexapod", {{"stiffness_min", "minimize", "N/m"}, kSize}, kRunC, 0));
  expect_error({a, (dir_ / "s").string()}, "", "", "objectives[0].sense: expected 'maximize'");
  write("one/pareto.json",
        pareto_json_text("one", "hexapod", {kStiffness, kForce}, {{{1e7, 500}, true}}, 0));
  expect_error({a, (dir_ / "one").string()}, "", "",
               "expected at least two objectives shared by every run, found 1");
  expect_error({a, a}, "", "", "same folder");
}

// ---- CLI ------------------------------------------------------------------------------------

TEST_F(CompareTest, CliWritesOnePageWithEveryRun) {
  const fs::path html_path = dir_ / "out/compare.html";
  fs::create_directories(html_path.parent_path());
  const auto run =
      run_cli("compare " + dirs() + " --out " + html_path.string() + " --png " +
              (dir_ / "out/c.png").string() + " --svg " + (dir_ / "out/c.svg").string());
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_NE(run.out.find("compare: hexapod-box (hexapod, 4 designs)"), std::string::npos)
      << run.out;
  const std::string html = read_text(html_path);
  // Self-contained: no URL, no external resource.
  EXPECT_EQ(html.find("http"), std::string::npos);
  EXPECT_EQ(html.find("src="), std::string::npos);
  // Every run: its legend entry "study (model)" and one marker per design with finite values.
  const std::vector<std::string> labels{"hexapod-box (hexapod)", "hexaglide-box (hexaglide)",
                                        "linear-delta-box (linear_delta)"};
  const std::vector<std::size_t> shown{4, 2, 2};
  for (std::size_t r = 0; r < 3; ++r) {
    const std::string run_attr = "data-run=\"" + std::to_string(r) + "\"";
    EXPECT_EQ(count(html, "<g class=\"legend\" " + run_attr), 1u);
    EXPECT_NE(html.find(labels[r] + " &#8212; " + std::to_string(shown[r]) + " designs shown"),
              std::string::npos)
        << labels[r];
    EXPECT_EQ(count(html, run_attr + " data-id="), shown[r]) << "run " << r;
    EXPECT_EQ(count(html, "class=\"run-row\" " + run_attr), 1u);
  }
  // Knees: run A's d0001 and run B's d0000 drawn large; run C has none.
  EXPECT_EQ(count(html, "class=\"mk knee\""), 2u);
  EXPECT_NE(html.find("class=\"mk knee\" data-run=\"0\" data-id=\"d0001\""), std::string::npos);
  EXPECT_NE(html.find("hexapod-box (hexapod): knee design d0001"), std::string::npos);
  EXPECT_NE(html.find("No knee design named by the run."), std::string::npos);
  // The knee tables list the parameters.
  EXPECT_EQ(count(html, "<td>base_radius</td>"), 2u);
  // Axes in user units and sense.
  EXPECT_NE(html.find("stiffness_min [N/m] (max)"), std::string::npos);
  EXPECT_NE(html.find("machine_size [m^3] (min)"), std::string::npos);
  // Hypervolumes as written equal the independent computation.
  const std::vector<double> expected = expected_hypervolumes();
  const std::vector<double> found = html_hypervolumes(html);
  ASSERT_EQ(found.size(), 3u);
  for (std::size_t r = 0; r < 3; ++r) EXPECT_NEAR(found[r], expected[r], 1e-9 * expected[r]);

  const std::string png = read_text(dir_ / "out/c.png");
  ASSERT_GE(png.size(), 8u);
  EXPECT_EQ(png.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  const std::string svg = read_text(dir_ / "out/c.svg");
  EXPECT_NE(svg.find("xmlns=\"http://www.w3.org/2000/svg\""), std::string::npos);
  EXPECT_EQ(count(svg, " data-id="), 8u);
}

TEST_F(CompareTest, CliChoosesTheAxes) {
  const fs::path html_path = dir_ / "axes.html";
  const auto run = run_cli("compare " + dirs() + " --out " + html_path.string() +
                           " --x machine_size --y stiffness_min");
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_NE(run.out.find("on machine_size x stiffness_min"), std::string::npos) << run.out;
  const std::string html = read_text(html_path);
  EXPECT_NE(html.find("stiffness_min [N/m] (max) against machine_size [m^3] (min)"),
            std::string::npos);
}

TEST_F(CompareTest, CliErrorsExitTwoAndWriteNothing) {
  write("bad/pareto.json", "{\"format\": \"pkmopt-pareto-1\",\n  \"study\": }\n");
  write("nofront/summary.json", "{}");
  write("badsummary/pareto.json", pareto_json_text("bs", "hexapod", {kStiffness, kSize}, kRunC, 0));
  write("badsummary/summary.json", "{ not json");
  write(
      dir_ / "units/pareto.json",
      pareto_json_text("u", "hexapod", {kStiffness, {"machine_size", "minimize", "m"}}, kRunC, 0));
  const std::string a = (dir_ / "a").string();
  struct Case {
    std::string args, message;
  };
  const std::vector<Case> cases{
      {a, "expected at least two results folders, found 1"},
      {a + " " + (dir_ / "missing").string(), "missing: expected a results folder"},
      {a + " " + (dir_ / "nofront").string(), "nofront/pareto.json: expected the Pareto front"},
      {a + " " + (dir_ / "bad").string(), "bad/pareto.json:2:"},
      {a + " " + (dir_ / "badsummary").string(), "badsummary/summary.json: expected a JSON"},
      {a + " " + (dir_ / "units").string(), "units/pareto.json: objectives[1].unit"},
      {dirs() + " --x workspace_volume", "--x: expected an objective of every run"},
  };
  for (const Case& c : cases) {
    const auto run = run_cli("compare " + c.args + " --out " + (dir_ / "e.html").string() +
                             " --png " + (dir_ / "e.png").string());
    EXPECT_EQ(run.status, 2) << c.args << "\n" << run.err;
    EXPECT_NE(run.err.find(c.message), std::string::npos) << run.err;
    EXPECT_FALSE(fs::exists(dir_ / "e.html")) << c.args;
    EXPECT_FALSE(fs::exists(dir_ / "e.png")) << c.args;
  }
  const auto folder_out = run_cli("compare " + dirs() + " --out " + dir_.string() + " --png " +
                                  (dir_ / "e.png").string());
  EXPECT_EQ(folder_out.status, 2);
  EXPECT_NE(folder_out.err.find("--out: expected a file name"), std::string::npos)
      << folder_out.err;
  EXPECT_FALSE(fs::exists(dir_ / "e.png"));
  // A plot in a folder that does not exist: not even the HTML page is written.
  const auto no_folder = run_cli("compare " + dirs() + " --out " + (dir_ / "e.html").string() +
                                 " --png " + (dir_ / "nowhere/e.png").string());
  EXPECT_EQ(no_folder.status, 2);
  EXPECT_NE(no_folder.err.find("--png: expected a file in an existing folder"), std::string::npos)
      << no_folder.err;
  EXPECT_FALSE(fs::exists(dir_ / "e.html"));
}

}  // namespace

namespace {

// Two tiny hexapod design studies run by `pkmopt run`, then compared: the command reads what
// the real writer wrote.
TEST_F(CompareTest, EndToEndTwoRealRuns) {
  std::string study = read_text(fs::path(PKMOPT_SOURCE_DIR) / "studies/library/hexapod-quick.yaml");
  const std::string optimizer = "optimizer: {algorithm: nsga2, population: 60, generations: 80";
  ASSERT_NE(study.find(optimizer), std::string::npos);
  study.replace(study.find(optimizer), optimizer.size(),
                "optimizer: {algorithm: nsga2, population: 16, generations: 20");
  std::vector<fs::path> dirs;
  for (const std::string name : {"quick-1", "quick-2"}) {
    std::string text = study;
    text.replace(text.find("study: hexapod-quick"), 20, "study: " + name);
    if (name == "quick-2") text.replace(text.find("seed: 1"), 7, "seed: 2");
    write(name + ".yaml", text);
    dirs.push_back(dir_ / name);
    const auto run = run_cli("run " + (dir_ / (name + ".yaml")).string() + " --out " +
                             dirs.back().string() + " --threads 1");
    ASSERT_EQ(run.status, 0) << run.err;
  }
  const fs::path html_path = dir_ / "real.html";
  const auto r = run_cli("compare " + dirs[0].string() + " " + dirs[1].string() + " --out " +
                         html_path.string());
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string html = read_text(html_path);
  std::vector<std::vector<std::vector<double>>> minimised(2);
  for (std::size_t k = 0; k < 2; ++k) {
    const auto front = nlohmann::json::parse(read_text(dirs[k] / "pareto.json"));
    EXPECT_NE(html.find("quick-" + std::to_string(k + 1) + " (hexapod)"), std::string::npos);
    std::size_t shown = 0;
    for (const auto& d : front["designs"]) {
      const auto& stiffness = d["objectives"]["stiffness_min"];
      const auto& size = d["objectives"]["machine_size"];
      if (!stiffness.is_number() || !size.is_number()) continue;
      ++shown;
      if (d["feasible"].get<bool>()) {
        minimised[k].push_back({-stiffness.get<double>(), size.get<double>()});
      }
    }
    ASSERT_LE(minimised[k].size(), 20u);  // inclusion-exclusion stays cheap
    EXPECT_EQ(count(html, "data-run=\"" + std::to_string(k) + "\" data-id="), shown);
  }
  ASSERT_FALSE(minimised[0].empty() && minimised[1].empty());
  const std::vector<double> expected = common_reference_hypervolumes(minimised);
  const std::vector<double> found = html_hypervolumes(html);
  ASSERT_EQ(found.size(), 2u);
  for (std::size_t k = 0; k < 2; ++k) {
    EXPECT_NEAR(found[k], expected[k], 1e-9 * std::abs(expected[k]) + 1e-300) << "run " << k;
  }
}

}  // namespace
