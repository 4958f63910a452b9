#include "io/results/pareto_json.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <set>
#include <string_view>

#include "io/format/csv.hpp"
#include "io/format/input_error.hpp"
#include "io/format/number_policy.hpp"

namespace pkmopt {
namespace {

using nlohmann::json;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// ---------------------------------------------------------------------------------------------
// Reading pareto.json

std::string describe(const json& v) {
  switch (v.type()) {
    case json::value_t::null:
      return "null";
    case json::value_t::boolean:
      return v.get<bool>() ? "true" : "false";
    case json::value_t::number_integer:
    case json::value_t::number_unsigned:
    case json::value_t::number_float:
      return "the number " + v.dump();
    case json::value_t::string:
      return "the string " + quote_found(v.get<std::string>());
    case json::value_t::array:
      return fmt::format("an array of {} elements", v.size());
    case json::value_t::object:
      return "an object";
    default:
      return "an unsupported value";
  }
}

class ParetoReader {
 public:
  explicit ParetoReader(std::string file) : file_(std::move(file)) {}

  [[noreturn]] void fail(const std::string& key, std::string_view expected,
                         const std::string& found) const {
    throw InputError(fmt::format("{}: {}: expected {}, found {}", file_, key, expected, found));
  }

  const json& member(const json& object, const std::string& path, const std::string& key,
                     std::string_view expected) const {
    const std::string where = path.empty() ? key : path + "." + key;
    const auto it = object.find(key);
    if (it == object.end()) fail(where, expected, "no such key");
    return *it;
  }

  const json& object(const json& parent, const std::string& path, const std::string& key) const {
    const json& v = member(parent, path, key, "an object");
    if (!v.is_object()) fail(join(path, key), "an object", describe(v));
    return v;
  }

  const json& array(const json& parent, const std::string& path, const std::string& key) const {
    const json& v = member(parent, path, key, "an array");
    if (!v.is_array()) fail(join(path, key), "an array", describe(v));
    return v;
  }

  std::string string(const json& parent, const std::string& path, const std::string& key) const {
    const json& v = member(parent, path, key, "a string");
    if (!v.is_string()) fail(join(path, key), "a string", describe(v));
    return v.get<std::string>();
  }

  /// A number; null becomes NaN when `null_allowed`.
  double number(const json& parent, const std::string& path, const std::string& key,
                bool null_allowed) const {
    const std::string expected = null_allowed ? "a number or null" : "a number";
    const json& v = member(parent, path, key, expected);
    return number_value(v, join(path, key), null_allowed);
  }

  double number_value(const json& v, const std::string& where, bool null_allowed) const {
    if (v.is_null() && null_allowed) return kNaN;
    if (!v.is_number()) fail(where, null_allowed ? "a number or null" : "a number", describe(v));
    const double x = v.get<double>();
    // The input number policy (io/format/number_policy.hpp): plots and tables stay finite.
    if (!sane_input_number(x)) fail(where, std::string(kSaneNumberText), describe(v));
    return x;
  }

  bool boolean(const json& parent, const std::string& path, const std::string& key) const {
    const json& v = member(parent, path, key, "true or false");
    if (!v.is_boolean()) fail(join(path, key), "true or false", describe(v));
    return v.get<bool>();
  }

  static std::string join(const std::string& path, const std::string& key) {
    return path.empty() ? key : path + "." + key;
  }
  static std::string index(const std::string& path, std::size_t i) {
    return fmt::format("{}[{}]", path, i);
  }

  const std::string& file() const { return file_; }

 private:
  std::string file_;
};

// The number policy's underflow rule (docs/conventions.md): a number written non-zero that is too
// small for a double (1e-400, which the JSON parser reads as 0) is refused, as in every other
// input. JSON numbers stand outside strings only.
void check_json_underflow(const std::string& text, const std::string& file) {
  int line = 1;
  std::size_t line_start = 0;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '\n') {
      ++line;
      line_start = i + 1;
    } else if (c == '"') {
      for (++i; i < text.size() && text[i] != '"'; ++i)
        if (text[i] == '\\') ++i;
    } else if (c == '-' || (c >= '0' && c <= '9')) {
      std::size_t end = i + 1;
      while (end < text.size() &&
             std::string_view("0123456789.eE+-").find(text[end]) != std::string_view::npos)
        ++end;
      const std::string token = text.substr(i, end - i);
      char* stop = nullptr;
      const double v = read_input_number(token.c_str(), &stop);
      if (stop == token.c_str() + token.size() && v != 0.0 &&
          std::abs(v) < std::numeric_limits<double>::min())
        throw InputError(
            fmt::format("{}expected {}, found '{}'",
                        location_prefix(file, line, static_cast<int>(i - line_start) + 1),
                        kSaneNumberText, token));
      i = end - 1;
    }
  }
}

json parse_json_text(const std::string& text, const std::string& file) {
  require_utf8(text, file);
  check_json_underflow(text, file);
  try {
    return json::parse(text);
  } catch (const json::out_of_range& e) {
    // A number too large for a double (1e999): nlohmann names it in its message.
    std::string detail = e.what();
    const auto at = detail.find("number overflow");
    throw InputError(fmt::format("{}expected JSON numbers that fit a double, found {}",
                                 location_prefix(file),
                                 at == std::string::npos ? detail : detail.substr(at)));
  } catch (const json::parse_error& e) {
    // e.byte: 1-based index of the last byte read.
    const std::size_t end = std::min<std::size_t>(e.byte > 0 ? e.byte - 1 : 0, text.size());
    int line = 1, column = 1;
    for (std::size_t i = 0; i < end; ++i) {
      if (text[i] == '\n') {
        ++line;
        column = 1;
      } else {
        ++column;
      }
    }
    std::string detail = e.what();
    const auto colon = detail.find(": ", detail.find("column"));
    if (colon != std::string::npos) detail = detail.substr(colon + 2);
    throw InputError(fmt::format("{}expected JSON, found a syntax error ({})",
                                 location_prefix(file, line, column), detail));
  }
}

// Reads {"name": number|null, ...} for exactly the names given, in that order.
std::vector<double> named_values(const ParetoReader& r, const json& parent, const std::string& path,
                                 const std::string& key, const std::vector<std::string>& names) {
  const json& values = r.object(parent, path, key);
  const std::string where = ParetoReader::join(path, key);
  std::vector<double> out;
  for (const std::string& name : names) out.push_back(r.number(values, where, name, true));
  for (const auto& [name, value] : values.items()) {
    if (std::find(names.begin(), names.end(), name) == names.end()) {
      r.fail(ParetoReader::join(where, name), "one of the names listed at the top of the file",
             quote_found(name));
    }
  }
  return out;
}

json number_or_null(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

}  // namespace

int ParetoFront::design_index(const std::string& id) const {
  for (std::size_t d = 0; d < designs.size(); ++d) {
    if (designs[d].id == id) return static_cast<int>(d);
  }
  return -1;
}

bool ParetoFront::home_height_is_parameter() const {
  return std::any_of(parameters.begin(), parameters.end(),
                     [](const ParetoParameter& p) { return p.name == "home_height"; });
}

namespace {

// The columns: parameters, fixed parameters, objectives and constraints (names used once).
void read_columns(const ParetoReader& r, const json& root, ParetoFront& front) {
  std::set<std::string> names;  // every column name must be unique
  auto unique = [&](const std::string& where, const std::string& name) {
    if (name.empty()) r.fail(where, "a non-empty name", "''");
    if (!names.insert(name).second) r.fail(where, "a name used once", quote_found(name));
  };
  const json& parameters = r.array(root, "", "parameters");
  for (std::size_t i = 0; i < parameters.size(); ++i) {
    const std::string where = ParetoReader::index("parameters", i);
    const json& p = parameters[i];
    if (!p.is_object()) r.fail(where, "an object", describe(p));
    ParetoParameter par;
    par.name = r.string(p, where, "name");
    unique(where + ".name", par.name);
    par.unit = r.string(p, where, "unit");
    par.min = r.number(p, where, "min", false);
    par.max = r.number(p, where, "max", false);
    front.parameters.push_back(par);
  }
  const json& fixed = r.object(root, "", "fixed_parameters");
  for (const auto& [name, value] : fixed.items()) {
    front.fixed_parameters.emplace_back(
        name, r.number_value(value, ParetoReader::join("fixed_parameters", name), false));
  }
  const json& objectives = r.array(root, "", "objectives");
  for (std::size_t i = 0; i < objectives.size(); ++i) {
    const std::string where = ParetoReader::index("objectives", i);
    const json& o = objectives[i];
    if (!o.is_object()) r.fail(where, "an object", describe(o));
    ParetoObjective obj;
    obj.name = r.string(o, where, "name");
    unique(where + ".name", obj.name);
    obj.sense = r.string(o, where, "sense");
    if (obj.sense != "minimize" && obj.sense != "maximize") {
      r.fail(where + ".sense", "'minimize' or 'maximize'", quote_found(obj.sense));
    }
    obj.unit = r.string(o, where, "unit");
    front.objectives.push_back(obj);
  }
  if (front.objectives.empty()) r.fail("objectives", "at least one objective", "an empty array");
  const json& constraints = r.array(root, "", "constraints");
  for (std::size_t i = 0; i < constraints.size(); ++i) {
    const std::string where = ParetoReader::index("constraints", i);
    const json& c = constraints[i];
    if (!c.is_object()) r.fail(where, "an object", describe(c));
    ParetoConstraint con;
    con.name = r.string(c, where, "name");
    unique(where + ".name", con.name);
    con.metric = r.string(c, where, "metric");
    con.kind = r.string(c, where, "kind");
    if (con.kind != "max" && con.kind != "min" && con.kind != "reachable") {
      r.fail(where + ".kind", "'max', 'min' or 'reachable'", quote_found(con.kind));
    }
    con.bound = r.number(c, where, "bound", false);
    con.unit = r.string(c, where, "unit");
    front.constraints.push_back(con);
  }
}

// The task: centre, wrench, tilt and yaw, and the extent of the task positions if given.
ParetoTask read_task(const ParetoReader& r, const json& root) {
  ParetoTask out;
  const json& task = r.object(root, "", "task");
  const json& centre = r.array(task, "task", "centre");
  if (centre.size() != 3) r.fail("task.centre", "3 numbers", describe(centre));
  for (int k = 0; k < 3; ++k) {
    out.centre(k) = r.number_value(centre[static_cast<std::size_t>(k)],
                                   ParetoReader::index("task.centre", k), false);
  }
  const json& wrench = r.array(task, "task", "wrench");
  if (wrench.size() != 6) r.fail("task.wrench", "6 numbers", describe(wrench));
  for (std::size_t k = 0; k < 6; ++k) {
    out.wrench[k] = r.number_value(wrench[k], ParetoReader::index("task.wrench", k), false);
  }
  out.tilt_deg = r.number(task, "task", "tilt_deg", false);
  out.yaw_deg = r.number(task, "task", "yaw_deg", false);
  if (task.contains("positions_min") || task.contains("positions_max")) {
    Eigen::Vector3d extent[2];
    const char* keys[2] = {"positions_min", "positions_max"};
    for (int e = 0; e < 2; ++e) {
      const json& v = r.array(task, "task", keys[e]);
      const std::string where = ParetoReader::join("task", keys[e]);
      if (v.size() != 3) r.fail(where, "3 numbers", describe(v));
      for (int k = 0; k < 3; ++k)
        extent[e](k) =
            r.number_value(v[static_cast<std::size_t>(k)],
                           ParetoReader::index(where, static_cast<std::size_t>(k)), false);
    }
    if (!(extent[0].array() <= extent[1].array()).all())
      r.fail("task.positions_max", "a corner above task.positions_min",
             describe(task["positions_max"]));
    out.positions = std::make_pair(extent[0], extent[1]);
  }
  return out;
}

// How the front was selected and how the hypervolume converged (both optional).
void read_selection_and_convergence(const ParetoReader& r, const json& root, ParetoFront& front) {
  if (root.contains("front_selection")) {
    const json& f = r.object(root, "", "front_selection");
    ParetoSelection sel;
    sel.rule = r.string(f, "front_selection", "rule");
    sel.evaluations = r.number(f, "front_selection", "evaluations", false);
    sel.feasible_evaluations = r.number(f, "front_selection", "feasible_evaluations", false);
    sel.archive_size = r.number(f, "front_selection", "archive_size", false);
    front.selection = sel;
  }
  if (root.contains("convergence")) {
    const json& c = r.object(root, "", "convergence");
    ParetoConvergence conv;
    const json& evals = r.array(c, "convergence", "evaluations");
    const json& hv = r.array(c, "convergence", "hypervolume");
    if (evals.size() != hv.size())
      r.fail("convergence.hypervolume",
             fmt::format("{} numbers (one per evaluations entry)", evals.size()),
             fmt::format("{}", hv.size()));
    for (std::size_t k = 0; k < evals.size(); ++k) {
      conv.evaluations.push_back(
          r.number_value(evals[k], ParetoReader::index("convergence.evaluations", k), false));
      conv.hypervolume.push_back(
          r.number_value(hv[k], ParetoReader::index("convergence.hypervolume", k), false));
    }
    front.convergence = conv;
  }
}

// Design `i` of `designs`, its values named by the front's columns.
ParetoDesign read_design(const ParetoReader& r, const json& d, const std::string& where,
                         const ParetoFront& front, const std::vector<std::string>& parameter_names,
                         const std::vector<std::string>& objective_names,
                         const std::vector<std::string>& constraint_names) {
  ParetoDesign design;
  design.id = r.string(d, where, "id");
  if (design.id.empty()) r.fail(where + ".id", "a non-empty id", "''");
  if (front.design_index(design.id) >= 0) {
    r.fail(where + ".id", "an id used once", quote_found(design.id));
  }
  design.parameters = named_values(r, d, where, "parameters", parameter_names);
  design.home_height = r.number(d, where, "home_height", false);
  design.objectives = named_values(r, d, where, "objectives", objective_names);
  design.constraints = named_values(r, d, where, "constraints", constraint_names);
  design.feasible = r.boolean(d, where, "feasible");
  if (d.contains("actuator") && !d["actuator"].is_null()) {
    const std::string a = where + ".actuator";
    const json& actuator = r.object(d, where, "actuator");
    design.actuator = ParetoActuator{.name = r.string(actuator, a, "name"),
                                     .max_force = r.number(actuator, a, "max_force", false),
                                     .stroke = r.number(actuator, a, "stroke", false),
                                     .cost = r.number(actuator, a, "cost", false),
                                     .force_reserve = r.number(actuator, a, "force_reserve", true)};
  }
  if (d.contains("machine_file")) {
    const std::string file = r.string(d, where, "machine_file");
    if (file.empty() || std::filesystem::path(file).is_absolute()) {
      r.fail(where + ".machine_file", "a path relative to the results folder", quote_found(file));
    }
    design.machine_file = file;
  }
  return design;
}

// A design id or null at `where` (knee, compromise, an entry of high_trade_off).
std::optional<std::string> read_design_id(const ParetoReader& r, const ParetoFront& front,
                                          const json& value, const std::string& where) {
  if (value.is_null()) return std::nullopt;
  if (!value.is_string()) r.fail(where, "a design id or null", describe(value));
  const std::string id = value.get<std::string>();
  if (front.design_index(id) < 0) r.fail(where, "the id of a design in `designs`", quote_found(id));
  return id;
}

}  // namespace

ParetoFront read_pareto_json(const std::string& path) {
  const std::string text = read_input_file(path);
  const json root = parse_json_text(text, path);
  const ParetoReader r(path);
  if (!root.is_object()) r.fail("(top level)", "an object", describe(root));
  ParetoFront front;
  front.file = path;
  front.format = r.string(root, "", "format");
  if (front.format != "pkmopt-pareto-1") {
    r.fail("format", "'pkmopt-pareto-1'", quote_found(front.format));
  }
  front.pkmopt_version = r.string(root, "", "pkmopt_version");
  front.study = r.string(root, "", "study");
  front.description = r.string(root, "", "description");
  front.model = r.string(root, "", "model");

  read_columns(r, root, front);
  front.task = read_task(r, root);
  read_selection_and_convergence(r, root, front);
  if (root.contains("actuator_catalog") && !root["actuator_catalog"].is_null())
    front.actuator_catalog =
        r.string(r.object(root, "", "actuator_catalog"), "actuator_catalog", "name");
  std::vector<std::string> parameter_names, objective_names, constraint_names;
  for (const auto& p : front.parameters) parameter_names.push_back(p.name);
  for (const auto& o : front.objectives) objective_names.push_back(o.name);
  for (const auto& c : front.constraints) constraint_names.push_back(c.name);
  const json& designs = r.array(root, "", "designs");
  for (std::size_t i = 0; i < designs.size(); ++i) {
    const std::string where = ParetoReader::index("designs", i);
    const json& d = designs[i];
    if (!d.is_object()) r.fail(where, "an object", describe(d));
    front.designs.push_back(
        read_design(r, d, where, front, parameter_names, objective_names, constraint_names));
  }
  front.knee = read_design_id(r, front, r.member(root, "", "knee", "a design id or null"), "knee");
  // compromise and high_trade_off are optional (files of earlier pkmopt versions lack them).
  if (root.contains("compromise"))
    front.compromise = read_design_id(r, front, root["compromise"], "compromise");
  if (root.contains("high_trade_off")) {
    const json& ids = r.array(root, "", "high_trade_off");
    for (std::size_t i = 0; i < ids.size(); ++i) {
      const std::string where = ParetoReader::index("high_trade_off", i);
      const std::optional<std::string> id = read_design_id(r, front, ids[i], where);
      if (!id) r.fail(where, "a design id", "null");
      front.high_trade_off.push_back(*id);
    }
  }
  return front;
}

std::string pareto_csv(const ParetoFront& front) {
  std::vector<std::string> header{"id"};
  for (const auto& p : front.parameters) header.push_back(p.name);
  const bool home_column = !front.home_height_is_parameter();
  if (home_column) header.push_back("home_height");
  for (const auto& o : front.objectives) header.push_back(o.name);
  for (const auto& c : front.constraints) header.push_back(c.name);
  if (front.actuator_catalog) header.push_back("actuator");
  header.push_back("feasible");
  header.push_back("knee");
  std::string out;
  for (std::size_t k = 0; k < header.size(); ++k) out += (k ? "," : "") + csv_field(header[k]);
  out += '\n';
  auto cell = [](double v) { return std::isfinite(v) ? format_number(v) : std::string(); };
  for (const ParetoDesign& d : front.designs) {
    out += csv_field(d.id);
    for (double v : d.parameters) out += ',' + cell(v);
    if (home_column) out += ',' + cell(d.home_height);
    for (double v : d.objectives) out += ',' + cell(v);
    for (double v : d.constraints) out += ',' + cell(v);
    if (front.actuator_catalog) out += ',' + (d.actuator ? csv_field(d.actuator->name) : "");
    out += d.feasible ? ",1" : ",0";
    out += front.knee && *front.knee == d.id ? ",1" : ",0";
    out += '\n';
  }
  return out;
}

std::string pareto_json(const ParetoFront& front) {
  nlohmann::ordered_json root;
  root["format"] = front.format;
  root["pkmopt_version"] = front.pkmopt_version;
  root["study"] = front.study;
  root["description"] = front.description;
  root["model"] = front.model;
  root["parameters"] = nlohmann::ordered_json::array();
  for (const auto& p : front.parameters) {
    root["parameters"].push_back(
        {{"name", p.name}, {"unit", p.unit}, {"min", p.min}, {"max", p.max}});
  }
  root["fixed_parameters"] = nlohmann::ordered_json::object();
  for (const auto& [name, value] : front.fixed_parameters) root["fixed_parameters"][name] = value;
  root["objectives"] = nlohmann::ordered_json::array();
  for (const auto& o : front.objectives) {
    root["objectives"].push_back({{"name", o.name}, {"sense", o.sense}, {"unit", o.unit}});
  }
  root["constraints"] = nlohmann::ordered_json::array();
  for (const auto& c : front.constraints) {
    root["constraints"].push_back({{"name", c.name},
                                   {"metric", c.metric},
                                   {"kind", c.kind},
                                   {"bound", c.bound},
                                   {"unit", c.unit}});
  }
  if (front.actuator_catalog) root["actuator_catalog"] = {{"name", *front.actuator_catalog}};
  root["task"] = {{"centre", {front.task.centre(0), front.task.centre(1), front.task.centre(2)}},
                  {"wrench", front.task.wrench},
                  {"tilt_deg", front.task.tilt_deg},
                  {"yaw_deg", front.task.yaw_deg}};
  if (const auto& p = front.task.positions) {
    root["task"]["positions_min"] = {p->first(0), p->first(1), p->first(2)};
    root["task"]["positions_max"] = {p->second(0), p->second(1), p->second(2)};
  }
  if (const auto& sel = front.selection)
    root["front_selection"] = {{"rule", sel->rule},
                               {"evaluations", sel->evaluations},
                               {"feasible_evaluations", sel->feasible_evaluations},
                               {"archive_size", sel->archive_size}};
  if (const auto& c = front.convergence)
    root["convergence"] = {{"evaluations", c->evaluations}, {"hypervolume", c->hypervolume}};
  root["designs"] = nlohmann::ordered_json::array();
  for (const ParetoDesign& d : front.designs) {
    nlohmann::ordered_json design;
    design["id"] = d.id;
    design["parameters"] = nlohmann::ordered_json::object();
    for (std::size_t k = 0; k < d.parameters.size(); ++k) {
      design["parameters"][front.parameters[k].name] = number_or_null(d.parameters[k]);
    }
    design["home_height"] = d.home_height;
    design["objectives"] = nlohmann::ordered_json::object();
    for (std::size_t k = 0; k < d.objectives.size(); ++k) {
      design["objectives"][front.objectives[k].name] = number_or_null(d.objectives[k]);
    }
    design["constraints"] = nlohmann::ordered_json::object();
    for (std::size_t k = 0; k < d.constraints.size(); ++k) {
      design["constraints"][front.constraints[k].name] = number_or_null(d.constraints[k]);
    }
    if (front.actuator_catalog) {
      design["actuator"] = nullptr;
      if (const auto& a = d.actuator)
        design["actuator"] = {{"name", a->name},
                              {"max_force", a->max_force},
                              {"stroke", a->stroke},
                              {"cost", a->cost},
                              {"force_reserve", number_or_null(a->force_reserve)}};
    }
    design["feasible"] = d.feasible;
    if (d.machine_file) design["machine_file"] = *d.machine_file;
    root["designs"].push_back(design);
  }
  root["knee"] = front.knee ? nlohmann::ordered_json(*front.knee) : nlohmann::ordered_json();
  root["compromise"] =
      front.compromise ? nlohmann::ordered_json(*front.compromise) : nlohmann::ordered_json();
  root["high_trade_off"] = front.high_trade_off;
  return root.dump(2) + "\n";
}

}  // namespace pkmopt
