// Tests of io/machine/machine_file_leg_chain: the field lists of the leg-chain machine files give
// the docs tables of docs/machines.md, and the writers built on them
// (delta_machine_file and the others) give files the readers read back to the same design with
// every optional key set; the keys read by hand next to the lists (link stiffness alternatives,
// platform or platform_joints, the generic form's legs and actuator error) keep their messages.
#include "io/machine/machine_file_leg_chain.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "io/format/csv.hpp"
#include "io/format/input_error.hpp"
#include "io/format/yaml_reader.hpp"
#include "io/machine/machine_file.hpp"
#include "io/machine/model_registry.hpp"
#include "problems/design/leg_chain_design.hpp"
#include "tests/io/machine/readback.hpp"

namespace pkmopt {
namespace {

using readback_test::expect_angle;

const std::string kSource = PKMOPT_SOURCE_DIR;

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

YamlValue yaml(const std::string& text) { return YamlValue::load_string(text, "m.yaml"); }

std::string error_of(const std::string& text) {
  try {
    (void)load_machine(yaml(text));
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

void expect_vector_angles(const Eigen::Vector3d& read, const Eigen::Vector3d& written,
                          const std::string& what) {
  for (int i = 0; i < 3; ++i) expect_angle(read(i), written(i), what);
}

TEST(LegChainMachineFileFields, DocsCarryTheGeneratedTables) {
  const std::string docs = read_text(kSource + "/docs/machines.md");
  for (const char* model : {"delta", "linear_delta", "hexaglide", "tripod_3prs", "leg_chain"}) {
    const std::string block = std::string("<!-- fields: ") + model + " -->\n" +
                              leg_chain_machine_fields_markdown(model) + "<!-- /fields -->\n";
    EXPECT_NE(docs.find(block), std::string::npos)
        << "docs/machines.md lacks the generated " << model << " table:\n"
        << block;
  }
  EXPECT_THROW(leg_chain_machine_fields_markdown("tetrapod"), std::invalid_argument);
}

// Every optional key away from its default; E and area, then the axial form.
TEST(LegChainMachineFileFields, DeltaRoundTripsEveryKey) {
  DeltaDesign d;
  d.base_radius = 0.2;
  d.platform_radius = 0.05;
  d.upper_arm = 0.4;
  d.rod = 0.9;
  d.theta_min = deg_to_rad(-40.0);
  d.theta_max = deg_to_rad(90.0);
  d.branch = -1;
  d.stiffness = {0.0, 7.1e10, 6.0e-5, 5.0e4};
  d.elbow_max_angle = deg_to_rad(35.0);
  d.platform_max_angle = deg_to_rad(40.0);
  d.tcp = {0.0, 0.01, -0.05};
  d.characteristic_length = 0.3;
  d.actuator_error = deg_to_rad(2e-3);
  for (int form = 0; form < 2; ++form) {
    if (form == 1) d.stiffness = {3.0e6, 0.0, 0.0, 5.0e4};
    const std::string text = delta_machine_file(d);
    const DeltaDesign r = read_delta_design(yaml(text));
    EXPECT_EQ(r.base_radius, d.base_radius);
    EXPECT_EQ(r.platform_radius, d.platform_radius);
    EXPECT_EQ(r.upper_arm, d.upper_arm);
    EXPECT_EQ(r.rod, d.rod);
    expect_angle(r.theta_min, d.theta_min, "theta_min");
    expect_angle(r.theta_max, d.theta_max, "theta_max");
    EXPECT_EQ(r.branch, d.branch);
    EXPECT_EQ(r.stiffness.axial_stiffness, d.stiffness.axial_stiffness);
    EXPECT_EQ(r.stiffness.E, d.stiffness.E);
    EXPECT_EQ(r.stiffness.area, d.stiffness.area);
    EXPECT_EQ(r.stiffness.actuator_stiffness, d.stiffness.actuator_stiffness);
    expect_angle(r.elbow_max_angle, d.elbow_max_angle, "elbow_max_angle");
    expect_angle(r.platform_max_angle, d.platform_max_angle, "platform_max_angle");
    EXPECT_EQ(r.tcp, d.tcp);
    EXPECT_EQ(r.characteristic_length, d.characteristic_length);
    expect_angle(r.actuator_error, d.actuator_error, "actuator_error");
    EXPECT_EQ(delta_machine_file(r), text);
  }
  EXPECT_EQ(delta_machine_file(d),
            "model: delta\nbase_radius: 0.2\nplatform_radius: 0.05\nupper_arm: 0.4\nrod: 0.9\n"
            "drive_range_deg: [-40, 90]\nbranch: elbow_in\nrods: {axial_stiffness: 3000000}\n"
            "drive_stiffness: 50000\n"
            "joints: {elbow_max_angle_deg: 35, platform_max_angle_deg: 40}\n"
            "tool: {tcp: [0, 0.01, -0.05]}\ncharacteristic_length: 0.3\n"
            "actuator_error_deg: 0.002\n");
}

TEST(LegChainMachineFileFields, LinearDeltaRoundTripsEveryKey) {
  LinearDeltaDesign d;
  d.guide_radius = 0.3;
  d.platform_radius = 0.05;
  d.rod = 0.7;
  d.inclination = deg_to_rad(12.0);
  d.q_min = 0.05;
  d.q_max = 0.8;
  d.stiffness = {0.0, 7.0e10, 2.5e-5, 1.5e8};
  d.carriage_max_angle = deg_to_rad(60.0);
  d.platform_max_angle = deg_to_rad(65.0);
  d.tcp = {0.01, 0.0, -0.05};
  d.characteristic_length = 0.2;
  d.actuator_error = 2e-5;
  const std::string text = linear_delta_machine_file(d);
  const LinearDeltaDesign r = read_linear_delta_design(yaml(text));
  EXPECT_EQ(r.guide_radius, d.guide_radius);
  EXPECT_EQ(r.platform_radius, d.platform_radius);
  EXPECT_EQ(r.rod, d.rod);
  expect_angle(r.inclination, d.inclination, "inclination");
  EXPECT_EQ(r.q_min, d.q_min);
  EXPECT_EQ(r.q_max, d.q_max);
  EXPECT_EQ(r.stiffness.E, d.stiffness.E);
  EXPECT_EQ(r.stiffness.area, d.stiffness.area);
  EXPECT_EQ(r.stiffness.actuator_stiffness, d.stiffness.actuator_stiffness);
  expect_angle(r.carriage_max_angle, d.carriage_max_angle, "carriage_max_angle");
  expect_angle(r.platform_max_angle, d.platform_max_angle, "platform_max_angle");
  EXPECT_EQ(r.tcp, d.tcp);
  EXPECT_EQ(r.characteristic_length, d.characteristic_length);
  EXPECT_EQ(r.actuator_error, d.actuator_error);
  EXPECT_EQ(linear_delta_machine_file(r), text);
  // A rigid drive (no carriage_stiffness) reads back rigid, not as the design default.
  d.stiffness.actuator_stiffness = 0.0;
  const std::string rigid = linear_delta_machine_file(d);
  EXPECT_EQ(rigid.find("carriage_stiffness"), std::string::npos) << rigid;
  EXPECT_EQ(read_linear_delta_design(yaml(rigid)).stiffness.actuator_stiffness, 0.0);
}

TEST(LegChainMachineFileFields, HexaglideRoundTripsEveryKey) {
  HexaglideDesign d;
  d.guide_y = {0.5, 0.45, 0.4, -0.55, -0.5, 0.42};
  d.guide_z = {0.01, -0.01, 0.02, -0.02, 0.0, 0.03};
  d.inclination = deg_to_rad(5.0);
  d.strut = 0.9;
  d.platform_joints.col(2) += Eigen::Vector3d(0.01, -0.02, 0.005);
  d.q_min = -1.0;
  d.q_max = 1.3;
  d.stiffness = {0.0, 2.0e11, 3.5e-4, 1.0e8};
  d.carriage_max_angle = deg_to_rad(70.0);
  d.platform_max_angle = deg_to_rad(50.0);
  d.tcp = {0.0, 0.0, -0.12};
  d.characteristic_length = 0.25;
  d.actuator_error = 3e-5;
  d.home_height = 0.65;
  const std::string text = hexaglide_machine_file(d);
  const HexaglideDesign r = read_hexaglide_design(yaml(text));
  EXPECT_EQ(r.guide_y, d.guide_y);
  EXPECT_EQ(r.guide_z, d.guide_z);
  expect_angle(r.inclination, d.inclination, "inclination");
  EXPECT_EQ(r.strut, d.strut);
  EXPECT_EQ(r.platform_joints, d.platform_joints);
  EXPECT_EQ(r.q_min, d.q_min);
  EXPECT_EQ(r.q_max, d.q_max);
  EXPECT_EQ(r.stiffness.E, d.stiffness.E);
  EXPECT_EQ(r.stiffness.area, d.stiffness.area);
  EXPECT_EQ(r.stiffness.actuator_stiffness, d.stiffness.actuator_stiffness);
  expect_angle(r.carriage_max_angle, d.carriage_max_angle, "carriage_max_angle");
  expect_angle(r.platform_max_angle, d.platform_max_angle, "platform_max_angle");
  EXPECT_EQ(r.tcp, d.tcp);
  EXPECT_EQ(r.characteristic_length, d.characteristic_length);
  EXPECT_EQ(r.actuator_error, d.actuator_error);
  EXPECT_EQ(r.home_height, d.home_height);
  EXPECT_EQ(hexaglide_machine_file(r), text);
}

TEST(LegChainMachineFileFields, Tripod3PrsRoundTripsEveryKey) {
  Tripod3PrsDesign d;
  d.base_radius = 0.32;
  d.platform_radius = 0.14;
  d.strut = 0.6;
  d.q_min = 0.05;
  d.q_max = 0.9;
  d.tool_length = 0.25;
  d.revolute_max_angle = deg_to_rad(45.0);
  d.platform_max_angle = deg_to_rad(60.0);
  d.stiffness = {0.0, 2.0e11, 5.0e-4, 1.0e8};
  d.characteristic_length = 0.4;
  d.actuator_error = 1.5e-5;
  const std::string text = tripod_3prs_machine_file(d);
  const Tripod3PrsDesign r = read_tripod_3prs_design(yaml(text));
  EXPECT_EQ(r.base_radius, d.base_radius);
  EXPECT_EQ(r.platform_radius, d.platform_radius);
  EXPECT_EQ(r.strut, d.strut);
  EXPECT_EQ(r.q_min, d.q_min);
  EXPECT_EQ(r.q_max, d.q_max);
  EXPECT_EQ(r.tool_length, d.tool_length);
  expect_angle(r.revolute_max_angle, d.revolute_max_angle, "revolute_max_angle");
  expect_angle(r.platform_max_angle, d.platform_max_angle, "platform_max_angle");
  EXPECT_EQ(r.stiffness.E, d.stiffness.E);
  EXPECT_EQ(r.stiffness.area, d.stiffness.area);
  EXPECT_EQ(r.stiffness.actuator_stiffness, d.stiffness.actuator_stiffness);
  EXPECT_EQ(r.characteristic_length, d.characteristic_length);
  EXPECT_EQ(r.actuator_error, d.actuator_error);
  EXPECT_EQ(tripod_3prs_machine_file(r), text);
}

void expect_same_leg(const LegChainLeg& r, const LegChainLeg& d, const std::string& what) {
  EXPECT_EQ(r.kind, d.kind) << what;
  EXPECT_EQ(r.base_point, d.base_point) << what;
  EXPECT_EQ(r.platform_point, d.platform_point) << what;
  if (d.kind == LegKind::kRUS) {
    expect_angle(r.q_min, d.q_min, what + " q_min");
    expect_angle(r.q_max, d.q_max, what + " q_max");
    EXPECT_EQ(r.crank_zero, d.crank_zero) << what;
    EXPECT_EQ(r.crank_length, d.crank_length) << what;
  } else {
    EXPECT_EQ(r.q_min, d.q_min) << what;
    EXPECT_EQ(r.q_max, d.q_max) << what;
  }
  if (d.kind != LegKind::kUPS) {
    EXPECT_EQ(r.axis, d.axis) << what;
    EXPECT_EQ(r.link_length, d.link_length) << what;
    EXPECT_EQ(r.branch, d.branch) << what;
  }
  EXPECT_EQ(r.axial_stiffness, d.axial_stiffness) << what;
  if (d.axial_stiffness <= 0.0 && !d.link_section) {  // a section replaces E and area
    EXPECT_EQ(r.E, d.E) << what;
    EXPECT_EQ(r.area, d.area) << what;
  }
  EXPECT_EQ(r.rods, d.rods) << what;
  EXPECT_EQ(r.actuator_stiffness, d.actuator_stiffness) << what;
  expect_angle(r.base_max_angle, d.base_max_angle, what + " base_max_angle");
  expect_angle(r.platform_max_angle, d.platform_max_angle, what + " platform_max_angle");
  EXPECT_EQ(r.base_axis, d.base_axis) << what;
  EXPECT_EQ(r.platform_axis, d.platform_axis) << what;
}

void expect_same_leg_chain(const LegChainDesign& r, const LegChainDesign& d,
                           const std::string& what) {
  EXPECT_EQ(r.mobility, d.mobility) << what;
  if (d.mobility == PlatformMobility::kSchoenflies) {
    EXPECT_EQ(r.rotation_axis, d.rotation_axis) << what;
  }
  EXPECT_EQ(r.tcp, d.tcp) << what;
  EXPECT_EQ(r.characteristic_length, d.characteristic_length) << what;
  EXPECT_EQ(r.home.position, d.home.position) << what;
  expect_vector_angles(r.home.angles, d.home.angles, what + " home angles");
  ASSERT_EQ(r.legs.size(), d.legs.size()) << what;
  const bool revolute = d.legs.front().kind == LegKind::kRUS;
  if (revolute) {
    expect_angle(r.actuator_error, d.actuator_error, what + " actuator_error");
  } else {
    EXPECT_EQ(r.actuator_error, d.actuator_error) << what;
  }
  for (std::size_t i = 0; i < d.legs.size(); ++i)
    expect_same_leg(r.legs[i], d.legs[i], what + " leg " + std::to_string(i));
}

// The generic form: the Schoenflies example with every optional key set, and the named models'
// leg chains (RUS legs of the delta, planar legs of the tripod, PUS legs of the hexaglide).
TEST(LegChainMachineFileFields, GenericFormRoundTripsEveryKey) {
  LegChainDesign d =
      read_leg_chain_design(YamlValue::load_file(kSource + "/examples/schoenflies_4pus.yaml"));
  d.rotation_axis = Eigen::Vector3d(0, 0, 1);
  d.tcp = {0.0, 0.01, -0.06};
  d.characteristic_length = 0.12;
  d.actuator_error = 2e-5;
  d.home.position = {0.0, 0.0, -0.05};
  d.home.angles = {0.0, 0.0, deg_to_rad(5.0)};
  d.legs[1].axial_stiffness = 4e6;  // the axial form on one leg
  d.legs[2].rods = 1;
  d.legs[3].base_axis = Eigen::Vector3d(0, 0, 1);
  const std::string text = leg_chain_machine_file(d);
  const LegChainDesign r = read_leg_chain_design(yaml(text));
  expect_same_leg_chain(r, d, "schoenflies");
  EXPECT_EQ(leg_chain_machine_file(r), text);
  EXPECT_NE(text.find("rotation_axis: [0, 0, 1]\n"), std::string::npos) << text;
  EXPECT_NE(text.find("link: {axial_stiffness: 4000000, rods: 2}"), std::string::npos) << text;

  const std::vector<std::pair<std::string, LegChainDesign>> named = {
      {"delta", delta_design(DeltaDesign{})},
      {"hexaglide", hexaglide_design(HexaglideDesign{})},
      {"tripod_3prs", tripod_3prs_design(Tripod3PrsDesign{})}};
  for (const auto& [name, design] : named) {
    const std::string file = leg_chain_machine_file(design);
    const LegChainDesign back = read_leg_chain_design(yaml(file));
    expect_same_leg_chain(back, design, name);
    EXPECT_EQ(file.find("rotation_axis"), std::string::npos) << file;
    EXPECT_NE(file.find(name == "delta" ? "actuator_error_deg: " : "actuator_error: "),
              std::string::npos)
        << file;
  }
}

// The shipped examples read, written and read again give the same files.
TEST(LegChainMachineFileFields, ExamplesAreFixedPointsOfReadAndWrite) {
  const DeltaDesign delta =
      read_delta_design(YamlValue::load_file(kSource + "/examples/delta.yaml"));
  EXPECT_EQ(delta_machine_file(read_delta_design(yaml(delta_machine_file(delta)))),
            delta_machine_file(delta));
  const LinearDeltaDesign linear =
      read_linear_delta_design(YamlValue::load_file(kSource + "/examples/linear_delta.yaml"));
  EXPECT_EQ(
      linear_delta_machine_file(read_linear_delta_design(yaml(linear_delta_machine_file(linear)))),
      linear_delta_machine_file(linear));
  const HexaglideDesign glide =
      read_hexaglide_design(YamlValue::load_file(kSource + "/examples/hexaglide.yaml"));
  EXPECT_EQ(hexaglide_machine_file(read_hexaglide_design(yaml(hexaglide_machine_file(glide)))),
            hexaglide_machine_file(glide));
  const Tripod3PrsDesign tripod =
      read_tripod_3prs_design(YamlValue::load_file(kSource + "/examples/tripod_3prs.yaml"));
  EXPECT_EQ(
      tripod_3prs_machine_file(read_tripod_3prs_design(yaml(tripod_3prs_machine_file(tripod)))),
      tripod_3prs_machine_file(tripod));
}

void expect_same_section(const std::optional<BeamSection>& read,
                         const std::optional<BeamSection>& written, const std::string& what) {
  ASSERT_EQ(read.has_value(), written.has_value()) << what;
  if (!written) return;
  EXPECT_EQ(read->E, written->E) << what;
  EXPECT_EQ(read->G, written->G) << what;
  EXPECT_EQ(read->A, written->A) << what;
  EXPECT_EQ(read->Iy, written->Iy) << what;
  EXPECT_EQ(read->Iz, written->Iz) << what;
  EXPECT_EQ(read->J, written->J) << what;
}

// Link sections and parallelogram widths: written as the section's values, read back to the same
// design, the writer a fixed point; a tube in a file is the tube_section of its diameters.
TEST(LegChainMachineFileFields, LinkSectionsRoundTrip) {
  const BeamSection tube = tube_section(2.1e11, 8.1e10, 0.08, 0.06);
  const BeamSection box{7.0e10, 2.6e10, 6e-4, 1.2e-7, 3.0e-7, 2.0e-7};
  Tripod3PrsDesign t;
  t.stiffness = {0.0, 0.0, 0.0, 2.0e8};
  t.stiffness.section = tube;
  std::string text = tripod_3prs_machine_file(t);
  EXPECT_NE(text.find("struts: {section: {E: 210000000000, G: 81000000000, A: "), std::string::npos)
      << text;
  Tripod3PrsDesign tr = read_tripod_3prs_design(yaml(text));
  expect_same_section(tr.stiffness.section, t.stiffness.section, "tripod");
  EXPECT_EQ(tripod_3prs_machine_file(tr), text);
  // The tube form reads as tube_section; the API's E and area are not written with a section.
  t.stiffness.E = 2.1e11;
  t.stiffness.area = 6e-4;
  EXPECT_EQ(tripod_3prs_machine_file(t), text);
  const std::string head =
      "model: tripod_3prs\nbase_radius: 0.3\nplatform_radius: 0.15\nstrut: 0.55\nstroke: [0, "
      "0.95]\n";
  tr = read_tripod_3prs_design(
      yaml(head + "struts: {section: {E: 2.1e11, G: 8.1e10, outer_diameter: 0.08, "
                  "inner_diameter: 0.06}}\n"));
  expect_same_section(tr.stiffness.section, tube, "tripod tube");
  tr = read_tripod_3prs_design(
      yaml(head + "struts: {section: {E: 2.1e11, G: 8.1e10, outer_diameter: 0.05}}\n"));
  expect_same_section(tr.stiffness.section, tube_section(2.1e11, 8.1e10, 0.05), "solid rod");

  DeltaDesign d;
  d.stiffness = {0.0, 7.0e10, 5.0e-5, 1.5e5};
  d.stiffness.parallelogram_width = 0.1;
  d.crank_section = box;
  text = delta_machine_file(d);
  EXPECT_NE(text.find("rods: {E: 70000000000, area: 5e-05, parallelogram_width: 0.1}\n"
                      "crank_section: {E: 70000000000, G: 26000000000, A: 0.0006, Iy: 1.2e-07, "
                      "Iz: 3e-07, J: 2e-07}\n"),
            std::string::npos)
      << text;
  const DeltaDesign dr = read_delta_design(yaml(text));
  EXPECT_EQ(dr.stiffness.parallelogram_width, 0.1);
  expect_same_section(dr.crank_section, d.crank_section, "delta crank");
  EXPECT_EQ(delta_machine_file(dr), text);

  LinearDeltaDesign l;
  l.stiffness = {0.0, 0.0, 0.0, 2.0e7};
  l.stiffness.section = tube_section(7.0e10, 2.6e10, 0.012, 0.008);
  l.stiffness.parallelogram_width = 0.06;
  text = linear_delta_machine_file(l);
  const LinearDeltaDesign lr = read_linear_delta_design(yaml(text));
  expect_same_section(lr.stiffness.section, l.stiffness.section, "linear delta");
  EXPECT_EQ(lr.stiffness.parallelogram_width, 0.06);
  EXPECT_EQ(linear_delta_machine_file(lr), text);

  HexaglideDesign g;
  g.stiffness = {0.0, 0.0, 0.0, 2.0e8};
  g.stiffness.section = tube_section(2.1e11, 8.1e10, 0.05, 0.04);
  text = hexaglide_machine_file(g);
  const HexaglideDesign gr = read_hexaglide_design(yaml(text));
  expect_same_section(gr.stiffness.section, g.stiffness.section, "hexaglide");
  EXPECT_EQ(hexaglide_machine_file(gr), text);

  // The generic form, leg by leg: link.section, crank_section, parallelogram_width and _axis.
  const std::vector<std::pair<std::string, LegChainDesign>> generic = {
      {"tripod", tripod_3prs_design(t)},
      {"delta", delta_design(d)},
      {"linear", linear_delta_design(l)}};
  for (const auto& [name, design] : generic) {
    text = leg_chain_machine_file(design);
    const LegChainDesign back = read_leg_chain_design(yaml(text));
    expect_same_leg_chain(back, design, name);
    for (std::size_t i = 0; i < design.legs.size(); ++i) {
      const LegChainLeg& w = design.legs[i];
      const LegChainLeg& r = back.legs[i];
      expect_same_section(r.link_section, w.link_section, name + " link");
      expect_same_section(r.crank_section, w.crank_section, name + " crank");
      EXPECT_EQ(r.parallelogram_width, w.parallelogram_width) << name;
    }
    EXPECT_EQ(leg_chain_machine_file(back), text) << name;
    // The machines agree: the same compliance at a pose.
    const LegChainMachine a(design), b(back);
    const Pose pose = name == "tripod"  ? Pose{{0, 0, 1.2}, {0.2, -0.1, 0}}
                      : name == "delta" ? Pose{{0.05, -0.1, -1.0}, {0, 0, 0}}
                                        : Pose{{0.02, 0.01, 0.2}, {0, 0, 0}};
    PoseMetrics ma, mb;
    const auto da = a.make_data(), db = b.make_data();
    a.analyze(*da, pose, Wrench::Zero(), ma);
    b.analyze(*db, pose, Wrench::Zero(), mb);
    ASSERT_TRUE(a.link_compliance_model()) << name;
    EXPECT_EQ(da->matrices.compliance, db->matrices.compliance) << name;
  }
  text = leg_chain_machine_file(linear_delta_design(l));
  EXPECT_NE(text.find("parallelogram_width: 0.06, parallelogram_axis: ["), std::string::npos)
      << text;
  text = leg_chain_machine_file(delta_design(d));
  EXPECT_NE(text.find("crank_section: {E: 70000000000, G: 26000000000"), std::string::npos) << text;
}

TEST(LegChainMachineFileFields, LinkSectionErrorsAreLocated) {
  const std::string head =
      "model: tripod_3prs\nbase_radius: 0.3\nplatform_radius: 0.15\nstrut: 0.55\nstroke: [0, "
      "0.95]\n";
  EXPECT_EQ(error_of(head + "struts: {section: {E: 2.1e11, G: 8.1e10, outer_diameter: 0.08}}\n"),
            "no error");
  EXPECT_EQ(error_of(head + "struts: {E: 2.1e11, section: {E: 2.1e11, G: 8.1e10, "
                            "outer_diameter: 0.08}}\n"),
            "m.yaml:6:13: struts.E: either a section (its E and A give the axial stiffness) or E "
            "and area (or axial_stiffness), not both");
  EXPECT_EQ(error_of(head + "struts: {section: {E: 2.1e11, G: 8.1e10, A: 2e-3, Iy: 1e-6}}\n"),
            "m.yaml:6:19: struts.section: missing required key 'Iz'");
  EXPECT_EQ(error_of(head + "struts: {section: {E: 2.1e11, outer_diameter: 0.08}}\n"),
            "m.yaml:6:19: struts.section: missing required key 'G'");
  EXPECT_EQ(error_of(head + "struts: {section: {E: 2.1e11, G: 8.1e10}}\n"),
            "m.yaml:6:19: struts.section: a section needs outer_diameter (and inner_diameter) of "
            "a tube, or A, Iy, Iz and J");
  EXPECT_EQ(error_of(head + "struts: {section: {E: 2.1e11, G: 8.1e10, outer_diameter: 0.08, "
                            "J: 1e-6}}\n"),
            "m.yaml:6:67: struts.section.J: either outer_diameter (and inner_diameter) of a tube "
            "or A, Iy, Iz and J, not both");
  EXPECT_EQ(error_of(head + "struts: {section: {E: 2.1e11, G: 8.1e10, inner_diameter: 0.06}}\n"),
            "m.yaml:6:19: struts.section: missing required key 'outer_diameter'");
  EXPECT_EQ(error_of(head + "struts: {section: {E: 2.1e11, G: 8.1e10, outer_diameter: 0.06, "
                            "inner_diameter: 0.06}}\n"),
            "m.yaml:6:80: struts.section.inner_diameter: expected a number < outer_diameter (m), "
            "found '0.06'");
  EXPECT_EQ(error_of(head + "struts: {section: {E: 2.1e11, G: -8.1e10, outer_diameter: 0.08}}\n"),
            "m.yaml:6:34: struts.section.G: expected a number > 0, found '-8.1e10'");
  EXPECT_EQ(error_of(head + "struts: {section: {E: 2.1e11, G: 8.1e10, outer_diameter: 0.08, "
                            "D: 1}}\n"),
            "m.yaml:6:64: struts.section.D: unknown key 'D'; allowed keys here: E, G, "
            "outer_diameter, inner_diameter, A, Iy, Iz, J");
  const std::string delta =
      "model: delta\nbase_radius: 0.164\nplatform_radius: 0.044\nupper_arm: 0.524\nrod: 1.244\n"
      "drive_range_deg: [-60, 100]\n";
  EXPECT_EQ(error_of(delta + "rods: {E: 7.0e10, area: 5.0e-5, parallelogram_width: 0}\n"),
            "m.yaml:7:54: rods.parallelogram_width: expected a number > 0, found '0'");
  EXPECT_EQ(error_of(delta + "rods: {E: 7.0e10, area: 5.0e-5}\ncrank_section: {E: 7e10}\n"),
            "m.yaml:8:16: crank_section: missing required key 'G'");
  // The generic form: crank_section only on RUS legs, a pair's axis non-zero.
  const std::string leg =
      "  - kind: PUS\n    base_point: [0.4, 0, 0]\n    axis: [0, 0, 1]\n    link_length: 0.5\n"
      "    platform_point: [0.06, 0.1, 0]\n    range: [-0.5, 1.0]\n    branch: -1\n"
      "    link: {E: 7.0e10, area: 3.0e-5, rods: 2}\n";
  const std::string generic = "model: leg_chain\nmobility: schoenflies\nlegs:\n" + leg + leg + leg;
  EXPECT_EQ(
      error_of(generic + leg + "    crank_section: {E: 7e10, G: 2.6e10, outer_diameter: 0.05}\n"),
      "m.yaml:36:5: legs[3].crank_section: unknown key 'crank_section'; allowed keys here: "
      "kind, base_point, platform_point, range, link, joints, actuator_stiffness, drive, "
      "axis, link_length, branch");
  std::string zero_axis = leg;
  zero_axis.replace(zero_axis.find("rods: 2}"), 8,
                    "rods: 2, parallelogram_width: 0.05, parallelogram_axis: [0, 0, 0]}");
  EXPECT_EQ(error_of(generic + zero_axis),
            "m.yaml:35:93: legs[3].link.parallelogram_axis: expected a non-zero vector, found a "
            "list of 3");
}

// The figures of studies/library/tripod-z3.md: the Sprint Z3-like head with 80/60 mm steel tube
// struts against the axial model of the same E*A, at the task centre and over the task.
TEST(LegChainMachineFileFields, TripodZ3StudyFiguresHold) {
  const std::string dir = kSource + "/studies/library/tripod-z3/";
  const CsvTable task = read_csv_file(dir + "task.csv");
  ASSERT_EQ(task.rows.size(), 80u);
  const Wrench w = (Wrench() << 2000, 0, -3000, 0, 0, 0).finished();
  struct Figures {
    const char* file;
    double centre, task_min;  // N/um, as the README gives them
    double tolerance;
  };
  for (const Figures& f :
       {Figures{"z3-axial.yaml", 134.2, 39.8, 0.05}, Figures{"z3-tube.yaml", 17.5, 8.45, 0.005}}) {
    const auto root = YamlValue::load_file(dir + f.file);
    const LegChainMachine m(tripod_3prs_design(read_tripod_3prs_design(root)));
    EXPECT_EQ(m.link_compliance_model(), std::string(f.file) == "z3-tube.yaml");
    auto data = m.make_data();
    PoseMetrics metrics;
    m.analyze(*data, Pose{{0, 0, 1.2}, {0, 0, 0}}, w, metrics);
    EXPECT_NEAR(metrics.stiffness_min / 1e6, f.centre, 0.05) << f.file;
    double worst = std::numeric_limits<double>::infinity();
    for (const CsvRow& row : task.rows) {
      Eigen::Vector3d p, a;
      for (int k = 0; k < 3; ++k) {
        p(k) = task.number(row, k);
        a(k) = task.number(row, 3 + k);
      }
      m.analyze(*data, Pose{p, deg_to_rad(a)}, w, metrics);
      EXPECT_TRUE(metrics.reachable) << f.file << " line " << row.line;
      worst = std::min(worst, metrics.stiffness_min);
    }
    EXPECT_NEAR(worst / 1e6, f.task_min, f.tolerance) << f.file;
  }
}

TEST(LegChainMachineFileFields, KeysReadByHandKeepTheirMessages) {
  const std::string delta =
      "model: delta\nbase_radius: 0.164\nplatform_radius: 0.044\nupper_arm: 0.524\nrod: 1.244\n"
      "drive_range_deg: [-60, 100]\n";
  EXPECT_EQ(error_of(delta + "rods: {E: 7.0e10, area: 5.0e-5}\n"), "no error");
  EXPECT_EQ(error_of(delta + "rods: {E: 7.0e10, axial_stiffness: 1e6}\n"),
            "m.yaml:7:36: rods.axial_stiffness: either axial_stiffness or E and area, not both");
  EXPECT_EQ(error_of(delta + "rods: {E: 7.0e10}\n"),
            "m.yaml:7:7: rods: missing required key 'area'");
  EXPECT_EQ(error_of(delta + "rods: {}\n"),
            "m.yaml:7:7: rods: missing the link stiffness: give axial_stiffness (N/m), or E (Pa) "
            "and area (m^2)");
  EXPECT_EQ(error_of(delta + "rods: {E: 7.0e10, area: 5.0e-5}\nbranch: sideways\n"),
            "m.yaml:8:9: branch: expected elbow_out or elbow_in, found 'sideways'");
  EXPECT_EQ(error_of("model: delta\nbase_radius: 0.164\nplatform_radius: 0.044\nupper_arm: 0.524\n"
                     "rod: 1.244\ndrive_range_deg: [-200, 100]\nrods: {E: 7.0e10, area: 5.0e-5}\n"),
            "m.yaml:6:18: drive_range_deg: expected a range within [-180, 180] deg, found [-200, "
            "100]");
  EXPECT_EQ(
      error_of(delta + "rods: {E: 7.0e10, area: 5.0e-5}\ncolour: red\n"),
      "m.yaml:8:1: colour: unknown key 'colour'; allowed keys here: model, name, "
      "description, base_radius, platform_radius, upper_arm, rod, drive_range_deg, branch, "
      "rods, crank_section, drive_stiffness, drive, joints, tool, characteristic_length, "
      "actuator_error_deg, masses, gravity, link_diameter, crank_diameter, min_clearance, bodies");
  const std::string glide =
      "model: hexaglide\nguides: {y: [0.46, 0.46, 0.39, -0.55, -0.55, 0.39]}\nstrut: 0.8\n"
      "stroke: [-1.2, 1.2]\nstruts: {E: 2.1e11, area: 3.0e-4}\n";
  EXPECT_EQ(
      error_of(glide + "platform: {radius: 0.25, pair_separation_deg: 20, rotation_deg: 90}\n"),
      "no error");
  EXPECT_EQ(error_of(glide), "m.yaml:1:1: missing required key 'platform' (or 'platform_joints')");
  EXPECT_EQ(
      error_of(glide + "platform: {radius: 0.25, pair_separation_deg: 20}\nplatform_joints: "
                       "[[0, 0, 0], [0, 0, 0], [0, 0, 0], [0, 0, 0], [0, 0, 0], [0, 0, 0]]\n"),
      "m.yaml:7:18: platform_joints: either 'platform' or 'platform_joints', not both");
  const std::string leg =
      "  - kind: PUS\n    base_point: [0.4, 0, 0]\n    axis: [0, 0, 1]\n    link_length: 0.5\n"
      "    platform_point: [0.06, 0.1, 0]\n    range: [-0.5, 1.0]\n    branch: -1\n"
      "    link: {E: 7.0e10, area: 3.0e-5, rods: 2}\n";
  const std::string head = "model: leg_chain\nmobility: schoenflies\n";
  EXPECT_EQ(
      error_of(head + "legs:\n" + leg + leg + leg +
               "  - kind: PUS\n    base_point: [0.4, 0, 0]\n    axis: [0, 0, 1]\n"
               "    link_length: 0.5\n    platform_point: [0.06, 0.1, 0]\n"
               "    range: [-0.5, 1.0]\n    branch: 0\n    link: {E: 7.0e10, area: 3.0e-5}\n"),
      "m.yaml:34:13: legs[3].branch: expected 1 or -1, found '0'");
  EXPECT_EQ(error_of(head + "actuator_error_deg: 0.01\nlegs:\n" + leg + leg + leg + leg),
            "m.yaml:3:21: actuator_error_deg: expected actuator_error in m (the legs are "
            "prismatic), found '0.01'");
  EXPECT_EQ(error_of("model: leg_chain\nmobility: six_dof\nrotation_axis: [0, 0, 1]\nlegs: []\n"),
            "m.yaml:3:16: rotation_axis: expected no rotation_axis (it is for mobility: "
            "schoenflies), found a list of 3");
  EXPECT_EQ(error_of(head + "legs:\n" + leg + leg + leg + leg + "    crank_length: 0.3\n"),
            "m.yaml:36:5: legs[3].crank_length: unknown key 'crank_length'; allowed keys here: "
            "kind, base_point, platform_point, range, link, joints, actuator_stiffness, drive, "
            "axis, link_length, branch");
}

// The writers against designs with every key away from its default: the file reads back to the
// same design (lengths exactly, angles to the 12 significant digits the writers give degrees), and
// a family design's file loads to the machine the family builds.
namespace readback {

constexpr double kInf = std::numeric_limits<double>::infinity();

YamlValue yaml(const std::string& text, const std::string& name) {
  return YamlValue::load_string(text, name);
}

// The file gives either axial_stiffness or E and area (the other is not read back).
void expect_stiffness(const LinkStiffness& read, const LinkStiffness& written) {
  EXPECT_EQ(read.axial_stiffness, written.axial_stiffness);
  if (written.axial_stiffness <= 0.0) {
    EXPECT_EQ(read.E, written.E);
    EXPECT_EQ(read.area, written.area);
  }
  EXPECT_EQ(read.actuator_stiffness, written.actuator_stiffness);
}

DeltaDesign sample_delta() {
  DeltaDesign d;
  d.base_radius = 0.2;
  d.platform_radius = 0.05;
  d.upper_arm = 0.4;
  d.rod = 0.9;
  d.theta_min = deg_to_rad(-40.0);
  d.theta_max = deg_to_rad(90.0);
  d.branch = -1;
  d.stiffness = {0.0, 7.1e10, 6.0e-5, 5.0e4};
  d.elbow_max_angle = deg_to_rad(35.0);
  d.platform_max_angle = deg_to_rad(40.0);
  d.tcp = {0.0, 0.01, -0.05};
  d.characteristic_length = 0.3;
  d.actuator_error = deg_to_rad(2e-3);
  return d;
}

LinearDeltaDesign sample_linear_delta() {
  LinearDeltaDesign d;
  d.guide_radius = 0.3;
  d.platform_radius = 0.05;
  d.rod = 0.7;
  d.inclination = deg_to_rad(12.0);
  d.q_min = 0.05;
  d.q_max = 0.8;
  d.stiffness = {2.0e7, 0.0, 0.0, 1.5e8};   // axial form
  d.carriage_max_angle = deg_to_rad(60.0);  // platform joints unlimited
  d.tcp = {0.01, 0.0, -0.05};
  d.actuator_error = 2e-5;
  return d;
}

HexaglideDesign sample_hexaglide() {
  HexaglideDesign d;  // the default platform joints and guides
  d.guide_z = {0.01, -0.01, 0.02, -0.02, 0.0, 0.03};
  d.inclination = deg_to_rad(5.0);
  d.strut = 0.9;
  d.q_min = -1.0;
  d.q_max = 1.3;
  d.stiffness = {0.0, 2.0e11, 3.5e-4, 1.0e8};
  d.platform_max_angle = deg_to_rad(50.0);
  d.tcp = {0.0, 0.0, -0.12};
  d.characteristic_length = 0.25;
  d.actuator_error = 3e-5;
  d.home_height = 0.65;
  return d;
}

Tripod3PrsDesign sample_tripod() {
  Tripod3PrsDesign d;
  d.base_radius = 0.32;
  d.platform_radius = 0.14;
  d.strut = 0.6;
  d.q_min = 0.05;
  d.q_max = 0.9;
  d.tool_length = 0.25;
  d.revolute_max_angle = deg_to_rad(45.0);
  d.platform_max_angle = deg_to_rad(60.0);
  d.stiffness = {3.0e8, 0.0, 0.0, 1.0e8};
  d.characteristic_length = 0.4;
  d.actuator_error = 1.5e-5;
  return d;
}

TEST(LegChainWriter, DeltaReadsBackToTheSameDesign) {
  const DeltaDesign d = sample_delta();
  const std::string text = delta_machine_file(d);
  EXPECT_EQ(text.rfind("model: delta\n", 0), 0u) << text;
  const DeltaDesign r = read_delta_design(yaml(text, "delta.yaml"));
  EXPECT_EQ(r.base_radius, d.base_radius);
  EXPECT_EQ(r.platform_radius, d.platform_radius);
  EXPECT_EQ(r.upper_arm, d.upper_arm);
  EXPECT_EQ(r.rod, d.rod);
  expect_angle(r.theta_min, d.theta_min, "theta_min");
  expect_angle(r.theta_max, d.theta_max, "theta_max");
  EXPECT_EQ(r.branch, -1);
  expect_stiffness(r.stiffness, d.stiffness);
  expect_angle(r.elbow_max_angle, d.elbow_max_angle, "elbow_max_angle");
  expect_angle(r.platform_max_angle, d.platform_max_angle, "platform_max_angle");
  EXPECT_EQ(r.tcp, d.tcp);
  EXPECT_EQ(r.characteristic_length, d.characteristic_length);
  expect_angle(r.actuator_error, d.actuator_error, "actuator_error");
  // Writing the design read gives the same text: a fixed point.
  EXPECT_EQ(delta_machine_file(r), text);
}

TEST(LegChainWriter, LinearDeltaReadsBackToTheSameDesign) {
  const LinearDeltaDesign d = sample_linear_delta();
  const std::string text = linear_delta_machine_file(d);
  EXPECT_EQ(text.rfind("model: linear_delta\n", 0), 0u) << text;
  const LinearDeltaDesign r = read_linear_delta_design(yaml(text, "linear_delta.yaml"));
  EXPECT_EQ(r.guide_radius, d.guide_radius);
  EXPECT_EQ(r.platform_radius, d.platform_radius);
  EXPECT_EQ(r.rod, d.rod);
  expect_angle(r.inclination, d.inclination, "inclination");
  EXPECT_EQ(r.q_min, d.q_min);
  EXPECT_EQ(r.q_max, d.q_max);
  expect_stiffness(r.stiffness, d.stiffness);
  expect_angle(r.carriage_max_angle, d.carriage_max_angle, "carriage_max_angle");
  EXPECT_EQ(r.platform_max_angle, kInf);
  EXPECT_EQ(r.tcp, d.tcp);
  EXPECT_FALSE(r.characteristic_length.has_value());
  EXPECT_EQ(r.actuator_error, d.actuator_error);
  EXPECT_EQ(linear_delta_machine_file(r), text);
}

TEST(LegChainWriter, HexaglideReadsBackToTheSameDesign) {
  const HexaglideDesign d = sample_hexaglide();
  const std::string text = hexaglide_machine_file(d);
  EXPECT_EQ(text.rfind("model: hexaglide\n", 0), 0u) << text;
  const HexaglideDesign r = read_hexaglide_design(yaml(text, "hexaglide.yaml"));
  EXPECT_EQ(r.guide_y, d.guide_y);
  EXPECT_EQ(r.guide_z, d.guide_z);
  expect_angle(r.inclination, d.inclination, "inclination");
  EXPECT_EQ(r.strut, d.strut);
  EXPECT_EQ(r.platform_joints, d.platform_joints);
  EXPECT_EQ(r.q_min, d.q_min);
  EXPECT_EQ(r.q_max, d.q_max);
  expect_stiffness(r.stiffness, d.stiffness);
  EXPECT_EQ(r.carriage_max_angle, kInf);
  expect_angle(r.platform_max_angle, d.platform_max_angle, "platform_max_angle");
  EXPECT_EQ(r.tcp, d.tcp);
  EXPECT_EQ(r.characteristic_length, d.characteristic_length);
  EXPECT_EQ(r.actuator_error, d.actuator_error);
  EXPECT_EQ(r.home_height, d.home_height);
  EXPECT_EQ(hexaglide_machine_file(r), text);
}

TEST(LegChainWriter, Tripod3PrsReadsBackToTheSameDesign) {
  const Tripod3PrsDesign d = sample_tripod();
  const std::string text = tripod_3prs_machine_file(d);
  EXPECT_EQ(text.rfind("model: tripod_3prs\n", 0), 0u) << text;
  const Tripod3PrsDesign r = read_tripod_3prs_design(yaml(text, "tripod.yaml"));
  EXPECT_EQ(r.base_radius, d.base_radius);
  EXPECT_EQ(r.platform_radius, d.platform_radius);
  EXPECT_EQ(r.strut, d.strut);
  EXPECT_EQ(r.q_min, d.q_min);
  EXPECT_EQ(r.q_max, d.q_max);
  EXPECT_EQ(r.tool_length, d.tool_length);
  expect_angle(r.revolute_max_angle, d.revolute_max_angle, "revolute_max_angle");
  expect_angle(r.platform_max_angle, d.platform_max_angle, "platform_max_angle");
  expect_stiffness(r.stiffness, d.stiffness);
  EXPECT_EQ(r.characteristic_length, d.characteristic_length);
  EXPECT_EQ(r.actuator_error, d.actuator_error);
  EXPECT_EQ(tripod_3prs_machine_file(r), text);
}

// A family writes its designs with the writer it was made with.
TEST(LegChainWriter, DeltaFamilyWritesItsDesignsWithItsWriter) {
  EXPECT_EQ(delta_family(sample_delta(), delta_machine_file)
                .machine_file({0.2, 0.05, 0.4, 0.9, deg_to_rad(-40), deg_to_rad(90), 0.0}),
            [] {
              DeltaDesign d = sample_delta();
              d.base_radius = 0.2;
              d.platform_radius = 0.05;
              d.upper_arm = 0.4;
              d.rod = 0.9;
              d.theta_min = deg_to_rad(-40);
              d.theta_max = deg_to_rad(90);
              return delta_machine_file(d);
            }());
}

// The written machine file of a family
// design, read by the machine-file reader, gives the machine the family builds.
TEST(LegChainWriter, FamilyDesignsLoadBackToTheSameMachine) {
  const std::vector<std::pair<DesignFamily, std::vector<double>>> cases = {
      {delta_family(DeltaDesign{}, delta_machine_file),
       {0.2, 0.05, 0.4, 0.9, deg_to_rad(-40), deg_to_rad(90), 0.0}},
      {linear_delta_family(LinearDeltaDesign{}, linear_delta_machine_file),
       {0.4, 0.05, 0.8, 0.7, deg_to_rad(12), 0.0}},
      {hexaglide_family(HexaglideDesign{}, hexaglide_machine_file),
       {0.2, deg_to_rad(25), 0.2, 0.9, 1.6, deg_to_rad(5), 0.1}},
      {tripod_3prs_family(Tripod3PrsDesign{}, tripod_3prs_machine_file),
       {0.32, 0.14, 0.6, 0.9, 0.0}}};
  const std::vector<Pose> poses = {
      Pose{{0.02, 0.03, -0.75}, {0, 0, 0}}, Pose{{0.02, 0.03, -0.55}, {0, 0, 0}},
      Pose{{0.05, -0.02, 0.45}, {0.03, 0.02, -0.01}}, Pose{{0.0, 0.0, 1.0}, {0.2, -0.1, 0.0}}};
  for (std::size_t c = 0; c < cases.size(); ++c) {
    const auto& [family, p] = cases[c];
    const std::string text = family.machine_file(p);
    const YamlValue root = YamlValue::load_string(text, family.model + ".yaml");
    const std::unique_ptr<Machine> loaded = load_machine(root);
    ASSERT_NE(loaded, nullptr) << text;
    const std::unique_ptr<Machine> built = family.build(p);
    EXPECT_EQ(loaded->model(), family.model);
    EXPECT_NEAR(*loaded->envelope_volume() / *built->envelope_volume(), 1.0, 1e-12);
    PoseMetrics a, b;
    loaded->analyze(*loaded->make_data(), poses[c], Wrench::Constant(50.0), a);
    built->analyze(*built->make_data(), poses[c], Wrench::Constant(50.0), b);
    ASSERT_FALSE(b.singular) << family.model;
    EXPECT_EQ(a.reachable, b.reachable) << family.model;
    EXPECT_NEAR((a.q - b.q).norm(), 0.0, 1e-9) << family.model;
    EXPECT_NEAR((a.tau - b.tau).norm() / b.tau.norm(), 0.0, 1e-9) << family.model;
    EXPECT_NEAR(a.stiffness_min / b.stiffness_min, 1.0, 1e-9) << family.model;
  }
}

}  // namespace readback

}  // namespace
}  // namespace pkmopt
