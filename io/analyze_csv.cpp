#include "io/analyze_csv.hpp"

#include <sstream>

#include "models/leg_interference.hpp"

namespace pkmopt {

std::string analyze_csv(const Machine& machine, const PoseTable& poses,
                        const std::vector<PoseMetrics>& metrics, const AnalyzeCsvOptions& options) {
  const CsvTable& table = poses.table;
  const std::vector<int> passthrough = poses.other_columns();
  const int na = machine.num_actuators();
  const double q_scale = machine.revolute_actuators() ? kRadToDeg : 1.0;
  std::ostringstream out;
  out << "x,y,z,rx,ry,rz,reachable";
  for (int j = 1; j <= na; ++j) out << ",q_" << j;
  for (int j = 1; j <= na; ++j) out << ",tau_" << j;
  out << ",stiffness_min,singularity_margin,det_j,tcp_error_max";
  out << ",tcp_deflection,tcp_rotation_deflection_deg,stiffness_min_loaded,stiffness_dir_x,"
         "stiffness_dir_y,stiffness_dir_z";
  const bool interference = machine.checks_leg_interference();
  if (interference) out << ",leg_clearance,clearance_pair";
  const int nf = machine.natural_frequency_count();
  for (int j = 1; j <= nf; ++j) out << ",natural_frequency_" << j;
  const int axes = machine.mode_axis_count();
  static constexpr const char* kTwist[] = {"dx", "dy", "dz", "drx", "dry", "drz"};
  if (options.modes) {
    for (int k = 1; k <= nf; ++k) {
      for (int a = 1; a <= axes; ++a) out << ",mode_" << k << "_axis_" << a;
      for (const char* c : kTwist) out << ",mode_" << k << '_' << c;
    }
  }
  if (options.compliance)
    for (int a = 1; a <= 6; ++a)
      for (int b = 1; b <= 6; ++b) out << ",C_" << a << b;
  for (int c : passthrough) out << ',' << csv_field(table.header[static_cast<std::size_t>(c)]);
  out << '\n';
  for (std::size_t i = 0; i < metrics.size(); ++i) {
    const PoseMetrics& m = metrics[i];
    std::string line;
    line.reserve(512);
    for (int k = 0; k < 3; ++k) line += format_number(poses.poses[i].position(k)) + ',';
    for (int k = 0; k < 3; ++k) line += format_number(poses.angles_deg[i](k)) + ',';
    line += m.reachable ? '1' : '0';
    for (int j = 0; j < na; ++j) line += ',' + format_number(m.q(j) * q_scale);
    for (int j = 0; j < na; ++j) line += ',' + format_number(m.tau(j));
    line += ',' + format_number(m.stiffness_min);
    line += ',' + format_number(m.singularity_margin);
    line += ',' + format_number(m.det_j);
    line += ',' + format_number(m.tcp_error_max);
    line += ',' + format_number(m.tcp_deflection);
    line += ',' + format_number(m.tcp_rotation_deflection * kRadToDeg);
    line += ',' + format_number(m.stiffness_min_loaded);
    for (int k = 0; k < 3; ++k) line += ',' + format_number(m.stiffness_min_direction(k) + 0.0);
    if (interference) {
      line += ',' + format_number(m.leg_clearance);
      line += ',' + clearance_pair_text(m.clearance_first, m.clearance_second);
    }
    for (int j = 0; j < nf; ++j) {
      const bool have = j < m.natural_frequencies.size();
      line += ',' + format_number(have ? m.natural_frequencies(j) : 0.0);
    }
    if (options.modes) {
      const Eigen::MatrixXd& shapes = (*options.modes)[i].shapes;
      const bool have = shapes.rows() == axes + 6 && shapes.cols() >= nf;
      for (int k = 0; k < nf; ++k)
        for (int r = 0; r < axes + 6; ++r)
          line += ',' + format_number(have ? shapes(r, k) + 0.0 : 0.0);
    }
    if (options.compliance)
      for (int a = 0; a < 6; ++a)
        for (int b = 0; b < 6; ++b)
          line += ',' + format_number((*options.compliance)[i].compliance(a, b) + 0.0);
    for (int c : passthrough)
      line += ',' + csv_field(table.rows[i].cells[static_cast<std::size_t>(c)]);
    out << line << '\n';
  }
  return out.str();
}

}  // namespace pkmopt
