// pkmopt fk MACHINE.yaml --q q1,...,qn [--guess x,y,z,rx,ry,rz] [--all]
#include <fmt/format.h>

#include <cstdio>
#include <iostream>
#include <memory>

#include "app/cli_args.hpp"
#include "app/commands.hpp"
#include "io/format/input_error.hpp"
#include "io/format/number_policy.hpp"
#include "io/machine/machine_file.hpp"
#include "io/results/fk_csv.hpp"
#include "models/core/capabilities.hpp"

namespace pkmopt::cli {
namespace {

struct FkCommandOptions {
  std::string machine_file;
  std::string q;
  std::string guess;
  int max_iterations = 100;
  bool all = false;
};

// --all: every real solution, one row each; the counts on standard error; failed paths exit 3.
void print_all_solutions(const Machine& machine, const Eigen::VectorXd& q,
                         const std::optional<Pose>& guess) {
  const Capability<AllForwardKinematics> solver = machine.all_forward_kinematics_solver();
  if (!solver) throw InputError("--all: expected a hexapod machine file, found " + solver.reason());
  const ForwardSolutions s = solver->all_forward_kinematics(q, guess);
  std::cout << fk_all_csv(s);
  std::cout.flush();
  fmt::print(stderr,
             "fk: {} real assembly modes, {} complex, {} at infinity, {} failed, of {} paths "
             "(the first row is the one nearest the {})\n",
             s.real.size(), s.complex_count, s.at_infinity, s.failed, s.paths,
             guess ? "guess" : "home pose");
  if (s.architecture_singular)
    throw ProbablyWrongResult(
        "fk --all: the machine is singular at every pose (architecture singularity: e.g. base and "
        "platform similar planar hexagons): its forward kinematics has curves of solutions "
        "(self-motions), not a finite set of assembly modes");
  if (s.failed > 0)
    throw ProbablyWrongResult(
        fmt::format("fk --all: {} of {} paths failed ({}); real solutions "
                    "may be missing",
                    s.failed, s.paths, s.failures.front()));
}

void run_fk(const FkCommandOptions& opt) {
  const std::unique_ptr<Machine> machine = load_machine_file(opt.machine_file);
  const int na = machine->num_actuators();
  // Linear actuators' coordinates are lengths (+-1000 m); revolute ones are angles in degrees.
  const bool all_revolute = machine->revolute_actuators();
  const bool mixed = !all_revolute && machine->any_revolute_actuator();
  const auto q_values = parse_number_list("--q", opt.q, static_cast<std::size_t>(na),
                                          all_revolute || mixed ? 1e15 : kMaxInputLength);
  Eigen::VectorXd q(na);
  for (int i = 0; i < na; ++i) {
    const double value = q_values[static_cast<std::size_t>(i)];
    if (machine->revolute_actuator(i)) {
      q(i) = value * kDegToRad;
    } else if (!sane_input_length(value)) {
      throw InputError(
          fmt::format("--q: expected value {} (a linear axis) within +-{:g} m, found "
                      "'{}'",
                      i + 1, kMaxInputLength, opt.q));
    } else {
      q(i) = value;
    }
  }
  if (const std::string expected = machine->actuator_coordinates_requirement(q);
      !expected.empty()) {
    throw InputError(fmt::format("--q: expected {}, found '{}'", expected, opt.q));
  }
  std::optional<Pose> guess;
  if (!opt.guess.empty()) {
    const auto g = parse_number_list("--guess", opt.guess, 6);
    for (int k = 0; k < 3; ++k)
      if (!sane_input_length(g[static_cast<std::size_t>(k)]))
        throw InputError(
            fmt::format("--guess: expected positions x,y,z within +-{:g} m, found '{}'",
                        kMaxInputLength, opt.guess));
    guess = Pose{{g[0], g[1], g[2]}, deg_to_rad(Eigen::Vector3d(g[3], g[4], g[5]))};
  }
  if (opt.max_iterations < 1) {
    throw InputError(
        fmt::format("--max-iterations: expected an integer >= 1, found {}", opt.max_iterations));
  }
  if (opt.all) {
    print_all_solutions(*machine, q, guess);
    return;
  }
  FkOptions fk_options;
  fk_options.max_iterations = opt.max_iterations;
  const FkResult r = machine->forward_kinematics(q, guess, fk_options);
  std::cout << fk_csv(r);
  std::cout.flush();
  // The pose columns of a solve that did not converge are not a pose of the machine: exit 3.
  if (!r.converged) throw ProbablyWrongResult("fk: " + r.message);
  // A pose the machine cannot take (strokes, joint limits) from actuator coordinates that the
  // leg geometry allows is most often a unit mix-up: said, the pose is still printed.
  std::unique_ptr<MachineData> data = machine->make_data();
  if (!machine->reachable(*data, r.pose))
    fmt::print(stderr,
               "pkmopt: warning: fk: the pose solves --q but lies outside the machine's strokes "
               "or joint limits ({}); check the units of --q ({})\n",
               opt.machine_file,
               machine->revolute_actuators() ? "degrees"
               : mixed                       ? "metres for linear axes, degrees for rotary ones"
                                             : "metres, not millimetres");
}

}  // namespace

void add_fk_command(CLI::App& app) {
  auto opt = std::make_shared<FkCommandOptions>();
  CLI::App* cmd = app.add_subcommand(
      "fk", "Forward kinematics: the TCP pose for given actuator coordinates (damped Newton)");
  cmd->add_option("machine", opt->machine_file, "Machine file (YAML)")->required();
  cmd->add_option(
         "--q", opt->q,
         "Actuator coordinates q1,...,qn (m for legs and linear axes, deg for revolute drives and "
         "rotary axes)")
      ->required();
  cmd->add_option("--guess", opt->guess,
                  "Start pose x,y,z,rx,ry,rz (m, deg); default: the machine's home pose");
  cmd->add_option("--max-iterations", opt->max_iterations, "Iteration limit (default 100)");
  cmd->add_flag("--all", opt->all,
                "Every real solution (assembly mode) of a hexapod, one row each, nearest the "
                "guess or home pose first, by a 40-path parameter homotopy");
  cmd->callback([opt] { run_fk(*opt); });
}

}  // namespace pkmopt::cli
