// pkmopt draw MACHINE.yaml [--pose x,y,z,rx,ry,rz] [--out FILE.svg]
//
// The machine drawn at a pose as an SVG picture (report/machine_drawing.hpp): front and top
// views of the base, the legs and the platform. Without --pose, the platform level half way up
// the reachable part of the vertical above the centroid of the base joints (drawing_pose).
#include <fmt/format.h>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>

#include "app/cli_args.hpp"
#include "app/commands.hpp"
#include "io/format/input_error.hpp"
#include "io/format/number_policy.hpp"
#include "io/format/output_file.hpp"
#include "io/machine/machine_file.hpp"
#include "report/machine_drawing.hpp"

namespace pkmopt::cli {
namespace {

struct DrawOptions {
  std::string machine_file;
  std::string pose;
  std::string out_file;
};

void run_draw(const DrawOptions& opt) {
  const std::unique_ptr<Machine> machine = load_machine_file(opt.machine_file);
  Pose pose;
  if (!opt.pose.empty()) {
    const auto v = parse_number_list("--pose", opt.pose, 6);
    for (int k = 0; k < 3; ++k)
      if (!sane_input_length(v[static_cast<std::size_t>(k)]))
        throw InputError(
            fmt::format("--pose: expected positions within +-1000 m, found '{}'", opt.pose));
    pose = Pose{{v[0], v[1], v[2]}, deg_to_rad(Eigen::Vector3d(v[3], v[4], v[5]))};
  } else {
    const std::optional<Pose> home = drawing_pose(*machine);
    if (!home)
      throw InputError(fmt::format(
          "{}: expected a machine with a reachable level pose above the middle of its workspace, "
          "found none; give the pose with --pose x,y,z,rx,ry,rz",
          opt.machine_file));
    pose = *home;
  }
  MachineSketch sketch;
  if (!machine->sketch(*machine->make_data(), pose, sketch))
    throw InputError(
        fmt::format("--pose: the legs of {} cannot assemble at '{}' (no inverse "
                    "kinematics solution)",
                    opt.machine_file, opt.pose));
  const std::string title = fmt::format(
      "{} at ({:.1f}, {:.1f}, {:.1f}) mm, ({:.4g}, {:.4g}, {:.4g}) deg", machine->model(),
      1e3 * pose.position.x(), 1e3 * pose.position.y(), 1e3 * pose.position.z(),
      rad_to_deg(pose.angles.x()), rad_to_deg(pose.angles.y()), rad_to_deg(pose.angles.z()));
  const std::string svg = machine_svg(sketch, {.title = title});
  if (opt.out_file.empty()) {
    std::cout << svg;
    std::cout.flush();
  } else {
    write_file_atomically(opt.out_file, svg);
  }
  if (!sketch.reachable)
    std::fprintf(stderr,
                 "pkmopt: warning: draw: the pose is outside the strokes or joint limits of %s "
                 "(drawn anyway)\n",
                 opt.machine_file.c_str());
}

}  // namespace

void add_draw_command(CLI::App& app) {
  auto opt = std::make_shared<DrawOptions>();
  CLI::App* cmd = app.add_subcommand(
      "draw", "Draw a machine at a pose as SVG: front and top views of base, legs and platform");
  cmd->add_option("machine", opt->machine_file, "Machine file (YAML)")->required();
  cmd->add_option("--pose", opt->pose,
                  "TCP pose x,y,z,rx,ry,rz (m, degrees); default: level, half way up the "
                  "reachable vertical above the centroid of the base joints");
  cmd->add_option("--out", opt->out_file, "Output SVG (default: standard output)");
  cmd->callback([opt] { run_draw(*opt); });
}

}  // namespace pkmopt::cli
