#include "io/machine_file_leg_chain.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

#include "io/csv.hpp"
#include "io/input_error.hpp"
#include "models/hexapod.hpp"

namespace pkmopt {
namespace {

double angle_limit(const YamlValue& value) {
  const double v = value.as_double();
  if (!(v > 0.0 && v <= 180.0)) value.fail("an angle in degrees in (0, 180]", value.describe());
  return deg_to_rad(v);
}

// A guide inclination in degrees, (-90, 90), returned in rad.
double read_inclination(const YamlValue& value) {
  const double a = value.as_double();
  if (!(a > -90.0 && a < 90.0)) value.fail("an angle in degrees in (-90, 90)", value.describe());
  return deg_to_rad(a);
}

Eigen::Vector3d read_vector3(const YamlValue& value) {
  const auto v = value.as_doubles(3);
  return {v[0], v[1], v[2]};
}

// [low, high] with low < high, each within [lo_bound, hi_bound]; scale converts to the code's unit.
std::pair<double, double> read_range(const YamlValue& value, double lo_bound, double hi_bound,
                                     const char* unit) {
  const auto v = value.as_doubles(2);
  if (!(v[0] < v[1])) {
    value.fail(fmt::format("[low, high] with low < high ({})", unit), value.describe());
  }
  if (!(v[0] >= lo_bound && v[1] <= hi_bound)) {
    value.fail(fmt::format("a range within [{}, {}] {}", format_number(lo_bound),
                           format_number(hi_bound), unit),
               fmt::format("[{}, {}]", format_number(v[0]), format_number(v[1])));
  }
  return {v[0], v[1]};
}

// {E, area} or {axial_stiffness}, into k (actuator stiffness untouched).
void read_link_stiffness(const YamlValue& section, LinkStiffness& k) {
  section.check_keys({"E", "area", "axial_stiffness"});
  const bool has_axial = section.has("axial_stiffness");
  const bool has_e = section.has("E");
  const bool has_area = section.has("area");
  if (has_axial && (has_e || has_area)) {
    section.required("axial_stiffness").fail("either axial_stiffness or E and area, not both");
  }
  if (has_axial) {
    k.axial_stiffness = section.required("axial_stiffness").as_positive();
    k.E = 0.0;
    k.area = 0.0;
  } else if (has_e || has_area) {
    k.axial_stiffness = 0.0;
    k.E = section.required("E").as_positive();
    k.area = section.required("area").as_positive();
  } else {
    section.fail(
        "missing the link stiffness: give axial_stiffness (N/m), or E (Pa) and area (m^2)");
  }
}

// The links' stiffness under `links_key` and the actuator stiffness under the optional
// `drive_key` (N/m, or N*m/rad for cranks; absent: a rigid drive).
void read_links_and_drive(const YamlValue& root, const char* links_key, const char* drive_key,
                          LinkStiffness& k) {
  read_link_stiffness(root.required(links_key), k);
  k.actuator_stiffness = 0.0;
  if (auto v = root.optional(drive_key)) k.actuator_stiffness = v->as_positive();
}

// `stroke: [min, max]` (m) into the actuator range.
void read_stroke(const YamlValue& root, double& q_min, double& q_max) {
  const double inf = std::numeric_limits<double>::infinity();
  const auto stroke = read_range(root.required("stroke"), -inf, inf, "m");
  q_min = stroke.first;
  q_max = stroke.second;
}

void read_common(const YamlValue& root, Eigen::Vector3d& tcp,
                 std::optional<double>& characteristic_length) {
  if (auto tool = root.optional("tool")) {
    tool->check_keys({"tcp"});
    if (auto v = tool->optional("tcp")) tcp = read_vector3(*v);
  }
  if (auto v = root.optional("characteristic_length")) characteristic_length = v->as_positive();
}

void read_joint_limits(const YamlValue& root, const char* base_key, double& base_limit,
                       double& platform_limit) {
  if (auto joints = root.optional("joints")) {
    joints->check_keys({base_key, "platform_max_angle_deg"});
    if (auto v = joints->optional(base_key)) base_limit = angle_limit(*v);
    if (auto v = joints->optional("platform_max_angle_deg")) platform_limit = angle_limit(*v);
  }
}

// Runs the machine's own validation and turns its message into an InputError at `root`.
template <typename Design, typename Make>
void validate(const YamlValue& root, const Design& design, Make make) {
  try {
    (void)make(design);
  } catch (const std::invalid_argument& e) {
    root.fail(e.what());
  }
}

}  // namespace

DeltaDesign read_delta_design(const YamlValue& root) {
  root.check_keys({"model", "name", "description", "base_radius", "platform_radius", "upper_arm",
                   "rod", "drive_range_deg", "branch", "rods", "drive_stiffness", "joints", "tool",
                   "characteristic_length", "actuator_error_deg"});
  DeltaDesign d;
  d.base_radius = root.required("base_radius").as_positive();
  d.platform_radius = root.required("platform_radius").as_non_negative();
  d.upper_arm = root.required("upper_arm").as_positive();
  d.rod = root.required("rod").as_positive();
  const auto range = read_range(root.required("drive_range_deg"), -180.0, 180.0, "deg");
  d.theta_min = deg_to_rad(range.first);
  d.theta_max = deg_to_rad(range.second);
  if (auto v = root.optional("branch")) {
    const std::string b = v->as_string();
    if (b == "elbow_out") {
      d.branch = 1;
    } else if (b == "elbow_in") {
      d.branch = -1;
    } else {
      v->fail("elbow_out or elbow_in", quote_found(b));
    }
  }
  read_links_and_drive(root, "rods", "drive_stiffness", d.stiffness);
  read_joint_limits(root, "elbow_max_angle_deg", d.elbow_max_angle, d.platform_max_angle);
  read_common(root, d.tcp, d.characteristic_length);
  if (auto v = root.optional("actuator_error_deg"))
    d.actuator_error = deg_to_rad(v->as_non_negative());
  validate(root, d, make_delta);
  return d;
}

LinearDeltaDesign read_linear_delta_design(const YamlValue& root) {
  root.check_keys({"model", "name", "description", "guide_radius", "platform_radius", "rod",
                   "inclination_deg", "stroke", "rods", "carriage_stiffness", "joints", "tool",
                   "characteristic_length", "actuator_error"});
  LinearDeltaDesign d;
  d.guide_radius = root.required("guide_radius").as_positive();
  d.platform_radius = root.required("platform_radius").as_non_negative();
  d.rod = root.required("rod").as_positive();
  if (auto v = root.optional("inclination_deg")) d.inclination = read_inclination(*v);
  read_stroke(root, d.q_min, d.q_max);
  read_links_and_drive(root, "rods", "carriage_stiffness", d.stiffness);
  read_joint_limits(root, "carriage_max_angle_deg", d.carriage_max_angle, d.platform_max_angle);
  read_common(root, d.tcp, d.characteristic_length);
  if (auto v = root.optional("actuator_error")) d.actuator_error = v->as_non_negative();
  validate(root, d, make_linear_delta);
  return d;
}

HexaglideDesign read_hexaglide_design(const YamlValue& root) {
  root.check_keys({"model", "name", "description", "guides", "strut", "platform", "platform_joints",
                   "stroke", "struts", "carriage_stiffness", "joints", "tool",
                   "characteristic_length", "actuator_error", "home_height"});
  HexaglideDesign d;
  const YamlValue guides = root.required("guides");
  guides.check_keys({"y", "z", "inclination_deg"});
  const auto ys = guides.required("y").as_doubles(6);
  for (int i = 0; i < 6; ++i)
    d.guide_y[static_cast<std::size_t>(i)] = ys[static_cast<std::size_t>(i)];
  if (auto v = guides.optional("z")) {
    const auto zs = v->as_doubles(6);
    for (int i = 0; i < 6; ++i)
      d.guide_z[static_cast<std::size_t>(i)] = zs[static_cast<std::size_t>(i)];
  }
  if (auto v = guides.optional("inclination_deg")) d.inclination = read_inclination(*v);
  d.strut = root.required("strut").as_positive();
  const bool has_form = root.has("platform");
  const bool has_list = root.has("platform_joints");
  if (has_form && has_list) {
    root.required("platform_joints").fail("either 'platform' or 'platform_joints', not both");
  }
  if (!has_form && !has_list) root.fail("missing required key 'platform' (or 'platform_joints')");
  if (has_form) {
    const YamlValue p = root.required("platform");
    p.check_keys({"radius", "pair_separation_deg", "rotation_deg"});
    const double radius = p.required("radius").as_positive();
    const YamlValue sep_value = p.required("pair_separation_deg");
    const double sep = sep_value.as_double();
    if (!(sep >= 0.0 && sep <= 120.0)) {
      sep_value.fail("an angle in degrees in [0, 120]", sep_value.describe());
    }
    double rotation = 0.0;
    if (auto v = p.optional("rotation_deg")) rotation = deg_to_rad(v->as_double());
    d.platform_joints = Eigen::AngleAxisd(rotation, Eigen::Vector3d::UnitZ()).toRotationMatrix() *
                        semi_regular_platform_joints(radius, deg_to_rad(sep));
  } else {
    const auto rows = root.required("platform_joints").elements(6);
    for (int i = 0; i < 6; ++i)
      d.platform_joints.col(i) = read_vector3(rows[static_cast<std::size_t>(i)]);
  }
  read_stroke(root, d.q_min, d.q_max);
  read_links_and_drive(root, "struts", "carriage_stiffness", d.stiffness);
  read_joint_limits(root, "carriage_max_angle_deg", d.carriage_max_angle, d.platform_max_angle);
  read_common(root, d.tcp, d.characteristic_length);
  if (auto v = root.optional("actuator_error")) d.actuator_error = v->as_non_negative();
  if (auto v = root.optional("home_height")) d.home_height = v->as_double();
  validate(root, d, make_hexaglide);
  return d;
}

Tripod3PrsDesign read_tripod_3prs_design(const YamlValue& root) {
  root.check_keys({"model", "name", "description", "base_radius", "platform_radius", "strut",
                   "stroke", "tool_length", "struts", "slide_stiffness", "joints",
                   "characteristic_length", "actuator_error"});
  Tripod3PrsDesign d;
  d.base_radius = root.required("base_radius").as_positive();
  d.platform_radius = root.required("platform_radius").as_positive();
  d.strut = root.required("strut").as_positive();
  read_stroke(root, d.q_min, d.q_max);
  if (auto v = root.optional("tool_length")) d.tool_length = v->as_double();
  read_links_and_drive(root, "struts", "slide_stiffness", d.stiffness);
  read_joint_limits(root, "revolute_max_angle_deg", d.revolute_max_angle, d.platform_max_angle);
  if (auto v = root.optional("characteristic_length")) d.characteristic_length = v->as_positive();
  if (auto v = root.optional("actuator_error")) d.actuator_error = v->as_non_negative();
  validate(root, d, make_tripod_3prs);
  return d;
}

namespace {

LegKind read_leg_kind(const YamlValue& value) {
  const std::string kind = value.as_string();
  if (kind == "UPS") return LegKind::kUPS;
  if (kind == "PUS" || kind == "PUU") return LegKind::kPUS;
  if (kind == "RUS") return LegKind::kRUS;
  value.fail("UPS, PUS, PUU or RUS", quote_found(kind));
}

LegChainLeg read_leg(const YamlValue& node, PlatformMobility mobility, bool& revolute) {
  node.expect_map();
  LegChainLeg leg;
  leg.kind = read_leg_kind(node.required("kind"));
  revolute = leg.kind == LegKind::kRUS;
  std::vector<std::string> keys = {"kind", "base_point", "platform_point",    "range",
                                   "link", "joints",     "actuator_stiffness"};
  if (leg.kind != LegKind::kUPS) {
    for (const char* k : {"axis", "link_length", "branch"}) keys.emplace_back(k);
  }
  if (leg.kind == LegKind::kRUS) {
    for (const char* k : {"crank_zero", "crank_length"}) keys.emplace_back(k);
  }
  if (mobility == PlatformMobility::kPlanarLegs) keys.emplace_back("plane_normal");
  node.check_keys(keys);
  leg.base_point = read_vector3(node.required("base_point"));
  leg.platform_point = read_vector3(node.required("platform_point"));
  const double inf = std::numeric_limits<double>::infinity();
  if (leg.kind == LegKind::kRUS) {
    const auto range = read_range(node.required("range"), -180.0, 180.0, "deg");
    leg.q_min = deg_to_rad(range.first);
    leg.q_max = deg_to_rad(range.second);
  } else {
    const auto range =
        read_range(node.required("range"), leg.kind == LegKind::kUPS ? 0.0 : -inf, inf, "m");
    if (leg.kind == LegKind::kUPS && !(range.first > 0.0)) {
      node.required("range").fail("leg lengths [min, max] with min > 0 (m)",
                                  node.required("range").describe());
    }
    leg.q_min = range.first;
    leg.q_max = range.second;
  }
  if (leg.kind != LegKind::kUPS) {
    const YamlValue axis = node.required("axis");
    leg.axis = read_vector3(axis);
    if (!(leg.axis.norm() > 1e-12)) axis.fail("a non-zero vector", axis.describe());
    leg.link_length = node.required("link_length").as_positive();
    if (auto v = node.optional("branch")) {
      const long long b = v->as_int();
      if (b != 1 && b != -1) v->fail("1 or -1", v->describe());
      leg.branch = static_cast<int>(b);
    }
  }
  if (leg.kind == LegKind::kRUS) {
    leg.crank_zero = read_vector3(node.required("crank_zero"));
    leg.crank_length = node.required("crank_length").as_positive();
  }
  if (mobility == PlatformMobility::kPlanarLegs) {
    const YamlValue normal = node.required("plane_normal");
    leg.plane_normal = read_vector3(normal);
    if (!(leg.plane_normal.norm() > 1e-12)) normal.fail("a non-zero vector", normal.describe());
  }
  // link: {E, area, rods} or {axial_stiffness}
  const YamlValue link = node.required("link");
  link.check_keys({"E", "area", "axial_stiffness", "rods"});
  LinkStiffness k;
  {
    // read_link_stiffness checks its own keys; give it a view without `rods`.
    const bool has_axial = link.has("axial_stiffness");
    const bool has_e = link.has("E") || link.has("area");
    if (has_axial && has_e) {
      link.required("axial_stiffness").fail("either axial_stiffness or E and area, not both");
    }
    if (has_axial) {
      k.axial_stiffness = link.required("axial_stiffness").as_positive();
      k.E = 0.0;
      k.area = 0.0;
    } else if (has_e) {
      k.E = link.required("E").as_positive();
      k.area = link.required("area").as_positive();
    } else {
      link.fail("missing the link stiffness: give axial_stiffness (N/m), or E (Pa) and area (m^2)");
    }
  }
  leg.axial_stiffness = k.axial_stiffness;
  leg.E = k.E;
  leg.area = k.area;
  if (auto v = link.optional("rods")) {
    const long long rods = v->as_int();
    if (rods < 1 || rods > 16) v->fail("an integer in [1, 16]", v->describe());
    leg.rods = static_cast<int>(rods);
  }
  if (auto v = node.optional("actuator_stiffness")) leg.actuator_stiffness = v->as_positive();
  if (auto joints = node.optional("joints")) {
    joints->check_keys(
        {"base_max_angle_deg", "platform_max_angle_deg", "base_axis", "platform_axis"});
    if (auto v = joints->optional("base_max_angle_deg")) leg.base_max_angle = angle_limit(*v);
    if (auto v = joints->optional("platform_max_angle_deg"))
      leg.platform_max_angle = angle_limit(*v);
    for (const char* key : {"base_axis", "platform_axis"}) {
      if (auto v = joints->optional(key)) {
        const Eigen::Vector3d a = read_vector3(*v);
        if (!(a.norm() > 1e-12)) v->fail("a non-zero vector", v->describe());
        (std::string(key) == "base_axis" ? leg.base_axis : leg.platform_axis) = a;
      }
    }
  }
  return leg;
}

}  // namespace

LegChainDesign read_leg_chain_design(const YamlValue& root) {
  root.check_keys({"model", "name", "description", "mobility", "rotation_axis", "legs", "tool",
                   "characteristic_length", "actuator_error", "actuator_error_deg", "home"});
  LegChainDesign d;
  d.model = "leg_chain";
  const YamlValue mobility = root.required("mobility");
  const std::string m = mobility.as_string();
  int expected_legs = 0;
  if (m == "six_dof") {
    d.mobility = PlatformMobility::kSixDof;
    expected_legs = 6;
  } else if (m == "translational") {
    d.mobility = PlatformMobility::kTranslational;
    expected_legs = 3;
  } else if (m == "schoenflies") {
    d.mobility = PlatformMobility::kSchoenflies;
    expected_legs = 4;
  } else if (m == "planar_legs") {
    d.mobility = PlatformMobility::kPlanarLegs;
    expected_legs = 3;
  } else {
    mobility.fail("six_dof, translational, schoenflies or planar_legs", quote_found(m));
  }
  if (auto v = root.optional("rotation_axis")) {
    if (d.mobility != PlatformMobility::kSchoenflies) {
      v->fail("no rotation_axis (it is for mobility: schoenflies)", v->describe());
    }
    d.rotation_axis = read_vector3(*v);
    if (!(d.rotation_axis.norm() > 1e-12)) v->fail("a non-zero vector", v->describe());
  }
  const auto legs = root.required("legs").elements(expected_legs);
  int revolute = 0;
  for (const YamlValue& node : legs) {
    bool is_revolute = false;
    d.legs.push_back(read_leg(node, d.mobility, is_revolute));
    revolute += is_revolute ? 1 : 0;
  }
  if (revolute != 0 && revolute != expected_legs) {
    root.required("legs").fail(
        "legs that are all RUS or all prismatic (UPS, PUS)",
        std::to_string(revolute) + " RUS legs of " + std::to_string(expected_legs));
  }
  read_common(root, d.tcp, d.characteristic_length);
  if (revolute > 0) {
    if (auto v = root.optional("actuator_error")) {
      v->fail("actuator_error_deg (the legs are revolute)", v->describe());
    }
    d.actuator_error = deg_to_rad(1e-3);
    if (auto v = root.optional("actuator_error_deg"))
      d.actuator_error = deg_to_rad(v->as_non_negative());
  } else {
    if (auto v = root.optional("actuator_error_deg")) {
      v->fail("actuator_error in m (the legs are prismatic)", v->describe());
    }
    if (auto v = root.optional("actuator_error")) d.actuator_error = v->as_non_negative();
  }
  if (auto home = root.optional("home")) {
    home->check_keys({"position", "angles_deg"});
    d.home.position = read_vector3(home->required("position"));
    if (auto v = home->optional("angles_deg")) d.home.angles = deg_to_rad(read_vector3(*v));
  }
  validate(root, d, make_leg_chain_machine);
  return d;
}

std::unique_ptr<Machine> load_leg_chain_machine(const YamlValue& root, const std::string& model) {
  if (model == "delta") return make_delta(read_delta_design(root));
  if (model == "linear_delta") return make_linear_delta(read_linear_delta_design(root));
  if (model == "hexaglide") return make_hexaglide(read_hexaglide_design(root));
  if (model == "tripod_3prs") return make_tripod_3prs(read_tripod_3prs_design(root));
  if (model == "leg_chain") return make_leg_chain_machine(read_leg_chain_design(root));
  return nullptr;
}

const char* leg_chain_model_names() {
  return "delta, linear_delta, hexaglide, tripod_3prs, leg_chain";
}

}  // namespace pkmopt
