#include "io/results/analyze_csv.hpp"

#include "models/core/capabilities.hpp"
#include "models/geometry/leg_interference.hpp"

namespace pkmopt {

std::vector<std::string> analyze_value_columns(const Machine& machine, bool modes,
                                               bool compliance) {
  const int na = machine.num_actuators();
  std::vector<std::string> names{"reachable"};
  for (int j = 1; j <= na; ++j) names.push_back("q_" + std::to_string(j));
  for (int j = 1; j <= na; ++j) names.push_back("tau_" + std::to_string(j));
  for (const char* name : {"stiffness_min", "singularity_margin", "det_j", "tcp_error_max",
                           "tcp_deflection", "tcp_rotation_deflection_deg", "stiffness_min_loaded",
                           "stiffness_dir_x", "stiffness_dir_y", "stiffness_dir_z"})
    names.emplace_back(name);
  if (machine.checks_leg_interference()) names.emplace_back("leg_clearance");
  const Capability<Dynamics> dynamics = machine.dynamics();
  const int nf = dynamics ? dynamics->natural_frequency_count() : 0;
  for (int j = 1; j <= nf; ++j) names.push_back("natural_frequency_" + std::to_string(j));
  const int axes = dynamics ? dynamics->mode_axis_count() : 0;
  static constexpr const char* kTwist[] = {"dx", "dy", "dz", "drx", "dry", "drz"};
  if (modes) {
    for (int k = 1; k <= nf; ++k) {
      const std::string mode = "mode_" + std::to_string(k) + "_";
      for (int a = 1; a <= axes; ++a) names.push_back(mode + "axis_" + std::to_string(a));
      for (const char* c : kTwist) names.push_back(mode + c);
    }
  }
  if (compliance)
    for (int a = 1; a <= 6; ++a)
      for (int b = 1; b <= 6; ++b) names.push_back("C_" + std::to_string(a) + std::to_string(b));
  return names;
}

void analyze_values(const Machine& machine, const PoseMetrics& m, const PoseModes* modes,
                    const PoseCompliance* compliance, double* out) {
  const int na = machine.num_actuators();
  *out++ = m.reachable ? 1.0 : 0.0;
  for (int j = 0; j < na; ++j) *out++ = m.q(j) * (machine.revolute_actuator(j) ? kRadToDeg : 1.0);
  for (int j = 0; j < na; ++j) *out++ = m.tau(j);
  *out++ = m.stiffness_min;
  *out++ = m.singularity_margin;
  *out++ = m.det_j;
  *out++ = m.tcp_error_max;
  *out++ = m.tcp_deflection;
  *out++ = m.tcp_rotation_deflection * kRadToDeg;
  *out++ = m.stiffness_min_loaded;
  for (int k = 0; k < 3; ++k) *out++ = m.stiffness_min_direction(k) + 0.0;
  if (machine.checks_leg_interference()) *out++ = m.leg_clearance;
  const Capability<Dynamics> dynamics = machine.dynamics();
  const int nf = dynamics ? dynamics->natural_frequency_count() : 0;
  for (int j = 0; j < nf; ++j) {
    const bool have = j < m.natural_frequencies.size();
    *out++ = have ? m.natural_frequencies(j) : 0.0;
  }
  if (modes) {
    const int axes = dynamics ? dynamics->mode_axis_count() : 0;
    const Eigen::MatrixXd& shapes = modes->shapes;
    const bool have = shapes.rows() == axes + 6 && shapes.cols() >= nf;
    for (int k = 0; k < nf; ++k)
      for (int r = 0; r < axes + 6; ++r) *out++ = have ? shapes(r, k) + 0.0 : 0.0;
  }
  if (compliance)
    for (int a = 0; a < 6; ++a)
      for (int b = 0; b < 6; ++b) *out++ = compliance->compliance(a, b) + 0.0;
}

std::string analyze_csv_header(const Machine& machine, const PoseTable& poses,
                               const AnalyzeCsvOptions& options) {
  const std::vector<std::string> names =
      analyze_value_columns(machine, options.modes != nullptr, options.compliance != nullptr);
  std::string out = "x,y,z,rx,ry,rz";
  for (const std::string& name : names) {
    out += ',' + name;
    if (name == "leg_clearance") out += ",clearance_pair";
  }
  for (int c : poses.other_columns())
    out += ',' + csv_field(poses.table.header[static_cast<std::size_t>(c)]);
  return out + '\n';
}

namespace {

std::string row_text(const Machine& machine, const PoseTable& poses, std::size_t row,
                     const PoseMetrics& m, const PoseModes* modes, const PoseCompliance* compliance,
                     const std::vector<std::string>& names) {
  const bool interference = machine.checks_leg_interference();
  std::vector<double> values(names.size());
  analyze_values(machine, m, modes, compliance, values.data());
  std::string line;
  line.reserve(512);
  for (int k = 0; k < 3; ++k) line += format_number(poses.poses[row].position(k)) + ',';
  for (int k = 0; k < 3; ++k) line += format_number(poses.angles_deg[row](k)) + ',';
  line += m.reachable ? '1' : '0';
  for (std::size_t c = 1; c < names.size(); ++c) {
    line += ',' + format_number(values[c]);
    if (interference && names[c] == "leg_clearance")
      line += ',' + clearance_pair_text(m.clearance_first, m.clearance_second);
  }
  for (int c : poses.other_columns())
    line += ',' + csv_field(poses.table.rows[row].cells[static_cast<std::size_t>(c)]);
  return line + '\n';
}

}  // namespace

std::string analyze_csv_row(const Machine& machine, const PoseTable& poses, std::size_t row,
                            const PoseMetrics& metrics, const PoseModes* modes,
                            const PoseCompliance* compliance) {
  return row_text(machine, poses, row, metrics, modes, compliance,
                  analyze_value_columns(machine, modes != nullptr, compliance != nullptr));
}

std::string analyze_csv(const Machine& machine, const PoseTable& poses,
                        const std::vector<PoseMetrics>& metrics, const AnalyzeCsvOptions& options) {
  std::string out = analyze_csv_header(machine, poses, options);
  const std::vector<std::string> names =
      analyze_value_columns(machine, options.modes != nullptr, options.compliance != nullptr);
  for (std::size_t i = 0; i < metrics.size(); ++i)
    out += row_text(machine, poses, i, metrics[i], options.modes ? &(*options.modes)[i] : nullptr,
                    options.compliance ? &(*options.compliance)[i] : nullptr, names);
  return out;
}

}  // namespace pkmopt
