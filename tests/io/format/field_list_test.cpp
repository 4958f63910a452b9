// Tests of io/format/field_list.hpp: one field list gives the strict reader, the writer and the
// docs.
#include "io/format/field_list.hpp"

#include <gtest/gtest.h>

#include <array>
#include <numbers>
#include <string>
#include <vector>

#include "io/format/input_error.hpp"

namespace pkmopt {

// A local config struct with one field of every supported kind.
struct SampleOptions {
  std::size_t points = 21;
  int iterations = 100;
  double tolerance = 1e-8;
  double probability = 0.5;
  unsigned population = 0;  // 0: unset
  bool equality = false;
  std::string name = "SLSQP";
  std::vector<double> start;
};

template <class Fields>
void describe_fields(Fields& f, SampleOptions& o) {
  f.field("points", o.points, {.min = 2, .even = true, .doc = "front points"});
  f.field("iterations", o.iterations, {.min = 1, .required = true, .doc = "iterations"});
  f.field("tolerance", o.tolerance, {.min = 0, .min_exclusive = true, .unit = "m", .doc = "tol"});
  f.field("probability", o.probability, {.min = 0, .max = 1, .doc = "p"});
  f.field("population", o.population, {.min = 1, .zero_is_unset = true, .doc = "pop"});
  f.field("equality", o.equality, {.doc = "eq"});
  f.field("name", o.name, {.doc = "algorithm"});
  f.field("start", o.start, {.default_text = "centre", .doc = "start"});
  f.note("extra", "a map", "", "none", "read by hand");
}

namespace {

std::string error_of(const std::string& yaml) {
  try {
    SampleOptions o;
    read_fields(YamlValue::load_string(yaml, "s.yaml"), o);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(FieldList, ReadsEveryKindAndKeepsDefaultsOfAbsentKeys) {
  SampleOptions o;
  read_fields(YamlValue::load_string(
                  "{points: 8, iterations: 3, probability: 1, equality: true, name: COBYLA, "
                  "start: [1, 2.5], extra: {a: 1}}",
                  "s.yaml"),
              o);
  EXPECT_EQ(o.points, 8u);
  EXPECT_EQ(o.iterations, 3);
  EXPECT_EQ(o.tolerance, 1e-8);
  EXPECT_EQ(o.probability, 1.0);
  EXPECT_EQ(o.population, 0u);
  EXPECT_TRUE(o.equality);
  EXPECT_EQ(o.name, "COBYLA");
  EXPECT_EQ(o.start, (std::vector<double>{1.0, 2.5}));
}

TEST(FieldList, BoundsAndKindsGiveLocatedMessages) {
  EXPECT_EQ(error_of("{iterations: 1, points: 7}"),
            "s.yaml:1:25: points: expected an even integer >= 2, found '7'");
  EXPECT_EQ(error_of("{iterations: 0}"),
            "s.yaml:1:14: iterations: expected an integer >= 1, found '0'");
  EXPECT_EQ(error_of("{iterations: 1, tolerance: 0}"),
            "s.yaml:1:28: tolerance: expected a number > 0, found '0'");
  EXPECT_EQ(error_of("{iterations: 1, probability: 1.5}"),
            "s.yaml:1:30: probability: expected a number in [0, 1], found '1.5'");
  EXPECT_EQ(error_of("{iterations: 1, population: -3}"),
            "s.yaml:1:29: population: expected an integer >= 1, found '-3'");
}

TEST(FieldList, UnknownKeysComeFirstAndRequiredKeysAreRequired) {
  const std::string unknown = error_of("{points: 7, iterations: 1, colour: red}");
  EXPECT_NE(unknown.find("colour"), std::string::npos) << unknown;
  EXPECT_EQ(unknown.find("even"), std::string::npos) << unknown;
  const std::string missing = error_of("{points: 4}");
  EXPECT_NE(missing.find("missing required key 'iterations'"), std::string::npos) << missing;
}

TEST(FieldList, WriterRoundTripsAndLeavesUnsetKeysOut) {
  SampleOptions o;
  o.points = 22;  // the default 21 is not even: it would not read back
  o.iterations = 7;
  o.tolerance = 2.5e-7;
  o.start = {0.25, -1};
  const std::string yaml = fields_flow_map(o);
  EXPECT_EQ(yaml,
            "{points: 22, iterations: 7, tolerance: 2.5e-07, probability: 0.5, equality: false, "
            "name: SLSQP, start: [0.25, -1]}");
  SampleOptions back;
  read_fields(YamlValue::load_string(yaml, "w.yaml"), back);
  EXPECT_EQ(back.points, o.points);
  EXPECT_EQ(back.iterations, o.iterations);
  EXPECT_EQ(back.tolerance, o.tolerance);
  EXPECT_EQ(back.start, o.start);
  o.population = 40;
  EXPECT_NE(fields_flow_map(o).find("population: 40"), std::string::npos);
}

TEST(FieldList, DocsTableHasOneRowPerKeyWithDefaultsAndBounds) {
  const std::string table = fields_markdown(SampleOptions{});
  EXPECT_EQ(table,
            "| key | allowed | unit | default | meaning |\n"
            "| --- | --- | --- | --- | --- |\n"
            "| `points` | an even integer >= 2 | – | 21 | front points |\n"
            "| `iterations` | an integer >= 1 | – | required | iterations |\n"
            "| `tolerance` | a number > 0 | m | 1e-08 | tol |\n"
            "| `probability` | a number in [0, 1] | – | 0.5 | p |\n"
            "| `population` | an integer >= 1 | – | unset | pop |\n"
            "| `equality` | true or false | – | false | eq |\n"
            "| `name` | a text | – | SLSQP | algorithm |\n"
            "| `start` | a list of finite numbers | – | centre | start |\n"
            "| `extra` | a map | – | none | read by hand |\n");
}

// A struct with one field of each kind added for the machine files: ranges, choices, columns,
// fixed-size lists, point lists, open intervals and angle vectors.
struct MachineOptions {
  double low = 0.0, high = 1.0;              // a stroke (m)
  double theta_min = -0.5, theta_max = 0.5;  // rad, written in degrees
  int branch = 1;
  std::array<double, 3> heights{0.0, 0.0, 0.0};
  double k1 = 0.0, k2 = 0.0;                                  // one per axis
  double a_min = 0.0, a_max = 0.0, b_min = 0.0, b_max = 0.0;  // one range per axis
  Eigen::Matrix<double, 3, 2> points = Eigen::Matrix<double, 3, 2>::Zero();
  double tilt = 0.0;                                 // rad, (-90, 90) deg
  Eigen::Vector3d angles = Eigen::Vector3d::Zero();  // rad, written in degrees
};

template <class Fields>
void describe_fields(Fields& f, MachineOptions& o) {
  FieldRange stroke{o.low, o.high};
  f.field("stroke", stroke, {.required = true, .unit = "m", .doc = "travel"});
  FieldRange drive{o.theta_min, o.theta_max};
  f.field("drive_deg", drive,
          {.min = -180, .max = 180, .degrees = true, .digits = 12, .unit = "deg", .doc = "drive"});
  FieldChoice<int> branch{o.branch, {{"out", 1}, {"outwards", 1}, {"in", -1}}};
  f.field("branch", branch, {.doc = "branch"});
  f.field("heights", o.heights, {.min = 0, .unit = "m", .doc = "heights"});
  FieldColumn k{{&o.k1, &o.k2}};
  f.field("k", k, {.min = 0, .unit = "N/m", .doc = "per axis"});
  std::vector<FieldRange> ranges;
  ranges.push_back({.low = o.a_min, .high = o.a_max, .closed = true, .found_values = true});
  ranges.push_back({.low = o.b_min, .high = o.b_max, .closed = true, .found_values = true});
  f.field("ranges", ranges, {.expected = "[min, max] with min <= max (m)", .doc = "per axis"});
  f.field("points", o.points, {.unit = "m", .doc = "points"});
  f.field("tilt_deg", o.tilt,
          {.min = -90,
           .max = 90,
           .min_exclusive = true,
           .max_exclusive = true,
           .degrees = true,
           .digits = 12,
           .unit = "deg",
           .doc = "tilt"});
  f.field("angles_deg", o.angles, {.degrees = true, .digits = 12, .unit = "deg", .doc = "angles"});
}

std::string machine_error_of(const std::string& yaml) {
  try {
    MachineOptions o;
    read_fields(YamlValue::load_string(yaml, "m.yaml"), o);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(FieldListKinds, ReadsRangesChoicesListsAndConvertsDegrees) {
  MachineOptions o;
  read_fields(YamlValue::load_string(
                  "{stroke: [-0.5, 1.5], drive_deg: [-90, 45], branch: in, heights: [1, 2, 3], "
                  "k: [10, 20], ranges: [[-1, 1], [0, 0]], points: [[1, 2, 3], [4, 5, 6]], "
                  "tilt_deg: -30, angles_deg: [90, 0, 180]}",
                  "m.yaml"),
              o);
  EXPECT_EQ(o.low, -0.5);
  EXPECT_EQ(o.high, 1.5);
  EXPECT_EQ(o.theta_min, -90 * (std::numbers::pi / 180.0));
  EXPECT_EQ(o.theta_max, 45 * (std::numbers::pi / 180.0));
  EXPECT_EQ(o.branch, -1);
  EXPECT_EQ(o.heights, (std::array<double, 3>{1, 2, 3}));
  EXPECT_EQ(o.k1, 10.0);
  EXPECT_EQ(o.k2, 20.0);
  EXPECT_EQ(o.a_min, -1.0);
  EXPECT_EQ(o.a_max, 1.0);
  EXPECT_EQ(o.b_min, 0.0);  // closed: low == high allowed
  EXPECT_EQ(o.b_max, 0.0);
  EXPECT_EQ(o.points.col(1), Eigen::Vector3d(4, 5, 6));
  EXPECT_EQ(o.tilt, -30 * (std::numbers::pi / 180.0));
  EXPECT_EQ(o.angles, Eigen::Vector3d(90, 0, 180) * (std::numbers::pi / 180.0));
  // A synonym gives the same value.
  read_fields(YamlValue::load_string("{stroke: [0, 1], branch: outwards}", "m.yaml"), o);
  EXPECT_EQ(o.branch, 1);
}

TEST(FieldListKinds, BadValuesGiveLocatedMessages) {
  EXPECT_EQ(machine_error_of("{stroke: [1, 0]}"),
            "m.yaml:1:10: stroke: expected [low, high] with low < high (m), found a list of 2");
  EXPECT_EQ(machine_error_of("{stroke: [0]}"),
            "m.yaml:1:10: stroke: expected a list of 2, found a list of 1");
  EXPECT_EQ(machine_error_of("{stroke: [0, 1], drive_deg: [-200, 0]}"),
            "m.yaml:1:29: drive_deg: expected a range within [-180, 180] deg, found [-200, 0]");
  EXPECT_EQ(machine_error_of("{stroke: [0, 1], branch: sideways}"),
            "m.yaml:1:26: branch: expected out, outwards or in, found 'sideways'");
  EXPECT_EQ(machine_error_of("{stroke: [0, 1], heights: [1, 2]}"),
            "m.yaml:1:27: heights: expected a list of 3, found a list of 2");
  EXPECT_EQ(machine_error_of("{stroke: [0, 1], heights: [1, -2, 3]}"),
            "m.yaml:1:31: heights[1]: expected a number >= 0, found '-2'");
  EXPECT_EQ(machine_error_of("{stroke: [0, 1], k: [1, 2, 3]}"),
            "m.yaml:1:21: k: expected a list of 2, found a list of 3");
  EXPECT_EQ(machine_error_of("{stroke: [0, 1], k: [1, -2]}"),
            "m.yaml:1:25: k[1]: expected a number >= 0, found '-2'");
  EXPECT_EQ(machine_error_of("{stroke: [0, 1], ranges: [[0, 1], [1, -1]]}"),
            "m.yaml:1:35: ranges[1]: expected [min, max] with min <= max (m), found [1, -1]");
  EXPECT_EQ(machine_error_of("{stroke: [0, 1], points: [[1, 2, 3]]}"),
            "m.yaml:1:26: points: expected a list of 2, found a list of 1");
  EXPECT_EQ(machine_error_of("{stroke: [0, 1], tilt_deg: 90}"),
            "m.yaml:1:28: tilt_deg: expected a number in (-90, 90), found '90'");
}

TEST(FieldListKinds, OpenIntervalsAndRangeOverridesInMessages) {
  struct Open {
    double x = 0.0;
    double lo = 1.0, hi = 2.0;
  };
  auto error = [](const std::string& yaml, double max, bool max_exclusive) {
    try {
      Open o;
      const YamlValue root = YamlValue::load_string(yaml, "o.yaml");
      FieldReader reader(root);  // holds a reference: keep the map alive
      reader.field("x", o.x, {.max = max, .max_exclusive = max_exclusive});
      FieldRange range{o.lo, o.hi};
      reader.field(
          "r", range,
          {.min = 0, .min_exclusive = true, .expected = "[low, high] with 0 < low < high"});
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(error("{x: 5}", 5, true), "o.yaml:1:5: x: expected a number < 5, found '5'");
  EXPECT_EQ(error("{x: 5}", 5, false), "");
  EXPECT_EQ(error("{x: 6}", 5, false), "o.yaml:1:5: x: expected a number <= 5, found '6'");
  // With `expected`, both the order and the bounds fail with that text.
  EXPECT_EQ(error("{r: [0, 1]}", 5, false),
            "o.yaml:1:5: r: expected [low, high] with 0 < low < high, found a list of 2");
  EXPECT_EQ(error("{r: [2, 1]}", 5, false),
            "o.yaml:1:5: r: expected [low, high] with 0 < low < high, found a list of 2");
}

TEST(FieldListKinds, WriterGivesFlowListsAndDegreesAndLeavesUnmatchedChoicesOut) {
  MachineOptions o;
  o.low = 0.25;
  o.theta_min = std::numbers::pi / 3;  // 60 deg: 12 digits, not 59.99999999999999
  o.theta_max = std::numbers::pi / 2;
  o.branch = -1;
  o.heights = {0.5, 0, 1};
  o.k1 = 2e8;
  o.a_max = 1.5;
  o.points.col(0) = Eigen::Vector3d(1, 2, 3);
  o.tilt = std::numbers::pi / 6;
  o.angles = Eigen::Vector3d(std::numbers::pi, 0, 0);
  FieldWriter writer;
  describe_fields(writer, o);
  EXPECT_EQ(writer.flow_lines(),
            "stroke: [0.25, 1]\n"
            "drive_deg: [60, 90]\n"
            "branch: in\n"
            "heights: [0.5, 0, 1]\n"
            "k: [200000000, 0]\n"
            "ranges: [[0, 1.5], [0, 0]]\n"
            "points: [[1, 2, 3], [0, 0, 0]]\n"
            "tilt_deg: 30\n"
            "angles_deg: [180, 0, 0]\n");
  MachineOptions back;
  read_fields(YamlValue::load_string(fields_flow_map(o), "w.yaml"), back);
  EXPECT_EQ(back.low, o.low);
  EXPECT_NEAR(back.theta_min, o.theta_min, 1e-15);
  EXPECT_EQ(back.branch, o.branch);
  EXPECT_EQ(back.heights, o.heights);
  EXPECT_EQ(back.k1, o.k1);
  EXPECT_EQ(back.a_max, o.a_max);
  EXPECT_EQ(back.points, o.points);
  EXPECT_NEAR(back.tilt, o.tilt, 1e-15);
  // The first name of a value is written; a value no name has is left out.
  o.branch = 1;
  EXPECT_NE(fields_flow_map(o).find("branch: out,"), std::string::npos);
  o.branch = 7;
  EXPECT_EQ(fields_flow_map(o).find("branch"), std::string::npos);
  // Nested maps: flow maps in flow_lines, indented in block.
  struct Nested {
    double a = 1, b = 2;
  };
  Nested n;
  FieldWriter nested;
  nested.field("a", n.a);
  nested.section("sub", {}, [&](auto& g) { g.field("b", n.b); });
  EXPECT_EQ(nested.flow_lines(), "a: 1\nsub: {b: 2}\n");
  EXPECT_EQ(nested.block(), "a: 1\nsub:\n  b: 2\n");
}

// A design-parameter section: FieldBounds (fixed or free) and an integer list.
struct ParameterOptions {
  double radius_lo = 0.5, radius_hi = 0.5;
  double height_lo = 0.0, height_hi = 0.0;
  std::array<int, 3> points{1, 1, 1};
};

template <class Fields>
void describe_fields(Fields& f, ParameterOptions& o) {
  FieldBounds radius{o.radius_lo, o.radius_hi};
  FieldBounds height{o.height_lo, o.height_hi};
  f.field("radius", radius, {.min = 0, .min_exclusive = true, .unit = "m", .doc = "r"});
  f.field("height", height, {.doc = "h"});
  f.field("points", o.points, {.min = 1, .max = 1000, .doc = "grid"});
}

std::string parameter_error_of(const std::string& yaml) {
  try {
    ParameterOptions o;
    read_fields(YamlValue::load_string(yaml, "p.yaml"), o);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(FieldListBounds, ReadsFixedAndFreeParametersAndIntegerLists) {
  ParameterOptions o;
  read_fields(
      YamlValue::load_string(
          "{radius: {min: 0.25, max: 0.75}, height: -0.125, points: [2, 3, 1000]}", "p.yaml"),
      o);
  EXPECT_EQ(o.radius_lo, 0.25);
  EXPECT_EQ(o.radius_hi, 0.75);
  EXPECT_EQ(o.height_lo, -0.125);
  EXPECT_EQ(o.height_hi, -0.125);
  EXPECT_EQ(o.points, (std::array<int, 3>{2, 3, 1000}));
  // Written back: free as {min, max}, fixed as the number; and read again to the same values.
  const std::string yaml = fields_flow_map(o);
  EXPECT_EQ(yaml, "{radius: {min: 0.25, max: 0.75}, height: -0.125, points: [2, 3, 1000]}");
  ParameterOptions again;
  read_fields(YamlValue::load_string(yaml, "p.yaml"), again);
  EXPECT_EQ(again.radius_lo, o.radius_lo);
  EXPECT_EQ(again.radius_hi, o.radius_hi);
  EXPECT_EQ(again.points, o.points);
}

TEST(FieldListBounds, BadBoundsAndCountsGiveLocatedMessages) {
  EXPECT_EQ(parameter_error_of("{radius: {min: 0.5, max: 0.5}}"),
            "p.yaml:1:26: radius.max: expected max > min, found '0.5'");
  EXPECT_EQ(parameter_error_of("{radius: {min: 0, max: 0.5}}"),
            "p.yaml:1:10: radius: expected values > 0, found a map");
  EXPECT_EQ(parameter_error_of("{radius: -1}"),
            "p.yaml:1:10: radius: expected values > 0, found '-1'");
  EXPECT_EQ(parameter_error_of("{radius: {min: 0.1, mx: 0.5}}"),
            "p.yaml:1:21: radius.mx: unknown key 'mx'; allowed keys here: min, max");
  EXPECT_EQ(parameter_error_of("{points: [1, 0, 1]}"),
            "p.yaml:1:14: points[1]: expected an integer in [1, 1000], found '0'");
  EXPECT_EQ(parameter_error_of("{points: [1, 1.5, 1]}").find("points[1]: expected an integer"),
            std::string("p.yaml:1:14: ").size());
  EXPECT_EQ(parameter_error_of("{points: [1, 1]}"),
            "p.yaml:1:10: points: expected a list of 3, found a list of 2");
}

TEST(FieldListBounds, DocsAndNestedBlocksIndentEachLevel) {
  EXPECT_EQ(
      fields_markdown(ParameterOptions{}),
      "| key | allowed | unit | default | meaning |\n"
      "| --- | --- | --- | --- | --- |\n"
      "| `radius` | a number (fixed) or {min, max} with min < max (free); values > 0 | m | "
      "0.5 | r |\n"
      "| `height` | a number (fixed) or {min, max} with min < max (free); finite values | – | "
      "0 | h |\n"
      "| `points` | a list of 3 integers in [1, 1000] | – | [1, 1, 1] | grid |\n");
  ParameterOptions o;
  FieldWriter writer;
  writer.section("outer", {},
                 [&](auto& g) { g.section("inner", {}, [&](auto& h) { describe_fields(h, o); }); });
  EXPECT_EQ(writer.block(2),
            "  outer:\n    inner:\n      radius: 0.5\n      height: 0\n      points: [1, 1, 1]\n");
}

TEST(FieldListKinds, DocsTableDescribesEachKind) {
  EXPECT_EQ(
      fields_markdown(MachineOptions{}),
      "| key | allowed | unit | default | meaning |\n"
      "| --- | --- | --- | --- | --- |\n"
      "| `stroke` | [low, high] with low < high | m | required | travel |\n"
      "| `drive_deg` | [low, high] with low < high within [-180, 180] | deg | [-28.6478897565, "
      "28.6478897565] | drive |\n"
      "| `branch` | out, outwards or in | – | out | branch |\n"
      "| `heights` | a list of 3 numbers >= 0 | m | [0, 0, 0] | heights |\n"
      "| `k` | a list of numbers >= 0 | N/m | [0, 0] | per axis |\n"
      "| `ranges` | a list of [min, max] with min <= max (m) | – | [[0, 0], [0, 0]] | per "
      "axis |\n"
      "| `points` | [[x, y, z] × 2] | m | [[0, 0, 0], [0, 0, 0]] | points |\n"
      "| `tilt_deg` | a number in (-90, 90) | deg | 0 | tilt |\n"
      "| `angles_deg` | [x, y, z] | deg | [0, 0, 0] | angles |\n");
}

}  // namespace
}  // namespace pkmopt
