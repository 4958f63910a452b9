// Tests of report/pareto_report (plots, the knee slice, the HTML report) and `pkmopt export`
// (CSV, JSON and HTML of a results folder; bad input). Reading and writing pareto.json and the
// CSV of a front (io/results/pareto_json) are tested in tests/io/results/pareto_json_test.cpp.
#include "report/pareto_report.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "io/format/csv.hpp"
#include "tests/cli_runner.hpp"
#include "tests/scratch_dir.hpp"

namespace fs = std::filesystem;
using cli_runner::read_text;

namespace {

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

// pareto.json fixtures, shared with tests/io/results/pareto_json_test.cpp.
const fs::path kFixtures = fs::path(PKMOPT_SOURCE_DIR) / "tests/io/data/pareto_json";

class ExportTest : public scratch::ScratchDirTest {
 protected:
  // A copy of a fixture folder in the scratch folder (outputs land next to pareto.json).
  fs::path fixture(const std::string& name) {
    const fs::path target = dir_ / name;
    fs::copy(kFixtures / name, target, fs::copy_options::recursive);
    return target;
  }
  static std::size_t file_count(const fs::path& dir) {
    std::size_t n = 0;
    for (const auto& entry : fs::recursive_directory_iterator(dir)) n += entry.is_regular_file();
    return n;
  }
};

nlohmann::json load_json(const fs::path& path) { return nlohmann::json::parse(read_text(path)); }

// ---- Library ------------------------------------------------------------------------------

TEST(Base64, Rfc4648TestVectors) {
  // RFC 4648 section 10.
  EXPECT_EQ(pkmopt::base64(""), "");
  EXPECT_EQ(pkmopt::base64("f"), "Zg==");
  EXPECT_EQ(pkmopt::base64("fo"), "Zm8=");
  EXPECT_EQ(pkmopt::base64("foo"), "Zm9v");
  EXPECT_EQ(pkmopt::base64("foob"), "Zm9vYg==");
  EXPECT_EQ(pkmopt::base64("fooba"), "Zm9vYmE=");
  EXPECT_EQ(pkmopt::base64("foobar"), "Zm9vYmFy");
  EXPECT_EQ(pkmopt::base64(std::string("\xff\x00\x80", 3)), "/wCA");
}

TEST(ParetoPlot, PngAndSvgHaveOnePointPerDesignAndNamedAxes) {
  const auto front = pkmopt::read_pareto_json((kFixtures / "two/pareto.json").string());
  const std::string png = pkmopt::pareto_plot_png(front);
  ASSERT_GT(png.size(), 8u);
  EXPECT_EQ(png.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  const std::string svg = pkmopt::pareto_plot_svg(front);
  EXPECT_EQ(count(svg, "<circle class=\"pt"), 4u);
  EXPECT_NE(svg.find("stiffness_min [N/µm] (max)"), std::string::npos);
  EXPECT_NE(svg.find("machine_size [l] (min)"), std::string::npos);
  EXPECT_NE(svg.find("knee d0001"), std::string::npos);
}

pkmopt::ParetoFront two_objective_front(const std::vector<std::pair<double, double>>& points,
                                        const std::string& knee) {
  pkmopt::ParetoFront front;
  front.objectives = {{"f1", "minimize", ""}, {"f2", "minimize", ""}};
  for (std::size_t k = 0; k < points.size(); ++k) {
    pkmopt::ParetoDesign d;
    d.id = "d" + std::to_string(k);
    d.objectives = {points[k].first, points[k].second};
    front.designs.push_back(d);
  }
  front.knee = knee;
  return front;
}

TEST(KneeText, SaysHowPronouncedTheKneeIs) {
  // A bent front: the knee (0.1, 0.1) lies (1 - 0.2) / sqrt(2) = 0.566 below the line through
  // the extremes (0, 1) and (1, 0).
  const std::string bent =
      pkmopt::knee_text(two_objective_front({{0, 1}, {0.1, 0.1}, {1, 0}}, "d1"));
  EXPECT_NE(bent.find("d1 lies 0.566 below that plane"), std::string::npos) << bent;
  EXPECT_EQ(bent.find("no pronounced knee"), std::string::npos) << bent;
  // A straight front: every point on the line, the knee no better than its neighbours.
  const std::string flat =
      pkmopt::knee_text(two_objective_front({{0, 1}, {0.5, 0.5}, {1, 0}}, "d1"));
  EXPECT_NE(flat.find("d1 lies 0.000 below that plane"), std::string::npos) << flat;
  EXPECT_NE(flat.find("no pronounced knee"), std::string::npos) << flat;
}

TEST(ConvergencePlot, OnePolylineThroughEveryPoint) {
  pkmopt::ParetoFront front = two_objective_front({{0, 1}, {1, 0}}, "d0");
  EXPECT_EQ(pkmopt::convergence_svg(front), "");
  front.convergence = pkmopt::ParetoConvergence{{10, 20, 30}, {0.1, 0.4, 0.5}};
  const std::string svg = pkmopt::convergence_svg(front);
  EXPECT_EQ(count(svg, "<polyline"), 1u);
  const auto at = svg.find("<polyline points=\"");
  ASSERT_NE(at, std::string::npos);
  const std::string points = svg.substr(at, svg.find('"', at + 18) - at);
  EXPECT_EQ(count(points, ","), 3u);
}

TEST(KneeSlice, IsTakenAtTheTaskCentreHeightOfTheKneeMachine) {
  const auto front = pkmopt::read_pareto_json((kFixtures / "two/pareto.json").string());
  const auto slice = pkmopt::knee_workspace_slice(front, (kFixtures / "two").string(), 40);
  ASSERT_TRUE(slice.has_value());
  EXPECT_EQ(slice->normal_axis, 'z');
  EXPECT_DOUBLE_EQ(slice->offset, 0.9 + 0.0);
  ASSERT_EQ(slice->inside.size(), static_cast<std::size_t>(slice->width * slice->height));
  // The sample hexapod reaches z = 0.9 m at the centre (its workspace spans z 0.45..0.96 m).
  std::size_t inside = 0;
  for (auto v : slice->inside) inside += v;
  EXPECT_GT(inside, 0u);
  EXPECT_LT(inside, slice->inside.size());
  // No knee machine file: no slice.
  const auto three = pkmopt::read_pareto_json((kFixtures / "three/pareto.json").string());
  EXPECT_FALSE(pkmopt::knee_workspace_slice(three, (kFixtures / "three").string()).has_value());
}

// ---- The command --------------------------------------------------------------------------

TEST_F(ExportTest, CsvRoundTripsEveryValue) {
  for (const std::string name : {"two", "three"}) {
    const fs::path dir = fixture(name);
    const auto r = run_cli("export " + dir.string() + " --format csv");
    ASSERT_EQ(r.status, 0) << r.err;
    const nlohmann::json source = load_json(dir / "pareto.json");
    const pkmopt::CsvTable csv = pkmopt::read_csv_file((dir / "pareto_export.csv").string());
    ASSERT_EQ(csv.rows.size(), source["designs"].size());
    const bool home_is_parameter = name == "three";
    EXPECT_EQ(csv.column("home_height") >= 0, true);
    EXPECT_EQ(csv.header.back(), "knee");
    for (std::size_t d = 0; d < csv.rows.size(); ++d) {
      const auto& design = source["designs"][d];
      const auto& row = csv.rows[d];
      EXPECT_EQ(row.cells[static_cast<std::size_t>(csv.require_column("id"))],
                design["id"].get<std::string>());
      for (const char* group : {"parameters", "objectives", "constraints"}) {
        for (const auto& [key, value] : design[group].items()) {
          const int c = csv.require_column(key);
          if (value.is_null()) {
            EXPECT_EQ(row.cells[static_cast<std::size_t>(c)], "") << key;
          } else {
            EXPECT_EQ(csv.number(row, c), value.get<double>()) << key;
          }
        }
      }
      if (!home_is_parameter) {
        EXPECT_EQ(csv.number(row, csv.require_column("home_height")),
                  design["home_height"].get<double>());
      }
      EXPECT_EQ(csv.number(row, csv.require_column("feasible")),
                design["feasible"].get<bool>() ? 1.0 : 0.0);
      EXPECT_EQ(csv.number(row, csv.require_column("knee")),
                design["id"] == source["knee"] ? 1.0 : 0.0);
    }
    // home_height appears once even when it is a free parameter.
    int columns_named_home = 0;
    for (const auto& h : csv.header) columns_named_home += h == "home_height";
    EXPECT_EQ(columns_named_home, 1);
  }
}

TEST_F(ExportTest, JsonIsTheSameFrontNormalised) {
  for (const std::string name : {"two", "three"}) {
    const fs::path dir = fixture(name);
    const fs::path out = dir_ / (name + "_front.json");
    const auto r = run_cli("export " + dir.string() + " --format json --out " + out.string());
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_FALSE(fs::exists(dir / "pareto_export.json"));
    // The file parses to exactly the source JSON (every key, every number bit for bit).
    EXPECT_EQ(load_json(out), load_json(dir / "pareto.json")) << name;
    // And reading it again gives the same text.
    EXPECT_EQ(pkmopt::pareto_json(pkmopt::read_pareto_json(out.string())), read_text(out));
  }
}

TEST_F(ExportTest, HtmlIsSelfContainedWithOnePointPerDesignAndTheKneeSlice) {
  const fs::path dir = fixture("two");
  const auto r = run_cli("export " + dir.string() + " --format html");
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string html = read_text(dir / "report.html");
  EXPECT_EQ(html.find("http"), std::string::npos);  // no URL of any kind
  EXPECT_EQ(html.find("src=\"/"), std::string::npos);
  EXPECT_EQ(count(html, "<circle class=\"pt"), 4u);
  for (const char* id : {"d0000", "d0001", "d0002", "d0003"}) {
    EXPECT_NE(html.find(std::string("<circle class=\"pt") +
                        (std::string(id) == "d0001" ? " knee" : "") + "\" data-id=\"" + id),
              std::string::npos)
        << id;
  }
  EXPECT_EQ(count(html, "<polyline class=\"pc"), 0u);  // two objectives: no parallel view
  EXPECT_NE(html.find("<h2>Knee design d0001</h2>"), std::string::npos);
  EXPECT_NE(html.find("data:image/png;base64,iVBORw0KGgo"), std::string::npos);  // a PNG
  EXPECT_NE(html.find("&lt;b&gt; &amp; &quot;quotes&quot;"), std::string::npos);
  EXPECT_EQ(html.find("<b> & \"quotes\""), std::string::npos);
  EXPECT_EQ(count(html, "<script"), 4u);  // the data, the decision rules, the parallel view, the page
  EXPECT_EQ(html.find("<script src"), std::string::npos);
  // The embedded data is the front in file units, each quantity with its display unit.
  const auto begin = html.find("id=\"report-data\">") + 17;
  const auto end = html.find("</script>", begin);
  const nlohmann::json data = nlohmann::json::parse(html.substr(begin, end - begin));
  const nlohmann::json file = load_json(dir / "pareto.json");
  ASSERT_EQ(data["designs"].size(), file["designs"].size());
  ASSERT_EQ(data["objectives"].size(), file["objectives"].size());
  for (std::size_t k = 0; k < file["objectives"].size(); ++k) {
    const std::string name = file["objectives"][k]["name"];
    EXPECT_EQ(data["objectives"][k]["name"], name);
    for (std::size_t d = 0; d < file["designs"].size(); ++d)
      EXPECT_EQ(data["designs"][d]["objectives"][k], file["designs"][d]["objectives"][name]);
  }
  EXPECT_EQ(data["knee"], file["knee"]);
  // Plots for papers next to the report.
  for (const char* file : {"pareto.svg", "pareto.png", "knee_slice.svg", "knee_slice.png"}) {
    EXPECT_TRUE(fs::exists(dir / file)) << file;
  }
  EXPECT_EQ(read_text(dir / "pareto.png").substr(1, 3), "PNG");
}

TEST_F(ExportTest, HtmlWithThreeObjectivesHasParallelCoordinates) {
  const fs::path dir = fixture("three");
  const fs::path out = dir_ / "three.html";
  const auto r = run_cli("export " + dir.string() + " --format html --out " + out.string());
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string html = read_text(out);
  EXPECT_EQ(html.find("http"), std::string::npos);
  EXPECT_EQ(count(html, "<circle class=\"pt"), 3u);
  EXPECT_EQ(count(html, "<polyline class=\"pc"), 3u);
  EXPECT_NE(html.find("<polyline class=\"pc knee\" data-id=\"b\""), std::string::npos);
  EXPECT_NE(html.find("No workspace slice"), std::string::npos);
  EXPECT_TRUE(fs::exists(dir_ / "pareto.svg"));  // next to --out
  EXPECT_FALSE(fs::exists(dir / "pareto.svg"));
}

TEST_F(ExportTest, PlotsFlagWritesThePlotsWithCsv) {
  const fs::path dir = fixture("three");
  const auto r = run_cli("export " + dir.string() + " --format csv --plots");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir / "pareto.svg"));
  EXPECT_TRUE(fs::exists(dir / "pareto.png"));
  EXPECT_FALSE(fs::exists(dir / "knee_slice.png"));  // the knee has no machine file
}

TEST_F(ExportTest, EndToEndRunThenHtmlReport) {
  // A tiny design study (hexapod-quick with a short NSGA-II run).
  std::string study = read_text(fs::path(PKMOPT_SOURCE_DIR) / "studies/library/hexapod-quick.yaml");
  const std::string optimizer = "optimizer: {algorithm: nsga2, population: 60, generations: 80";
  ASSERT_NE(study.find(optimizer), std::string::npos);
  study.replace(study.find(optimizer), optimizer.size(),
                "optimizer: {algorithm: nsga2, population: 16, generations: 10");
  write(dir_ / "tiny.yaml", study);
  const fs::path dir = dir_ / "tiny";
  const auto run =
      run_cli("run " + (dir_ / "tiny.yaml").string() + " --out " + dir.string() + " --threads 1");
  ASSERT_EQ(run.status, 0) << run.err;
  ASSERT_TRUE(fs::exists(dir / "pareto.json"));
  const auto r = run_cli("export " + dir.string() + " --format html");
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json front = load_json(dir / "pareto.json");
  ASSERT_GT(front["designs"].size(), 0u);
  const std::string html = read_text(dir / "report.html");
  EXPECT_EQ(count(html, "<circle class=\"pt"), front["designs"].size());
  EXPECT_EQ(html.find("http"), std::string::npos);
  if (front["knee"].is_string()) {
    EXPECT_NE(html.find("<h2>Knee design " + front["knee"].get<std::string>() + "</h2>"),
              std::string::npos);
    EXPECT_NE(html.find("data:image/png;base64,"), std::string::npos);
    EXPECT_TRUE(fs::exists(dir / "knee_slice.png"));
  }
  // Every design drawn (in the embedded data), the convergence plot, the knee in words.
  EXPECT_EQ(count(html, "class=\\\"machine\\\""), front["designs"].size());
  EXPECT_NE(html.find("<svg id=\"convergence\""), std::string::npos);
  EXPECT_NE(html.find("The knee is the design whose objectives"), std::string::npos);
  EXPECT_NE(html.find("<select id=\"x-axis\">"), std::string::npos);
  // The CSV export has the same designs as the run's own pareto.csv.
  ASSERT_EQ(run_cli("export " + dir.string() + " --format csv").status, 0);
  const auto exported = pkmopt::read_csv_file((dir / "pareto_export.csv").string());
  const auto original = pkmopt::read_csv_file((dir / "pareto.csv").string());
  ASSERT_EQ(exported.rows.size(), original.rows.size());
  for (std::size_t d = 0; d < exported.rows.size(); ++d) {
    for (const std::string& column : original.header) {
      if (column == "failure" || exported.column(column) < 0) continue;
      EXPECT_EQ(exported.rows[d].cells[static_cast<std::size_t>(exported.column(column))],
                original.rows[d].cells[static_cast<std::size_t>(original.column(column))])
          << column;
    }
  }
}

// ---- Bad input: exit 2, one exact message, no file written ----------------------------------

TEST_F(ExportTest, MissingFolder) {
  const fs::path dir = dir_ / "nothing";
  const auto r = run_cli("export " + dir.string() + " --format csv");
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err, "pkmopt: error: " + dir.string() +
                       ": expected a results folder of `pkmopt run`, found no such folder\n");
  EXPECT_FALSE(fs::exists(dir));
}

TEST_F(ExportTest, MissingParetoJson) {
  const fs::path dir = dir_ / "empty";
  fs::create_directories(dir);
  const auto r = run_cli("export " + dir.string() + " --format html");
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err, "pkmopt: error: " + (dir / "pareto.json").string() +
                       ": cannot open the file (does it exist and is it readable?)\n");
  EXPECT_EQ(file_count(dir), 0u);
}

TEST_F(ExportTest, MalformedJson) {
  const fs::path dir = fixture("two");
  write(dir / "pareto.json", "{\n  \"format\": \"pkmopt-pareto-1\",\n  \"study\": ,\n}\n");
  const auto r = run_cli("export " + dir.string() + " --format html");
  EXPECT_EQ(r.status, 2);
  const std::string prefix = "pkmopt: error: " + (dir / "pareto.json").string() +
                             ":3:12: expected JSON, found a syntax error (";
  EXPECT_EQ(r.err.substr(0, prefix.size()), prefix) << r.err;
  EXPECT_FALSE(fs::exists(dir / "report.html"));
  EXPECT_FALSE(fs::exists(dir / "pareto.svg"));
}

TEST_F(ExportTest, MissingOrWrongKeys) {
  struct Case {
    std::string edit_path;  // JSON pointer of the value to remove or replace
    nlohmann::json replacement;
    bool remove;
    std::string message;
  };
  const std::vector<Case> cases = {
      {"/designs/2/feasible", nullptr, true,
       "designs[2].feasible: expected true or false, found no such key"},
      {"/designs/0/objectives/machine_size", nullptr, true,
       "designs[0].objectives.machine_size: expected a number or null, found no such key"},
      {"/designs/1/objectives/stiffness_min", "2.5e7", false,
       "designs[1].objectives.stiffness_min: expected a number or null, found the string "
       "'2.5e7'"},
      {"/designs/1/parameters/stroke", 0.45, false,
       "designs[1].parameters.stroke: expected one of the names listed at the top of the file, "
       "found 'stroke'"},
      {"/objectives", nullptr, true, "objectives: expected an array, found no such key"},
      {"/task/centre", nlohmann::json::array({0, 0}), false,
       "task.centre: expected 3 numbers, found an array of 2 elements"},
      {"/format", "pkmopt-pareto-9", false,
       "format: expected 'pkmopt-pareto-1', found 'pkmopt-pareto-9'"},
      {"/knee", "d0042", false, "knee: expected the id of a design in `designs`, found 'd0042'"},
      {"/knee", nullptr, true, "knee: expected a design id or null, found no such key"},
      {"/designs/3/id", "d0000", false, "designs[3].id: expected an id used once, found 'd0000'"},
      {"/objectives/1/sense", "max", false,
       "objectives[1].sense: expected 'minimize' or 'maximize', found 'max'"},
  };
  const fs::path dir = fixture("two");
  const nlohmann::json original = load_json(dir / "pareto.json");
  for (const Case& c : cases) {
    nlohmann::json edited = original;
    const nlohmann::json::json_pointer pointer(c.edit_path);
    if (c.remove) {
      edited[pointer.parent_pointer()].erase(pointer.back());
    } else {
      edited[pointer] = c.replacement;
    }
    write(dir / "pareto.json", edited.dump(2));
    for (const char* format : {"csv", "json", "html"}) {
      const auto r = run_cli("export " + dir.string() + " --format " + format);
      EXPECT_EQ(r.status, 2) << c.edit_path;
      EXPECT_EQ(r.err,
                "pkmopt: error: " + (dir / "pareto.json").string() + ": " + c.message + "\n");
    }
    EXPECT_EQ(file_count(dir), 2u) << c.edit_path;  // pareto.json and designs/d0001.yaml
  }
}

TEST_F(ExportTest, UnknownFormat) {
  const fs::path dir = fixture("two");
  const auto r = run_cli("export " + dir.string() + " --format xml");
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err, "pkmopt: error: --format: expected csv, json or html, found 'xml'\n");
  EXPECT_EQ(file_count(dir), 2u);
}

TEST_F(ExportTest, BrokenKneeMachineFileWritesNothing) {
  const fs::path dir = fixture("two");
  write(dir / "designs/d0001.yaml", "model: hexapod\nbase: {radius: abc}\n");
  const auto r = run_cli("export " + dir.string() + " --format html");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find((dir / "designs/d0001.yaml").string()), std::string::npos) << r.err;
  EXPECT_EQ(file_count(dir), 2u);
}

}  // namespace
