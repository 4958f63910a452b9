// pkmopt analyze MACHINE.yaml --poses POSES.csv [--wrench fx,fy,fz,mx,my,mz] [--out FILE.csv]
#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <iostream>
#include <memory>
#include <sstream>

#include "app/cli_args.hpp"
#include "app/commands.hpp"
#include "app/csv.hpp"
#include "app/input_error.hpp"
#include "app/machine_file.hpp"
#include "app/output_file.hpp"
#include "models/hexapod.hpp"
#include "models/hexapod_batch.hpp"

namespace pkmopt::cli {
namespace {

struct AnalyzeOptions {
  std::string machine_file;
  std::string poses_file;
  std::string wrench;
  std::string out_file;
};

void run_analyze(const AnalyzeOptions& opt) {
  // Read and validate every input before anything is written.
  const std::unique_ptr<Machine> machine = load_machine_file(opt.machine_file);
  Wrench wrench = Wrench::Zero();
  if (!opt.wrench.empty()) {
    const auto w = parse_number_list("--wrench", opt.wrench, 6);
    for (int i = 0; i < 6; ++i) wrench(i) = w[static_cast<std::size_t>(i)];
  }
  const CsvTable table = read_csv_file(opt.poses_file);
  const int cx = table.require_column("x");
  const int cy = table.require_column("y");
  const int cz = table.require_column("z");
  const int crx = table.column("rx"), cry = table.column("ry"), crz = table.column("rz");
  std::vector<int> passthrough;
  for (int c = 0; c < static_cast<int>(table.header.size()); ++c) {
    if (c != cx && c != cy && c != cz && c != crx && c != cry && c != crz) passthrough.push_back(c);
  }
  const std::size_t n = table.rows.size();
  std::vector<Pose> poses(n);
  std::vector<Eigen::Vector3d> angles_deg(n, Eigen::Vector3d::Zero());
  for (std::size_t i = 0; i < n; ++i) {
    const CsvRow& row = table.rows[i];
    poses[i].position = {table.number(row, cx), table.number(row, cy), table.number(row, cz)};
    if (crx >= 0) angles_deg[i](0) = table.number(row, crx);
    if (cry >= 0) angles_deg[i](1) = table.number(row, cry);
    if (crz >= 0) angles_deg[i](2) = table.number(row, crz);
    poses[i].angles = deg_to_rad(angles_deg[i]);
  }

  // Evaluate in parallel: the machine is shared, each thread owns its data. A hexapod goes
  // through the SIMD batch path (models/hexapod_batch.hpp: the same metrics, four poses at a
  // time) on slices of kSlice poses; a pose's result does not depend on its slice.
  std::vector<PoseMetrics> metrics(n);
  if (const auto* hexapod = dynamic_cast<const Hexapod*>(machine.get())) {
    constexpr std::size_t kSlice = 1024;
#pragma omp parallel for schedule(static)
    for (std::size_t start = 0; start < n; start += kSlice) {
      analyze_hexapod_batch(*hexapod, poses.data() + start, std::min(kSlice, n - start), wrench,
                            metrics.data() + start);
    }
  } else {
#pragma omp parallel
    {
      const std::unique_ptr<MachineData> data = machine->make_data();
#pragma omp for schedule(static)
      for (std::size_t i = 0; i < n; ++i) machine->analyze(*data, poses[i], wrench, metrics[i]);
    }
  }

  const int na = machine->num_actuators();
  const double q_scale = machine->revolute_actuators() ? kRadToDeg : 1.0;
  std::ostringstream out;
  out << "x,y,z,rx,ry,rz,reachable";
  for (int j = 1; j <= na; ++j) out << ",q_" << j;
  for (int j = 1; j <= na; ++j) out << ",tau_" << j;
  out << ",stiffness_min,singularity_margin,det_j,tcp_error_max";
  for (int c : passthrough) out << ',' << csv_field(table.header[static_cast<std::size_t>(c)]);
  out << '\n';
  for (std::size_t i = 0; i < n; ++i) {
    const PoseMetrics& m = metrics[i];
    std::string line;
    line.reserve(512);
    for (int k = 0; k < 3; ++k) line += format_number(poses[i].position(k)) + ',';
    for (int k = 0; k < 3; ++k) line += format_number(angles_deg[i](k)) + ',';
    line += m.reachable ? '1' : '0';
    for (int j = 0; j < na; ++j) line += ',' + format_number(m.q(j) * q_scale);
    for (int j = 0; j < na; ++j) line += ',' + format_number(m.tau(j));
    line += ',' + format_number(m.stiffness_min);
    line += ',' + format_number(m.singularity_margin);
    line += ',' + format_number(m.det_j);
    line += ',' + format_number(m.tcp_error_max);
    for (int c : passthrough)
      line += ',' + csv_field(table.rows[i].cells[static_cast<std::size_t>(c)]);
    out << line << '\n';
  }
  if (opt.out_file.empty()) {
    std::cout << out.str();
    std::cout.flush();
  } else {
    write_file_atomically(opt.out_file, out.str());
  }
}

}  // namespace

void add_analyze_command(CLI::App& app) {
  auto opt = std::make_shared<AnalyzeOptions>();
  CLI::App* cmd =
      app.add_subcommand("analyze",
                         "Evaluate a machine at every pose of a CSV file: reachability, actuator "
                         "coordinates and forces, stiffness, singularity margin, accuracy");
  cmd->add_option("machine", opt->machine_file, "Machine file (YAML)")->required();
  cmd->add_option("--poses", opt->poses_file,
                  "Pose CSV with columns x,y,z (m) and optionally rx,ry,rz (deg)")
      ->required();
  cmd->add_option("--wrench", opt->wrench,
                  "External wrench at the TCP, base axes: fx,fy,fz,mx,my,mz (N, N*m); default 0");
  cmd->add_option("--out", opt->out_file, "Output CSV (default: standard output)");
  cmd->callback([opt] { run_analyze(*opt); });
}

}  // namespace pkmopt::cli
